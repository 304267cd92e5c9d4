#include "tfdem/hard_sphere/engine.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "tfdem/analysis.h"
#include "tfdem/data_file.h"

namespace tfdem::hard_sphere {
namespace {

// Version 2 adds the neighbour lists (a version 1 file resumes with lists built anew)
constexpr char kMagic[16] = "TFDEM-HS-RST-2\n";
constexpr char kMagicWithoutLists[16] = "TFDEM-HS-RST-1\n";
// The deepest overlap, as a fraction of d, hard spheres start from without a warning: a pour
// by tfdem pack keeps below it (tfdem.packing.MAX_OVERLAP), and EventFlight takes them as
// touching a millionth closer than they are, so they part as the bed moves
constexpr double kOverlapTolerated = 0.05;

// A table of one value (every pair / every type) or `count` values, checked
std::vector<double> table(const std::vector<double> &values, std::size_t count, const std::string &what,
                          const std::string &source) {
  if (values.size() == 1) return std::vector<double>(count, values[0]);
  if (values.size() == count) return values;
  throw std::runtime_error(source + " has atom types that dem.hard_sphere." + what + " does not fit: it gives " +
                           std::to_string(values.size()) + " values where one, or " + std::to_string(count) +
                           ", belong");
}

template <typename T>
void put(std::ostream &out, const T &value) {
  out.write(reinterpret_cast<const char *>(&value), sizeof value);
}

template <typename T>
void get(std::istream &in, T &value) {
  in.read(reinterpret_cast<char *>(&value), sizeof value);
}

template <typename T>
void put_vector(std::ostream &out, const std::vector<T> &values) {
  put(out, static_cast<std::uint64_t>(values.size()));
  out.write(reinterpret_cast<const char *>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(T)));
}

// A vector of at most `most` values (a damaged size must not allocate without bound)
template <typename T>
void get_vector(std::istream &in, std::vector<T> &values, std::uint64_t most) {
  std::uint64_t count = 0;
  get(in, count);
  if (!in || count > most) {
    in.setstate(std::ios::failbit);
    return;
  }
  values.resize(count);
  in.read(reinterpret_cast<char *>(values.data()), static_cast<std::streamsize>(count * sizeof(T)));
}

void put_lists(std::ostream &out, const EventFlight::NeighbourLists &lists) {
  put(out, static_cast<char>(lists.built));
  put(out, lists.capacity);
  put(out, lists.skin);
  for (int a = 0; a < 3; ++a) {
    put(out, lists.cells[a]);
    put(out, lists.width[a]);
  }
  put_vector(out, lists.anchor);
  for (const std::vector<int> *v : {&lists.partners, &lists.degree, &lists.head, &lists.next, &lists.previous,
                                    &lists.cell})
    put_vector(out, *v);
  put_vector(out, lists.contact);
}

EventFlight::NeighbourLists get_lists(std::istream &in, std::uint64_t particles) {
  EventFlight::NeighbourLists lists;
  char built = 0;
  get(in, built);
  lists.built = built != 0;
  get(in, lists.capacity);
  get(in, lists.skin);
  for (int a = 0; a < 3; ++a) {
    get(in, lists.cells[a]);
    get(in, lists.width[a]);
  }
  const std::uint64_t slots = particles * static_cast<std::uint64_t>(std::max(lists.capacity, 0));
  get_vector(in, lists.anchor, particles);
  get_vector(in, lists.partners, slots);
  get_vector(in, lists.degree, particles);
  get_vector(in, lists.head, std::max<std::uint64_t>(64, 8 * particles));
  for (std::vector<int> *v : {&lists.next, &lists.previous, &lists.cell}) get_vector(in, *v, particles);
  get_vector(in, lists.contact, slots);
  return lists;
}

std::string synced(const std::string &path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    const std::string reason = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    return reason;
  }
  ::close(fd);
  return "";
}

