#include "dem_instance.h"

#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "atom.h"
#include "fix_property_global.h"
#include "fix_tfdem_coupling.h"
#include "input.h"
#include "lammps.h"
#include "modify.h"
#include "tfdem_liggghts.h"
#include "update.h"

namespace tfdem {

DemInstance::DemInstance(MPI_Comm comm, const std::string &script, const std::string &log_file) {
  if (!std::ifstream(script).good())
    throw std::runtime_error("DEM input script '" + script + "' not found or not readable");
  const std::string screen = log_file + ".screen";
  std::vector<std::string> args = {"tfdem", "-log", log_file, "-screen", screen, "-echo", "none"};
  std::vector<char *> argv;
  for (auto &a : args) argv.push_back(a.data());
  lmp_ = new LAMMPS_NS::LAMMPS(static_cast<int>(argv.size()), argv.data(), comm);
  register_fix_styles(lmp_);
  lmp_->input->file(script.c_str());
  for (int i = 0; i < lmp_->modify->nfix; ++i)
    if (std::strcmp(lmp_->modify->fix[i]->style, "tfdem/coupling") == 0)
      fix_ = static_cast<LAMMPS_NS::FixTfdemCoupling *>(lmp_->modify->fix[i]);
  if (!fix_)
    throw std::runtime_error("DEM input script '" + script +
                             "' defines no 'fix ID all tfdem/coupling': the coupler cannot apply fluid forces");
}

DemInstance::~DemInstance() { delete lmp_; }

void DemInstance::run(long steps) {
  if (global_count() == 0 && !inserts_particles()) return;  // LIGGGHTS 3.8.0 cannot run empty
  const std::string line = "run " + std::to_string(steps) + (set_up_ ? " pre no post no" : " post no");
  lmp_->input->one(line.c_str());
  set_up_ = true;
}

void DemInstance::command(const std::string &line) { lmp_->input->one(line.c_str()); }

bool DemInstance::inserts_particles() const {
  for (int i = 0; i < lmp_->modify->nfix; ++i)
    if (std::strncmp(lmp_->modify->fix[i]->style, "insert/", 7) == 0) return true;
  return false;
}

double DemInstance::time_step() const { return lmp_->update->dt; }

std::size_t DemInstance::local_count() const { return static_cast<std::size_t>(lmp_->atom->nlocal); }

const double *DemInstance::positions() const { return local_count() ? lmp_->atom->x[0] : nullptr; }

const double *DemInstance::velocities() const { return local_count() ? lmp_->atom->v[0] : nullptr; }

const double *DemInstance::radii() const { return lmp_->atom->radius; }

const double *DemInstance::masses() const { return lmp_->atom->rmass; }

const int *DemInstance::tags() const { return lmp_->atom->tag; }

double *DemInstance::fluid_force() { return local_count() ? fix_->fluid_force(0) : nullptr; }

long DemInstance::global_count() const { return static_cast<long>(lmp_->atom->natoms); }

namespace {

// Value (1,1) of a per-type-pair fix property/global named `name`, or `fallback` when absent.
double type_pair_property(LAMMPS_NS::LAMMPS *lmp, const char *name, double fallback) {
  LAMMPS_NS::Fix *fix = lmp->modify->find_fix_property(name, "property/global", "peratomtypepair", 0, 0,
                                                       "tfdem", false);
  return fix ? static_cast<LAMMPS_NS::FixPropertyGlobal *>(fix)->compute_array(0, 0) : fallback;
}

}  // namespace

bool DemInstance::linear_contact(LinearContact &out) const {
  out.stiffness = type_pair_property(lmp_, "kn", -1.0);
  out.damping = type_pair_property(lmp_, "gamman_abs", -1.0);
  out.restitution = type_pair_property(lmp_, "coefficientRestitution", -1.0);
  return out.stiffness > 0.0;
}

}  // namespace tfdem
