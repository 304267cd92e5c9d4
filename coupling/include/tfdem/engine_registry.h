// The particle engines, each registered by name in one line of its own folder:
//
//     TFDEM_ENGINE(hard_sphere, "event-driven hard spheres (seed 001 sec. 3.3)", read_settings, start);
//
// The name is coupling.yaml's dem.engine; `read_settings` reads the engine's own keys of the
// dem section (each declared for the reference) and returns its EngineSettings; `start` makes
// the engine for a run. The solver and the configuration know the engines only from here, so
// a new engine is a folder of its own and that one line (linked whole into the programs that
// run it: tfdem_link_engines in CMake).
#ifndef TFDEM_ENGINE_REGISTRY_H
#define TFDEM_ENGINE_REGISTRY_H

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tfdem/config.h"
#include "tfdem/particle_engine.h"

namespace tfdem {

// What an engine starts from: the case's settings, the checkpoint it resumes from, gravity
// and the gas step it advances by.
struct EngineStart {
  int communicator = 0;                // the DEM's ranks, as MPI_Comm_c2f gives them (the core needs no MPI)
  const CouplingConfig *config = nullptr;
  const DemResume *resume = nullptr;   // null on a fresh start
  double gravity[3] = {0, 0, 0};       // m/s^2 (constant/g)
  double gas_step = 0;                 // s: one coupling interval
  std::string log_file;                // where an engine with a log of its own writes it
};

struct EngineType {
  std::string name;     // coupling.yaml's dem.engine
  std::string summary;  // what it is, one line (the reference, messages)
  std::function<std::shared_ptr<const EngineSettings>(ConfigSection &dem)> read;
  std::function<std::unique_ptr<ParticleEngine>(const EngineStart &)> start;
  bool is_default = false;  // the engine when coupling.yaml names none
};

// Add an engine; true (for a static registration's initializer). A name given twice throws.
bool register_engine(EngineType type);
// The engine of that name, or null
const EngineType *find_engine(const std::string &name);
// The registered engines' names, in the order they registered
std::vector<std::string> engine_names();
// The engine registered as the default ("" when none is)
std::string default_engine_name();

}  // namespace tfdem

#define TFDEM_ENGINE(name, summary, read, start) \
  static const bool tfdem_engine_registered_##name = ::tfdem::register_engine({#name, summary, read, start, false})
// The same, and the engine coupling.yaml gets when it names none
#define TFDEM_DEFAULT_ENGINE(name, summary, read, start) \
  static const bool tfdem_engine_registered_##name = ::tfdem::register_engine({#name, summary, read, start, true})

#endif
