// coupling.yaml parsing: every problem reported at once with file, line, key path and fix.
#include <gtest/gtest.h>

#include <cfenv>
#include <fstream>
#include <map>

#include "liggghts_engine.h"
#include "tfdem/config.h"
#include "tfdem/hard_sphere/engine.h"

namespace {

using namespace tfdem;

const char *kValid = R"(gas:
  density: 1.2
  viscosity: 1.8e-5
particles:
  diameter: 0.0025
  density: 2526
dem:
  script: in.bed
  coupling_interval: 50
coupling:
  transfer: per_particle
  drag_law: beetstra
  void_fraction:
    method: porous_cube
    cube_factor: 1.2
    two_dimensional: true
    floor: 0.3
)";

std::vector<std::string> problems_of(const std::string &text) {
  try {
    parse_coupling_config("case/coupling.yaml", text);
  } catch (const ConfigError &e) {
    return e.problems();
  }
  return {};
}

bool contains(const std::vector<std::string> &problems, const std::string &text) {
  for (const auto &p : problems)
    if (p.find(text) != std::string::npos) return true;
  return false;
}

std::string replaced(std::string text, const std::string &from, const std::string &to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Config, ValidFileGivesTypedValues) {
  const CouplingConfig c = parse_coupling_config("coupling.yaml", kValid);
  EXPECT_DOUBLE_EQ(c.gas.viscosity, 1.8e-5);
  EXPECT_EQ(c.particle_diameters, std::vector<double>{0.0025});
  EXPECT_EQ(c.engine, "liggghts");  // the default
  const auto &liggghts = static_cast<const LiggghtsSettings &>(*c.engine_settings);
  EXPECT_EQ(liggghts.script, "in.bed");
  EXPECT_EQ(liggghts.coupling_interval, 50);
  EXPECT_EQ(c.transfer.method, TransferMethod::PerParticle);
  EXPECT_EQ(c.transfer.law, drag::Law::Beetstra);
  EXPECT_DOUBLE_EQ(c.transfer.gas.density, 1.2);
  EXPECT_EQ(c.void_fraction.method, VoidFractionMethod::PorousCube);
  EXPECT_DOUBLE_EQ(c.void_fraction.cube_factor, 1.2);
  EXPECT_TRUE(c.void_fraction.two_dimensional);
  EXPECT_DOUBLE_EQ(c.void_fraction.void_fraction_floor, 0.3);
  EXPECT_TRUE(c.pressure_gradient_force);
}

// The viscous-stress force of seed 000 eq. 28 is not modelled: asking for it is an error, not
// a setting silently dropped.
TEST(Config, ViscousForceIsRefused) {
  const auto p = problems_of(replaced(kValid, "  drag_law: beetstra", "  drag_law: beetstra\n  viscous_force: true"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "coupling.viscous_force: not modelled")) << p[0];
}

TEST(Config, DescribeRoundTrips) {
  const CouplingConfig c = parse_coupling_config("coupling.yaml", kValid);
  const std::string text = describe(c);
  const CouplingConfig again = parse_coupling_config("described.yaml", text);
  EXPECT_EQ(describe(again).substr(describe(again).find('\n')), text.substr(text.find('\n')));
}

TEST(Config, MalformedYamlNamesLine) {
  const auto p = problems_of("gas:\n  density: [1.2\nparticles: {}\n");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "case/coupling.yaml:3:10: malformed YAML: end of sequence flow not found")) << p[0];
}

TEST(Config, MissingRequiredKeysAreAllReported) {
  const auto p = problems_of("gas:\n  density: 1.2\n");
  EXPECT_TRUE(contains(p, "particles: missing (required)"));
  EXPECT_TRUE(contains(p, "dem: missing (required)"));
  const auto q = problems_of(replaced(kValid, "  script: in.bed\n", ""));
  ASSERT_EQ(q.size(), 1u);
  EXPECT_TRUE(contains(q, "dem.script: missing (required)")) << q[0];
}

