#include "tfdem/data_file.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace tfdem::data_file {
namespace {

// The line without its '#' comment, trimmed
std::string content(const std::string &line) {
  std::string text = line.substr(0, line.find('#'));
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

bool starts_section(const std::string &text) {
  return !text.empty() && (std::isalpha(static_cast<unsigned char>(text[0])) != 0);
}

}  // namespace

Boundary boundary_from_words(const std::vector<std::string> &words) {
  Boundary b;
  if (words.size() != 3) throw std::invalid_argument("'boundary' takes three styles (one per axis)");
  for (int a = 0; a < 3; ++a) {
    const std::string &w = words[a];
    if (w.empty() || w.size() > 2 || w.find_first_not_of("pfsm") != std::string::npos)
      throw std::invalid_argument("boundary style '" + w + "' is not p, f, s or m");
    b.drops[a][0] = w.front() == 'f';
    b.drops[a][1] = w.back() == 'f';
  }
  return b;
}

std::vector<std::string> atoms_outside_box(const std::string &text, const std::string &file, const Boundary &boundary,
                                           std::size_t limit, std::size_t &count) {
  static const char *kAxis = "xyz";
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  bool box[3] = {false, false, false};
  std::vector<std::string> outside;
  count = 0;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // the title
  int number = 1;
  bool atoms = false;
  while (std::getline(in, line)) {
    ++number;
    const std::string c = content(line);
    if (c.empty()) continue;
    const std::string where = file + ":" + std::to_string(number) + ": ";
    if (starts_section(c)) {
      atoms = c.compare(0, 5, "Atoms") == 0;
      continue;
    }
    std::istringstream words(c);
    if (!atoms) {
      for (int a = 0; a < 3; ++a) {
        const std::string key = std::string(1, kAxis[a]) + "lo " + kAxis[a] + "hi";
        if (c.size() > key.size() && c.compare(c.size() - key.size(), key.size(), key) == 0) {
          if (!(words >> lo[a] >> hi[a])) throw std::invalid_argument(where + "cannot read the box bounds '" + c + "'");
          box[a] = true;
        }
      }
      continue;
    }
    // id type diameter density x y z, read as LIGGGHTS does (strtod: nan and inf too)
    double v[7];
    int read = 0;
    for (std::string word; read < 7 && words >> word; ++read) {
      char *end = nullptr;
      v[read] = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0') break;
    }
    if (read < 7)
      throw std::invalid_argument(where + "cannot read an atom (id type diameter density x y z) from '" + c + "'");
    const long id = std::lround(v[0]);
    const double *x = v + 4;
    if (!std::isfinite(v[2]) || !std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) {
      if (++count <= limit)
        outside.push_back("id " + std::to_string(id) + " (line " + std::to_string(number) +
                          "): its diameter or position is not a finite number ('" + c + "')");
      continue;
    }
    for (int a = 0; a < 3; ++a) {
      if (!box[a]) continue;
      const bool below = boundary.drops[a][0] && x[a] < lo[a];
      const bool above = boundary.drops[a][1] && x[a] > hi[a];
      if (!below && !above) continue;
      if (++count <= limit) {
        std::ostringstream text_of;
        text_of.precision(10);
        text_of << "id " << id << " at (" << x[0] << ", " << x[1] << ", " << x[2] << ") m (line " << number
                << "): " << kAxis[a] << " is " << (below ? "below " : "above ") << kAxis[a] << (below ? "lo = " : "hi = ")
                << (below ? lo[a] : hi[a]) << " m";
        outside.push_back(text_of.str());
      }
      break;
    }
  }
  return outside;
}

}  // namespace tfdem::data_file
