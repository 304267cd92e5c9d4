// fix tfdem/coupling: per-atom fluid force set by the coupling side, applied every DEM step.
//
// Syntax:  fix ID group-ID tfdem/coupling [weight_fraction f gravity gx gy gz]
//   weight_fraction f  stand-alone DEM use: every atom's stored fluid force starts as
//                      -f m g (f = 1 cancels gravity, f = 0.5 halves it); needs `gravity`.
//   gravity gx gy gz   gravitational acceleration vector in m/s^2.
// The stored force is a per-atom array: it moves with its atom between ranks, and dumps
// read it as f_ID[1..3].

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
  void setup(int vflag) override;
  void post_force(int vflag) override;
  void grow_arrays(int nmax) override;
  void copy_arrays(int i, int j, int delflag) override;
  int pack_exchange(int i, double *buf) override;
  int unpack_exchange(int nlocal, double *buf) override;
  double memory_usage() override;

  // Fluid force on local atom i (N), as last set by the coupling side.
  double *fluid_force(int i) { return fluid_force_[i]; }
  // Number of doubles stored per atom.
  static constexpr int kValuesPerAtom = 3;

 private:
  void parse_arguments(int narg, char **arg);
  void set_scaled_weight();

  double **fluid_force_ = nullptr;
  double weight_fraction_ = 0.0;
  double gravity_[3] = {0.0, 0.0, 0.0};
  bool has_weight_fraction_ = false;
  bool has_gravity_ = false;
  bool initialised_ = false;
};

}  // namespace LAMMPS_NS

#endif
#endif
