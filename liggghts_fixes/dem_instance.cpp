#include "dem_instance.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "atom.h"
#include "dem_console.h"
#include "fix_gravity.h"
#include "fix_property_global.h"
#include "fix_tfdem_coupling.h"
#include "input.h"
#include "lammps.h"
#include "modify.h"
#include "tfdem/dem_script.h"
#include "tfdem_liggghts.h"
#include "universe.h"
#include "update.h"

namespace tfdem {
namespace {

std::string read_text(const std::string &path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("DEM input script '" + path + "' not found or not readable");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int rank_of(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

}  // namespace

DemInstance::DemInstance(MPI_Comm comm, const std::string &script, const std::string &log_file,
                         const std::string &restart_file)
    : comm_(comm) {
  const std::string to_run = script_to_run(script, restart_file);
  const std::string screen = log_file + ".screen";
  std::vector<std::string> args = {"tfdem", "-log", log_file, "-screen", screen, "-echo", "none"};
  std::vector<char *> argv;
  for (auto &a : args) argv.push_back(a.data());
  lmp_ = new LAMMPS_NS::LAMMPS(static_cast<int>(argv.size()), argv.data(), comm);
  // LIGGGHTS' screen becomes the console: the same file on rank 0, ERROR lines on every rank.
  const int rank = rank_of(comm);
  if (lmp_->screen) std::fclose(lmp_->screen);
  console_ = std::make_unique<DemConsole>(screen, rank == 0, rank);
  lmp_->screen = lmp_->universe->uscreen = console_->stream();
  register_fix_styles(lmp_);
  lmp_->input->file(to_run.c_str());
  for (int i = 0; i < lmp_->modify->nfix; ++i)
    if (std::strcmp(lmp_->modify->fix[i]->style, "tfdem/coupling") == 0)
      fix_ = static_cast<LAMMPS_NS::FixTfdemCoupling *>(lmp_->modify->fix[i]);
  if (!fix_) throw std::runtime_error("DEM input script '" + script + "' defined no 'fix ID all tfdem/coupling'");
}

std::string DemInstance::script_to_run(const std::string &script, const std::string &restart_file) const {
  const std::string text = read_text(script);
  std::string problems;
  for (const std::string &p : dem_script::coupled_script_problems(script, dem_script::parse(text)))
    problems += "\n  " + p;
  if (!problems.empty()) throw std::runtime_error("the DEM input script cannot be coupled:" + problems);
  if (restart_file.empty()) return script;
  std::string resumed;
  try {
    resumed = dem_script::resumed_script(script, text, restart_file);
  } catch (const std::invalid_argument &e) {
    throw std::runtime_error(e.what());
  }
  const std::string path = script + ".resumed";
  if (rank_of(comm_) == 0) {
    std::ofstream out(path);
    out << "# " << script << " resumed from " << restart_file << " by the coupler\n" << resumed;
    if (!out) throw std::runtime_error("cannot write the resumed DEM script '" + path + "'");
  }
  MPI_Barrier(comm_);
  return path;
}

DemInstance::~DemInstance() {
  delete lmp_;
  console_.reset();
}

void DemInstance::run(long steps, bool sample_contacts) {
  if (global_count() == 0 && !inserts_particles()) return;  // LIGGGHTS 3.8.0 cannot run empty
  fix_->sample_contacts_at(sample_contacts ? lmp_->update->ntimestep + steps : -1);
  const std::string line = "run " + std::to_string(steps) + (set_up_ ? " pre no post no" : " post no");
  lmp_->input->one(line.c_str());
  set_up_ = true;
}

bool DemInstance::write_restart(const std::string &path) {
  if (global_count() == 0 && !inserts_particles()) return false;  // as run(): LIGGGHTS cannot init
  const std::string partial = path + ".tmp";
  command("write_restart " + partial);
  // write_restart re-exchanges atoms and rebuilds the ghosts: the next run sets up again
  // (as a run resumed from this file does, so both continue alike)
  set_up_ = false;
  if (rank_of(comm_) == 0 && std::rename(partial.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename the DEM restart file '" + partial + "' to '" + path + "'");
  MPI_Barrier(comm_);
  return true;
}

void DemInstance::remove_particles(const std::vector<int> &tags) {
  if (tags.empty()) return;
  constexpr std::size_t kIdsPerCommand = 500;
  for (std::size_t first = 0; first < tags.size(); first += kIdsPerCommand) {
    std::string ids;
    for (std::size_t i = first; i < std::min(tags.size(), first + kIdsPerCommand); ++i)
      ids += " " + std::to_string(tags[i]);
    command("group tfdem_leaving id" + ids);
  }
  command("delete_atoms group tfdem_leaving compress no");
  command("group tfdem_leaving delete");
  set_up_ = false;  // atoms renumbered locally: neighbour lists and ghosts are rebuilt
}

void DemInstance::command(const std::string &line) { lmp_->input->one(line.c_str()); }

bool DemInstance::integrates() const {
  for (int i = 0; i < lmp_->modify->nfix; ++i) {
    const std::string style = lmp_->modify->fix[i]->style;
    for (const char *prefix : {"nve", "nvt", "npt", "rigid"})
      if (style.compare(0, std::strlen(prefix), prefix) == 0) return true;
  }
  return false;
}

bool DemInstance::inserts_particles() const {
  for (int i = 0; i < lmp_->modify->nfix; ++i)
    if (std::strncmp(lmp_->modify->fix[i]->style, "insert/", 7) == 0) return true;
  return false;
}

double DemInstance::time_step() const { return lmp_->update->dt; }

long long DemInstance::step() const { return static_cast<long long>(lmp_->update->ntimestep); }

std::size_t DemInstance::local_count() const { return static_cast<std::size_t>(lmp_->atom->nlocal); }

const double *DemInstance::positions() const { return local_count() ? lmp_->atom->x[0] : nullptr; }

const double *DemInstance::velocities() const { return local_count() ? lmp_->atom->v[0] : nullptr; }

const double *DemInstance::radii() const { return lmp_->atom->radius; }

const double *DemInstance::masses() const { return lmp_->atom->rmass; }

const int *DemInstance::tags() const { return lmp_->atom->tag; }

const int *DemInstance::types() const { return lmp_->atom->type; }

int DemInstance::type_count() const { return lmp_->atom->ntypes; }

void DemInstance::set_fluid_force(const std::vector<double> &force) {
  const std::size_t n = local_count();
  if (force.size() != 3 * n)
    throw std::invalid_argument("set_fluid_force: " + std::to_string(force.size() / 3) + " forces for " +
                                std::to_string(n) + " local particles");
  for (std::size_t i = 0; i < n; ++i) {
    double *f = fix_->fluid_force(static_cast<int>(i));
    for (int k = 0; k < 3; ++k) f[k] = force[3 * i + k];
  }
}

void DemInstance::contact_sample(std::vector<double> &force, std::vector<int> &coordination) const {
  const std::size_t n = local_count();
  force.resize(3 * n);
  coordination.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double *f = fix_->contact_force(static_cast<int>(i));
    for (int k = 0; k < 3; ++k) force[3 * i + k] = f[k];
    coordination[i] = fix_->coordination(static_cast<int>(i));
  }
}

bool DemInstance::gravity(double g[3]) const {
  g[0] = g[1] = g[2] = 0.0;
  bool found = false;
  for (int i = 0; i < lmp_->modify->nfix; ++i) {
    if (std::strcmp(lmp_->modify->fix[i]->style, "gravity") != 0) continue;
    found = true;
    double one[3];
    lmp_->modify->fix[i]->init();  // sets the acceleration vector (before any run)
    static_cast<LAMMPS_NS::FixGravity *>(lmp_->modify->fix[i])->get_gravity(one);
    for (int k = 0; k < 3; ++k) g[k] += one[k];
  }
  return found;
}

long DemInstance::global_count() const { return static_cast<long>(lmp_->atom->natoms); }

namespace {

// Value (a, b) (0-based) of a per-type-pair fix property/global named `name`, or `fallback`
// when absent.
double type_pair_property(LAMMPS_NS::LAMMPS *lmp, const char *name, int a, int b, double fallback) {
  LAMMPS_NS::Fix *fix = lmp->modify->find_fix_property(name, "property/global", "peratomtypepair", 0, 0,
                                                       "tfdem", false);
  return fix ? static_cast<LAMMPS_NS::FixPropertyGlobal *>(fix)->compute_array(a, b) : fallback;
}

// Value of atom type a (0-based) of a per-type fix property/global named `name`, or `fallback`.
double type_property(LAMMPS_NS::LAMMPS *lmp, const char *name, int a, double fallback) {
  LAMMPS_NS::Fix *fix = lmp->modify->find_fix_property(name, "property/global", "peratomtype", 0, 0, "tfdem", false);
  return fix ? static_cast<LAMMPS_NS::FixPropertyGlobal *>(fix)->compute_vector(a) : fallback;
}

}  // namespace

bool DemInstance::hertz_contact(int a, int b, HertzContact &out) const {
  out.young_a = type_property(lmp_, "youngsModulus", a - 1, -1.0);
  out.young_b = type_property(lmp_, "youngsModulus", b - 1, -1.0);
  out.poisson_a = type_property(lmp_, "poissonsRatio", a - 1, 0.0);
  out.poisson_b = type_property(lmp_, "poissonsRatio", b - 1, 0.0);
  return out.young_a > 0.0 && out.young_b > 0.0;
}

bool DemInstance::linear_contact(int a, int b, LinearContact &out) const {
  out.stiffness = type_pair_property(lmp_, "kn", a - 1, b - 1, -1.0);
  out.damping = type_pair_property(lmp_, "gamman_abs", a - 1, b - 1, -1.0);
  out.restitution = type_pair_property(lmp_, "coefficientRestitution", a - 1, b - 1, -1.0);
  return out.stiffness > 0.0;
}

}  // namespace tfdem
