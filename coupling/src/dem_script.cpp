#include "tfdem/dem_script.h"

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

}  // namespace

std::vector<Command> parse(const std::string &text) {
  const std::vector<std::string> lines = split_lines(text);
  std::vector<Command> commands;
  for (std::size_t i = 0; i < lines.size();) {
    Command c;
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

std::vector<std::string> coupled_script_problems(const std::string &file, const std::vector<Command> &commands) {
  std::vector<std::string> problems;
  std::vector<int> coupling_fix_lines;
  for (const Command &c : commands) {
    const std::string &name = c.words[0];
    const std::string at = file + ":" + std::to_string(c.line) + ": ";
    if (name == "run" || name == "rerun" || name == "minimize")
      problems.push_back(at + "'" + name + "' in a coupled DEM script: the coupler advances the DEM one coupling " +
                         "interval at a time and its clock would run ahead of the gas; remove the command");
    if (name == "clear")
      problems.push_back(at + "'clear' drops TFDEM's fix styles from LIGGGHTS; remove the command");
    if (is_coupling_fix(c)) coupling_fix_lines.push_back(c.line);
  }
  if (coupling_fix_lines.empty())
    problems.push_back(file + ": no 'fix ID all tfdem/coupling': the coupler cannot apply fluid forces; add one");
  if (coupling_fix_lines.size() > 1) {
    std::string lines;
    for (const int l : coupling_fix_lines) lines += (lines.empty() ? "" : ", ") + std::to_string(l);
    problems.push_back(file + ": " + std::to_string(coupling_fix_lines.size()) +
                       " 'fix ... tfdem/coupling' (lines " + lines +
                       "): each would apply the fluid force again; keep exactly one");
  }
  return problems;
}

std::string resumed_script(const std::string &file, const std::string &text, const std::string &restart_file) {
  std::vector<std::string> lines = split_lines(text);
  std::vector<std::string> appended;
  int read_data = 0;
  const auto replace = [&lines](const Command &c, const std::string &command) {
    lines[c.line - 1] = command;
    for (int k = 1; k < c.line_count; ++k) lines[c.line - 1 + k].clear();
  };
  for (Command c : parse(text)) {
    if (c.words[0] == "read_data") {
      ++read_data;
      replace(c, "read_restart " + restart_file);
    } else if (c.words.size() >= 4 && c.words[0] == "fix" && c.words[3] == "print") {
      for (std::size_t k = 5; k < c.words.size(); ++k)
        if (c.words[k] == "file") c.words[k] = "append";
      replace(c, joined(c.words));
    } else if (c.words[0] == "dump" && c.words.size() >= 2) {
      appended.push_back("dump_modify " + c.words[1] + " append yes");
    }
  }
  if (read_data != 1)
    throw std::invalid_argument(file + ": resuming needs exactly one 'read_data' (the coupler replaces it by " +
                                "'read_restart " + restart_file + "'); the script has " +
                                std::to_string(read_data));
  std::string out;
  for (const std::string &l : lines) out += l + "\n";
  if (!appended.empty()) out += "# added by the coupler on restart: outputs continue\n";
  for (const std::string &l : appended) out += l + "\n";
  return out;
}

}  // namespace tfdem::dem_script
