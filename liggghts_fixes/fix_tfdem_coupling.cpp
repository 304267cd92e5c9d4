#include "fix_tfdem_coupling.h"

#include <cstdlib>
#include <string>
#include <vector>

#include "atom.h"
#include "error.h"
#include "memory.h"
#include "tfdem/particle_forces.h"
#include "tfdem/suggest.h"

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {

// Stop LIGGGHTS with `message` (error->all prints it on rank 0 and exits on every rank).
void fail(Error *error, const std::string &message) { error->all(FLERR, message.c_str()); }

// Parse a floating-point argument or stop with a message naming it.
double parse_double(Error *error, const char *keyword, const char *text) {
  char *end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0')
    fail(error, std::string("fix tfdem/coupling: argument of '") + keyword + "' must be a number, got '" + text + "'");
  return value;
}

}  // namespace

// Parse arguments, register the per-atom array and its callbacks.
FixTfdemCoupling::FixTfdemCoupling(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg) {
  parse_arguments(narg, arg);
  if (!atom->rmass_flag)
    error->all(FLERR, "fix tfdem/coupling needs per-atom mass (atom_style sphere or granular)");
  peratom_flag = 1;
  size_peratom_cols = kValuesPerAtom;
  peratom_freq = 1;
  grow_arrays(atom->nmax);
  atom->add_callback(0);
  for (int i = 0; i < atom->nmax; ++i)
    for (int k = 0; k < kValuesPerAtom; ++k) fluid_force_[i][k] = 0.0;
}

// Unregister the callbacks and free the per-atom array.
FixTfdemCoupling::~FixTfdemCoupling() {
  atom->delete_callback(id, 0);
  memory->destroy(fluid_force_);
}

// Read the optional keywords; any unknown or incomplete one is an error naming it.
void FixTfdemCoupling::parse_arguments(int narg, char **arg) {
  int iarg = 3;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (key == "weight_fraction") {
      if (iarg + 1 >= narg) error->all(FLERR, "fix tfdem/coupling: 'weight_fraction' needs a value");
      weight_fraction_ = parse_double(error, "weight_fraction", arg[iarg + 1]);
      has_weight_fraction_ = true;
      iarg += 2;
    } else if (key == "gravity") {
      if (iarg + 3 >= narg) error->all(FLERR, "fix tfdem/coupling: 'gravity' needs three values gx gy gz");
      for (int k = 0; k < 3; ++k) gravity_[k] = parse_double(error, "gravity", arg[iarg + 1 + k]);
      has_gravity_ = true;
      iarg += 4;
    } else {
      const std::vector<std::string> keywords = {"weight_fraction", "gravity"};
      fail(error, "fix tfdem/coupling: unknown argument '" + key + "'" + tfdem::did_you_mean(key, keywords) +
                      "; valid keywords: " + tfdem::quoted_list(keywords));
    }
  }
  if (has_weight_fraction_ && !has_gravity_)
    error->all(FLERR, "fix tfdem/coupling: 'weight_fraction' needs 'gravity gx gy gz' as well");
}

// Hooks: the fluid force is added after pair and wall forces.
int FixTfdemCoupling::setmask() { return POST_FORCE; }

// At the first run, set the stand-alone force; then add the stored force once.
void FixTfdemCoupling::setup(int vflag) {
  if (has_weight_fraction_ && !initialised_) set_scaled_weight();
  initialised_ = true;
  post_force(vflag);
}

// Stand-alone mode: fluid force = -f m g for every local atom of the group.
void FixTfdemCoupling::set_scaled_weight() {
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; ++i) {
    if (!(atom->mask[i] & groupbit)) continue;
    tfdem::scaled_weight_counterforce(atom->rmass[i], gravity_, weight_fraction_, fluid_force_[i]);
  }
}

// Add the stored fluid force of each local atom of the group to its total force.
void FixTfdemCoupling::post_force(int) {
  double **f = atom->f;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; ++i) {
    if (!(mask[i] & groupbit)) continue;
    f[i][0] += fluid_force_[i][0];
    f[i][1] += fluid_force_[i][1];
    f[i][2] += fluid_force_[i][2];
  }
}

// Grow the per-atom array to nmax atoms.
void FixTfdemCoupling::grow_arrays(int nmax) {
  memory->grow(fluid_force_, nmax, kValuesPerAtom, "tfdem/coupling:fluid_force");
  array_atom = fluid_force_;
}

// Copy atom i's values to slot j (atom sorting and deletion).
void FixTfdemCoupling::copy_arrays(int i, int j, int) {
  for (int k = 0; k < kValuesPerAtom; ++k) fluid_force_[j][k] = fluid_force_[i][k];
}

// Pack atom i's values for migration to another rank.
int FixTfdemCoupling::pack_exchange(int i, double *buf) {
  for (int k = 0; k < kValuesPerAtom; ++k) buf[k] = fluid_force_[i][k];
  return kValuesPerAtom;
}

// Unpack a migrated atom's values into slot nlocal.
int FixTfdemCoupling::unpack_exchange(int nlocal, double *buf) {
  for (int k = 0; k < kValuesPerAtom; ++k) fluid_force_[nlocal][k] = buf[k];
  return kValuesPerAtom;
}

// Bytes held by the per-atom array.
double FixTfdemCoupling::memory_usage() {
  return static_cast<double>(atom->nmax) * kValuesPerAtom * sizeof(double);
}
