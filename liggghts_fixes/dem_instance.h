// A LIGGGHTS instance run in-process by the coupler, with TFDEM's fixes registered.
// Exposes plain arrays only, so callers need no LIGGGHTS headers (and OpenFOAM code can use
// it without name clashes).
#ifndef TFDEM_DEM_INSTANCE_H
#define TFDEM_DEM_INSTANCE_H

#include <mpi.h>

#include <cstddef>
#include <string>

namespace LAMMPS_NS {
class LAMMPS;
class FixTfdemCoupling;
}  // namespace LAMMPS_NS

namespace tfdem {

class DemInstance {
 public:
  // Start LIGGGHTS on `comm` in `directory`, log to log_file (screen output to
  // log_file + ".screen"), register our fixes and run `script` (which must set up the
  // particles and one `fix tfdem/coupling`, and not `run`). Throws std::runtime_error naming
  // a missing script or a script without the coupling fix.
  DemInstance(MPI_Comm comm, const std::string &script, const std::string &log_file);
  ~DemInstance();
  DemInstance(const DemInstance &) = delete;
  DemInstance &operator=(const DemInstance &) = delete;

  // Advance `steps` DEM steps (LIGGGHTS `run`, set-up only the first time). With no
  // particles and no insertion fix there is nothing to advance (and LIGGGHTS 3.8.0 stops
  // with "Atom types must start from 1"), so nothing runs.
  void run(long steps);
  // True when the script has a particle insertion fix (style insert/*).
  bool inserts_particles() const;
  // Run one LIGGGHTS command (e.g. output set-up from the coupler).
  void command(const std::string &line);
  double time_step() const;
  // Particles on this rank and their per-atom arrays (x, v: 3 per atom; radius, mass: 1).
  std::size_t local_count() const;
  const double *positions() const;
  const double *velocities() const;
  const double *radii() const;
  const double *masses() const;
  // Atom IDs of the local particles.
  const int *tags() const;
  // Fluid force applied to each local particle every DEM step until set again (3 per atom).
  double *fluid_force();
  // Total particles over all ranks.
  long global_count() const;

  // Particle-particle (type 1) normal contact parameters of a linear model, as the script set
  // them with fix property/global: stiffness k_n (N/m) and either absolute damping eta_n
  // (N s/m, gamman_abs) or restitution e_n (coefficientRestitution). False when k_n is absent
  // (e.g. a Hertz model).
  struct LinearContact {
    double stiffness = 0.0;
    double damping = -1.0;      // < 0 when not given
    double restitution = -1.0;  // < 0 when not given
  };
  bool linear_contact(LinearContact &out) const;

 private:
  LAMMPS_NS::LAMMPS *lmp_ = nullptr;
  LAMMPS_NS::FixTfdemCoupling *fix_ = nullptr;
  bool set_up_ = false;
};

}  // namespace tfdem

#endif
