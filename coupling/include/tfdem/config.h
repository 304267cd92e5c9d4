// YAML configuration: a checked reader every module uses for its own keys, and the
// case-level coupling.yaml that gathers them.
//
// Every problem in a file is collected (not just the first) and reported at once as
// "file:line:column: path.to.key: message"; unknown keys name the nearest valid key.
#ifndef TFDEM_CONFIG_H
#define TFDEM_CONFIG_H

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tfdem/drag.h"
#include "tfdem/transfer.h"
#include "tfdem/void_fraction.h"

namespace YAML {
class Node;
}

namespace tfdem {

// All problems found in one configuration file.
class ConfigError : public std::runtime_error {
 public:
  explicit ConfigError(const std::vector<std::string> &problems);
  const std::vector<std::string> &problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

// A mapping in a YAML file with its dotted path; records problems instead of throwing.
class ConfigSection {
 public:
  // The whole document of `file` (its text in `text`); problems go to `problems`.
  ConfigSection(const std::string &file, const std::string &text, std::vector<std::string> &problems);
  ~ConfigSection();
  ConfigSection(ConfigSection &&) noexcept;

  // Sub-mapping `key`; an empty section (all reads give defaults) when absent and optional.
  ConfigSection section(const std::string &key, bool required = false);
  // Number in [min, max]; `fallback` when absent and not required.
  double number(const std::string &key, double fallback, double min, double max, bool required = false);
  // Whole number in [min, max].
  long integer(const std::string &key, long fallback, long min, long max, bool required = false);
  bool boolean(const std::string &key, bool fallback);
  std::string text(const std::string &key, const std::string &fallback, bool required = false);
  // A list of numbers in [min, max] (a YAML sequence, or one number); empty when absent.
  std::vector<double> number_list(const std::string &key, double min, double max, bool required = false);
  // A table of numbers in [min, max] row by row: one number, a list, or a list of lists (a
  // matrix, flattened); `fallback` when absent and not required.
  std::vector<double> number_table(const std::string &key, std::vector<double> fallback, double min, double max,
                                   bool required = false);
  // A list of texts (a YAML sequence, or one text); empty when absent.
  std::vector<std::string> text_list(const std::string &key);
  // Text that must be one of `choices`.
  std::string choice(const std::string &key, const std::string &fallback, const std::vector<std::string> &choices);
  // Report keys present but never read, with the nearest read key. Call after all reads.
  void reject_unknown_keys();
  bool has(const std::string &key) const;
  // Whether an optional key is given, the key known to this section either way (a misspelt
  // one is answered with its name)
  bool given(const std::string &key) {
    known_keys_.push_back(key);
    return has(key);
  }
  // Record a problem with `key` found by the caller's own check.
  void report(const std::string &key, const std::string &message) { problem(key, message); }
  // A key that does not belong here, whatever its value: reported with `message`, not again as
  // unknown.
  void refuse(const std::string &key, const std::string &message) {
    known_keys_.push_back(key);
    problem(key, message);
  }
  const std::string &path() const { return path_; }

 private:
  ConfigSection(const std::string &file, std::unique_ptr<YAML::Node> node, std::string path,
                std::vector<std::string> &problems);
  void problem(const std::string &key, const std::string &message);
  std::string where(const std::string &key) const;
  std::string key_path(const std::string &key) const;
  std::optional<YAML::Node> child(const std::string &key, bool required);
  template <typename T>
  T scalar(const std::string &key, T fallback, T min, T max, bool required, const char *kind);

  std::string file_;
  std::unique_ptr<YAML::Node> node_;
  std::string path_;
  std::vector<std::string> *problems_;
  std::vector<std::string> known_keys_;
};

// What the coupler writes besides the gas fields (coupling.yaml `output:`).
struct OutputOptions {
  // Seconds between samples of the particle statistics (postProcessing/tfdemParticles: count,
  // mass, mean height, bulk coordination number, multicontact ratio) and of the per-cell
  // contact and drag force fields (seed 000 Fig. 5, 7, 9, 11, 12); 0 = none. A whole number
  // of gas steps.
  double statistics_interval = 0.0;
  // Particles (position, velocity, diameter, N_c, contact, drag and fluid forces) as legacy
  // VTK at every gas write time, VTK/particles_<time>.vtk.
  bool particles_vtk = true;
};

// The hard-sphere engine's collision model (coupling.yaml dem.hard_sphere; seed 001 eqs. 17-21):
// normal restitution e_n, tangential restitution beta_0 and friction mu, between particle
// types (one value for every pair, or an n x n matrix row by row) and against the walls (one
// value, or one per type; the particles' own when the scalar is given and dem.hard_sphere.wall
// is absent).
struct HardSphereOptions {
  std::vector<double> restitution, tangential_restitution, friction;
  std::vector<double> wall_restitution, wall_tangential_restitution, wall_friction;
  // TC model (Luding & McNamara 1998): a collision within this many seconds of either
  // particle's previous one is elastic and smooth (0: off)
  double elastic_within = 1e-5;
  // Collisions per particle in one flow step above which the run stops (inelastic collapse)
  long max_collisions_per_particle = 10000;
  // N_c counts the pairs closer than this fraction of their mean diameter (hard spheres
  // touch only at the instant they collide)
  double contact_gap = 0.01;
  // false: the particles stay where they are (a fixed bed, as a LIGGGHTS script without
  // time integration)
  bool move = true;
};

// The particle engine (coupling.yaml dem.engine).
enum class Engine { Liggghts, HardSphere };
const std::vector<std::string> &engine_names();

// Module readers: each module owns its keys.
drag::Gas read_gas(ConfigSection &section);
HardSphereOptions read_hard_sphere(ConfigSection &section);
VoidFractionOptions read_void_fraction(ConfigSection &section);
OutputOptions read_output(ConfigSection &section);

// coupling.yaml of a case.
struct CouplingConfig {
  std::string file;
  drag::Gas gas{1.2, 1.8e-5};
  // d_p (m) of each particle size in the bed, ascending (one for a monodisperse bed): every DEM
  // particle must have one of them; the 2-D rule's cell depth; the scene check uses the smallest.
  std::vector<double> particle_diameters;
  double particle_density = 0.0;   // rho_p (kg/m^3)
  Engine engine = Engine::Liggghts;
  std::string dem_script;         // liggghts: the LIGGGHTS input, relative to the case directory
  long coupling_interval = 0;     // liggghts: DEM steps per gas step; 0 (left out): deltaT / the DEM step
  std::string dem_particles;      // hard_sphere: the particles' LIGGGHTS data file
  HardSphereOptions hard_sphere;  // hard_sphere: the collision model
  std::vector<std::string> outlets;  // gas patches through which particles leave the DEM
  TransferOptions transfer;       // method, drag law, gas
  VoidFractionOptions void_fraction;
  bool pressure_gradient_force = true;  // -V_p grad p of eq. 28
  bool void_fraction_time_derivative = true;  // d(eps)/dt in gas continuity
  OutputOptions output;
};

// Parse coupling.yaml from text; throws ConfigError listing every problem.
CouplingConfig parse_coupling_config(const std::string &file, const std::string &text);
// Read and parse a file; a missing or unreadable file is a ConfigError naming it.
CouplingConfig load_coupling_config(const std::string &file);
// The effective configuration, every value including defaults, as YAML.
std::string describe(const CouplingConfig &config);

}  // namespace tfdem

#endif
