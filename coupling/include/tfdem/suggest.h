// Suggestions for misspelt names in error messages ("did you mean ...?").
#ifndef TFDEM_SUGGEST_H
#define TFDEM_SUGGEST_H

#include <string>
#include <vector>

namespace tfdem {

// Levenshtein edit distance between a and b (insertions, deletions, substitutions).
std::size_t edit_distance(const std::string &a, const std::string &b);

// The valid name nearest to `given`, or "" when none is within half its length in edits.
std::string nearest_name(const std::string &given, const std::vector<std::string> &valid);

// " (did you mean 'x'?)" for the nearest valid name, or "" when there is none.
std::string did_you_mean(const std::string &given, const std::vector<std::string> &valid);

// Position of `name` in `names`; throws std::invalid_argument "unknown <what> 'name' (did you
// mean ...?); valid: ..." when it is not there.
std::size_t index_of_name(const std::string &name, const std::vector<std::string> &names, const std::string &what);

// The valid names as "'a', 'b', 'c'".
std::string quoted_list(const std::vector<std::string> &names);

}  // namespace tfdem

#endif
