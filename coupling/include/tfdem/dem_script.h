// LIGGGHTS input scripts as the coupler runs them: the checks a coupled script must pass and
// the rewrite that resumes it from a checkpoint. Text only; no LIGGGHTS headers.
//
// A coupled script sets up particles, contacts, walls, gravity, integration and exactly one
// `fix ID group tfdem/coupling`; the coupler advances it, so the script has no `run`. On a
// restart the coupler runs the same script with its one `read_data` replaced by
// `read_restart <checkpoint>`, `fix ... print ... file F` turned into `append F`, and
// `dump_modify ID append yes` added for every dump, so a resumed run continues its outputs.
#ifndef TFDEM_DEM_SCRIPT_H
#define TFDEM_DEM_SCRIPT_H

#include <string>
#include <vector>

namespace tfdem::dem_script {

// One command of a script: the line it starts on (1-based), the lines it spans ('&'
// continuations) and its words ('#' comments removed outside quotes; quotes kept).
struct Command {
  int line = 0;
  int line_count = 1;
  std::vector<std::string> words;
};

std::vector<Command> parse(const std::string &text);

// Problems of a script the coupler is to run, each "file:line: message" with the fix:
// run/rerun/minimize (the coupler advances the DEM), clear (drops TFDEM's fix styles), and
// not exactly one `fix ... tfdem/coupling`. `include` and `jump` are not followed.
std::vector<std::string> coupled_script_problems(const std::string &file, const std::vector<Command> &commands);

// The script resumed from `restart_file` (see above), with the original line numbers kept
// (added commands go at the end). Throws std::invalid_argument naming the file unless the
// script has exactly one read_data.
std::string resumed_script(const std::string &file, const std::string &text, const std::string &restart_file);

}  // namespace tfdem::dem_script

#endif