TEST(Config, UnknownKeysSuggestNearestAndGiveLine) {
  const auto p = problems_of(replaced(kValid, "    cube_factor: 1.2", "    cube_factr: 1.2"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "case/coupling.yaml:15:5: coupling.void_fraction.cube_factr: unknown key (did you mean 'cube_factor'?)")) << p[0];
  const auto q = problems_of(std::string(kValid) + "gass:\n  density: 1\n");
  EXPECT_TRUE(contains(q, "gass: unknown key (did you mean 'gas'?)")) << q[0];
}

TEST(Config, WrongTypesAreReported) {
  const auto p = problems_of(replaced(replaced(kValid, "density: 1.2", "density: heavy"), "two_dimensional: true",
                                      "two_dimensional: maybe"));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_TRUE(contains(p, "case/coupling.yaml:2:12: gas.density: must be a number, got 'heavy'")) << p[0];
  EXPECT_TRUE(contains(p, "coupling.void_fraction.two_dimensional: must be true or false, got 'maybe'")) << p[1];
  const auto q = problems_of(replaced(kValid, "coupling_interval: 50", "coupling_interval: 2.5"));
  EXPECT_TRUE(contains(q, "dem.coupling_interval: must be a whole number, got '2.5'")) << q[0];
}

TEST(Config, OutOfRangeValuesAreReported) {
  const auto p = problems_of(replaced(replaced(kValid, "diameter: 0.0025", "diameter: -0.0025"), "floor: 0.3", "floor: 1"));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_TRUE(contains(p, "particles.diameter: value -0.0025 is out of range [1e-09, 1]"));
  EXPECT_TRUE(contains(p, "coupling.void_fraction.floor: value 1 leaves no room for particles"));
  const auto q = problems_of(replaced(kValid, "cube_factor: 1.2", "cube_factor: 0.7"));
  EXPECT_TRUE(contains(q, "coupling.void_fraction.cube_factor: value 0.7 is out of range [0.805996")) << q[0];
}

// .nan in any number is refused by name; checked with the floating-point trap OpenFOAM runs
// under (FOAM_SIGFPE), where comparing a NaN stops the process.
TEST(Config, NotANumberIsRefusedUnderTheTrap) {
  feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
  const auto p = problems_of(replaced(replaced(kValid, "density: 2526", "density: .nan"), "diameter: 0.0025",
                                      "diameter: [0.002, .NaN]"));
  fedisableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_TRUE(contains(p, "particles.diameter: must be a number or a list of numbers, got '.NaN' (not a number)")) << p[0];
  EXPECT_TRUE(contains(p, "particles.density: must be a number, got '.nan' (not a number)")) << p[1];
}

TEST(Config, UnclosedQuoteIsNamed) {
  const auto p = problems_of(replaced(kValid, "script: in.bed", "script: \"in.bed"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "case/coupling.yaml:8: a quote (\") opens here and is not closed")) << p[0];
  const auto q = problems_of(replaced(kValid, "script: in.bed", "script: 'in.bed"));
  ASSERT_EQ(q.size(), 1u);
  EXPECT_TRUE(contains(q, "case/coupling.yaml:8: a quote (') opens here")) << q[0];
  // quotes that close, an apostrophe inside a plain value and quotes in comments are fine
  EXPECT_TRUE(problems_of(replaced(kValid, "script: in.bed", "script: \"in.bed\"  # it's \"quoted\"")).empty());
  EXPECT_TRUE(problems_of(replaced(kValid, "script: in.bed", "script: bed's.in")).empty());
}

TEST(Config, CouplingIntervalLeftOutIsDerivedBySolver) {
  const auto c = parse_coupling_config("coupling.yaml", replaced(kValid, "  coupling_interval: 50\n", ""));
  EXPECT_EQ(static_cast<const LiggghtsSettings &>(*c.engine_settings).coupling_interval, 0);  // deltaT / the DEM step
}

