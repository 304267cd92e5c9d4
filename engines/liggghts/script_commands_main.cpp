// tfdem-liggghts-script SCRIPT: a LIGGGHTS input script's commands as the engine reads them
// (dem_script::load: comments dropped, '&' continuations joined, includes followed relative to
// the script's folder), one JSON object per line: {"file": ..., "line": N, "words": [...]}.
// Python's tfdem.liggghts reads scripts through it, so one reader knows the script syntax.
// Exit 2 with each problem ("file:line: message") on stderr when the script cannot be read.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "dem_script.h"

namespace {

std::string read_text(const std::string &path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string json_string(const std::string &text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

int main(int argc, char **argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: tfdem-liggghts-script SCRIPT: the script's commands as JSON lines\n");
    return 2;
  }
  const std::string path = argv[1];
  const std::size_t slash = path.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  if (chdir(folder.c_str()) != 0) {
    std::fprintf(stderr, "%s: cannot enter its folder\n", path.c_str());
    return 2;
  }
  tfdem::dem_script::Script script;
  try {
    script = tfdem::dem_script::load(name, read_text);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
    return 2;
  }
  if (!script.problems.empty()) {
    for (const std::string &p : script.problems) std::fprintf(stderr, "%s\n", p.c_str());
    return 2;
  }
  for (const tfdem::dem_script::Command &c : script.commands) {
    std::cout << "{\"file\": " << json_string(c.file) << ", \"line\": " << c.line << ", \"words\": [";
    for (std::size_t i = 0; i < c.words.size(); ++i) std::cout << (i ? ", " : "") << json_string(c.words[i]);
    std::cout << "]}\n";
  }
  return 0;
}
