// LIGGGHTS' checks of itself against the case at the start of a coupled run: the DEM's copy
// of gravity against the gas's, the DEM step against each contact's time by the core's one rule
// (tfdem::dem_step_problem), the gas step a whole number of DEM steps, the scene check, and
// how evenly LIGGGHTS' processor grid shares the particles.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "dem_instance.h"
#include "liggghts_engine.h"
#include "tfdem/contact.h"
#include "tfdem/scene_check.h"

namespace tfdem {
namespace {

// Past this overlap at the free fall's impact, as a fraction of the smaller diameter, soft
// contacts let particles pass halfway through one another
constexpr double kLargestSoundImpactOverlap = 0.5;
// The fullest rank's particles over the mean above which the processor grid is called uneven
constexpr double kDemImbalance = 1.5;

// Numbers in messages at 10 significant digits, as the solver prints them
class Text {
 public:
  Text() { out_.precision(10); }
  template <typename T>
  Text &operator<<(const T &v) {
    out_ << v;
    return *this;
  }
  operator std::string() const { return out_.str(); }

 private:
  std::ostringstream out_;
};

std::string vector_text(const double v[3]) { return Text() << "(" << v[0] << " " << v[1] << " " << v[2] << ")"; }

// Smallest value of a per-particle property (mass, radius) of each atom type (index type - 1;
// infinity: a type without particles, e.g. a wall material), over all ranks.
std::vector<double> smallest_of_type(const DemInstance &dem, const double *values, MPI_Comm comm) {
  std::vector<double> smallest(dem.type_count(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < dem.local_count(); ++i) {
    double &m = smallest[dem.types()[i] - 1];
    m = std::min(m, values[i]);
  }
  MPI_Allreduce(MPI_IN_PLACE, smallest.data(), static_cast<int>(smallest.size()), MPI_DOUBLE, MPI_MIN, comm);
  return smallest;
}

// Reduced value (1/a + 1/b)^-1 of a contact's two sides (effective mass, effective radius);
// a type without particles is a wall (infinite mass and radius).
double reduced(double a, double b) {
  if (std::isinf(a)) return b;
  if (std::isinf(b)) return a;
  return contact::effective_mass(a, b);
}

// The contact of atom types a and b between their lightest, smallest particles: its time, what
// it is (for the messages), its restitution and the deepest overlap of an elastic impact at
// each of `speeds`; a negative time when the script gives no contact model we know.
struct ContactOfTypes {
  double time = -1, restitution = kUnknownRestitution;
  std::string model;
  std::vector<double> overlaps;
};

ContactOfTypes contact_of_types(const DemInstance &dem, int a, int b, double m_eff, double r_eff, double impact,
                                const std::vector<double> &speeds) {
  ContactOfTypes c;
  c.overlaps.assign(speeds.size(), 0);
  DemInstance::LinearContact linear;
  if (dem.linear_contact(a, b, linear) && (linear.damping >= 0 || linear.restitution >= 0)) {
    const bool damped = linear.damping >= 0;
    c.model = Text() << "linear, k_n = " << linear.stiffness << " N/m, " << (damped ? "eta_n = " : "e_n = ")
                     << (damped ? linear.damping : linear.restitution) << (damped ? " N s/m" : "")
                     << ", m_eff = " << m_eff << " kg";
    c.restitution = damped ? contact::restitution_from_damping(linear.stiffness, linear.damping, m_eff)
                           : linear.restitution;
    for (std::size_t k = 0; k < speeds.size(); ++k)
      c.overlaps[k] = contact::linear_impact_overlap(linear.stiffness, m_eff, speeds[k]);
    c.time = damped ? contact::contact_time_from_damping(linear.stiffness, linear.damping, m_eff)
                    : contact::contact_time(linear.stiffness, linear.restitution, m_eff);
    return c;
  }
  DemInstance::HertzContact hertz;
  if (dem.hertz_contact(a, b, hertz)) {
    const double modulus = contact::effective_modulus(hertz.young_a, hertz.poisson_a, hertz.young_b, hertz.poisson_b);
    c.model = Text() << "Hertz, E* = " << modulus << " Pa, R* = " << r_eff << " m, m_eff = " << m_eff
                     << " kg, elastic at impact speed " << impact << " m/s";
    for (std::size_t k = 0; k < speeds.size(); ++k)
      c.overlaps[k] = contact::hertz_impact_overlap(modulus, r_eff, m_eff, speeds[k]);
    c.time = contact::hertz_contact_time(modulus, r_eff, m_eff, impact);
  }
  return c;
}

// Every pair of atom types' contact time against the DEM step (a Hertz contact's at the
// largest impact speed to expect: the fastest inflow, or a fall over the domain's height)
void check_contact_times(const DemInstance &dem, const std::string &script, double impact, double fall,
                         MPI_Comm comm, StartReport &r) {
  if (!dem.integrates()) {
    r.lines.push_back("TFDEM coupling: the DEM script integrates no particle motion (no fix nve*): a frozen bed, "
                      "contact time not checked");
    return;
  }
  const std::vector<double> lightest = smallest_of_type(dem, dem.masses(), comm);
  const std::vector<double> smallest = smallest_of_type(dem, dem.radii(), comm);
  const double dt = dem.time_step();
  bool checked = false;
  for (int a = 1; a <= dem.type_count(); ++a)
    for (int b = a; b <= dem.type_count(); ++b) {
      const double m_eff = reduced(lightest[a - 1], lightest[b - 1]);
      if (std::isinf(m_eff)) continue;
      const ContactOfTypes c = contact_of_types(dem, a, b, m_eff, reduced(smallest[a - 1], smallest[b - 1]), impact,
                                                {impact, fall});
      if (c.time < 0) continue;
      checked = true;
      const double d = 2 * std::min(smallest[a - 1], smallest[b - 1]);
      r.lines.push_back(Text() << "TFDEM coupling: contact of atom types " << a << " and " << b << " (" << c.model
                               << "): t_c = " << c.time << " s (lightest particles), " << c.time / dt
                               << " DEM steps per contact; deepest overlap " << 100 * c.overlaps[1] / d
                               << " % of d at a free fall's impact (" << fall << " m/s), " << 100 * c.overlaps[0] / d
                               << " % at " << impact << " m/s");
      if (c.overlaps[1] > kLargestSoundImpactOverlap * d)
        r.warnings.push_back(Text() << "contact of atom types " << a << " and " << b << ": a particle falling " << fall
                                    << " m/s onto another sinks " << 100 * c.overlaps[1] / d
                                    << " % of its diameter into it (more than " << 100 * kLargestSoundImpactOverlap
                                    << " %): the contacts are too soft for the bed; stiffen k_n (or E)");
      const std::string problem = dem_step_problem(c.time, dt, c.restitution);
      if (!problem.empty()) {
        r.refusal = Text() << script << ": contact of atom types " << a << " and " << b << " (" << c.model
                           << "): " << problem;
        return;
      }
      const std::string advice = dem_step_advice(c.time, dt, c.restitution);
      if (!advice.empty())
        r.lines.push_back(Text() << "TFDEM coupling: advice: contact of atom types " << a << " and " << b << ": "
                                 << advice);
    }
  if (!checked)
    r.lines.push_back("TFDEM coupling: the DEM script gives neither a linear contact (k_n with gamman_abs or "
                      "coefficientRestitution) nor a Hertz one (youngsModulus): contact time not checked");
}

// The gas step a whole number of DEM steps: the coupling interval's, or (left out) deltaT / dt
void check_gas_step(const LiggghtsSettings &settings, const CaseAtStart &c, double dt, StartReport &r) {
  if (c.adjustable_gas_step) {
    r.refusal = "system/controlDict: adjustTimeStep must be 'no' for a coupled case: the gas step is "
                "coupling_interval DEM steps";
    return;
  }
  const double delta_t = c.gas_step;
  const long interval = coupling_interval(settings, delta_t, dt);
  if (interval >= 1 && std::abs(delta_t - interval * dt) <= 1e-9 * std::max(std::abs(delta_t), interval * dt)) return;
  if (settings.coupling_interval == 0) {
    const long below = std::max(1L, static_cast<long>(std::floor(delta_t / dt)));
    r.refusal = Text() << "system/controlDict: deltaT = " << delta_t << " s is not a whole number of DEM steps of " << dt
                       << " s (the DEM script's timestep; " << delta_t / dt << " of them): use deltaT = " << below
                       << " x " << dt << " = " << below * dt << " s, or a DEM timestep of deltaT / " << below << " = "
                       << delta_t / below << " s";
    return;
  }
  r.refusal = Text() << "system/controlDict: deltaT = " << delta_t << " s must equal dem.coupling_interval x DEM "
                     << "timestep = " << settings.coupling_interval << " x " << dt << " = " << interval * dt << " s ("
                     << c.config->file << "); the coupling interval must divide the gas step evenly";
}

// The core's scene check (tfdem::check_scene, as tfdem-scene-check) with the first contact
void scene(const DemInstance &dem, const LiggghtsSettings &settings, const CaseAtStart &c, StartReport &r) {
  DemInstance::LinearContact contact;
  const CouplingConfig &config = *c.config;
  if (!dem.linear_contact(1, 1, contact) || contact.damping < 0 || c.fastest_inflow <= 0 ||
      config.particle_diameters.empty()) {
    r.lines.push_back("TFDEM scene: not checked (it needs a linear contact with absolute damping and an inflow)");
    return;
  }
  Scene s;
  s.particle_diameter = config.particle_diameters.front();  // smallest: shortest contact
  s.particle_density = config.particle_density;
  s.gas = config.gas;
  s.gravity = std::sqrt(c.gravity[0] * c.gravity[0] + c.gravity[1] * c.gravity[1] + c.gravity[2] * c.gravity[2]);
  s.gas_velocity = c.fastest_inflow;
  s.cell_size = std::min(c.cell_size[0], c.cell_size[1]);
  s.normal_stiffness = contact.stiffness;
  s.normal_damping = contact.damping;
  s.dem_time_step = dem.time_step();
  s.coupling_interval = coupling_interval(settings, c.gas_step, dem.time_step());
  s.drag_law = config.transfer.law;
  try {
    std::istringstream report(format_report(check_scene(s)));
    for (std::string line; std::getline(report, line);) r.lines.push_back("TFDEM scene: " + line);
  } catch (const std::exception &e) {
    r.lines.push_back(std::string("TFDEM scene: not checked (") + e.what() + ")");
  }
}

// LIGGGHTS' processor grid against the particles: the fullest rank sets every DEM step's pace
void balance(const DemInstance &dem, MPI_Comm comm, StartReport &r) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  if (ranks < 2) return;
  const std::array<int, 3> grid = dem.processor_grid();
  double most = dem.local_count(), least = most, total = most;
  MPI_Allreduce(MPI_IN_PLACE, &most, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &least, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, comm);
  const double mean = total / ranks;
  std::string line = Text() << "TFDEM parallel: LIGGGHTS' processor grid " << grid[0] << " x " << grid[1] << " x "
                            << grid[2] << " (even cuts of the box): particles per rank " << least << " to " << most
                            << ", mean " << mean;
  if (mean > 0 && most > kDemImbalance * mean)
    line += Text() << ". TFDEM advice: the fullest rank holds " << most / mean << " times the mean and the others "
                   << "wait for it every DEM step (its cuts leave ranks in the freeboard). Fix: cut only across the "
                   << "bed (processors * 1 1; * 1 * for a 3-D bed)";
  r.lines.push_back(line);
}

}  // namespace

StartReport DemInstance::check_start(const CaseAtStart &c) const {
  StartReport r;
  const auto &settings = static_cast<const LiggghtsSettings &>(*c.config->engine_settings);
  if (c.resuming)
    for (const std::string &name : unresumable_outputs())
      r.warnings.push_back(name + ": an output named by a pattern or a variable is not cut back to the checkpoint "
                                  "(files written after it by the stopped run stay until written again)");
  const double dt = time_step();
  r.lines.push_back(Text() << "TFDEM coupling: " << global_count() << " particles, DEM step " << dt << " s, "
                           << coupling_interval(settings, c.gas_step, dt) << " DEM steps per gas step");
  balance(*this, comm_, r);
  double g[3];
  if (!gravity(g)) {
    r.warnings.push_back("the DEM script has no fix gravity: the particles feel no weight (the gas has constant/g = " +
                         vector_text(c.gravity) + " m/s^2)");
  } else {
    const double diff = std::hypot(g[0] - c.gravity[0], g[1] - c.gravity[1], g[2] - c.gravity[2]);
    const double scale = std::max(std::hypot(c.gravity[0], c.gravity[1], c.gravity[2]), 1e-300);
    if (diff > 1e-9 * scale) {
      r.refusal = "gravity disagrees: constant/g is " + vector_text(c.gravity) +
                  " m/s^2, the DEM script's fix gravity gives " + vector_text(g) + " m/s^2. Make them equal.";
      return r;
    }
  }
  check_contact_times(*this, settings.script, std::max(c.fastest_inflow, c.fall_speed), c.fall_speed, comm_, r);
  if (!r.refusal.empty()) return r;
  check_gas_step(settings, c, dt, r);
  if (!r.refusal.empty()) return r;
  scene(*this, settings, c, r);
  return r;
}

double DemInstance::overlap_energy(int a, int b, double ra, double rb, double depth) const {
  LinearContact linear;
  if (linear_contact(a, b, linear)) return 0.5 * linear.stiffness * depth * depth;
  HertzContact hertz;
  if (hertz_contact(a, b, hertz)) {
    const double modulus = contact::effective_modulus(hertz.young_a, hertz.poisson_a, hertz.young_b, hertz.poisson_b);
    return 8.0 / 15.0 * modulus * std::sqrt(ra * rb / (ra + rb)) * std::pow(depth, 2.5);
  }
  return -1;
}

}  // namespace tfdem
