#include "tfdem/config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <type_traits>

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

bool ConfigSection::has(const std::string &key) const {
  const YAML::Node &map = *node_;
  return map.IsMap() && map[key];
}

std::optional<YAML::Node> ConfigSection::child(const std::string &key, bool required) {
  known_keys_.push_back(key);
  if (!has(key)) {
    if (required) problems_->push_back(location(file_, node_->Mark()) + ": " + key_path(key) + ": missing (required)");
    return std::nullopt;
  }
  const YAML::Node &map = *node_;
  return map[key];
}

ConfigSection ConfigSection::section(const std::string &key, bool required) {
  const std::optional<YAML::Node> value = child(key, required);
  auto node = std::make_unique<YAML::Node>(YAML::NodeType::Map);
  if (value) {
    if (value->IsMap())
      node->reset(*value);
    else
      problem(key, "must be a mapping of keys to values");
  }
  return ConfigSection(file_, std::move(node), key_path(key), *problems_);
}

template <typename T>
T ConfigSection::scalar(const std::string &key, T fallback, T min, T max, bool required, const char *kind) {
  const std::optional<YAML::Node> value = child(key, required);
  if (!value) return fallback;
  T v;
  try {
    v = value->as<T>();
  } catch (const YAML::Exception &) {
    problem(key, std::string("must be ") + kind + ", got '" +
                     (value->IsScalar() ? value->Scalar() : std::string("a collection")) + "'");
    return fallback;
  }
  if (not_a_number(v)) {
    problem(key, "must be a number, got '" + value->Scalar() + "' (not a number)");
    return fallback;
  }
  if (!(v >= min && v <= max)) {
    problem(key, "value " + format_number(v) + " is out of range [" + format_number(min) + ", " + format_number(max) + "]");
    return fallback;
  }
  return v;
}

double ConfigSection::number(const std::string &key, double fallback, double min, double max, bool required) {
  return scalar<double>(key, fallback, min, max, required, "a number");
}

long ConfigSection::integer(const std::string &key, long fallback, long min, long max, bool required) {
  return scalar<long>(key, fallback, min, max, required, "a whole number");
}

bool ConfigSection::boolean(const std::string &key, bool fallback) {
  const std::optional<YAML::Node> value = child(key, false);
  if (!value) return fallback;
  try {
    return value->as<bool>();
  } catch (const YAML::Exception &) {
    problem(key, "must be true or false, got '" + (value->IsScalar() ? value->Scalar() : std::string("a collection")) + "'");
    return fallback;
  }
}

std::string ConfigSection::text(const std::string &key, const std::string &fallback, bool required) {
  const std::optional<YAML::Node> value = child(key, required);
  if (!value) return fallback;
  if (!value->IsScalar()) {
    problem(key, "must be a single value");
    return fallback;
  }
  return value->Scalar();
}

std::vector<double> ConfigSection::number_list(const std::string &key, double min, double max, bool required) {
  const std::optional<YAML::Node> value = child(key, required);
  if (!value) return {};
  std::vector<double> out;
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
  return out;
}

std::vector<double> ConfigSection::number_table(const std::string &key, std::vector<double> fallback, double min,
                                                double max, bool required) {
  const std::optional<YAML::Node> value = child(key, required);
  if (!value) return fallback;
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
  return ok && !out.empty() ? out : fallback;
}

std::vector<std::string> ConfigSection::text_list(const std::string &key) {
  const std::optional<YAML::Node> value = child(key, false);
  if (!value) return {};
  if (value->IsScalar()) return {value->Scalar()};
  std::vector<std::string> out;
  if (value->IsSequence())
    for (const auto &item : *value)
      if (item.IsScalar()) out.push_back(item.Scalar());
  if (!value->IsSequence() || out.size() != value->size()) problem(key, "must be a name or a list of names");
  return out;
}

std::string ConfigSection::choice(const std::string &key, const std::string &fallback,
                                  const std::vector<std::string> &choices) {
  const std::string v = text(key, fallback);
  if (std::find(choices.begin(), choices.end(), v) != choices.end()) return v;
  problem(key, "unknown value '" + v + "'" + did_you_mean(v, choices) + "; valid: " + quoted_list(choices));
  return fallback;
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
  gas.density = section.number("density", 1.2, 1e-6, 1e4);
  gas.viscosity = section.number("viscosity", 1.8e-5, 1e-9, 1e3);
  section.reject_unknown_keys();
  return gas;
}

