#include "tfdem/data_file.h"

#include <cmath>
#include <cstdlib>
#include <unordered_map>
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
  std::istringstream in(text);
  return atoms_outside_box(in, file, boundary, limit, count);
}

std::vector<std::string> atoms_outside_box(std::istream &in, const std::string &file, const Boundary &boundary,
                                           std::size_t limit, std::size_t &count) {
  static const char *kAxis = "xyz";
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  bool box[3] = {false, false, false};
  std::vector<std::string> outside;
  count = 0;
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

Atoms read_atoms(const std::string &text, const std::string &file) {
  static const char *kAxis = "xyz";
  Atoms atoms;
  long declared = -1;
  std::istringstream in(text);
  std::string line, section;
  std::getline(in, line);  // the title
  int number = 1;
  std::unordered_map<long, std::size_t> index;  // id -> atom, for the Velocities section
  const auto numbers = [](const std::string &c, std::vector<double> &out) {
    out.clear();
    std::istringstream words(c);
    for (std::string word; words >> word;) {
      char *end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0') return false;
      out.push_back(v);
    }
    return true;
  };
  std::vector<double> v;
  while (std::getline(in, line)) {
    ++number;
    const std::string c = content(line);
    if (c.empty()) continue;
    const std::string where = file + ":" + std::to_string(number) + ": ";
    if (starts_section(c)) {
      section = c.substr(0, c.find_first_of(" \t"));
      continue;
    }
    if (section.empty()) {
      std::istringstream words(c);
      double a = 0, b = 0;
      std::string w1, w2;
      if (!(words >> a)) throw std::invalid_argument(where + "cannot read the header line '" + c + "'");
      if (c.find("atom types") != std::string::npos) {
        atoms.type_count = static_cast<int>(a);
      } else if (c.find("atoms") != std::string::npos) {
        declared = static_cast<long>(a);
      } else {
        for (int k = 0; k < 3; ++k)
          if (c.find(std::string(1, kAxis[k]) + "lo " + kAxis[k] + "hi") != std::string::npos) {
            if (!(words >> b)) throw std::invalid_argument(where + "cannot read the box bounds '" + c + "'");
            atoms.lower[k] = a;
            atoms.upper[k] = b;
          }
      }
      continue;
    }
    if (section == "Atoms") {
      if (!numbers(c, v) || v.size() < 7)
        throw std::invalid_argument(where + "cannot read an atom (id type diameter density x y z) from '" + c + "'");
      const int type = static_cast<int>(v[1]);
      if (type < 1 || type > atoms.type_count)
        throw std::invalid_argument(where + "atom type " + std::to_string(type) + " is not among the header's " +
                                    std::to_string(atoms.type_count) + " atom types");
      index.emplace(std::lround(v[0]), atoms.id.size());
      atoms.id.push_back(static_cast<int>(std::lround(v[0])));
      atoms.type.push_back(type);
      atoms.diameter.push_back(v[2]);
      atoms.density.push_back(v[3]);
      atoms.position.insert(atoms.position.end(), {v[4], v[5], v[6]});
      atoms.velocity.insert(atoms.velocity.end(), {0.0, 0.0, 0.0});
      atoms.spin.insert(atoms.spin.end(), {0.0, 0.0, 0.0});
    } else if (section == "Velocities") {
      if (!numbers(c, v) || v.size() < 4)
        throw std::invalid_argument(where + "cannot read a velocity (id vx vy vz [wx wy wz]) from '" + c + "'");
      const long id = std::lround(v[0]);
      const auto found = index.find(id);
      if (found == index.end()) throw std::invalid_argument(where + "a velocity for atom " + std::to_string(id) +
                                                            ", which the Atoms section does not have");
      for (int k = 0; k < 3; ++k) {
        atoms.velocity[3 * found->second + k] = v[1 + k];
        if (v.size() >= 7) atoms.spin[3 * found->second + k] = v[4 + k];
      }
    }
  }
  if (declared < 0 || static_cast<long>(atoms.id.size()) != declared)
    throw std::invalid_argument(file + ": the header declares " + std::to_string(declared) + " atoms, the Atoms " +
                                "section holds " + std::to_string(atoms.id.size()) + " (cut short?)");
  return atoms;
}

}  // namespace tfdem::data_file
