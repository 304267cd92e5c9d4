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

#include <string>
#include <vector>

#include "tfdem/config.h"
#include "tfdem/hard_sphere/event_flight.h"
#include "tfdem/particle_engine.h"

namespace tfdem::hard_sphere {

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