// A positive length in metres under `key` (0 when absent): a bare number, since a unit such as
// '1 cm' or a multiple of the diameter would be read as something else.
double read_length(ConfigSection &section, const std::string &key) {
  if (!section.given(key)) return 0.0;
  const std::string text = section.text(key, "");
  double value = 0.0;
  std::size_t used = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception &) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value)) {
    section.report(key, "must be a length in metres, a plain number (e.g. 0.01 for 1 cm), got '" + text + "'");
    return 0.0;
  }
  if (!(value > 0.0)) {
    section.report(key, "value " + text + " is not a bandwidth: give a length above 0 in metres (3-6 particle "
                        "diameters), or leave the key out for no smoothing");
    return 0.0;
  }
  return value;
}

// Three whole numbers >= 1 under `key` (gas cells per particle-field cell along x, y, z);
// 1, 1, 1 when absent. Whether they divide the gas grid is the filter's check (the grid is the
// mesh's).
std::array<int, 3> read_block(ConfigSection &section, const std::string &key) {
  std::array<int, 3> block{1, 1, 1};
  if (!section.given(key)) return block;
  const std::vector<double> values = section.number_list(key, 1, 1e6);
  bool whole = values.size() == 3;
  for (double v : values) whole = whole && v == std::floor(v);
  if (!whole) {
    section.report(key, "must be three whole numbers of 1 or more, the gas cells per particle-field cell along x, "
                        "y and z (e.g. [1, 2, 1]: the particle field on cells twice the gas cells' height)");
    return block;
  }
  for (int a = 0; a < 3; ++a) block[a] = static_cast<int>(values[a]);
  return block;
}

VoidFractionOptions read_void_fraction(ConfigSection &section) {
  VoidFractionOptions o;
  o.method = void_fraction_method_from_name(section.choice("method", "centroid", void_fraction_method_names()));
  o.cube_factor = section.number("cube_factor", 1.0, minimum_cube_factor(), 10.0);
  o.divided_points_per_diameter = static_cast<int>(section.integer("divided_points_per_diameter", 6, 2, 64));
  o.two_dimensional = section.boolean("two_dimensional", false);
  o.void_fraction_floor = section.number("floor", 0.0, 0.0, 1.0);
  if (o.void_fraction_floor >= 1.0) {
    section.report("floor", "value 1 leaves no room for particles: the floor must be below 1 (e.g. 0.3)");
    o.void_fraction_floor = 0.0;
  }
  o.diffusion_bandwidth = read_length(section, "diffusion_bandwidth");
  o.particle_field_block = read_block(section, "particle_field_block");
  section.reject_unknown_keys();
  return o;
}

const std::vector<std::string> &engine_names() {
  static const std::vector<std::string> names = {"liggghts", "hard_sphere"};
  return names;
}

HardSphereOptions read_hard_sphere(ConfigSection &section) {
  HardSphereOptions o;
  o.restitution = section.number_table("restitution", {}, 0, 1, true);
  o.tangential_restitution = section.number_table("tangential_restitution", {}, 0, 1, true);
  o.friction = section.number_table("friction", {}, 0, 1e3, true);
  ConfigSection wall = section.section("wall");
  const auto own = [](const std::vector<double> &particles) {
    return particles.size() == 1 ? particles : std::vector<double>{};
  };
  o.wall_restitution = wall.number_table("restitution", own(o.restitution), 0, 1);
  o.wall_tangential_restitution = wall.number_table("tangential_restitution", own(o.tangential_restitution), 0, 1);
  o.wall_friction = wall.number_table("friction", own(o.friction), 0, 1e3);
  for (auto [where, values] : {std::pair{&section, &o.restitution}, std::pair{&wall, &o.wall_restitution}})
    if (std::any_of(values->begin(), values->end(), [](double e) { return e == 0; }))
      where->report("restitution", "e_n = 0 leaves a pair that collided touching and at rest against each other, "
                                   "which binary collisions cannot part (each later contact is a collision at zero "
                                   "gap, without end): give e_n above 0 (glass on glass 0.9-0.97)");
  for (const auto &[key, values] : {std::pair{"restitution", &o.wall_restitution},
                                    std::pair{"tangential_restitution", &o.wall_tangential_restitution},
                                    std::pair{"friction", &o.wall_friction}})
    if (values->empty() && !wall.has(key))
      wall.report(key, std::string("missing: the particles' ") + key + " is a matrix, so the walls' needs its " +
                           "own value (one, or one per type)");
  wall.reject_unknown_keys();
  o.elastic_within = section.number("elastic_within", o.elastic_within, 0, 1);
  o.max_collisions_per_particle = section.integer("max_collisions_per_particle", o.max_collisions_per_particle, 1,
                                                  100000000);
  o.contact_gap = section.number("contact_gap", o.contact_gap, 0, 1);
  o.move = section.boolean("move", o.move);
  section.reject_unknown_keys();
  return o;
}

OutputOptions read_output(ConfigSection &section) {
  OutputOptions o;
  o.statistics_interval = section.number("statistics_interval", 0.0, 0.0, 1e6);
  o.particles_vtk = section.boolean("particles_vtk", true);
  section.reject_unknown_keys();
  return o;
}

