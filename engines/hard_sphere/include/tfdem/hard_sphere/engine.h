// The hard-sphere engine as the coupler's particle engine (coupling.yaml dem.engine:
// hard_sphere): the particles of a LIGGGHTS data file in the box of its header, with a wall on
// every face (an outlet opens its face), collisions by seed 001 eqs. 11-21 (EventFlight).
//
// The external forces (gravity and the fluid force the coupling holds over the flow step)
// enter as half a kick at each end of the step, v += (g + F/m) dt/2, with the event-driven
// flight in between (kick-drift-kick): between collisions that is the exact parabola of a
// constant force (x gains v dt + a dt^2/2, v gains a dt); a collision sees the velocity of the
// half kick, so its impact speed is off by at most a dt/2 (Hoomans et al. 1996 apply the
// whole impulse at the step's start, an error twice as large).
//
// A fresh start takes the data file's overlaps (a soft-sphere packing's) as touching where
// they are (EventFlight::tolerate_overlaps), so the packing is kept exactly.
//
// One rank (serial); N_c counts the pairs closer than contact_gap of their mean diameter, and
// a particle's contact force is its collisions' impulse over the last step divided by the
// step (their mean force).
#ifndef TFDEM_HARD_SPHERE_ENGINE_H
#define TFDEM_HARD_SPHERE_ENGINE_H

#include <memory>
#include <string>
#include <vector>

#include "tfdem/config.h"
#include "tfdem/hard_sphere/event_flight.h"
#include "tfdem/particle_engine.h"

namespace tfdem::hard_sphere {

// The hard-sphere engine's keys of coupling.yaml's dem section: the particles' data file and
// the collision model (dem.hard_sphere; seed 001 eqs. 17-21): normal restitution e_n,
// tangential restitution beta_0 and friction mu, between particle types (one value for every
// pair, or an n x n matrix row by row) and against the walls (one value, or one per type; the
// particles' own when the scalar is given and dem.hard_sphere.wall is absent).
struct HardSphereOptions : EngineSettings {
  std::string particles;  // the particles' LIGGGHTS data file, relative to the case
  std::vector<double> restitution, tangential_restitution, friction;
  std::vector<double> wall_restitution, wall_tangential_restitution, wall_friction;
  // TC model (Luding & McNamara 1998): a collision within this many seconds of either
  // particle's previous one is elastic and smooth (0: off)
  double elastic_within = 1e-5;
  // The TC model's collisions keep the pair's friction and tangential restitution (e_n = 1 only)
  bool tc_keeps_friction = false;
  // Collisions per particle in one flow step above which the run stops (inelastic collapse)
  long max_collisions_per_particle = 10000;
  // N_c counts the pairs closer than this fraction of their mean diameter (hard spheres
  // touch only at the instant they collide)
  double contact_gap = 0.01;
  // false: the particles stay where they are (a fixed bed, as a LIGGGHTS script without
  // time integration)
  bool move = true;
};

// The dem section's hard-sphere keys (their part of the configuration reference)
std::shared_ptr<const EngineSettings> read_options(ConfigSection &dem);

class HardSphereEngine : public ParticleEngine {
 public:
  // The particles of `data_file` (relative to the working directory, the case), or, resumed,
  // of the restart file; gravity g (m/s^2). Throws std::runtime_error naming the file and
  // the problem (unreadable, collision laws that do not fit its atom types, a restart that
  // is not this engine's).
  HardSphereEngine(const HardSphereOptions &options, const std::string &data_file, const double gravity[3],
                   const DemResume *resume = nullptr);

  std::string name() const override { return "the hard-sphere engine"; }
  std::string key() const override { return "hard_sphere"; }
  // The particles, the flow step and gravity, and the data file's overlaps taken as touching
  StartReport check_start(const CaseAtStart &context) const override;
  // The collisions of the run
  std::string end_report() const override;
  std::string kept_overlaps_warning(double deepest) const override;
  void advance(double seconds, bool sample_contacts) override;
  long long step() const override { return step_; }
  double time() const override { return flight_.clock(); }

  std::size_t local_count() const override { return flight_.size(); }
  long global_count() const override { return static_cast<long>(flight_.size()); }
  const double *positions() const override { return flat(flight_.position); }
  const double *velocities() const override { return flat(flight_.velocity); }
  const double *radii() const override { return flight_.radius.data(); }
  const double *masses() const override { return flight_.mass.data(); }
  const int *tags() const override { return tags_.data(); }
  const int *types() const override { return types_.data(); }
  int type_count() const override { return type_count_; }

  void set_fluid_force(const std::vector<double> &force) override;
  void contact_sample(std::vector<double> &force, std::vector<int> &coordination) const override;
  void remove_particles(const std::vector<int> &tags) override;
  // Binary: a header (magic, version, counts, clock), then every particle's state
  bool write_restart(const std::string &path) override;

  Box box() const override;
  void open_outlet(int axis, int side) override;

  // Collisions since the start of this run (for the report and the bench)
  const FlightCounts &totals() const { return totals_; }
  // The data file's overlaps, taken as touching where they are (EventFlight::tolerate_overlaps)
  const EventFlight::Overlaps &overlaps() const { return overlaps_; }

 private:
  static const double *flat(const std::vector<Vec3> &v) { return &v.data()->x; }
  void read_restart(const DemResume &resume, const HardSphereOptions &options);
  void set_laws(const HardSphereOptions &options, const std::string &source);
  void sample_contacts(double seconds);

  EventFlight flight_;
  std::vector<int> tags_, types_;
  std::vector<Vec3> fluid_force_;
  std::vector<double> contact_force_;
  std::vector<int> coordination_;
  Vec3 gravity_;
  double contact_gap_ = 0;
  bool move_ = true;
  int type_count_ = 0;
  long long step_ = 0;
  FlightCounts totals_;
  EventFlight::Overlaps overlaps_;
};

}  // namespace tfdem::hard_sphere

#endif