// Every position, velocity and spin a finite number, else the particles named by id (what is
// not finite would stop the event search on a floating-point exception)
void check_finite(const data_file::Atoms &atoms, const std::string &file) {
  std::ostringstream bad;
  int count = 0;
  for (std::size_t i = 0; i < atoms.id.size(); ++i)
    for (const auto &[what, values] : {std::pair{"position", &atoms.position}, std::pair{"velocity", &atoms.velocity},
                                       std::pair{"spin", &atoms.spin}}) {
      const double *v = values->data() + 3 * i;
      if (std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2])) continue;
      if (++count <= 10) bad << "\n  id " << atoms.id[i] << ": " << what << " (" << v[0] << " " << v[1] << " " << v[2] << ")";
      break;
    }
  if (count)
    throw std::runtime_error("dem.particles: " + file + ": " + std::to_string(count) +
                             " particle(s) with a position, velocity or spin that is not a finite number:" +
                             bad.str() + "\nFix: give them finite values in the data file");
}

}  // namespace

void HardSphereEngine::set_laws(const HardSphereOptions &o, const std::string &source) {
  const std::size_t n = static_cast<std::size_t>(type_count_);
  const auto e = table(o.restitution, n * n, "restitution", source);
  const auto b = table(o.tangential_restitution, n * n, "tangential_restitution", source);
  const auto mu = table(o.friction, n * n, "friction", source);
  const auto ew = table(o.wall_restitution, n, "wall.restitution", source);
  const auto bw = table(o.wall_tangential_restitution, n, "wall.tangential_restitution", source);
  const auto muw = table(o.wall_friction, n, "wall.friction", source);
  std::vector<CollisionLaw> pairs(n * n), walls(n);
  for (std::size_t a = 0; a < n; ++a) {
    walls[a] = {ew[a], muw[a], bw[a]};
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t ab = a * n + k, ba = k * n + a;
      if (e[ab] != e[ba] || b[ab] != b[ba] || mu[ab] != mu[ba])
        throw std::runtime_error("dem.hard_sphere: the collision law of types " + std::to_string(a + 1) + " and " +
                                 std::to_string(k + 1) + " differs from that of " + std::to_string(k + 1) + " and " +
                                 std::to_string(a + 1) + ": the matrices must be symmetric");
      pairs[ab] = {e[ab], mu[ab], b[ab]};
    }
  }
  WallBox box = flight_.box();
  EventFlight laws(box, type_count_, pairs, walls, o.elastic_within, o.max_collisions_per_particle);
  laws.set_tc_keeps_friction(o.tc_keeps_friction);
  std::swap(laws.position, flight_.position);
  std::swap(laws.velocity, flight_.velocity);
  std::swap(laws.spin, flight_.spin);
  std::swap(laws.radius, flight_.radius);
  std::swap(laws.mass, flight_.mass);
  std::swap(laws.type, flight_.type);
  std::swap(laws.impulse, flight_.impulse);
  std::swap(laws.last_collision, flight_.last_collision);
  laws.set_clock(flight_.clock());
  flight_ = std::move(laws);
}