CouplingConfig parse_coupling_config(const std::string &file, const std::string &text) {
  std::vector<std::string> problems;
  ConfigSection root(file, text, problems);
  if (!problems.empty()) throw ConfigError(problems);  // unparsable: nothing else to check
  CouplingConfig c;
  c.file = file;
  ConfigSection gas = root.section("gas", true);
  c.gas = read_gas(gas);
  ConfigSection particles = root.section("particles", true);
  c.particle_diameters = particles.number_list("diameter", 1e-9, 1.0, true);
  std::sort(c.particle_diameters.begin(), c.particle_diameters.end());
  c.particle_density = particles.number("density", 0.0, 1e-3, 1e5, true);
  particles.reject_unknown_keys();
  ConfigSection dem = root.section("dem", true);
  const std::string engine = dem.choice("engine", "liggghts", engine_names());
  c.engine = engine == "hard_sphere" ? Engine::HardSphere : Engine::Liggghts;
  // each engine's own keys; the other's are refused by name
  const auto refuse = [&dem, &engine](const char *key, const char *whose) {
    if (dem.has(key))
      dem.refuse(key, std::string("applies to the ") + whose + " engine, not to dem.engine: " + engine +
                          "; remove the key");
  };
  if (c.engine == Engine::Liggghts) {
    c.dem_script = dem.text("script", "", true);
    // optional: the solver derives it as deltaT / the DEM step (which must be whole); given, it is checked
    c.coupling_interval = dem.given("coupling_interval") ? dem.integer("coupling_interval", 1, 1, 1000000) : 0;
    refuse("particles", "hard_sphere");
    refuse("hard_sphere", "hard_sphere");
  } else {
    c.dem_particles = dem.text("particles", "", true);
    ConfigSection hard = dem.section("hard_sphere", true);
    c.hard_sphere = read_hard_sphere(hard);
    refuse("script", "liggghts");
    refuse("coupling_interval", "liggghts (the hard-sphere engine's flow step is the gas step)");
  }
  c.outlets = dem.text_list("outlets");
  dem.reject_unknown_keys();
  ConfigSection coupling = root.section("coupling");
  c.transfer.method = transfer_method_from_name(coupling.choice("transfer", "averaged", transfer_method_names()));
  c.transfer.law = drag::law_from_name(coupling.choice("drag_law", "ergun_wen_yu", drag::law_names()));
  const std::string gas_velocity = coupling.choice("gas_velocity_at_particle", "cell", gas_at_particle_names());
  c.transfer.gas_velocity = gas_velocity == "interpolated" ? GasAtParticle::Interpolated : GasAtParticle::Cell;
  c.transfer.polydispersity =
      drag::polydispersity_from_name(coupling.choice("polydisperse_drag", "own_diameter", drag::polydispersity_names()));
  if (c.transfer.polydispersity != drag::Polydispersity::OwnDiameter && c.transfer.method == TransferMethod::Averaged)
    coupling.report("polydisperse_drag", "'" + drag::polydispersity_names()[static_cast<int>(c.transfer.polydispersity)] +
                                             "' gives each particle its own drag, which 'averaged' (eq. 33, one drag per "
                                             "unit volume in a cell) cannot: use transfer: per_particle_conservative");
  if (c.transfer.gas_velocity == GasAtParticle::Interpolated && c.transfer.method == TransferMethod::Averaged)
    coupling.report("gas_velocity_at_particle", "'interpolated' applies to the per-particle transfers; 'averaged' "
                                                "uses the cell's mean gas velocity (eq. 33): remove the key or use "
                                                "transfer: per_particle");
  c.transfer.gas = c.gas;
  c.pressure_gradient_force = coupling.boolean("pressure_gradient_force", true);
  if (coupling.has("viscous_force")) {
    coupling.boolean("viscous_force", false);
    coupling.report("viscous_force", "not modelled: the viscous-stress force V_p div(tau) of seed 000 eq. 28 is "
                                     "neglected, as the paper does (it is small beside drag in gas-fluidized beds); "
                                     "remove the key");
  }
  c.void_fraction_time_derivative = coupling.boolean("void_fraction_time_derivative", true);
  ConfigSection void_fraction = coupling.section("void_fraction");
  c.void_fraction = read_void_fraction(void_fraction);
  if (c.void_fraction.filters() && c.transfer.method == TransferMethod::Averaged)
    void_fraction.report(c.void_fraction.diffusion_bandwidth > 0.0 ? "diffusion_bandwidth" : "particle_field_block",
                         "the filtered fields need a per-particle transfer: 'averaged' shares a "
                         "cell's drag among the particles in that cell, and a filtered cell holds solids of "
                         "particles in other cells; use transfer: per_particle_conservative (or per_particle)");
  coupling.reject_unknown_keys();
  ConfigSection output = root.section("output");
  c.output = read_output(output);
  root.reject_unknown_keys();
  if (!problems.empty()) throw ConfigError(problems);
  return c;
}

