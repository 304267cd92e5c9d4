#include "tfdem/config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <type_traits>

#include "tfdem/engine_registry.h"
#include "tfdem/suggest.h"

namespace tfdem {
namespace {

std::string join_lines(const std::vector<std::string> &lines) {
  std::string out;
  for (const auto &l : lines) out += (out.empty() ? "" : "\n") + l;
  return out;
}

std::string location(const std::string &file, const YAML::Mark &mark) {
  if (mark.is_null()) return file;
  return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

// NaN, tested without comparing it: under OpenFOAM's floating-point trap an ordered
// comparison with NaN stops the process (SIGFPE)
template <typename T>
bool not_a_number(T v) {
  if constexpr (std::is_floating_point_v<T>) return std::isnan(v);
  return false;
}

template <typename T>
std::string format_number(T v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A value as the effective configuration writes it (10 digits: the solver's own precision)
std::string value_text(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

std::string list_text(const std::vector<double> &values) {
  std::string out = "[";
  for (std::size_t k = 0; k < values.size(); ++k) out += (k ? ", " : "") + value_text(values[k]);
  return out + "]";
}

std::string list_text(const std::vector<std::string> &values) {
  std::string out = "[";
  for (std::size_t k = 0; k < values.size(); ++k) out += (k ? ", " : "") + values[k];
  return out + "]";
}

std::string range_text(double min, double max) { return "[" + format_number(min) + ", " + format_number(max) + "]"; }

// Lines where a quote opens and does not close: YAML would take the lines after it into the
// value (a file name swallowing the rest of the file). No TFDEM value spans lines. A single
// quote counts only where it opens a value (an apostrophe inside a plain value is text).
std::vector<std::string> unclosed_quotes(const std::string &file, const std::string &text) {
  std::vector<std::string> problems;
  std::istringstream in(text);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    char open = 0;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (open == 0 && c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) break;
      if (open == '"' && c == '\\') {
        ++i;
      } else if (open == 0 && (c == '"' || c == '\'')) {
        const std::size_t before = i == 0 ? std::string::npos : line.find_last_not_of(" \t", i - 1);
        const bool opens_value = before == std::string::npos || std::string(":-[{,").find(line[before]) != std::string::npos;
        if (opens_value) open = c;
      } else if (c == open) {
        open = 0;
      }
    }
    if (open)
      problems.push_back(file + ":" + std::to_string(number) + ": a quote (" + open +
                         ") opens here and is not closed on this line: YAML would take the lines after it into the "
                         "value; close the quote");
  }
  return problems;
}

}  // namespace

ConfigError::ConfigError(const std::vector<std::string> &problems)
    : std::runtime_error(join_lines(problems)), problems_(problems) {}

ConfigSection::ConfigSection(const std::string &file, const std::string &text, std::vector<std::string> &problems)
    : file_(file), node_(std::make_unique<YAML::Node>()), problems_(&problems) {
  const std::vector<std::string> quotes = unclosed_quotes(file, text);
  if (!quotes.empty()) {
    problems.insert(problems.end(), quotes.begin(), quotes.end());
    *node_ = YAML::Node(YAML::NodeType::Map);
    return;
  }
  try {
    *node_ = YAML::Load(text);
  } catch (const YAML::ParserException &e) {
    problems.push_back(location(file, e.mark) + ": malformed YAML: " + e.msg);
    *node_ = YAML::Node(YAML::NodeType::Map);
    return;
  }
  if (node_->IsNull()) {
    *node_ = YAML::Node(YAML::NodeType::Map);
  } else if (!node_->IsMap()) {
    problems.push_back(location(file, node_->Mark()) + ": the file must be a mapping of keys to values");
    *node_ = YAML::Node(YAML::NodeType::Map);
  }
}

ConfigSection::ConfigSection(const std::string &file, std::unique_ptr<YAML::Node> node, std::string path,
                             std::vector<std::string> &problems)
    : file_(file), node_(std::move(node)), path_(std::move(path)), problems_(&problems) {}

ConfigSection ConfigSection::schema(std::vector<std::string> &problems) {
  ConfigSection root("(schema)", "", problems);
  root.schema_ = true;
  return root;
}

void ConfigSection::record(const Key &key, const std::string &kind, const std::string &fallback,
                           const std::string &range, const std::string &value) {
  records_->push_back({key_path(key.name), kind, key.unit, key.doc, fallback, range, condition_, value, has(key.name)});
}

void ConfigSection::declare(const Key &key, const std::string &kind, const std::string &fallback,
                            const std::string &range, const std::string &value) {
  known_keys_.push_back(key.name);
  record(key, kind, fallback, range, value);
}

ConfigSection::~ConfigSection() = default;
ConfigSection::ConfigSection(ConfigSection &&) noexcept = default;

std::string ConfigSection::key_path(const std::string &key) const { return path_.empty() ? key : path_ + "." + key; }

std::string ConfigSection::where(const std::string &key) const {
  const YAML::Node &map = *node_;
  const YAML::Node value = map[key];
  return location(file_, value ? value.Mark() : node_->Mark());
}

void ConfigSection::problem(const std::string &key, const std::string &message) {
  problems_->push_back(where(key) + ": " + key_path(key) + ": " + message);
}

std::string ConfigSection::raw(const std::string &key) const {
  const YAML::Node &map = *node_;
  return has(key) && map[key].IsScalar() ? map[key].Scalar() : std::string();
}

bool ConfigSection::has(const std::string &key) const {
  const YAML::Node &map = *node_;
  return map.IsMap() && map[key];
}

std::optional<YAML::Node> ConfigSection::child(const std::string &key, bool required) {
  known_keys_.push_back(key);
  if (!has(key)) {
    if (required && !schema_)
      problems_->push_back(location(file_, node_->Mark()) + ": " + key_path(key) + ": missing (required)");
    return std::nullopt;
  }
  const YAML::Node &map = *node_;
  return map[key];
}

ConfigSection ConfigSection::section(const Key &key, bool required) {
  const std::optional<YAML::Node> value = child(key.name, required);
  record(key, "a section", required ? "required" : "", "", "");
  auto node = std::make_unique<YAML::Node>(YAML::NodeType::Map);
  if (value) {
    if (value->IsMap())
      node->reset(*value);
    else
      problem(key.name, "must be a mapping of keys to values");
  }
  ConfigSection sub(file_, std::move(node), key_path(key.name), *problems_);
  sub.records_ = records_;
  sub.condition_ = condition_;
  sub.schema_ = schema_;
  return sub;
}

template <typename T>
T ConfigSection::scalar(const Key &k, T fallback, T min, T max, bool required, const char *kind) {
  const std::string &key = k.name;
  const std::optional<YAML::Node> value = child(key, required);
  const auto done = [&](T v) {
    record(k, kind, required ? "required" : value_text(static_cast<double>(fallback)), range_text(min, max),
           value_text(static_cast<double>(v)));
    return v;
  };
  if (!value) return done(fallback);
  T v;
  try {
    v = value->as<T>();
  } catch (const YAML::Exception &) {
    problem(key, std::string("must be ") + kind + ", got '" +
                     (value->IsScalar() ? value->Scalar() : std::string("a collection")) + "'");
    return done(fallback);
  }
  if (not_a_number(v)) {
    problem(key, "must be a number, got '" + value->Scalar() + "' (not a number)");
    return done(fallback);
  }
  if (!(v >= min && v <= max)) {
    problem(key, "value " + format_number(v) + " is out of range [" + format_number(min) + ", " + format_number(max) + "]");
    return done(fallback);
  }
  return done(v);
}

double ConfigSection::number(const Key &key, double fallback, double min, double max, bool required) {
  return scalar<double>(key, fallback, min, max, required, "a number");
}

long ConfigSection::integer(const Key &key, long fallback, long min, long max, bool required) {
  return scalar<long>(key, fallback, min, max, required, "a whole number");
}

bool ConfigSection::boolean(const Key &k, bool fallback) {
  const std::string &key = k.name;
  const std::optional<YAML::Node> value = child(key, false);
  bool v = fallback;
  if (value) {
    try {
      v = value->as<bool>();
    } catch (const YAML::Exception &) {
      problem(key, "must be true or false, got '" + (value->IsScalar() ? value->Scalar() : std::string("a collection")) +
                       "'");
    }
  }
  record(k, "true or false", fallback ? "true" : "false", "", v ? "true" : "false");
  return v;
}

std::string ConfigSection::text(const Key &k, const std::string &fallback, bool required) {
  const std::string &key = k.name;
  const std::optional<YAML::Node> value = child(key, required);
  std::string v = fallback;
  if (value) {
    if (value->IsScalar())
      v = value->Scalar();
    else
      problem(key, "must be a single value");
  }
  record(k, "a name", required ? "required" : fallback, "", v);
  return v;
}

std::vector<double> ConfigSection::number_list(const Key &k, double min, double max, bool required) {
  const std::string &key = k.name;
  const std::optional<YAML::Node> value = child(key, required);
  std::vector<double> out;
  const auto done = [&]() {
    record(k, "a number or a list of numbers", required ? "required" : "[]", range_text(min, max), list_text(out));
    return out;
  };
  if (!value) return done();
  const auto add = [&](const YAML::Node &item) {
    double v;
    try {
      v = item.as<double>();
    } catch (const YAML::Exception &) {
      problem(key, "must be a number or a list of numbers, got '" +
                       (item.IsScalar() ? item.Scalar() : std::string("a collection")) + "'");
      return;
    }
    if (not_a_number(v)) {
      problem(key, "must be a number or a list of numbers, got '" + item.Scalar() + "' (not a number)");
      return;
    }
    if (v >= min && v <= max)
      out.push_back(v);
    else
      problem(key, "value " + format_number(v) + " is out of range [" + format_number(min) + ", " + format_number(max) + "]");
  };
  if (value->IsSequence())
    for (const auto &item : *value) add(item);
  else
    add(*value);
  if (value->IsSequence() && value->size() == 0) problem(key, "is an empty list: give at least one value");
  return done();
}

std::vector<double> ConfigSection::number_table(const Key &k, std::vector<double> fallback, double min,
                                                double max, bool required) {
  const std::string &key = k.name;
  const std::optional<YAML::Node> value = child(key, required);
  const auto done = [&](const std::vector<double> &v) {
    record(k, "a number, a list, or a list of lists (a matrix, row by row)",
           required ? "required" : fallback.empty() ? "" : list_text(fallback), range_text(min, max), list_text(v));
    return v;
  };
  if (!value) return done(fallback);
  std::vector<double> out;
  bool ok = true;
  const auto add = [&](const YAML::Node &item) {
    double v = 0;
    try {
      v = item.as<double>();
    } catch (const YAML::Exception &) {
      ok = false;
      return;
    }
    if (not_a_number(v) || !(v >= min && v <= max)) {
      problem(key, "value " + item.Scalar() + " is out of range [" + format_number(min) + ", " + format_number(max) +
                       "]");
      return;
    }
    out.push_back(v);
  };
  if (value->IsScalar()) {
    add(*value);
  } else if (value->IsSequence()) {
    for (const auto &row : *value) {
      if (row.IsSequence())
        for (const auto &item : row) add(item);
      else
        add(row);
    }
  } else {
    ok = false;
  }
  if (!ok) problem(key, "must be a number, a list of numbers or a list of lists (a matrix, row by row)");
  return done(ok && !out.empty() ? out : fallback);
}

std::vector<std::string> ConfigSection::text_list(const Key &k) {
  const std::string &key = k.name;
  const std::optional<YAML::Node> value = child(key, false);
  std::vector<std::string> out;
  if (value && value->IsScalar()) {
    out.push_back(value->Scalar());
  } else if (value) {
    if (value->IsSequence())
      for (const auto &item : *value)
        if (item.IsScalar()) out.push_back(item.Scalar());
    if (!value->IsSequence() || out.size() != value->size()) problem(key, "must be a name or a list of names");
  }
  record(k, "a name or a list of names", "[]", "", list_text(out));
  return out;
}

std::string ConfigSection::choice(const Key &k, const std::string &fallback, const std::vector<std::string> &choices) {
  const std::string &key = k.name;
  const std::optional<YAML::Node> value = child(key, false);
  std::string v = fallback;
  if (value && !value->IsScalar()) {
    problem(key, "must be a single value");
  } else if (value) {
    v = value->Scalar();
    if (std::find(choices.begin(), choices.end(), v) == choices.end()) {
      problem(key, "unknown value '" + v + "'" + did_you_mean(v, choices) + "; valid: " + quoted_list(choices));
      v = fallback;
    }
  }
  std::string options;
  for (const auto &c : choices) options += (options.empty() ? "" : ", ") + c;
  record(k, "one of", fallback, options, v);
  return v;
}

void ConfigSection::reject_unknown_keys() {
  if (!node_->IsMap()) return;
  std::vector<std::pair<std::string, YAML::Mark>> seen;
  for (const auto &entry : *node_) {
    const std::string key = entry.first.as<std::string>();
    const auto first = std::find_if(seen.begin(), seen.end(), [&key](const auto &s) { return s.first == key; });
    if (first != seen.end())
      problems_->push_back(location(file_, entry.first.Mark()) + ": " + key_path(key) + ": given twice (first at " +
                           location(file_, first->second) + "); YAML keeps one of them silently: keep one");
    seen.emplace_back(key, entry.first.Mark());
    if (std::find(known_keys_.begin(), known_keys_.end(), key) != known_keys_.end()) continue;
    problems_->push_back(location(file_, entry.first.Mark()) + ": " + key_path(key) + ": unknown key" +
                         did_you_mean(key, known_keys_) + "; valid keys here: " + quoted_list(known_keys_));
  }
}

drag::Gas read_gas(ConfigSection &section) {
  drag::Gas gas;
  gas.density = section.number({"density", "kg/m^3", "the gas density rho_g (constant/transportProperties' rho: the same)"},
                               1.2, 1e-6, 1e4);
  gas.viscosity = section.number(
      {"viscosity", "Pa s", "the gas dynamic viscosity mu_g (rho_g times transportProperties' nu: the same)"}, 1.8e-5,
      1e-9, 1e3);
  section.reject_unknown_keys();
  return gas;
}

// A positive length in metres under `key` (0 when absent): a bare number, since a unit such as
// '1 cm' or a multiple of the diameter would be read as something else.
double read_length(ConfigSection &section, const Key &key) {
  const std::string text = section.raw(key.name);
  double value = 0.0;
  std::size_t used = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception &) {
    used = 0;
  }
  const bool given = section.has(key.name);
  if (given && (used == 0 || used != text.size() || !std::isfinite(value))) {
    section.report(key.name, "must be a length in metres, a plain number (e.g. 0.01 for 1 cm), got '" + text + "'");
    value = 0.0;
  } else if (given && !(value > 0.0)) {
    section.report(key.name, "value " + text + " is not a bandwidth: give a length above 0 in metres (3-6 particle "
                             "diameters), or leave the key out for no smoothing");
    value = 0.0;
  }
  section.declare(key, "a length", "none", "above 0", given ? value_text(value) : "");
  return given ? value : 0.0;
}

// Three whole numbers >= 1 under `key` (gas cells per particle-field cell along x, y, z);
// 1, 1, 1 when absent. Whether they divide the gas grid is the filter's check (the grid is the
// mesh's).
std::array<int, 3> read_block(ConfigSection &section, const Key &key) {
  std::array<int, 3> block{1, 1, 1};
  if (!section.has(key.name)) {
    section.declare(key, "three whole numbers", "[1, 1, 1]", "1 or more", "");
    return block;
  }
  const std::vector<double> values = section.number_list(key, 1, 1e6);
  bool whole = values.size() == 3;
  for (double v : values) whole = whole && v == std::floor(v);
  if (!whole) {
    section.report(key.name, "must be three whole numbers of 1 or more, the gas cells per particle-field cell along x, "
                             "y and z (e.g. [1, 2, 1]: the particle field on cells twice the gas cells' height)");
    return block;
  }
  for (int a = 0; a < 3; ++a) block[a] = static_cast<int>(values[a]);
  return block;
}

VoidFractionOptions read_void_fraction(ConfigSection &section) {
  VoidFractionOptions o;
  o.method = void_fraction_method_from_name(section.choice(
      {"method", "", "how a particle's volume is shared among the gas cells: centroid (seed 000 eq. 34, all in its "
                     "centre's cell), divided (over the cells its volume lies in), porous_cube (Link et al., seed 001 "
                     "eqs. 34-39: a cube of cube_factor diameters)"},
      "centroid", void_fraction_method_names()));
  o.cube_factor = section.number(
      {"cube_factor", "", "porous_cube: the cube's side in particle diameters (its smallest, the sphere's volume)"},
      1.0, minimum_cube_factor(), 10.0);
  o.divided_points_per_diameter = static_cast<int>(section.integer(
      {"divided_points_per_diameter", "", "divided: sample points across a diameter to share its volume"}, 6, 2, 64));
  o.two_dimensional = section.boolean(
      {"two_dimensional", "", "seed 000's 2-D rule: one particle layer in cells one diameter deep, one size, no "
                              "force across the depth"},
      false);
  o.void_fraction_floor = section.number(
      {"floor", "", "the lowest gas fraction a cell's drag sees (0: none; a crowded cell stops the run instead)"},
      0.0, 0.0, 1.0);
  if (o.void_fraction_floor >= 1.0) {
    section.report("floor", "value 1 leaves no room for particles: the floor must be below 1 (e.g. 0.3)");
    o.void_fraction_floor = 0.0;
  }
  o.diffusion_bandwidth = read_length(
      section, {"diffusion_bandwidth", "m",
                "each particle's fields spread to a Gaussian of this bandwidth b, variance b^2/2 per axis on every grid "
                "(the mapping into cells of h gives h^2/12 of it, diffusion the rest; 3-6 particle diameters; leave out "
                "for none)"});
  o.particle_field_block = read_block(
      section, {"particle_field_block", "",
                "gas cells per particle-field cell along x, y, z: the particle fields on coarser cells, interpolated "
                "back"});
  section.reject_unknown_keys();
  return o;
}

OutputOptions read_output(ConfigSection &section) {
  OutputOptions o;
  o.statistics_interval = section.number(
      {"statistics_interval", "s", "seconds between samples of the particle statistics and the force maps "
                                   "(postProcessing/tfdemParticles); 0: none; a whole number of gas steps"},
      0.0, 0.0, 1e6);
  o.particles_vtk = section.boolean(
      {"particles_vtk", "", "the particles as VTK files at every gas write time (VTK/particles_<time>.vtk)"}, true);
  section.reject_unknown_keys();
  return o;
}

namespace {

// The engines' keys of the dem section, each with the engine that takes it
std::vector<std::pair<std::string, std::string>> engine_keys() {
  std::vector<std::pair<std::string, std::string>> keys;
  for (const std::string &name : engine_names()) {
    std::vector<std::string> ignored;
    ConfigSection probe = ConfigSection::schema(ignored);
    find_engine(name)->read(probe);
    for (const std::string &key : probe.known_keys()) keys.emplace_back(key, name);
  }
  return keys;
}

// dem: the engine by name, its own keys read by its reader, the others' refused by name
void read_dem(ConfigSection &dem, CouplingConfig &c) {
  c.engine = dem.choice({"engine", "", "the particle engine (its keys below)"}, default_engine_name(), engine_names());
  const EngineType *engine = find_engine(c.engine);
  if (dem.is_schema()) {
    for (const std::string &name : engine_names()) {
      dem.set_condition("dem.engine: " + name);
      find_engine(name)->read(dem);
    }
    dem.set_condition("");
  } else if (engine) {
    c.engine_settings = engine->read(dem);
  }
  for (const auto &[key, owner] : engine_keys())
    if (owner != c.engine && dem.has(key) &&
        std::find(dem.known_keys().begin(), dem.known_keys().end(), key) == dem.known_keys().end())
      dem.refuse(key, "applies to the " + owner + " engine, not to dem.engine: " + c.engine + "; remove the key");
  c.outlets = dem.text_list(
      {"outlets", "", "gas patches through which particles leave the DEM (counted and removed; the DEM's box must "
                      "reach beyond them)"});
  dem.reject_unknown_keys();
}

void read_coupling(ConfigSection &coupling, CouplingConfig &c) {
  c.transfer.method = transfer_method_from_name(coupling.choice(
      {"transfer", "", "how drag passes between particles and gas: averaged (seed 000 eqs. 33-35, a cell's mean), "
                       "per_particle (eq. 29), per_particle_conservative (the gas gets minus the particles' sum)"},
      "averaged", transfer_method_names()));
  c.transfer.law = drag::law_from_name(
      coupling.choice({"drag_law", "", "the drag closure (seed 000 eqs. 29-31; seed 001 eqs. 3-6)"}, "ergun_wen_yu",
                      drag::law_names()));
  const std::string gas_velocity = coupling.choice(
      {"gas_velocity_at_particle", "", "the gas velocity a particle's drag sees: its cell's, or interpolated to its "
                                       "centre (the per-particle transfers)"},
      "cell", gas_at_particle_names());
  c.transfer.gas_velocity = gas_velocity == "interpolated" ? GasAtParticle::Interpolated : GasAtParticle::Cell;
  c.transfer.polydispersity = drag::polydispersity_from_name(coupling.choice(
      {"polydisperse_drag", "", "a mixture's drag: each particle at its own diameter, or Beetstra et al.'s (2007) "
                                "correction at the local Sauter mean"},
      "own_diameter", drag::polydispersity_names()));
  if (c.transfer.polydispersity != drag::Polydispersity::OwnDiameter && c.transfer.method == TransferMethod::Averaged)
    coupling.report("polydisperse_drag", "'" + drag::polydispersity_names()[static_cast<int>(c.transfer.polydispersity)] +
                                             "' gives each particle its own drag, which 'averaged' (eq. 33, one drag per "
                                             "unit volume in a cell) cannot: use transfer: per_particle_conservative");
  if (c.transfer.gas_velocity == GasAtParticle::Interpolated && c.transfer.method == TransferMethod::Averaged)
    coupling.report("gas_velocity_at_particle", "'interpolated' applies to the per-particle transfers; 'averaged' "
                                                "uses the cell's mean gas velocity (eq. 33): remove the key or use "
                                                "transfer: per_particle");
  c.transfer.gas = c.gas;
  c.pressure_gradient_force = coupling.boolean(
      {"pressure_gradient_force", "", "the force -V_p grad p on each particle (seed 000 eq. 28)"}, true);
  if (coupling.has("viscous_force"))
    coupling.refuse("viscous_force", "not modelled: the viscous-stress force V_p div(tau) of seed 000 eq. 28 is "
                                     "neglected, as the paper does (it is small beside drag in gas-fluidized beds); "
                                     "remove the key");
  c.void_fraction_time_derivative = coupling.boolean(
      {"void_fraction_time_derivative", "", "d(eps)/dt in the gas continuity equation (seed 001 eq. 7)"}, true);
  ConfigSection void_fraction = coupling.section({"void_fraction", "", "the particles' volume in the gas cells"});
  c.void_fraction = read_void_fraction(void_fraction);
  if (c.void_fraction.filters() && c.transfer.method == TransferMethod::Averaged)
    void_fraction.report(c.void_fraction.diffusion_bandwidth > 0.0 ? "diffusion_bandwidth" : "particle_field_block",
                         "the filtered fields need a per-particle transfer: 'averaged' shares a "
                         "cell's drag among the particles in that cell, and a filtered cell holds solids of "
                         "particles in other cells; use transfer: per_particle_conservative (or per_particle)");
  coupling.reject_unknown_keys();
}

// The whole document: every module's keys, read by its reader
CouplingConfig read_document(ConfigSection &root, const std::string &file) {
  CouplingConfig c;
  c.file = file;
  ConfigSection gas = root.section({"gas", "", "the gas (SI units)"}, true);
  c.gas = read_gas(gas);
  ConfigSection particles = root.section({"particles", "", "the particles the DEM holds"}, true);
  c.particle_diameters = particles.number_list(
      {"diameter", "m", "each particle size d_p, one number or a list (every DEM particle has one of them)"}, 1e-9,
      1.0, true);
  std::sort(c.particle_diameters.begin(), c.particle_diameters.end());
  c.particle_density = particles.number({"density", "kg/m^3", "the particle density rho_p"}, 0.0, 1e-3, 1e5, true);
  particles.reject_unknown_keys();
  ConfigSection dem = root.section({"dem", "", "the particle engine and its settings"}, true);
  read_dem(dem, c);
  ConfigSection coupling = root.section({"coupling", "", "drag, its transfer and the void fraction"});
  read_coupling(coupling, c);
  ConfigSection output = root.section({"output", "", "what the coupler writes besides the gas fields"});
  c.output = read_output(output);
  root.reject_unknown_keys();
  return c;
}

}  // namespace

CouplingConfig parse_coupling_config(const std::string &file, const std::string &text) {
  std::vector<std::string> problems;
  ConfigSection root(file, text, problems);
  if (!problems.empty()) throw ConfigError(problems);  // unparsable: nothing else to check
  CouplingConfig c = read_document(root, file);
  if (!problems.empty()) throw ConfigError(problems);
  c.keys = root.records();
  return c;
}

CouplingConfig load_coupling_config(const std::string &file) {
  std::ifstream in(file);
  if (!in) throw ConfigError({file + ": cannot open the coupling configuration (missing or unreadable)"});
  std::stringstream text;
  text << in.rdbuf();
  return parse_coupling_config(file, text.str());
}

std::vector<KeyRecord> coupling_reference() {
  std::vector<std::string> problems;
  ConfigSection root = ConfigSection::schema(problems);
  read_document(root, "(schema)");
  return root.records();
}

std::string describe(const CouplingConfig &c) {
  std::ostringstream s;
  s << "# effective coupling configuration (" << c.file << ")\n";
  for (const KeyRecord &k : c.keys) {
    const std::size_t depth = static_cast<std::size_t>(std::count(k.path.begin(), k.path.end(), '.'));
    const std::string name = k.path.substr(k.path.rfind('.') == std::string::npos ? 0 : k.path.rfind('.') + 1);
    if (k.kind == "a section") {
      s << std::string(2 * depth, ' ') << name << ":\n";
    } else if (!k.value.empty()) {
      s << std::string(2 * depth, ' ') << name << ": " << k.value << "\n";
    }
  }
  return s.str();
}

}  // namespace tfdem