// Optional keys are known when absent too: a misspelt one is answered with its name
TEST(Config, MisspeltOptionalKeysAreNamed) {
  const auto p = problems_of(replaced(kValid, "  coupling_interval: 50", "  coupling_intervall: 50"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "dem.coupling_intervall: unknown key (did you mean 'coupling_interval'?)")) << p[0];
  const auto q = problems_of(replaced(kValid, "    floor: 0.3", "    floor: 0.3\n    diffusion_bandwith: 0.01"));
  EXPECT_TRUE(contains(q, "diffusion_bandwith: unknown key (did you mean 'diffusion_bandwidth'?)")) << q[0];
}

const char *kHardSphere = R"(gas:
  density: 1.2
  viscosity: 1.8e-5
particles:
  diameter: [0.0015, 0.0025]
  density: 2526
dem:
  engine: hard_sphere
  particles: bed.data
  hard_sphere:
    restitution: [[0.97, 0.96], [0.96, 0.95]]
    tangential_restitution: 0.33
    friction: 0.1
    wall:
      restitution: [0.9, 0.8]
coupling:
  transfer: per_particle_conservative
)";

TEST(Config, HardSphereEngine) {
  const CouplingConfig c = parse_coupling_config("coupling.yaml", kHardSphere);
  EXPECT_EQ(c.engine, "hard_sphere");
  const auto &h = static_cast<const hard_sphere::HardSphereOptions &>(*c.engine_settings);
  EXPECT_EQ(h.particles, "bed.data");
  EXPECT_EQ(h.restitution, (std::vector<double>{0.97, 0.96, 0.96, 0.95}));  // row by row
  EXPECT_EQ(h.tangential_restitution, std::vector<double>{0.33});
  EXPECT_EQ(h.wall_restitution, (std::vector<double>{0.9, 0.8}));
  EXPECT_EQ(h.wall_friction, std::vector<double>{0.1});  // the particles' scalar
  EXPECT_DOUBLE_EQ(h.elastic_within, 1e-5);
  const CouplingConfig again = parse_coupling_config("described.yaml", describe(c));
  const auto &back = static_cast<const hard_sphere::HardSphereOptions &>(*again.engine_settings);
  EXPECT_EQ(back.restitution, h.restitution);
  EXPECT_EQ(back.wall_tangential_restitution, std::vector<double>{0.33});
}

// e_n = 0 is outside what binary collisions can run, for the particles and for the walls
TEST(Config, HardSphereZeroRestitutionIsRefusedWithItsReason) {
  const auto p = problems_of(replaced(kHardSphere, "restitution: [[0.97, 0.96], [0.96, 0.95]]", "restitution: 0"));
  ASSERT_EQ(p.size(), 1u) << p[0];
  EXPECT_TRUE(contains(p, "dem.hard_sphere.restitution: e_n = 0 leaves a pair that collided touching")) << p[0];
  const auto q = problems_of(replaced(kHardSphere, "restitution: [0.9, 0.8]", "restitution: [0.9, 0]"));
  ASSERT_EQ(q.size(), 1u) << q[0];
  EXPECT_TRUE(contains(q, "dem.hard_sphere.wall.restitution: e_n = 0")) << q[0];
}

TEST(Config, EachEngineRefusesTheOthersKeys) {
  const auto p = problems_of(replaced(kHardSphere, "  particles: bed.data\n", "  script: in.bed\n  coupling_interval: 10\n"));
  EXPECT_TRUE(contains(p, "dem.particles: missing (required)"));
  EXPECT_TRUE(contains(p, "dem.script: applies to the liggghts engine, not to dem.engine: hard_sphere"));
  EXPECT_TRUE(contains(p, "dem.coupling_interval: applies to the liggghts engine, not to dem.engine: hard_sphere"));
  const auto q = problems_of(replaced(kValid, "  coupling_interval: 50\n", "  coupling_interval: 50\n  particles: bed.data\n"));
  ASSERT_EQ(q.size(), 1u);
  EXPECT_TRUE(contains(q, "dem.particles: applies to the hard_sphere engine, not to dem.engine: liggghts")) << q[0];
  const auto r = problems_of(replaced(kHardSphere, "engine: hard_sphere", "engine: hardsphere"));
  EXPECT_TRUE(contains(r, "dem.engine: unknown value 'hardsphere' (did you mean 'hard_sphere'?)"));
}