CouplingConfig load_coupling_config(const std::string &file) {
  std::ifstream in(file);
  if (!in) throw ConfigError({file + ": cannot open the coupling configuration (missing or unreadable)"});
  std::stringstream text;
  text << in.rdbuf();
  return parse_coupling_config(file, text.str());
}

std::string describe(const CouplingConfig &c) {
  std::ostringstream s;
  s.precision(10);
  s << "# effective coupling configuration (" << c.file << ")\n"
    << "gas:\n  density: " << c.gas.density << "\n  viscosity: " << c.gas.viscosity << "\n"
    << "particles:\n  diameter: [" << [&c] {
         std::ostringstream list;
         list.precision(10);
         for (std::size_t k = 0; k < c.particle_diameters.size(); ++k) list << (k ? ", " : "") << c.particle_diameters[k];
         return list.str();
       }() << "]\n  density: " << c.particle_density << "\n"
    << "dem:\n  engine: " << engine_names()[static_cast<int>(c.engine)] << "\n" << [&c] {
         std::ostringstream dem;
         dem.precision(10);
         if (c.engine == Engine::Liggghts) {
           dem << "  script: " << c.dem_script << "\n";
           if (c.coupling_interval > 0) dem << "  coupling_interval: " << c.coupling_interval << "\n";
           return dem.str();
         }
         const auto list = [](const std::vector<double> &v) {
           std::ostringstream out;
           out.precision(10);
           out << "[";
           for (std::size_t k = 0; k < v.size(); ++k) out << (k ? ", " : "") << v[k];
           return out.str() + "]";
         };
         const HardSphereOptions &h = c.hard_sphere;
         dem << "  particles: " << c.dem_particles << "\n  hard_sphere:\n    restitution: " << list(h.restitution)
             << "\n    tangential_restitution: " << list(h.tangential_restitution) << "\n    friction: "
             << list(h.friction) << "\n    wall:\n      restitution: " << list(h.wall_restitution)
             << "\n      tangential_restitution: " << list(h.wall_tangential_restitution) << "\n      friction: "
             << list(h.wall_friction) << "\n    elastic_within: " << h.elastic_within
             << "\n    max_collisions_per_particle: " << h.max_collisions_per_particle
             << "\n    contact_gap: " << h.contact_gap << "\n    move: " << (h.move ? "true" : "false") << "\n";
         return dem.str();
       }()
    << "  outlets: [" << [&c] {
         std::string list;
         for (const auto &o : c.outlets) list += (list.empty() ? "" : ", ") + o;
         return list;
       }() << "]\n"
    << "coupling:\n  transfer: " << transfer_method_names()[static_cast<int>(c.transfer.method)] << "\n"
    << "  drag_law: " << drag::law_name(c.transfer.law) << "\n"
    << "  gas_velocity_at_particle: " << gas_at_particle_names()[static_cast<int>(c.transfer.gas_velocity)] << "\n"
    << "  polydisperse_drag: " << drag::polydispersity_names()[static_cast<int>(c.transfer.polydispersity)] << "\n"
    << "  pressure_gradient_force: " << (c.pressure_gradient_force ? "true" : "false") << "\n"
    << "  void_fraction_time_derivative: " << (c.void_fraction_time_derivative ? "true" : "false") << "\n"
    << "  void_fraction:\n    method: " << void_fraction_method_names()[static_cast<int>(c.void_fraction.method)] << "\n"
    << "    cube_factor: " << c.void_fraction.cube_factor << "\n"
    << "    divided_points_per_diameter: " << c.void_fraction.divided_points_per_diameter << "\n"
    << "    two_dimensional: " << (c.void_fraction.two_dimensional ? "true" : "false") << "\n"
    << "    floor: " << c.void_fraction.void_fraction_floor << "\n";
  if (c.void_fraction.diffusion_bandwidth > 0.0)
    s << "    diffusion_bandwidth: " << c.void_fraction.diffusion_bandwidth << "\n";
  if (c.void_fraction.particle_field_block != std::array<int, 3>{1, 1, 1})
    s << "    particle_field_block: [" << c.void_fraction.particle_field_block[0] << ", "
      << c.void_fraction.particle_field_block[1] << ", " << c.void_fraction.particle_field_block[2] << "]\n";
  s << "output:\n  statistics_interval: " << c.output.statistics_interval << "\n"
    << "  particles_vtk: " << (c.output.particles_vtk ? "true" : "false") << "\n";
  return s.str();
}

}  // namespace tfdem
