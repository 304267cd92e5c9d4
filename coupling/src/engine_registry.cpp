#include "tfdem/engine_registry.h"

#include <stdexcept>

namespace tfdem {
namespace {

// Function-local: the engines register from their own static initializers, in any order
std::vector<EngineType> &registry() {
  static std::vector<EngineType> engines;
  return engines;
}

}  // namespace

bool register_engine(EngineType type) {
  if (find_engine(type.name)) throw std::logic_error("two particle engines named '" + type.name + "'");
  registry().push_back(std::move(type));
  return true;
}

const EngineType *find_engine(const std::string &name) {
  for (const EngineType &e : registry())
    if (e.name == name) return &e;
  return nullptr;
}

std::vector<std::string> engine_names() {
  std::vector<std::string> names;
  for (const EngineType &e : registry()) names.push_back(e.name);
  return names;
}

std::string default_engine_name() {
  for (const EngineType &e : registry())
    if (e.is_default) return e.name;
  return "";
}

}  // namespace tfdem
