// LIGGGHTS as a registered particle engine (dem.engine: liggghts, the default): its keys of
// coupling.yaml's dem section and the DemInstance a run starts.
#ifndef TFDEM_LIGGGHTS_ENGINE_H
#define TFDEM_LIGGGHTS_ENGINE_H

#include <string>

#include "tfdem/config.h"

namespace tfdem {

struct LiggghtsSettings : EngineSettings {
  std::string script;         // the LIGGGHTS input, relative to the case directory
  long coupling_interval = 0;  // DEM steps per gas step; 0 (left out): deltaT / the DEM step
};

// The DEM steps per gas step: the settings' coupling_interval, or (left out) gas_step /
// dem_step, which the start checks require to be whole
long coupling_interval(const LiggghtsSettings &settings, double gas_step, double dem_step);

}  // namespace tfdem

#endif
