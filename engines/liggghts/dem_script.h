// LIGGGHTS input scripts as the coupler runs them: the checks a coupled script must pass, the
// files it writes, and the rewrite that resumes it from a checkpoint. Text only; no LIGGGHTS
// headers.
//
// A coupled script sets up particles, contacts, walls, gravity, integration and exactly one
// `fix ID group tfdem/coupling`; the coupler advances it, so the script has no `run`. Files it
// `include`s are followed (as LIGGGHTS reads them, relative to the case); `jump` is refused.
// On a restart the coupler runs the script flattened (includes inlined) with its one
// `read_data` or `create_box` replaced by `read_restart <checkpoint>`, the commands that make
// or change particles (create_atoms, set, velocity, displace_atoms, delete_atoms, read_dump)
// dropped, since the restart file holds the particles, and `dump_modify ID append yes` added
// for every dump that writes one file, so a resumed run continues its outputs.
#ifndef TFDEM_DEM_SCRIPT_H
#define TFDEM_DEM_SCRIPT_H

#include <functional>
#include <string>
#include <vector>

namespace tfdem::dem_script {

// One command of a script: the file and line it starts on (1-based), the lines it spans ('&'
// continuations) and its words ('#' comments removed outside quotes; quotes kept).
struct Command {
  std::string file;
  int line = 0;
  int line_count = 1;
  std::vector<std::string> words;

  // "file:line: " for messages
  std::string where() const;
};

std::vector<Command> parse(const std::string &text, const std::string &file = "");

// Reads a script file by the name it is given (relative to the case); throws
// std::runtime_error with the reason when it cannot.
using ReadFile = std::function<std::string(const std::string &path)>;

// A script with every `include` replaced by the commands of the included file, recursively,
// in the order LIGGGHTS runs them; an include named by a variable stays a command, unfollowed
// (its file is known only as LIGGGHTS runs: a pour's templates); `problems` holds what could
// not be followed (an unreadable or cyclic include), each "file:line: message" with the fix.
struct Script {
  std::vector<Command> commands;
  std::vector<std::string> problems;

  // The first command named `name` (e.g. "read_data"), or nullptr.
  const Command *first(const std::string &name) const;
};

Script load(const std::string &file, const ReadFile &read);

// Problems of a script the coupler is to run, each "file:line: message" with the fix: what
// load() could not follow, jump, run/rerun/minimize (the coupler advances the DEM), clear
// (drops TFDEM's fix styles), and not exactly one `fix ... tfdem/coupling`.
std::vector<std::string> coupled_script_problems(const std::string &file, const Script &script);

// The problem of the script's `processors Px Py Pz` command on a run of `ranks` MPI ranks,
// "file:line: message" with the fix, or "" when it can hold: LIGGGHTS splits the particles over
// every rank of the run, so the given counts' product must equal `ranks` (or divide it when an
// axis is '*', which LIGGGHTS then fills). A count given by a variable, or no processors
// command, is left to LIGGGHTS.
std::string processors_problem(const Script &script, int ranks);

// A file the script writes as the DEM runs: fix print and fix ave/* files (opened, and
// truncated unless `append`, when the script runs) and dumps that write one file (opened at
// their first snapshot). `every`: the dump's interval; for fix ave/*, its Nevery, Nrepeat and
// Nfreq.
struct OutputFile {
  enum class Kind { Print, Average, Dump };
  Kind kind = Kind::Print;
  std::string path;
  std::string id;  // fix or dump ID
  long every = 0, repeat = 0, frequency = 0;
  std::string where;  // "file:line: " of its command
};

// The script's output files whose names are literal (no variable, no '*' or '%' pattern:
// those are one file per snapshot or rank, each written whole); `skipped` gets the others'
// "file:line: name" for a warning.
std::vector<OutputFile> output_files(const Script &script, std::vector<std::string> *skipped = nullptr);

// The script flattened and resumed from `restart_file` (see above), one command per line.
// Throws std::invalid_argument naming the file unless it has exactly one read_data or
// create_box.
std::string resumed_script(const std::string &file, const Script &script, const std::string &restart_file);

}  // namespace tfdem::dem_script

#endif