HardSphereEngine::HardSphereEngine(const HardSphereOptions &options, const std::string &data_file,
                                   const double gravity[3], const DemResume *resume)
    : gravity_{gravity[0], gravity[1], gravity[2]}, contact_gap_(options.contact_gap), move_(options.move) {
  if (resume && !resume->restart_file.empty()) {
    read_restart(*resume, options);
  } else {
    std::ifstream in(data_file);
    if (!in) throw std::runtime_error("dem.particles: cannot read '" + data_file + "': " + std::strerror(errno));
    std::stringstream text;
    text << in.rdbuf();
    data_file::Atoms atoms;
    try {
      atoms = data_file::read_atoms(text.str(), data_file);
    } catch (const std::invalid_argument &e) {
      throw std::runtime_error(std::string("dem.particles: ") + e.what());
    }
    WallBox box;
    for (int a = 0; a < 3; ++a) {
      box.lower[a] = atoms.lower[a];
      box.upper[a] = atoms.upper[a];
    }
    // the laws cover the particles' types: a higher type of the header (LIGGGHTS' walls)
    // holds no particle and needs none
    type_count_ = atoms.id.empty() ? atoms.type_count : *std::max_element(atoms.type.begin(), atoms.type.end());
    check_finite(atoms, data_file);
    std::string outside;
    int outside_count = 0;
    for (std::size_t i = 0; i < atoms.id.size(); ++i)
      for (int a = 0; a < 3; ++a) {
        // a centre outside; a sphere sunk into a wall (a soft-sphere packing) is tolerated
        const double x = atoms.position[3 * i + a];
        if (x >= box.lower[a] && x <= box.upper[a]) continue;
        if (++outside_count <= 10)
          outside += "\n  id " + std::to_string(atoms.id[i]) + ": " + "xyz"[a] + " = " + std::to_string(x) +
                     " m, box " + std::to_string(box.lower[a]) + " to " + std::to_string(box.upper[a]) + " m";
        break;
      }
    if (outside_count)
      throw std::runtime_error("dem.particles: " + data_file + ": " + std::to_string(outside_count) +
                               " particle(s) with the centre outside the box of its header, whose faces are the "
                               "hard-sphere engine's walls:" + outside + "\nFix: move them inside, or widen the box");
    flight_ = EventFlight(box, 1, {CollisionLaw{}}, {CollisionLaw{}}, 0, 1);
    set_laws(options, data_file);
    constexpr double kPi = 3.14159265358979323846;
    for (std::size_t i = 0; i < atoms.id.size(); ++i) {
      const double d = atoms.diameter[i];
      const auto v3 = [i](const std::vector<double> &v) { return Vec3{v[3 * i], v[3 * i + 1], v[3 * i + 2]}; };
      flight_.add(v3(atoms.position), v3(atoms.velocity), v3(atoms.spin), d / 2, atoms.density[i] * kPi * d * d * d / 6,
                  atoms.type[i] - 1);
      tags_.push_back(atoms.id[i]);
      types_.push_back(atoms.type[i]);
    }
    if (!resume) overlaps_ = flight_.tolerate_overlaps();
    if (resume) {  // the bed had emptied: its particles left, the clock goes on
      flight_.remove([&] {
        std::vector<std::size_t> all(flight_.size());
        for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
        return all;
      }());
      tags_.clear();
      types_.clear();
      step_ = resume->step;
      flight_.set_clock(resume->time);
    }
    fluid_force_.assign(flight_.size(), Vec3{});
  }
}

void HardSphereEngine::advance(double seconds, bool sample) {
  const std::size_t n = flight_.size();
  if (!move_) {  // a fixed bed: only the clock moves
    flight_.set_clock(flight_.clock() + seconds);
    ++step_;
    if (sample) sample_contacts(seconds);
    return;
  }
  const auto kick = [&] {
    for (std::size_t i = 0; i < n; ++i)
      flight_.velocity[i] += (0.5 * seconds) * (gravity_ + (1 / flight_.mass[i]) * fluid_force_[i]);
  };
  kick();
  const FlightCounts c = flight_.fly(seconds);
  kick();
  ++step_;
  totals_.pair += c.pair;
  totals_.wall += c.wall;
  totals_.elastic += c.elastic;
  totals_.predictions += c.predictions;
  totals_.list_builds += c.list_builds;
  totals_.lists_renewed += c.lists_renewed;
  if (sample) sample_contacts(seconds);
}

void HardSphereEngine::sample_contacts(double seconds) {
  const std::size_t n = flight_.size();
  contact_force_.assign(3 * n, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) contact_force_[3 * i + a] = flight_.impulse[i][a] / seconds;
  std::vector<double> widened(n);
  for (std::size_t i = 0; i < n; ++i) widened[i] = 2 * flight_.radius[i] * (1 + contact_gap_);
  ParticleView view;
  view.count = n;
  view.position = positions();
  view.diameter = widened.data();
  coordination_ = analysis::coordination_numbers(n, analysis::contact_pairs(view));
}

void HardSphereEngine::set_fluid_force(const std::vector<double> &force) {
  if (force.size() != 3 * flight_.size())
    throw std::invalid_argument("set_fluid_force: " + std::to_string(force.size() / 3) + " forces for " +
                                std::to_string(flight_.size()) + " particles");
  for (std::size_t i = 0; i < flight_.size(); ++i) fluid_force_[i] = {force[3 * i], force[3 * i + 1], force[3 * i + 2]};
}