TEST(Config, HardSphereCollisionModelChecked) {
  const auto p = problems_of(replaced(replaced(kHardSphere, "    friction: 0.1\n", ""), "tangential_restitution: 0.33",
                                      "tangential_restitution: 1.33"));
  EXPECT_TRUE(contains(p, "dem.hard_sphere.friction: missing (required)"));
  EXPECT_TRUE(contains(p, "dem.hard_sphere.tangential_restitution: value 1.33 is out of range [0, 1]"));
  // a matrix for the particles needs the walls' own value
  const auto q = problems_of(replaced(kHardSphere, "    wall:\n      restitution: [0.9, 0.8]\n", ""));
  ASSERT_EQ(q.size(), 1u);
  EXPECT_TRUE(contains(q, "dem.hard_sphere.wall.restitution: missing: the particles' restitution is a matrix")) << q[0];
}

TEST(Config, UnknownChoicesListValidOnes) {
  const auto p = problems_of(replaced(kValid, "drag_law: beetstra", "drag_law: wen_yu"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "coupling.drag_law: unknown value 'wen_yu'")) << p[0];
  EXPECT_TRUE(contains(p, "'ergun_wen_yu'")) << p[0];
}

TEST(Config, DuplicateKeysAreReportedWithBothLines) {
  const auto p = problems_of(replaced(kValid, "  coupling_interval: 50\n", "  coupling_interval: 50\n  coupling_interval: 20\n"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "case/coupling.yaml:10:3: dem.coupling_interval: given twice (first at case/coupling.yaml:9:3)"))
      << p[0];
}

TEST(Config, OutputSection) {
  const CouplingConfig defaults = parse_coupling_config("coupling.yaml", kValid);
  EXPECT_EQ(defaults.output.statistics_interval, 0.0);
  EXPECT_TRUE(defaults.output.particles_vtk);
  const CouplingConfig c = parse_coupling_config(
      "coupling.yaml", std::string(kValid) + "output:\n  statistics_interval: 0.01\n  particles_vtk: false\n");
  EXPECT_DOUBLE_EQ(c.output.statistics_interval, 0.01);
  EXPECT_FALSE(c.output.particles_vtk);
  const auto q = problems_of(std::string(kValid) + "output:\n  statistic_interval: 0.01\n");
  EXPECT_TRUE(contains(q, "output.statistic_interval: unknown key (did you mean 'statistics_interval'?)")) << q[0];
}

TEST(Config, GasVelocityAtParticle) {
  const CouplingConfig c = parse_coupling_config(
      "coupling.yaml", replaced(kValid, "  drag_law: beetstra", "  drag_law: beetstra\n  gas_velocity_at_particle: interpolated"));
  EXPECT_EQ(c.transfer.gas_velocity, GasAtParticle::Interpolated);
  EXPECT_EQ(parse_coupling_config("coupling.yaml", kValid).transfer.gas_velocity, GasAtParticle::Cell);
  const auto p = problems_of(replaced(replaced(kValid, "transfer: per_particle", "transfer: averaged"), "  drag_law: beetstra",
                                      "  drag_law: beetstra\n  gas_velocity_at_particle: interpolated"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "coupling.gas_velocity_at_particle: 'interpolated' applies to the per-particle transfers")) << p[0];
}

