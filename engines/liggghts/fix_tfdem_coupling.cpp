#include "fix_tfdem_coupling.h"

#include <cstdlib>
#include <string>
#include <vector>

#include "atom.h"
#include "error.h"
#include "fix_gravity.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "pair.h"
#include "update.h"
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
  size_peratom_cols = kColumns;
  peratom_freq = 1;
  restart_peratom = 1;
  grow_arrays(atom->nmax);
  atom->add_callback(0);
  atom->add_callback(1);
  for (int i = 0; i < atom->nmax; ++i)
    for (int k = 0; k < kColumns; ++k) values_[i][k] = 0.0;
}

// Unregister the callbacks and free the per-atom array.
FixTfdemCoupling::~FixTfdemCoupling() {
  atom->delete_callback(id, 0);
  atom->delete_callback(id, 1);
  memory->destroy(values_);
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

// Gravity that the fix gravity commands defined before this one add to the force before
// post_force() runs here (subtracted from the force to leave the contacts).
void FixTfdemCoupling::init() {
  const int me = modify->find_fix(id);
  for (int k = 0; k < 3; ++k) gravity_before_[k] = 0.0;
  for (int f = 0; f < me; ++f) {
    if (std::string(modify->fix[f]->style) != "gravity") continue;
    double g[3];
    static_cast<FixGravity *>(modify->fix[f])->get_gravity(g);
    for (int k = 0; k < 3; ++k) gravity_before_[k] += g[k];
  }
}

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
    tfdem::scaled_weight_counterforce(atom->rmass[i], gravity_, weight_fraction_, fluid_force(i));
  }
}

// Add the stored fluid force of each local atom of the group to its total force (after a
// contact sample, when one is due at this step).
void FixTfdemCoupling::post_force(int) {
  if (update->ntimestep == sample_step_) sample_contacts();
  double **f = atom->f;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; ++i) {
    if (!(mask[i] & groupbit)) continue;
    const double *fluid = fluid_force(i);
    f[i][0] += fluid[0];
    f[i][1] += fluid[1];
    f[i][2] += fluid[2];
  }
}

// Contact force = force so far less the gravity added before this fix; then N_c.
void FixTfdemCoupling::sample_contacts() {
  const double *const *f = atom->f;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; ++i)
    for (int k = 0; k < 3; ++k) values_[i][kContactForce + k] = f[i][k] - atom->rmass[i] * gravity_before_[k];
  count_touching_neighbours();
}

// N_c of every local atom from the granular pair style's half neighbour list: pairs that
// overlap, counted for both atoms when both are local. With newton off a pair whose second
// atom is a ghost is listed on both ranks, so every particle counts each neighbour once.
void FixTfdemCoupling::count_touching_neighbours() {
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; ++i) values_[i][kCoordination] = 0.0;
  const NeighList *list = force->pair ? force->pair->list : nullptr;
  if (!list) return;
  const double *const *x = atom->x;
  const double *radius = atom->radius;
  for (int ii = 0; ii < list->inum; ++ii) {
    const int i = list->ilist[ii];
    const int *neighbours = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; ++jj) {
      const int j = neighbours[jj] & NEIGHMASK;
      const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
      const double reach = radius[i] + radius[j];
      if (dx * dx + dy * dy + dz * dz >= reach * reach) continue;
      if (i < nlocal) values_[i][kCoordination] += 1.0;
      if (j < nlocal) values_[j][kCoordination] += 1.0;
    }
  }
}

// Grow the per-atom array to nmax atoms.
void FixTfdemCoupling::grow_arrays(int nmax) {
  memory->grow(values_, nmax, kColumns, "tfdem/coupling:values");
  array_atom = values_;
}

// Copy atom i's values to slot j (atom sorting and deletion).
void FixTfdemCoupling::copy_arrays(int i, int j, int) {
  for (int k = 0; k < kColumns; ++k) values_[j][k] = values_[i][k];
}

// Pack atom i's values for migration to another rank.
int FixTfdemCoupling::pack_exchange(int i, double *buf) {
  for (int k = 0; k < kColumns; ++k) buf[k] = values_[i][k];
  return kColumns;
}

// Unpack a migrated atom's values into slot nlocal.
int FixTfdemCoupling::unpack_exchange(int nlocal, double *buf) {
  for (int k = 0; k < kColumns; ++k) values_[nlocal][k] = buf[k];
  return kColumns;
}

// Restart record of atom i: its length, then the held fluid force (the samples are not kept).
int FixTfdemCoupling::pack_restart(int i, double *buf) {
  buf[0] = 4;
  for (int k = 0; k < 3; ++k) buf[1 + k] = values_[i][kFluidForce + k];
  return 4;
}

// Read the held fluid force of atom nlocal from the nth per-atom restart record.
void FixTfdemCoupling::unpack_restart(int nlocal, int nth) {
  const double *extra = atom->extra[nlocal];
  int m = 0;
  for (int k = 0; k < nth; ++k) m += static_cast<int>(extra[m]);
  for (int k = 0; k < 3; ++k) values_[nlocal][kFluidForce + k] = extra[m + 1 + k];
}

int FixTfdemCoupling::size_restart(int) { return 4; }

int FixTfdemCoupling::maxsize_restart() { return 4; }

// Bytes held by the per-atom array.
double FixTfdemCoupling::memory_usage() {
  return static_cast<double>(atom->nmax) * kColumns * sizeof(double);
}