void HardSphereEngine::contact_sample(std::vector<double> &force, std::vector<int> &coordination) const {
  force = contact_force_;
  coordination = coordination_;
  force.resize(3 * flight_.size(), 0);
  coordination.resize(flight_.size(), 0);
}

void HardSphereEngine::remove_particles(const std::vector<int> &tags) {
  if (tags.empty()) return;
  std::unordered_map<int, char> leaving;
  for (const int t : tags) leaving[t] = 1;
  std::vector<std::size_t> indices;
  std::size_t out = 0;
  for (std::size_t i = 0; i < tags_.size(); ++i) {
    if (leaving.count(tags_[i])) {
      indices.push_back(i);
      continue;
    }
    tags_[out] = tags_[i];
    types_[out] = types_[i];
    fluid_force_[out] = fluid_force_[i];
    ++out;
  }
  tags_.resize(out);
  types_.resize(out);
  fluid_force_.resize(out);
  flight_.remove(indices);
  contact_force_.clear();
  coordination_.clear();
}

bool HardSphereEngine::write_restart(const std::string &path) {
  const std::string partial = path + ".tmp";
  {
    std::ofstream out(partial, std::ios::binary);
    out.write(kMagic, sizeof kMagic);
    const std::uint64_t n = flight_.size();
    put(out, n);
    put(out, step_);
    put(out, flight_.clock());
    put(out, type_count_);
    const WallBox &box = flight_.box();
    for (int a = 0; a < 3; ++a) {
      put(out, box.lower[a]);
      put(out, box.upper[a]);
    }
    for (std::size_t i = 0; i < n; ++i) {
      put(out, tags_[i]);
      put(out, types_[i]);
      put(out, flight_.radius[i]);
      put(out, flight_.mass[i]);
      for (const Vec3 *v : {&flight_.position[i], &flight_.velocity[i], &flight_.spin[i], &fluid_force_[i]})
        for (int a = 0; a < 3; ++a) put(out, (*v)[a]);
      put(out, flight_.last_collision[i]);
    }
    const std::uint64_t tolerated = flight_.tolerated().size();
    put(out, tolerated);
    for (const auto &[key, distance] : flight_.tolerated()) {
      put(out, key);
      put(out, distance);
    }
    for (const double reach : flight_.wall_reach()) put(out, reach);
    put_lists(out, flight_.lists());
    out.write(kMagic, sizeof kMagic);  // the end: a file cut short lacks it
    out.close();
    if (!out) throw std::runtime_error("the hard-sphere restart file '" + partial + "' could not be written: " +
                                       std::strerror(errno));
  }
  const std::string unsynced = synced(partial);
  if (!unsynced.empty()) throw std::runtime_error("'" + partial + "' cannot be synced to disk: " + unsynced);
  if (std::rename(partial.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename '" + partial + "' to '" + path + "': " + std::strerror(errno));
  return true;
}

void HardSphereEngine::read_restart(const DemResume &resume, const HardSphereOptions &options) {
  const std::string &path = resume.restart_file;
  std::ifstream in(path, std::ios::binary);
  char magic[sizeof kMagic];
  in.read(magic, sizeof magic);
  const bool with_lists = in && std::memcmp(magic, kMagic, sizeof kMagic) == 0;
  if (!with_lists && (!in || std::memcmp(magic, kMagicWithoutLists, sizeof kMagic) != 0))
    throw std::runtime_error("'" + path + "' is not a hard-sphere engine's restart file (a LIGGGHTS checkpoint? "
                             "resume it with dem.engine: liggghts)");
  std::uint64_t n = 0;
  double clock = 0;
  get(in, n);
  get(in, step_);
  get(in, clock);
  get(in, type_count_);
  WallBox box;
  for (int a = 0; a < 3; ++a) {
    get(in, box.lower[a]);
    get(in, box.upper[a]);
  }
  flight_ = EventFlight(box, 1, {CollisionLaw{}}, {CollisionLaw{}}, 0, 1);
  set_laws(options, path);
  for (std::uint64_t i = 0; i < n && in; ++i) {
    int tag = 0, type = 0;
    double r = 0, m = 0;
    Vec3 x, v, w, f;
    double last = 0;
    get(in, tag);
    get(in, type);
    get(in, r);
    get(in, m);
    for (Vec3 *q : {&x, &v, &w, &f})
      for (int a = 0; a < 3; ++a) get(in, (*q)[a]);
    get(in, last);
    flight_.add(x, v, w, r, m, type - 1);
    flight_.last_collision.back() = last;
    tags_.push_back(tag);
    types_.push_back(type);
    fluid_force_.push_back(f);
  }
  std::uint64_t tolerated = 0;
  get(in, tolerated);
  std::unordered_map<std::uint64_t, double> pairs;
  for (std::uint64_t k = 0; k < tolerated && in; ++k) {
    std::uint64_t key = 0;
    double distance = 0;
    get(in, key);
    get(in, distance);
    pairs[key] = distance;
  }
  std::vector<double> reach(6 * n);
  for (double &r : reach) get(in, r);
  EventFlight::NeighbourLists lists;
  if (with_lists) lists = get_lists(in, n);
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, with_lists ? kMagic : kMagicWithoutLists, sizeof kMagic) != 0)
    throw std::runtime_error("'" + path + "' is cut short: it ends before its " + std::to_string(n) + " particles");
  flight_.restore_tolerated(std::move(pairs), std::move(reach));
  try {
    flight_.restore_lists(std::move(lists));
  } catch (const std::invalid_argument &e) {
    throw std::runtime_error("'" + path + "' is damaged: " + e.what());
  }
  flight_.set_clock(clock);
}