// The diffusion smoothing's bandwidth: a length in metres above 0, with a per-particle
// transfer; left out, none; kept by describe().
TEST(Config, DiffusionBandwidth) {
  const auto with = [](const std::string &value) {
    return replaced(kValid, "    floor: 0.3", "    floor: 0.3\n    diffusion_bandwidth: " + value);
  };
  EXPECT_DOUBLE_EQ(parse_coupling_config("coupling.yaml", with("0.01")).void_fraction.diffusion_bandwidth, 0.01);
  EXPECT_DOUBLE_EQ(parse_coupling_config("coupling.yaml", kValid).void_fraction.diffusion_bandwidth, 0.0);
  const std::string described = describe(parse_coupling_config("coupling.yaml", with("0.0125")));
  EXPECT_DOUBLE_EQ(parse_coupling_config("described.yaml", described).void_fraction.diffusion_bandwidth, 0.0125);
  for (const std::string bad : {"0", "-0.01"}) {
    const auto p = problems_of(with(bad));
    ASSERT_EQ(p.size(), 1u) << bad;
    EXPECT_TRUE(contains(p, "coupling.void_fraction.diffusion_bandwidth: value " + bad +
                                " is not a bandwidth: give a length above 0 in metres"))
        << p[0];
  }
  for (const std::string bad : {"1 cm", "4 d_p", ".nan"}) {
    const auto p = problems_of(with(bad));
    ASSERT_EQ(p.size(), 1u) << bad;
    EXPECT_TRUE(contains(p, "coupling.void_fraction.diffusion_bandwidth: must be a length in metres, a plain number "
                            "(e.g. 0.01 for 1 cm), got '" + bad + "'"))
        << p[0];
  }
  const auto averaged = problems_of(replaced(with("0.01"), "transfer: per_particle", "transfer: averaged"));
  ASSERT_EQ(averaged.size(), 1u);
  EXPECT_TRUE(contains(averaged, "coupling.void_fraction.diffusion_bandwidth: the filtered fields need a per-particle "
                                 "transfer"))
      << averaged[0];
  EXPECT_TRUE(contains(averaged, "use transfer: per_particle_conservative")) << averaged[0];
}

// The particle-field block: three whole numbers >= 1 (whether they divide the mesh is the
// filter's check); left out, the gas cells; kept by describe(); with a per-particle transfer.
TEST(Config, ParticleFieldBlock) {
  const auto with = [](const std::string &value) {
    return replaced(kValid, "    floor: 0.3", "    floor: 0.3\n    particle_field_block: " + value);
  };
  EXPECT_EQ(parse_coupling_config("coupling.yaml", with("[1, 2, 1]")).void_fraction.particle_field_block,
            (std::array<int, 3>{1, 2, 1}));
  EXPECT_EQ(parse_coupling_config("coupling.yaml", kValid).void_fraction.particle_field_block,
            (std::array<int, 3>{1, 1, 1}));
  EXPECT_FALSE(parse_coupling_config("coupling.yaml", kValid).void_fraction.filters());
  const std::string described = describe(parse_coupling_config("coupling.yaml", with("[2, 4, 1]")));
  EXPECT_EQ(parse_coupling_config("described.yaml", described).void_fraction.particle_field_block,
            (std::array<int, 3>{2, 4, 1}));
  for (const std::string bad : {"[1, 2]", "[1, 1.5, 1]", "2"}) {
    const auto p = problems_of(with(bad));
    ASSERT_EQ(p.size(), 1u) << bad;
    EXPECT_TRUE(contains(p, "coupling.void_fraction.particle_field_block: must be three whole numbers of 1 or more"))
        << p[0];
  }
  const auto zero = problems_of(with("[0, 1, 1]"));
  ASSERT_FALSE(zero.empty());
  EXPECT_TRUE(contains(zero, "coupling.void_fraction.particle_field_block: value 0 is out of range")) << zero[0];
  const auto averaged = problems_of(replaced(with("[1, 2, 1]"), "transfer: per_particle", "transfer: averaged"));
  ASSERT_EQ(averaged.size(), 1u);
  EXPECT_TRUE(contains(averaged, "coupling.void_fraction.particle_field_block: the filtered fields need a "
                                 "per-particle transfer"))
      << averaged[0];
}

