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

// A key as its reader declares it: its name, its unit ("" for none) and what it sets, one line.
// The configuration reference is written from these declarations (tfdem-config-reference).
struct Key {
  std::string name, unit, doc;
};

// What one read declared and found: for the reference (a schema walk, no document) and for the
// effective configuration the solver prints (the values read, defaults included).
struct KeyRecord {
  std::string path;         // dotted, e.g. coupling.void_fraction.method
  std::string kind;         // a number, a whole number, true or false, ..., a section
  std::string unit, doc;
  std::string fallback;     // the default as text; "required" when there is none
  std::string range;        // [min, max], or the choices
  std::string condition;    // when the key applies, e.g. "dem.engine: liggghts"; "" always
  std::string value;        // the value read, as YAML text (the default when absent)
  bool given = false;       // the document gives it
};

// A mapping in a YAML file with its dotted path; records problems instead of throwing, and
// every read as a KeyRecord.
class ConfigSection {
 public:
  // The whole document of `file` (its text in `text`); problems go to `problems`.
  ConfigSection(const std::string &file, const std::string &text, std::vector<std::string> &problems);
  // An empty document read to list the keys (the reference): nothing is missing, every section
  // is walked, and the records are the declarations.
  static ConfigSection schema(std::vector<std::string> &problems);
  ~ConfigSection();
  ConfigSection(ConfigSection &&) noexcept;

  // Sub-mapping `key`; an empty section (all reads give defaults) when absent and optional.
  ConfigSection section(const Key &key, bool required = false);
  // Number in [min, max]; `fallback` when absent and not required.
  double number(const Key &key, double fallback, double min, double max, bool required = false);
  // Whole number in [min, max].
  long integer(const Key &key, long fallback, long min, long max, bool required = false);
  bool boolean(const Key &key, bool fallback);
  std::string text(const Key &key, const std::string &fallback, bool required = false);
  // A list of numbers in [min, max] (a YAML sequence, or one number); empty when absent.
  std::vector<double> number_list(const Key &key, double min, double max, bool required = false);
  // A table of numbers in [min, max] row by row: one number, a list, or a list of lists (a
  // matrix, flattened); `fallback` when absent and not required.
  std::vector<double> number_table(const Key &key, std::vector<double> fallback, double min, double max,
                                   bool required = false);
  // A list of texts (a YAML sequence, or one text); empty when absent.
  std::vector<std::string> text_list(const Key &key);
  // Text that must be one of `choices`.
  std::string choice(const Key &key, const std::string &fallback, const std::vector<std::string> &choices);
  // Reads that apply only under `condition` (e.g. "dem.engine: liggghts"), for the reference
  void set_condition(const std::string &condition) { condition_ = condition; }
  bool is_schema() const { return schema_; }
  // Every read so far, in reading order (shared with the sections made from this one)
  const std::vector<KeyRecord> &records() const { return *records_; }
  // The keys read directly in this section (not in its sub-sections)
  const std::vector<std::string> &known_keys() const { return known_keys_; }
  // Report keys present but never read, with the nearest read key. Call after all reads.
  void reject_unknown_keys();
  bool has(const std::string &key) const;
  // The text of a key given as a single value ("" otherwise), for a reader's own parsing
  std::string raw(const std::string &key) const;
  // Whether an optional key is given, the key known to this section either way (a misspelt
  // one is answered with its name)
  bool given(const std::string &key) {
    known_keys_.push_back(key);
    return has(key);
  }
  // A key a reader of its own reads (its declaration and the value it found, as text)
  void declare(const Key &key, const std::string &kind, const std::string &fallback, const std::string &range,
               const std::string &value);
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
  // Record a read of `key` (its declaration, and the value it gave as text)
  void record(const Key &key, const std::string &kind, const std::string &fallback, const std::string &range,
              const std::string &value);
  template <typename T>
  T scalar(const Key &key, T fallback, T min, T max, bool required, const char *kind);

  std::string file_;
  std::unique_ptr<YAML::Node> node_;
  std::string path_;
  std::vector<std::string> *problems_;
  std::vector<std::string> known_keys_;
  std::shared_ptr<std::vector<KeyRecord>> records_ = std::make_shared<std::vector<KeyRecord>>();
  std::string condition_;
  bool schema_ = false;
};

// A particle engine's own settings (its part of coupling.yaml's dem section), read by the
// reader it registers (tfdem/engine_registry.h); the engine knows its concrete type.
struct EngineSettings {
  virtual ~EngineSettings() = default;
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

// Module readers: each module owns its keys.
drag::Gas read_gas(ConfigSection &section);
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
  std::string engine;             // dem.engine: a registered engine's name
  std::shared_ptr<const EngineSettings> engine_settings;  // its own keys of the dem section
  std::vector<std::string> outlets;  // gas patches through which particles leave the DEM
  TransferOptions transfer;       // method, drag law, gas
  VoidFractionOptions void_fraction;
  bool pressure_gradient_force = true;  // -V_p grad p of eq. 28
  bool void_fraction_time_derivative = true;  // d(eps)/dt in gas continuity
  OutputOptions output;
  std::vector<KeyRecord> keys;     // every key read, with its value (defaults included)
};

// Parse coupling.yaml from text; throws ConfigError listing every problem.
CouplingConfig parse_coupling_config(const std::string &file, const std::string &text);
// Read and parse a file; a missing or unreadable file is a ConfigError naming it.
CouplingConfig load_coupling_config(const std::string &file);
// The effective configuration, every value including defaults, as YAML.
std::string describe(const CouplingConfig &config);
// Every key coupling.yaml takes, with every registered engine's, as its readers declare them.
std::vector<KeyRecord> coupling_reference();

}  // namespace tfdem

#endif
