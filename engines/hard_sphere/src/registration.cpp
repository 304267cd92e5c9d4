// The hard-sphere engine registered as dem.engine: hard_sphere, with its keys of the dem section.
#include <mpi.h>

#include <algorithm>
#include <memory>
#include <utility>

#include "tfdem/engine_registry.h"
#include "tfdem/hard_sphere/engine.h"

namespace tfdem::hard_sphere {
namespace {

std::unique_ptr<ParticleEngine> start(const EngineStart &start) {
  int ranks = 1;
  MPI_Comm_size(MPI_Comm_f2c(start.communicator), &ranks);
  if (ranks > 1)
    throw std::runtime_error("dem.engine: hard_sphere runs on one rank (its event-driven collisions are processed one "
                             "after another), not on " + std::to_string(ranks) +
                             ": run tfdemFoam without mpirun, or use dem.engine: liggghts");
  const auto &options = static_cast<const HardSphereOptions &>(*start.config->engine_settings);
  return std::make_unique<HardSphereEngine>(options, options.particles, start.gravity, start.resume);
}

}  // namespace

std::shared_ptr<const EngineSettings> read_options(ConfigSection &dem) {
  auto o = std::make_shared<HardSphereOptions>();
  o->particles = dem.text({"particles", "", "the particles' LIGGGHTS data file (atom_style granular), relative to the "
                                           "case; its box's faces are the walls"},
                          "", true);
  ConfigSection section = dem.section({"hard_sphere", "", "the collision model (seed 001 eqs. 17-21)"}, true);
  o->restitution = section.number_table(
      {"restitution", "", "normal restitution e_n of every pair of types (one value, or a matrix row by row)"}, {}, 0, 1,
      true);
  o->tangential_restitution = section.number_table(
      {"tangential_restitution", "", "tangential restitution beta_0 of every pair (one value, or a matrix)"}, {}, 0, 1,
      true);
  o->friction = section.number_table({"friction", "", "Coulomb friction mu of every pair (one value, or a matrix)"}, {},
                                     0, 1e3, true);
  ConfigSection wall = section.section({"wall", "", "the walls' collision model; left out, the particles' own"});
  const auto own = [](const std::vector<double> &particles) {
    return particles.size() == 1 ? particles : std::vector<double>{};
  };
  o->wall_restitution = wall.number_table(
      {"restitution", "", "a wall's e_n against each type (one value, or one per type)"}, own(o->restitution), 0, 1);
  o->wall_tangential_restitution = wall.number_table(
      {"tangential_restitution", "", "a wall's beta_0 against each type"}, own(o->tangential_restitution), 0, 1);
  o->wall_friction =
      wall.number_table({"friction", "", "a wall's mu against each type"}, own(o->friction), 0, 1e3);
  for (auto [where, values] : {std::pair{&section, &o->restitution}, std::pair{&wall, &o->wall_restitution}})
    if (std::any_of(values->begin(), values->end(), [](double e) { return e == 0; }))
      where->report("restitution", "e_n = 0 leaves a pair that collided touching and at rest against each other, "
                                   "which binary collisions cannot part (each later contact is a collision at zero "
                                   "gap, without end): give e_n above 0 (glass on glass 0.9-0.97)");
  for (const auto &[key, values] : {std::pair{"restitution", &o->wall_restitution},
                                    std::pair{"tangential_restitution", &o->wall_tangential_restitution},
                                    std::pair{"friction", &o->wall_friction}})
    if (values->empty() && !wall.has(key) && !wall.is_schema())
      wall.report(key, std::string("missing: the particles' ") + key + " is a matrix, so the walls' needs its " +
                           "own value (one, or one per type)");
  wall.reject_unknown_keys();
  o->elastic_within = section.number(
      {"elastic_within", "s", "TC model (Luding & McNamara 1998): a collision this soon after either particle's last "
                              "is elastic and smooth (0: off)"},
      o->elastic_within, 0, 1);
  o->tc_keeps_friction = section.boolean(
      {"tc_keeps_friction", "", "the TC model's collisions elastic in the normal direction only, keeping the pair's "
                                "friction and tangential restitution (false: elastic and smooth, as Luding & "
                                "McNamara's)"},
      o->tc_keeps_friction);
  o->max_collisions_per_particle = section.integer(
      {"max_collisions_per_particle", "", "collisions per particle in one flow step past which the run stops "
                                          "(inelastic collapse)"},
      o->max_collisions_per_particle, 1, 100000000);
  o->contact_gap = section.number(
      {"contact_gap", "", "N_c counts the pairs closer than this fraction of their mean diameter"}, o->contact_gap, 0,
      1);
  o->move = section.boolean({"move", "", "false: the particles stay where they are (a fixed bed)"}, o->move);
  section.reject_unknown_keys();
  return o;
}

TFDEM_ENGINE(hard_sphere, "event-driven hard spheres (seed 001 sec. 3.3), one rank", read_options, start);

}  // namespace tfdem::hard_sphere