// A mixture lists its sizes (sorted); a bad entry is named; Beetstra's polydisperse drag needs a
// per-particle transfer.
TEST(Config, MixtureSizesAndPolydisperseDrag) {
  const std::string mixture = replaced(kValid, "  diameter: 0.0025", "  diameter: [0.0025, 0.0015]");
  const CouplingConfig c = parse_coupling_config(
      "coupling.yaml", replaced(mixture, "  drag_law: beetstra", "  drag_law: beetstra\n  polydisperse_drag: beetstra_2007"));
  EXPECT_EQ(c.particle_diameters, (std::vector<double>{0.0015, 0.0025}));
  EXPECT_EQ(c.transfer.polydispersity, drag::Polydispersity::Beetstra2007);
  EXPECT_EQ(parse_coupling_config("coupling.yaml", kValid).transfer.polydispersity, drag::Polydispersity::OwnDiameter);
  auto p = problems_of(replaced(kValid, "  diameter: 0.0025", "  diameter: [0.0025, big]"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "particles.diameter: must be a number or a list of numbers, got 'big'")) << p[0];
  p = problems_of(replaced(replaced(kValid, "transfer: per_particle", "transfer: averaged"), "  drag_law: beetstra",
                           "  drag_law: beetstra\n  polydisperse_drag: beetstra_2007"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "coupling.polydisperse_drag: 'beetstra_2007' gives each particle its own drag")) << p[0];
  EXPECT_TRUE(contains(p, "use transfer: per_particle_conservative")) << p[0];
}

TEST(Config, Outlets) {
  EXPECT_TRUE(parse_coupling_config("coupling.yaml", kValid).outlets.empty());
  const CouplingConfig c =
      parse_coupling_config("coupling.yaml", replaced(kValid, "  coupling_interval: 50\n", "  coupling_interval: 50\n  outlets: [top, side]\n"));
  EXPECT_EQ(c.outlets, (std::vector<std::string>{"top", "side"}));
  const auto p = problems_of(replaced(kValid, "  coupling_interval: 50\n", "  coupling_interval: 50\n  outlets: {top: 1}\n"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(contains(p, "dem.outlets: must be a name or a list of names")) << p[0];
}

TEST(Config, MissingFileIsNamed) {
  try {
    load_coupling_config("/nonexistent/coupling.yaml");
    FAIL();
  } catch (const ConfigError &e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/coupling.yaml: cannot open"), std::string::npos);
  }
}

// The reference (docs/src/reference/coupling-yaml.md) is written from these records: every key
// the parser reads carries a description and a type, the engines' keys their condition, and the
// keys the docs once missed are among them with their defaults as config.cpp's readers set them
TEST(Config, ReferenceDescribesEveryKey) {
  const std::vector<KeyRecord> keys = coupling_reference();
  std::map<std::string, const KeyRecord *> by_path;
  for (const KeyRecord &k : keys) {
    by_path[k.path] = &k;
    if (k.kind == "a section") continue;
    EXPECT_FALSE(k.doc.empty()) << k.path << " has no description";
    EXPECT_FALSE(k.kind.empty()) << k.path << " has no type";
  }
  const std::map<std::string, std::string> defaults = {
      {"coupling.drag_law", "ergun_wen_yu"},
      {"coupling.pressure_gradient_force", "true"},
      {"coupling.void_fraction_time_derivative", "true"},
      {"coupling.void_fraction.cube_factor", "1"},
      {"coupling.void_fraction.divided_points_per_diameter", "6"},
      {"dem.hard_sphere.max_collisions_per_particle", "10000"},
      {"dem.engine", "liggghts"}};
  for (const auto &[path, fallback] : defaults) {
    ASSERT_TRUE(by_path.count(path)) << path << " missing from the reference";
    EXPECT_EQ(by_path[path]->fallback, fallback) << path;
  }
  EXPECT_EQ(by_path["dem.hard_sphere.restitution"]->condition, "dem.engine: hard_sphere");
  EXPECT_EQ(by_path["dem.script"]->condition, "dem.engine: liggghts");
  EXPECT_EQ(by_path["gas.density"]->unit, "kg/m^3");
}

}  // namespace
