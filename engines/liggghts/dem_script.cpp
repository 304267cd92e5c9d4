#include "dem_script.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace tfdem::dem_script {
namespace {

std::vector<std::string> split_lines(const std::string &text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The line without a '#' comment (a '#' inside double quotes is text).
std::string without_comment(const std::string &line) {
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '"') quoted = !quoted;
    if (line[i] == '#' && !quoted) return line.substr(0, i);
  }
  return line;
}

// Words separated by blanks; a double-quoted text is one word, quotes kept.
std::vector<std::string> split_words(const std::string &text) {
  std::vector<std::string> words;
  std::string word;
  bool quoted = false;
  for (const char c : text) {
    if (c == '"') quoted = !quoted;
    if (!quoted && (c == ' ' || c == '\t' || c == '\r')) {
      if (!word.empty()) words.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  if (!word.empty()) words.push_back(word);
  return words;
}

bool ends_with_continuation(std::string &line) {
  const std::size_t last = line.find_last_not_of(" \t\r");
  if (last == std::string::npos || line[last] != '&') return false;
  line.erase(last);
  return true;
}

bool is_coupling_fix(const Command &c) {
  return c.words.size() >= 4 && c.words[0] == "fix" && c.words[3] == "tfdem/coupling";
}

std::string joined(const std::vector<std::string> &words) {
  std::string text;
  for (const std::string &w : words) text += (text.empty() ? "" : " ") + w;
  return text;
}

bool uses_variable(const std::string &name) { return name.find('$') != std::string::npos; }

// Appends the commands of `file` (and of what it includes) to `script`; `open` holds the
// files being read, outermost first, to refuse a cycle.
void load_into(Script &script, const std::string &file, const std::string &text, const ReadFile &read,
               std::vector<std::string> &open) {
  open.push_back(file);
  for (Command &c : parse(text, file)) {
    if (c.words[0] != "include") {
      script.commands.push_back(std::move(c));
      continue;
    }
    if (c.words.size() != 2) {
      script.problems.push_back(c.where() + "'include' takes one file name");
      continue;
    }
    const std::string &name = c.words[1];
    if (uses_variable(name)) {
      script.commands.push_back(std::move(c));  // kept, not followed: its file is known only when LIGGGHTS runs
    } else if (std::find(open.begin(), open.end(), name) != open.end()) {
      script.problems.push_back(c.where() + "include '" + name + "' includes itself (through " + joined(open) +
                                "); LIGGGHTS would read it forever: remove the cycle");
    } else {
      try {
        load_into(script, name, read(name), read, open);
      } catch (const std::runtime_error &e) {
        script.problems.push_back(c.where() + "include '" + name + "': " + e.what());
      }
    }
  }
  open.pop_back();
}

// The value after keyword `key` from word `from` on, or "" when absent.
std::string keyword_value(const Command &c, std::size_t from, const std::string &key) {
  for (std::size_t k = from; k + 1 < c.words.size(); ++k)
    if (c.words[k] == key) return c.words[k + 1];
  return "";
}

long whole_number(const Command &c, std::size_t k) {
  if (k >= c.words.size()) return 0;
  try {
    return std::stol(c.words[k]);
  } catch (const std::exception &) {
    return 0;  // a variable: LIGGGHTS checks it
  }
}

}  // namespace

std::string Command::where() const { return (file.empty() ? "" : file + ":") + std::to_string(line) + ": "; }

std::vector<Command> parse(const std::string &text, const std::string &file) {
  const std::vector<std::string> lines = split_lines(text);
  std::vector<Command> commands;
  for (std::size_t i = 0; i < lines.size();) {
    Command c;
    c.file = file;
    c.line = static_cast<int>(i) + 1;
    std::string joined_text;
    bool more = true;
    while (more && i < lines.size()) {
      std::string line = without_comment(lines[i++]);
      more = ends_with_continuation(line);
      joined_text += line + " ";
    }
    c.line_count = static_cast<int>(i) + 1 - c.line;
    c.words = split_words(joined_text);
    if (!c.words.empty()) commands.push_back(c);
  }
  return commands;
}

const Command *Script::first(const std::string &name) const {
  for (const Command &c : commands)
    if (c.words[0] == name) return &c;
  return nullptr;
}

Script load(const std::string &file, const ReadFile &read) {
  Script script;
  std::vector<std::string> open;
  load_into(script, file, read(file), read, open);
  return script;
}

std::vector<std::string> coupled_script_problems(const std::string &file, const Script &script) {
  std::vector<std::string> problems = script.problems;
  std::vector<std::string> coupling_fixes;
  for (const Command &c : script.commands) {
    const std::string &name = c.words[0];
    if (name == "run" || name == "rerun" || name == "minimize")
      problems.push_back(c.where() + "'" + name + "' in a coupled DEM script: the coupler advances the DEM one " +
                         "coupling interval at a time and its clock would run ahead of the gas; remove the command");
    if (name == "clear") problems.push_back(c.where() + "'clear' drops TFDEM's fix styles from LIGGGHTS; remove the command");
    if (name == "jump")
      problems.push_back(c.where() + "'jump' in a coupled DEM script: the coupler cannot check or resume what it " +
                         "jumps to, and a coupled script has no loop to run; use 'include' for another file");
    if (name == "include")  // one named by variables, which load() kept unfollowed
      problems.push_back(c.where() + "include '" + c.words[1] + "': the coupler checks and resumes what a script " +
                         "includes, and cannot know a name made of variables; write the file name itself");
    if (is_coupling_fix(c)) coupling_fixes.push_back(c.where().substr(0, c.where().size() - 2));
  }
  if (coupling_fixes.empty())
    problems.push_back(file + ": no 'fix ID all tfdem/coupling' (in it or in what it includes): the coupler cannot " +
                       "apply fluid forces; add one");
  if (coupling_fixes.size() > 1) {
    std::string at;
    for (const std::string &w : coupling_fixes) at += (at.empty() ? "" : ", ") + w;
    problems.push_back(file + ": " + std::to_string(coupling_fixes.size()) + " 'fix ... tfdem/coupling' (" + at +
                       "): each would apply the fluid force again; keep exactly one");
  }
  return problems;
}

namespace {
std::string rank_count(long n) { return std::to_string(n) + (n == 1 ? " rank" : " ranks"); }
}  // namespace

std::string processors_problem(const Script &script, int ranks) {
  const Command *c = script.first("processors");
  if (!c || c->words.size() < 4) return "";
  long given = 1;
  int free_axes = 0;
  std::string grid;
  for (int axis = 1; axis <= 3; ++axis) {
    const std::string &w = c->words[axis];
    grid += (axis > 1 ? " " : "") + w;
    if (w == "*") {
      ++free_axes;
      continue;
    }
    if (w.empty() || w.find_first_not_of("0123456789") != std::string::npos) return "";  // a variable: LIGGGHTS'
    given *= std::stol(w);
  }
  const std::string run = " on a run of " + rank_count(ranks);
  const std::string why = ": LIGGGHTS splits the particles over every rank of the run. Fix: ";
  if (free_axes == 0 && given != ranks)
    return c->where() + "processors " + grid + " asks for " + rank_count(given) + " of the DEM" + run + why +
           "'processors * 1 1' (the box's x extent split over all ranks) or mpirun -np " + std::to_string(given);
  if (free_axes > 0 && (given == 0 || ranks % given != 0))
    return c->where() + "processors " + grid + " fixes " + rank_count(given) + " of the DEM on its given axes" +
           run + ", which " + std::to_string(given) + " does not divide" + why + "a '*' on every axis the rank count " +
           "should fill, or a rank count that is a multiple of " + std::to_string(given);
  return "";
}

std::vector<OutputFile> output_files(const Script &script, std::vector<std::string> *skipped) {
  std::vector<OutputFile> files;
  const auto add = [&](OutputFile f, const Command &c) {
    if (f.path.empty()) return;
    if (uses_variable(f.path) || f.path.find_first_of("*%") != std::string::npos) {
      if (skipped) skipped->push_back(c.where() + f.path);
      return;
    }
    f.where = c.where();
    files.push_back(f);
  };
  for (const Command &c : script.commands) {
    const std::vector<std::string> &w = c.words;
    OutputFile f;
    if (w[0] == "fix" && w.size() >= 4) {
      f.id = w[1];
      if (w[3] == "print") {
        f.kind = OutputFile::Kind::Print;
        f.every = whole_number(c, 4);
        f.path = keyword_value(c, 5, "file");
        if (f.path.empty()) f.path = keyword_value(c, 5, "append");
        add(f, c);
      } else if (w[3].compare(0, 4, "ave/") == 0) {
        f.kind = OutputFile::Kind::Average;
        f.every = whole_number(c, 4);
        f.repeat = whole_number(c, 5);
        f.frequency = whole_number(c, 6);
        f.path = keyword_value(c, 4, "file");
        add(f, c);
      }
    } else if (w[0] == "dump" && w.size() >= 6) {
      f.kind = OutputFile::Kind::Dump;
      f.id = w[1];
      f.every = whole_number(c, 4);
      f.path = w[5];
      add(f, c);
    }
  }
  return files;
}

std::string resumed_script(const std::string &file, const Script &script, const std::string &restart_file) {
  // Commands that make the box, and those that make or change particles: the restart file
  // holds both
  const std::vector<std::string> box = {"read_data", "create_box"};
  const std::vector<std::string> particles = {"create_atoms", "set", "velocity", "displace_atoms", "delete_atoms",
                                              "read_dump"};
  const auto is = [](const std::vector<std::string> &names, const std::string &name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  std::string out = "# " + file + " flattened and resumed from " + restart_file + " by the coupler\n";
  std::vector<std::string> appended;
  int boxes = 0;
  for (const Command &c : script.commands) {
    out += "# " + c.where().substr(0, c.where().size() - 1) + "\n";
    if (is(box, c.words[0])) {
      ++boxes;
      out += "read_restart " + restart_file + "\n";
    } else if (is(particles, c.words[0])) {
      out += "# dropped: the particles come from the restart file: " + joined(c.words) + "\n";
    } else {
      out += joined(c.words) + "\n";
    }
  }
  for (const OutputFile &f : output_files(script))
    if (f.kind == OutputFile::Kind::Dump) appended.push_back("dump_modify " + f.id + " append yes");
  if (boxes != 1)
    throw std::invalid_argument(file + ": resuming needs exactly one 'read_data' or 'create_box' (the coupler " +
                                "replaces it by 'read_restart " + restart_file + "'); the script has " +
                                std::to_string(boxes));
  if (!appended.empty()) out += "# added by the coupler on restart: dumps continue their files\n";
  for (const std::string &l : appended) out += l + "\n";
  return out;
}

}  // namespace tfdem::dem_script
