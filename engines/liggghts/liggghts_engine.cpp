#include "liggghts_engine.h"

#include <mpi.h>

#include <cmath>
#include <memory>

#include "dem_instance.h"
#include "tfdem/engine_registry.h"

namespace tfdem {
namespace {

std::shared_ptr<const EngineSettings> read_settings(ConfigSection &dem) {
  auto s = std::make_shared<LiggghtsSettings>();
  s->script = dem.text({"script", "", "the LIGGGHTS input script (contacts, walls, integration), relative to the case"},
                       "", true);
  s->coupling_interval = dem.integer(
      {"coupling_interval", "", "DEM steps per gas step; left out, the solver takes deltaT / the DEM step (which "
                                "must be whole)"},
      0, 1, 1000000);
  return s;
}

std::unique_ptr<ParticleEngine> start(const EngineStart &start) {
  const auto &settings = static_cast<const LiggghtsSettings &>(*start.config->engine_settings);
  try {
    return std::make_unique<DemInstance>(MPI_Comm_f2c(start.communicator), settings.script, start.log_file,
                                         start.resume);
  } catch (const std::runtime_error &e) {
    throw std::runtime_error("dem.script: " + std::string(e.what()));
  }
}

}  // namespace

long coupling_interval(const LiggghtsSettings &settings, double gas_step, double dem_step) {
  return settings.coupling_interval > 0 ? settings.coupling_interval : std::llround(gas_step / dem_step);
}

TFDEM_DEFAULT_ENGINE(liggghts, "LIGGGHTS' soft spheres: contacts, walls and integration from a DEM script",
                     read_settings, start);

}  // namespace tfdem
