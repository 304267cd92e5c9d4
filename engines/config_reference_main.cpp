// tfdem-config-reference: the reference of coupling.yaml as Markdown, written from the readers'
// own declarations (tfdem::coupling_reference, every registered engine's keys included), so it
// cannot drift from what the solver accepts. docs/reference.py puts it into the docs site.
#include <cstdio>
#include <iostream>
#include <map>
#include <string>

#include "tfdem/config.h"
#include "tfdem/engine_registry.h"

namespace {

std::string name_of(const std::string &path) {
  const std::size_t dot = path.rfind('.');
  return dot == std::string::npos ? path : path.substr(dot + 1);
}

int depth_of(const std::string &path) {
  int depth = 0;
  for (char c : path) depth += c == '.';
  return depth;
}

// The condition of the key's nearest enclosing section (sections come before their keys)
std::string parent_condition(const std::map<std::string, std::string> &section_conditions, const std::string &path) {
  const std::size_t dot = path.rfind('.');
  if (dot == std::string::npos) return "";
  const auto found = section_conditions.find(path.substr(0, dot));
  return found == section_conditions.end() ? "" : found->second;
}

// The whole file with every key at its default, as a user would write it; a condition is
// shown where it starts, not again on every key inside its section
void print_block(const std::vector<tfdem::KeyRecord> &keys) {
  std::map<std::string, std::string> section_conditions;
  std::cout << "```yaml\n";
  for (const tfdem::KeyRecord &k : keys) {
    const std::string indent(2 * depth_of(k.path), ' ');
    const bool new_condition = !k.condition.empty() && k.condition != parent_condition(section_conditions, k.path);
    const std::string when = new_condition ? "  # only with " + k.condition : "";
    if (k.kind == "a section") {
      section_conditions[k.path] = k.condition;
      std::cout << indent << name_of(k.path) << ":" << when << "\n";
    } else {
      std::cout << indent << name_of(k.path) << ": "
                << (k.fallback == "required" ? "<required>" : k.fallback.empty() ? "<none>" : k.fallback) << when
                << "\n";
    }
  }
  std::cout << "```\n\n";
}

// One key as a LAMMPS-style entry: its heading, what it sets, then its type, unit, default,
// range and condition on one line
void print_key(const tfdem::KeyRecord &k) {
  std::cout << "### `" << k.path << "`\n\n" << k.doc << "\n\n" << "*" << k.kind << "*";
  if (!k.unit.empty()) std::cout << " · unit " << k.unit;
  std::cout << (k.fallback == "required" ? " · required" : " · default " + (k.fallback.empty() ? "none" : k.fallback));
  if (!k.range.empty()) std::cout << (k.range[0] == '[' ? " · range " : " · choices ") << k.range;
  if (!k.condition.empty()) std::cout << " · only with `" << k.condition << "`";
  std::cout << "\n\n";
}

}  // namespace

int main(int argc, char **argv) {
  if (argc > 1) {
    std::fprintf(stderr, "usage: tfdem-config-reference (no arguments): coupling.yaml's reference as Markdown\n");
    return 2;
  }
  const std::vector<tfdem::KeyRecord> keys = tfdem::coupling_reference();
  std::cout << "# coupling.yaml\n\n"
            << "Every case's `coupling.yaml` sets what couples the gas and the particles. This page is written by "
               "`tfdem-config-reference` from the parser's own declarations: every key the solver accepts, its "
               "type, unit, default, range or choices, and what it sets. A key given twice, an unknown key (named "
               "with the nearest valid one) or a value out of range stops the run before it starts, with every "
               "problem of the file listed at once.\n\n"
            << "## The whole file, at its defaults\n\n";
  print_block(keys);
  std::cout << "## The particle engines (`dem.engine`)\n\n";
  for (const std::string &name : tfdem::engine_names())
    std::cout << "- `" << name << "`" << (name == tfdem::default_engine_name() ? " (the default)" : "") << ": "
              << tfdem::find_engine(name)->summary << "\n";
  std::cout << "\n";
  for (const tfdem::KeyRecord &k : keys) {
    if (k.kind == "a section" && depth_of(k.path) == 0)
      std::cout << "## " << k.path << "\n\n" << (k.doc.empty() ? "" : k.doc + "\n\n");
    else if (k.kind != "a section")
      print_key(k);
  }
  return 0;
}
