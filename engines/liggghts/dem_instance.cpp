#include "dem_instance.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <iterator>

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "dem_console.h"
#include "domain.h"
#include "fix_gravity.h"
#include "fix_property_global.h"
#include "fix_tfdem_coupling.h"
#include "input.h"
#include "lammps.h"
#include "modify.h"
#include "output.h"
#include "tfdem/data_file.h"
#include "dem_script.h"
#include "tfdem_liggghts.h"
#include "universe.h"
#include "update.h"

namespace tfdem {
namespace {

std::string read_text(const std::string &path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0)
    throw std::runtime_error("DEM input script '" + path + "' not found or not readable: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw std::runtime_error("DEM input script '" + path + "' is not a file (a directory?): name the LIGGGHTS " +
                             "input script itself");
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

// What rank 0 found, thrown on every rank (a collective step fails together).
void throw_on_every_rank(MPI_Comm comm, const std::string &problem_on_rank_0) {
  int length = static_cast<int>(problem_on_rank_0.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  if (length == 0) return;
  std::string problem(static_cast<std::size_t>(length), ' ');
  if (rank_of(comm) == 0) problem = problem_on_rank_0;
  MPI_Bcast(problem.data(), length, MPI_CHAR, 0, comm);
  throw std::runtime_error(problem);
}

std::string free_space(const std::string &path) {
  struct statvfs fs;
  if (::statvfs(path.c_str(), &fs) != 0) return "";
  std::ostringstream text;
  text << " (" << static_cast<double>(fs.f_bavail) * fs.f_frsize / 1e6 << " MB free on its file system)";
  return text.str();
}

// Whether a LIGGGHTS restart file is whole: it starts with the version record (flag 0, the
// version text) and ends with each rank's particle block (an int count n, then n doubles),
// rank 0 first, with the counts the ranks packed. "" when whole, else what is wrong.
std::string restart_file_problem(const std::string &path, const std::vector<int> &block_doubles,
                                 const std::string &version) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return "cannot be read back: " + std::string(std::strerror(errno));
  const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
  if (size == 0) return "is empty";
  const auto int_at = [&in](std::uint64_t offset) {
    int value = -1;
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(reinterpret_cast<char *>(&value), sizeof value);
    return in ? value : -1;
  };
  std::uint64_t end = size;
  for (std::size_t r = block_doubles.size(); r-- > 0;) {
    const std::uint64_t block = sizeof(int) + sizeof(double) * static_cast<std::uint64_t>(block_doubles[r]);
    if (end < block || int_at(end - block) != block_doubles[r])
      return "is cut short: " + std::to_string(size) + " bytes do not end with the particle data of the " +
             std::to_string(block_doubles.size()) + " rank(s)";
    end -= block;
  }
  const std::uint64_t header = 2 * sizeof(int) + version.size() + 1;
  if (end < header || int_at(0) != 0 || int_at(sizeof(int)) != static_cast<int>(version.size() + 1))
    return "has no LIGGGHTS header (version record) before its particle data";
  std::string text(version.size(), ' ');
  in.seekg(2 * sizeof(int));
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (!in || text != version) return "was written by another LIGGGHTS version or is damaged in its header";
  return "";
}

// A restart file another engine wrote is named as such (LIGGGHTS would stop with "Invalid flag
// in header").
void check_restart_engine(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  char start[12] = {};
  in.read(start, sizeof start);
  if (in && std::string(start, sizeof start) == "TFDEM-HS-RST")
    throw std::runtime_error("'" + path + "' was written by the hard-sphere engine: resume this checkpoint with "
                             "dem.engine: hard_sphere in coupling.yaml, or start afresh with LIGGGHTS (delete "
                             "the time folders after 0)");
}

// Flush a file's data to disk (a checkpoint must survive a crash of the machine too).
std::string synced(const std::string &path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    const std::string reason = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    return "cannot be synced to disk: " + reason;
  }
  ::close(fd);
  return "";
}

std::string directory_of(const std::string &path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

// The descriptor this process writes `path` through (a fix opened it), or -1.
int descriptor_of(const std::string &path) {
  struct stat target;
  if (::stat(path.c_str(), &target) != 0) return -1;
  DIR *fds = ::opendir("/proc/self/fd");
  if (!fds) return -1;
  int found = -1;
  const int listing = ::dirfd(fds);
  while (const dirent *entry = ::readdir(fds)) {
    const int fd = std::atoi(entry->d_name);
    struct stat st;
    if (entry->d_name[0] == '.' || fd == listing || ::fstat(fd, &st) != 0) continue;
    const int mode = ::fcntl(fd, F_GETFL) & O_ACCMODE;
    if (st.st_dev == target.st_dev && st.st_ino == target.st_ino && mode != O_RDONLY) found = fd;
  }
  ::closedir(fds);
  return found;
}

// Where the rows of step `step` begin in text[0, end): the last line whose first word is the
// step (a fix ave/time row, or the head of its vector block), else `end`.
std::uint64_t start_of_step_rows(const std::string &text, std::uint64_t end, long long step) {
  const std::string head = std::to_string(step) + " ";
  for (std::uint64_t line = end; line-- > 0;) {
    if (line != 0 && text[line - 1] != '\n') continue;
    if (text.compare(line, head.size(), head) == 0) return line;
  }
  return end;
}

std::uint64_t recorded_size(const DemResume &resume, const std::string &path, bool &found) {
  for (const OutputSize &o : resume.outputs)
    if (o.first == path) {
      found = true;
      return o.second;
    }
  found = false;
  return 0;
}

const char *kSetAside = ".tfdem-resume";

}  // namespace

DemInstance::DemInstance(MPI_Comm comm, const std::string &script, const std::string &log_file,
                         const DemResume *resume)
    : comm_(comm), log_file_(log_file) {
  const std::string to_run = script_to_run(script, resume);
  const int rank = rank_of(comm);
  if (resume) on_rank_0([&] { prepare_outputs(*resume); });
  // The logs are LIGGGHTS' own only after construction: started without them, so a resumed
  // run appends to them instead of truncating what the stopped run wrote.
  std::vector<std::string> args = {"tfdem", "-log", "none", "-screen", "none", "-echo", "none"};
  std::vector<char *> argv;
  for (auto &a : args) argv.push_back(a.data());
  lmp_ = new LAMMPS_NS::LAMMPS(static_cast<int>(argv.size()), argv.data(), comm);
  // LIGGGHTS' screen becomes the console: the same file on rank 0, ERROR lines on every rank.
  console_ = std::make_unique<DemConsole>(log_file + ".screen", rank == 0, rank, resume != nullptr);
  lmp_->screen = lmp_->universe->uscreen = console_->stream();
  command("log " + log_file + (resume ? " append" : ""));
  register_fix_styles(lmp_);
  lmp_->input->file(to_run.c_str());
  for (int i = 0; i < lmp_->modify->nfix; ++i)
    if (std::strcmp(lmp_->modify->fix[i]->style, "tfdem/coupling") == 0)
      fix_ = static_cast<LAMMPS_NS::FixTfdemCoupling *>(lmp_->modify->fix[i]);
  if (!fix_) throw std::runtime_error("DEM input script '" + script + "' defined no 'fix ID all tfdem/coupling'");
  if (!resume) return;
  command("print \"TFDEM: the DEM resumes from " +
          (resume->restart_file.empty() ? std::string("an emptied bed") : resume->restart_file) + " at step " +
          std::to_string(resume->step) + "\"");
  if (resume->restart_file.empty()) {  // the bed had emptied: the script's set-up, no particles
    command("delete_atoms group all compress no");
    command("reset_timestep " + std::to_string(resume->step));
  }
  // Dumps written at the checkpoint step are not written again (as in a straight run)
  LAMMPS_NS::Output *output = lmp_->output;
  for (int i = 0; i < output->ndump; ++i)
    if (output->every_dump[i] > 0 && resume->step % output->every_dump[i] == 0) output->last_dump[i] = resume->step;
  on_rank_0([&] { continue_outputs(*resume); });
}

std::string DemInstance::lost_particles_hint() const {
  return "LIGGGHTS drops particles that leave its domain. Likely causes: a contact that blew up (DEM step too large "
         "for k_n, or the damping; see the contact-time lines above), a particle pushed through a wall, or an open "
         "side of the DEM's box. Particles meant to leave through a gas outlet need it in coupling.yaml dem.outlets "
         "and a DEM box that reaches beyond it (LIGGGHTS boundary m). DEM log: \"" + log_file_ + ".screen\"";
}

void DemInstance::on_rank_0(const std::function<void()> &step) const {
  std::string problem;
  if (rank_of(comm_) == 0) {
    try {
      step();
    } catch (const std::exception &e) {
      problem = e.what();
    }
  }
  throw_on_every_rank(comm_, problem);
}

std::string DemInstance::script_to_run(const std::string &script, const DemResume *resume) {
  const dem_script::Script parsed = dem_script::load(script, read_text);
  std::string problems;
  for (const std::string &p : dem_script::coupled_script_problems(script, parsed)) problems += "\n  " + p;
  int ranks = 1;
  MPI_Comm_size(comm_, &ranks);
  const std::string grid = dem_script::processors_problem(parsed, ranks);
  if (!grid.empty()) problems += "\n  " + grid;
  if (!problems.empty()) throw std::runtime_error("the DEM input script cannot be coupled:" + problems);
  outputs_ = dem_script::output_files(parsed, &unresumable_outputs_);
  if (!resume) on_rank_0([&] { check_data_file(parsed); });
  if (!resume || resume->restart_file.empty()) return script;
  on_rank_0([&] { check_restart_engine(resume->restart_file); });
  std::string resumed;
  try {
    resumed = dem_script::resumed_script(script, parsed, resume->restart_file);
  } catch (const std::invalid_argument &e) {
    throw std::runtime_error(e.what());
  }
  const std::string path = script + ".resumed";
  std::string problem;
  if (rank_of(comm_) == 0) {
    std::ofstream out(path);
    out << resumed;
    out.close();
    if (!out) problem = "cannot write the resumed DEM script '" + path + "': " + std::strerror(errno);
  }
  throw_on_every_rank(comm_, problem);
  return path;
}

void DemInstance::check_data_file(const dem_script::Script &script) const {
  const dem_script::Command *read = script.first("read_data");
  const dem_script::Command *style = script.first("atom_style");
  if (!read || read->words.size() < 2 || read->words[1].find('$') != std::string::npos) return;
  if (!style || style->words.size() < 2 || (style->words[1] != "granular" && style->words[1] != "sphere")) return;
  const std::string &file = read->words[1];
  std::ifstream in(file);
  if (!in) return;  // LIGGGHTS names it
  data_file::Boundary boundary;
  const dem_script::Command *sides = script.first("boundary");
  std::size_t count = 0;
  std::vector<std::string> outside;
  try {
    if (sides) boundary = data_file::boundary_from_words({sides->words.begin() + 1, sides->words.end()});
    outside = data_file::atoms_outside_box(in, file, boundary, 10, count);
  } catch (const std::invalid_argument &e) {
    throw std::runtime_error(read->where() + e.what());
  }
  if (count == 0) return;
  std::string list;
  for (const std::string &o : outside) list += "\n  " + o;
  if (count > outside.size()) list += "\n  and " + std::to_string(count - outside.size()) + " more";
  throw std::runtime_error(read->where() + file + ": " + std::to_string(count) + " atom(s) LIGGGHTS cannot place " +
                           "(it would stop with 'Did not assign all atoms correctly'):" + list +
                           "\nFix: move them inside the box of the file's header, widen the box (xlo xhi ... lines), " +
                           "or make that side periodic or shrink-wrapped (boundary p, s or m)");
}

void DemInstance::prepare_outputs(const DemResume &resume) {
  for (const dem_script::OutputFile &f : outputs_) {
    const std::string aside = f.path + kSetAside;
    struct stat st;
    if (f.kind != dem_script::OutputFile::Kind::Dump) {
      // set aside (an earlier resume stopped before continuing it: its copy is the original)
      if (::stat(aside.c_str(), &st) != 0 && ::stat(f.path.c_str(), &st) == 0 &&
          std::rename(f.path.c_str(), aside.c_str()) != 0)
        throw std::runtime_error(f.where + "cannot set '" + f.path + "' aside to continue it: " + std::strerror(errno));
      continue;
    }
    bool recorded;
    const std::uint64_t size = recorded_size(resume, f.path, recorded);
    if (recorded && ::stat(f.path.c_str(), &st) == 0 && static_cast<std::uint64_t>(st.st_size) > size &&
        ::truncate(f.path.c_str(), static_cast<off_t>(size)) != 0)
      throw std::runtime_error(f.where + "cannot cut dump '" + f.path + "' back to its checkpoint size: " +
                               std::strerror(errno));
  }
}

void DemInstance::continue_outputs(const DemResume &resume) {
  std::fflush(nullptr);  // what the fixes wrote on opening reaches their files
  for (const dem_script::OutputFile &f : outputs_) {
    const std::string aside = f.path + kSetAside;
    if (f.kind == dem_script::OutputFile::Kind::Dump) continue;
    std::ifstream in(aside, std::ios::binary);
    if (!in) continue;  // nothing written before the checkpoint
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const int fd = descriptor_of(f.path);
    if (fd < 0)
      throw std::runtime_error(f.where + "'" + f.path + "' was not opened by the resumed script; its output up to " +
                               "the checkpoint is kept in '" + aside + "'");
    bool recorded;
    std::uint64_t keep = std::min<std::uint64_t>(recorded_size(resume, f.path, recorded), text.size());
    if (!recorded) keep = text.size();
    // fix ave/time writes the checkpoint step's row again when it sets up (its next valid step)
    if (f.kind == dem_script::OutputFile::Kind::Average && f.repeat == 1 && f.frequency > 0 &&
        resume.step % f.frequency == 0)
      keep = start_of_step_rows(text, keep, resume.step);
    bool written = ::ftruncate(fd, 0) == 0;
    for (std::uint64_t done = 0; written && done < keep;) {
      const ssize_t n = ::pwrite(fd, text.data() + done, keep - done, static_cast<off_t>(done));
      written = n > 0;
      done += written ? static_cast<std::uint64_t>(n) : 0;
    }
    if (!written || ::lseek(fd, static_cast<off_t>(keep), SEEK_SET) < 0)
      throw std::runtime_error(f.where + "cannot continue '" + f.path + "': " + std::strerror(errno) +
                               "; its output up to the checkpoint is kept in '" + aside + "'");
    std::remove(aside.c_str());
  }
}

DemInstance::~DemInstance() {
  delete lmp_;
  console_.reset();
}

void DemInstance::advance(double seconds, bool sample_contacts) {
  run(std::llround(seconds / time_step()), sample_contacts);
}

void DemInstance::run(long steps, bool sample_contacts) {
  if (global_count() == 0 && !inserts_particles()) {  // LIGGGHTS 3.8.0 cannot run empty:
    lmp_->update->reset_timestep(lmp_->update->ntimestep + steps);  // its clock goes on with the gas
    return;
  }
  fix_->sample_contacts_at(sample_contacts ? lmp_->update->ntimestep + steps : -1);
  // Every interval sets up (neighbour lists and forces built anew, the new fluid force in the
  // first half-kick), as a run resumed at that step does: a run stopped at any interval and
  // resumed stays bit for bit the straight run. It costs 2.4 % of the instructions on the
  // bubbling bed (80 steps an interval; bench/README.md, "Set-up every interval").
  lmp_->input->one(("run " + std::to_string(steps) + " post no").c_str());
}

bool DemInstance::write_restart(const std::string &path) {
  if (global_count() == 0 && !inserts_particles()) return false;  // as run(): LIGGGHTS cannot init
  const std::string partial = path + ".tmp";
  command("write_restart " + partial);
  const int ranks = [this] {
    int n = 1;
    MPI_Comm_size(comm_, &n);
    return n;
  }();
  const int mine = lmp_->atom->avec->size_restart();
  std::vector<int> blocks(static_cast<std::size_t>(ranks));
  MPI_Gather(&mine, 1, MPI_INT, blocks.data(), 1, MPI_INT, 0, comm_);
  std::string problem;
  if (rank_of(comm_) == 0) {
    problem = restart_file_problem(partial, blocks, lmp_->universe->version);
    if (problem.empty()) problem = synced(partial);
    if (problem.empty() && std::rename(partial.c_str(), path.c_str()) != 0)
      problem = "cannot be renamed to '" + path + "': " + std::strerror(errno);
    if (problem.empty()) problem = synced(directory_of(path));
    if (!problem.empty()) problem = "the DEM restart file '" + partial + "' " + problem + free_space(directory_of(path));
  }
  throw_on_every_rank(comm_, problem);
  return true;
}

std::vector<OutputSize> DemInstance::output_sizes() {
  std::fflush(nullptr);
  std::vector<OutputSize> sizes;
  if (rank_of(comm_) != 0) return sizes;
  for (const dem_script::OutputFile &f : outputs_) {
    struct stat st;
    if (::stat(f.path.c_str(), &st) == 0) sizes.emplace_back(f.path, static_cast<std::uint64_t>(st.st_size));
  }
  return sizes;
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

std::size_t DemInstance::ghost_count() const { return static_cast<std::size_t>(lmp_->atom->nghost); }

std::array<int, 3> DemInstance::processor_grid() const {
  return {lmp_->comm->procgrid[0], lmp_->comm->procgrid[1], lmp_->comm->procgrid[2]};
}

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

DemInstance::Box DemInstance::box() const {
  constexpr int kFixed = 1;  // LIGGGHTS Domain::boundary: 0 p, 1 f, 2 s, 3 m
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.lower[a] = lmp_->domain->boxlo[a];
    b.upper[a] = lmp_->domain->boxhi[a];
    for (int side = 0; side < 2; ++side) b.drops[a][side] = lmp_->domain->boundary[a][side] == kFixed;
  }
  return b;
}

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