StartReport HardSphereEngine::check_start(const CaseAtStart &c) const {
  const auto &options = static_cast<const HardSphereOptions &>(*c.config->engine_settings);
  std::ostringstream line;
  line.precision(10);
  line << "TFDEM coupling: " << global_count() << " particles in " << name() << " (" << options.particles
       << "), one flow step per gas step of " << c.gas_step << " s, gravity (" << gravity_[0] << " " << gravity_[1]
       << " " << gravity_[2] << ") m/s^2 (constant/g)";
  StartReport r;
  r.lines.push_back(line.str());
  if (overlaps_.pairs + overlaps_.walls > 0) {
    std::ostringstream kept;
    kept.precision(10);
    kept << "TFDEM hard spheres: " << overlaps_.pairs << " overlapping pairs and " << overlaps_.walls
         << " spheres into a wall in " << options.particles << " (deepest " << 100 * overlaps_.deepest
         << " % of a diameter) taken as touching where they are";
    r.lines.push_back(kept.str());
  }
  return r;
}

std::string HardSphereEngine::end_report() const {
  std::ostringstream out;
  out << "TFDEM hard spheres: " << totals_.pair << " pair and " << totals_.wall << " wall collisions ("
      << totals_.elastic << " made elastic by the TC model), " << totals_.predictions << " event predictions, "
      << totals_.list_builds << " builds of all neighbour lists and " << totals_.lists_renewed
      << " of one particle's over " << step_ << " flow steps";
  return out.str();
}

std::string HardSphereEngine::kept_overlaps_warning(double deepest) const {
  if (deepest <= kOverlapTolerated) return "";
  std::ostringstream out;
  out.precision(10);
  out << "the initial packing's pairs overlap up to " << 100 * deepest << " % of d, more than a pour by tfdem pack "
      << "leaves (" << 100 * kOverlapTolerated << " %): hard spheres do not push them apart, they stay so until "
      << "the pairs part (and count twice in the gas fraction). Fix: pour the bed with tfdem pack";
  return out.str();
}

ParticleEngine::Box HardSphereEngine::box() const {
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.lower[a] = flight_.box().lower[a];
    b.upper[a] = flight_.box().upper[a];
  }
  return b;  // walls reflect: no face drops particles
}

void HardSphereEngine::open_outlet(int axis, int side) { flight_.open(axis, side); }

}  // namespace tfdem::hard_sphere
