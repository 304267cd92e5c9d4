// fix tfdem/coupling: per-atom fluid force set by the coupling side, applied every DEM step;
// on request, each atom's contact force and coordination number N_c at the end of a run.
//
// Syntax:  fix ID group-ID tfdem/coupling [weight_fraction f gravity gx gy gz]
//   weight_fraction f  stand-alone DEM use: every atom's stored fluid force starts as
//                      -f m g (f = 1 cancels gravity, f = 0.5 halves it); needs `gravity`.
//   gravity gx gy gz   gravitational acceleration vector in m/s^2.
// Per-atom array (it moves with its atom between ranks; dumps read f_ID[1..7]):
//   1-3 fluid force (N), as last set by the coupler;
//   4-6 contact force (N) at the last sample: the sum of the pair and wall contact forces
//       (seed 000 eq. 15 and 23: what LIGGGHTS added before this fix, less the gravity of
//       any fix gravity defined before it; define the walls before this fix);
//   7   N_c at the last sample: touching neighbour particles (overlap > 0, seed 000 eq. 17).
// The fluid force is saved in restart files, so a resumed run applies the same held force.

#ifdef FIX_CLASS
FixStyle(tfdem/coupling,FixTfdemCoupling)
#else

#ifndef TFDEM_FIX_TFDEM_COUPLING_H
#define TFDEM_FIX_TFDEM_COUPLING_H

#include "fix.h"

namespace LAMMPS_NS {

class FixTfdemCoupling : public Fix {
 public:
  FixTfdemCoupling(class LAMMPS *lmp, int narg, char **arg);
  ~FixTfdemCoupling() override;
  int setmask() override;
  void init() override;
  void setup(int vflag) override;
  void post_force(int vflag) override;
  void grow_arrays(int nmax) override;
  void copy_arrays(int i, int j, int delflag) override;
  int pack_exchange(int i, double *buf) override;
  int unpack_exchange(int nlocal, double *buf) override;
  int pack_restart(int i, double *buf) override;
  void unpack_restart(int nlocal, int nth) override;
  int size_restart(int nlocal) override;
  int maxsize_restart() override;
  double memory_usage() override;

  // Fluid force on local atom i (N), as last set by the coupling side.
  double *fluid_force(int i) { return values_[i] + kFluidForce; }
  // Sample contact forces and N_c at the end of DEM step `step` (the last of the next run).
  void sample_contacts_at(bigint step) { sample_step_ = step; }
  // Contact force (3) and N_c of local atom i at the last sample.
  const double *contact_force(int i) const { return values_[i] + kContactForce; }
  int coordination(int i) const { return static_cast<int>(values_[i][kCoordination]); }

  // Columns of the per-atom array.
  static constexpr int kFluidForce = 0, kContactForce = 3, kCoordination = 6, kColumns = 7;

 private:
  void parse_arguments(int narg, char **arg);
  void set_scaled_weight();
  void sample_contacts();
  void count_touching_neighbours();

  double **values_ = nullptr;
  double weight_fraction_ = 0.0;
  double gravity_[3] = {0.0, 0.0, 0.0};
  // Gravity of the fix gravity commands before this fix (in the force when post_force runs).
  double gravity_before_[3] = {0.0, 0.0, 0.0};
  bigint sample_step_ = -1;
  bool has_weight_fraction_ = false;
  bool has_gravity_ = false;
  bool initialised_ = false;
};

}  // namespace LAMMPS_NS

#endif
#endif
