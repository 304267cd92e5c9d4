#include "tfdem/suggest.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace tfdem {

std::size_t edit_distance(const std::string &a, const std::string &b) {
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  std::iota(previous.begin(), previous.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::string nearest_name(const std::string &given, const std::vector<std::string> &valid) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(given.size() / 2, 1) + 1;
  for (const auto &name : valid) {
    const std::size_t d = edit_distance(given, name);
    if (d < best_distance) {
      best_distance = d;
      best = name;
    }
  }
  return best;
}

std::string did_you_mean(const std::string &given, const std::vector<std::string> &valid) {
  const std::string nearest = nearest_name(given, valid);
  return nearest.empty() ? std::string() : " (did you mean '" + nearest + "'?)";
}

std::size_t index_of_name(const std::string &name, const std::vector<std::string> &names, const std::string &what) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return i;
  throw std::invalid_argument("unknown " + what + " '" + name + "'" + did_you_mean(name, names) +
                              "; valid: " + quoted_list(names));
}

std::string quoted_list(const std::vector<std::string> &names) {
  std::string out;
  for (const auto &name : names) out += (out.empty() ? "'" : ", '") + name + "'";
  return out;
}

}  // namespace tfdem
