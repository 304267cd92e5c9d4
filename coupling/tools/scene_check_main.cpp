// tfdem-scene-check: the scene check of a case as a command.
//   tfdem-scene-check <coupling.yaml> --gas-velocity U --cell-size DX --kn K --damping ETA --dt DT
// Gas, particles, drag law and coupling interval come from coupling.yaml; the rest from the
// options (SI units). Exit code 1 when the scene has errors, 2 on bad input.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "tfdem/config.h"
#include "tfdem/scene_check.h"
#include "tfdem/suggest.h"

namespace {

const std::vector<std::string> kOptions = {"--gas-velocity", "--cell-size", "--kn", "--damping", "--dt"};

const char *kUsage =
    "usage: tfdem-scene-check <coupling.yaml> --gas-velocity U --cell-size DX --kn K --damping ETA --dt DT\n"
    "The dimensionless numbers of a gas-particle scene (St, Re_p, Ar, U_mf, terminal velocity,\n"
    "contact time, drag response time, cell/particle ratio) and what it needs: DEM step,\n"
    "coupling interval, void-fraction method. Gas, particles, drag law and coupling interval\n"
    "come from coupling.yaml; the rest from the options, SI units:\n"
    "  --gas-velocity U   characteristic (superficial inflow) gas velocity, m/s\n"
    "  --cell-size DX     smallest in-plane gas cell size, m\n"
    "  --kn K             particle-particle normal stiffness k_n, N/m\n"
    "  --damping ETA      particle-particle normal damping eta_n (absolute), N s/m\n"
    "  --dt DT            DEM time step, s\n"
    "Exit code: 0 fine, 1 the scene has errors, 2 bad input.\n";

int usage_error(const std::string &message) {
  std::fprintf(stderr, "tfdem-scene-check: %s\n%s", message.c_str(), kUsage);
  return 2;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::printf("%s", kUsage);
    return 0;
  }
  if (argc < 2) return usage_error("missing coupling.yaml");
  std::map<std::string, double> values;
  for (int i = 2; i < argc; i += 2) {
    const std::string option = argv[i];
    if (std::find(kOptions.begin(), kOptions.end(), option) == kOptions.end())
      return usage_error("unknown option '" + option + "'" + tfdem::did_you_mean(option, kOptions));
    if (i + 1 >= argc) return usage_error("option '" + option + "' needs a value");
    char *end = nullptr;
    const double v = std::strtod(argv[i + 1], &end);
    if (end == argv[i + 1] || *end != '\0')
      return usage_error("option '" + option + "' needs a number, got '" + argv[i + 1] + "'");
    values[option] = v;
  }
  for (const auto &option : kOptions)
    if (!values.count(option)) return usage_error("missing option " + option);
  try {
    const tfdem::CouplingConfig config = tfdem::load_coupling_config(argv[1]);
    tfdem::Scene scene;
    scene.particle_diameter = config.particle_diameters.front();  // smallest: shortest contact
    scene.particle_density = config.particle_density;
    scene.gas = config.gas;
    scene.drag_law = config.transfer.law;
    scene.coupling_interval = config.coupling_interval;
    scene.gas_velocity = values["--gas-velocity"];
    scene.cell_size = values["--cell-size"];
    scene.normal_stiffness = values["--kn"];
    scene.normal_damping = values["--damping"];
    scene.dem_time_step = values["--dt"];
    const tfdem::SceneReport report = tfdem::check_scene(scene);
    std::printf("%s", tfdem::format_report(report).c_str());
    return report.has_errors() ? 1 : 0;
  } catch (const tfdem::ConfigError &e) {
    std::fprintf(stderr, "tfdem-scene-check: %s\n", e.what());
  } catch (const std::exception &e) {
    std::fprintf(stderr, "tfdem-scene-check: %s\n", e.what());
  }
  return 2;
}
