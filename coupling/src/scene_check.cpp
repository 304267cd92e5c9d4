#include "tfdem/scene_check.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tfdem/contact.h"
#include "tfdem/particles.h"

namespace tfdem {
namespace {

// Cells narrower than this many diameters make the centroid void fraction unsafe.
constexpr double kCentroidCellsPerDiameter = 3.0;
// Explicit drag is stable while the drag response time exceeds this many coupling times.
constexpr double kDragResponseToCoupling = 2.0;

void require(double value, const char *name) {
  if (!(value > 0.0)) throw std::invalid_argument(std::string("scene check: ") + name + " must be > 0");
}

// Net weight minus drag of a sphere falling at u (N per unit of the common factor).
double fall_balance(double u, double d, double rho_p, const drag::Gas &gas, double g) {
  const double re = gas.density * u * d / gas.viscosity;
  const double cd = drag::drag_coefficient(re, 0.44);
  return (rho_p - gas.density) * g * sphere_volume(d) - 0.5 * cd * gas.density * kPi * d * d / 4.0 * u * u;
}

void add(SceneReport &r, Finding::Level level, const std::string &topic, const std::string &text) {
  r.findings.push_back({level, topic, text});
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

void time_step_findings(const Scene &s, SceneReport &r) {
  const SceneNumbers &n = r.numbers;
  const std::string problem = dem_step_problem(n.contact_time, s.dem_time_step, n.restitution);
  const std::string advice = dem_step_advice(n.contact_time, s.dem_time_step, n.restitution);
  if (!problem.empty())
    add(r, Finding::Level::Error, "DEM time step", problem);
  else if (!advice.empty())
    add(r, Finding::Level::Advice, "DEM time step", advice);
  else
    add(r, Finding::Level::Ok, "DEM time step", num(n.contact_time / s.dem_time_step) + " steps per contact");
}

void void_fraction_findings(SceneReport &r) {
  const double ratio = r.numbers.cell_to_particle;
  if (ratio < 1.0)
    add(r, Finding::Level::Advice, "void fraction",
        "cells are smaller than particles (" + num(ratio) +
            " d_p): use porous_cube (seed 001 eq. 34-37) with a floor; centroid and divided over-fill cells");
  else if (ratio < kCentroidCellsPerDiameter)
    add(r, Finding::Level::Advice, "void fraction",
        "cells are " + num(ratio) + " d_p wide: centroid void fraction is noisy and may over-fill cells; "
        "use porous_cube or divided");
  else
    add(r, Finding::Level::Ok, "void fraction", "cells are " + num(ratio) + " d_p wide: centroid is adequate");
}

void drag_findings(SceneReport &r) {
  const SceneNumbers &n = r.numbers;
  if (n.dense_drag_time < kDragResponseToCoupling * n.coupling_time)
    add(r, Finding::Level::Advice, "drag coupling",
        "drag response time in the packed bed " + num(n.dense_drag_time) + " s is below twice the coupling time " +
            num(n.coupling_time) + " s: couple more often or treat drag implicitly");
  else
    add(r, Finding::Level::Ok, "drag coupling",
        "drag response time " + num(n.dense_drag_time) + " s >> coupling time " + num(n.coupling_time) +
            " s: explicit particle drag per coupling interval is stable");
}

void gas_findings(SceneReport &r) {
  const SceneNumbers &n = r.numbers;
  if (n.stokes > 100.0)
    add(r, Finding::Level::Ok, "gas turbulence",
        "St = " + num(n.stokes) + " >> 1: particles do not follow small gas eddies; laminar gas (no subgrid "
        "turbulence model) is what seed 000 uses");
  else
    add(r, Finding::Level::Advice, "gas turbulence",
        "St = " + num(n.stokes) + ": particles respond to gas fluctuations; consider a turbulence model");
  add(r, Finding::Level::Ok, "fluid forces",
      "pressure-gradient force on (bed weight is carried by grad p); viscous-stress force negligible at "
      "Re_p = " + num(n.reynolds) + " (seed 000 neglects it)");
}

// Which particle engine fits, from the two engines' measured runs (bench/README.md, "Two
// particle engines"), U / U_mf of the smallest spheres: seed 000's uniform bed (1.5 U_mf,
// bubbling throughout) agreed with LIGGGHTS within noise at 5x less processor time, and
// Goldschmidt's bidisperse bed (1.55 U_mf) cost 10x less once bubbling; Bokkers' single-bubble
// bed at 0.99 U_mf, its spheres in enduring contact, cost 15x more (event-driven collisions
// chatter there, a million per sphere per second).
constexpr double kBubblingThroughout = 1.5;  // U / U_mf of the measured uniform bed

void engine_findings(const Scene &s, SceneReport &r) {
  const double ratio = s.gas_velocity / r.numbers.minimum_fluidization;
  if (ratio >= kBubblingThroughout)
    add(r, Finding::Level::Advice, "particle engine",
        "U = " + num(ratio) + " U_mf: a bed bubbling throughout; the hard-sphere engine (dem.engine: hard_sphere) "
        "ran seed 000's uniform bed (1.5 U_mf) within noise of LIGGGHTS at 5x less processor time and "
        "Goldschmidt's bidisperse bed (1.55 U_mf) at 10x less (bench/README.md, 'Two particle engines')");
  else
    add(r, Finding::Level::Ok, "particle engine",
        "U = " + num(ratio) + " U_mf: near minimum fluidization spheres stay in enduring contact, which soft "
        "spheres (LIGGGHTS) carry at a fixed cost per step and event-driven hard spheres by ever more collisions "
        "(the single-bubble bed at 0.99 U_mf: 15x the processor time)");
}

}  // namespace

double recommended_steps_per_contact(double restitution) {
  const StepsPerContactAt low = kJetBedStepRule, high = kBubblingBedStepRule;
  if (restitution < 0.0 || restitution >= high.restitution) return high.steps;
  if (restitution <= low.restitution) return low.steps;
  const double w = (restitution - low.restitution) / (high.restitution - low.restitution);
  return low.steps + w * (high.steps - low.steps);
}

std::string dem_step_problem(double contact_time, double dt, double restitution) {
  if (std::isinf(contact_time))
    return "the contact is overdamped (eta_n >= 2 sqrt(k_n m_eff), seed 000 eq. 26 has no real t_c): particles "
           "do not rebound and e_n is undefined; lower the damping (seed 001 eq. 27 gives eta_n for a chosen e_n)";
  if (dt > contact_time / kMinimumStepsPerContact) {
    const double steps = recommended_steps_per_contact(restitution);
    return "DEM step dt = " + num(dt) + " s is above t_c/10 = " + num(contact_time / kMinimumStepsPerContact) +
           " s (t_c = " + num(contact_time) + " s, seed 000 eq. 26): contacts are not resolved; use dt <= t_c/" +
           num(steps) + " = " + num(contact_time / steps) + " s";
  }
  return "";
}

std::string dem_step_advice(double contact_time, double dt, double restitution) {
  const double steps = recommended_steps_per_contact(restitution);
  if (std::isinf(contact_time) || dt <= contact_time / steps) return "";
  const std::string of = restitution < 0.0 ? "an unknown e_n" : "e_n = " + num(restitution);
  return "dt = " + num(dt) + " s resolves a contact with " + num(contact_time / dt) +
         " steps; the speed-against-error sweeps recommend >= " + num(steps) + " for " + of + " (dt <= " +
         num(contact_time / steps) + " s; bench/README.md)";
}

std::string gas_step_problem(double courant, double gas_step) {
  if (courant <= kLargestMeasuredCourantNumber) return "";
  return "the gas Courant number reached " + num(courant) + " (> " + num(kLargestMeasuredCourantNumber) +
         ", the largest the speed-against-error sweeps measured within noise; bench/README.md): the gas step " +
         num(gas_step) + " s is too long for the flow; use <= " +
         num(gas_step * kLargestMeasuredCourantNumber / courant) +
         " s (fewer dem.coupling_interval steps, deltaT to match)";
}

bool SceneReport::has_errors() const {
  for (const auto &f : findings)
    if (f.level == Finding::Level::Error) return true;
  return false;
}

double minimum_fluidization_velocity(double d, double rho_p, const drag::Gas &gas, double g) {
  const double ar = gas.density * (rho_p - gas.density) * g * d * d * d / (gas.viscosity * gas.viscosity);
  const double re_mf = std::sqrt(33.7 * 33.7 + 0.0408 * ar) - 33.7;
  return re_mf * gas.viscosity / (gas.density * d);
}

double terminal_velocity(double d, double rho_p, const drag::Gas &gas, double g) {
  double lo = 0.0, hi = 1.0;
  while (fall_balance(hi, d, rho_p, gas, g) > 0.0) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (mid > 0.0 && fall_balance(mid, d, rho_p, gas, g) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

SceneReport check_scene(const Scene &s) {
  require(s.particle_diameter, "particle diameter");
  require(s.particle_density, "particle density");
  require(s.gas.density, "gas density");
  require(s.gas.viscosity, "gas viscosity");
  require(s.gravity, "gravity");
  require(s.gas_velocity, "gas velocity");
  require(s.cell_size, "cell size");
  require(s.normal_stiffness, "normal stiffness");
  require(s.dem_time_step, "DEM time step");
  if (s.coupling_interval < 1) throw std::invalid_argument("scene check: coupling interval must be >= 1");
  const double d = s.particle_diameter, mu = s.gas.viscosity;
  const double m = contact::sphere_mass(d, s.particle_density);
  const double m_eff = contact::effective_mass(m, m);
  SceneReport r;
  SceneNumbers &n = r.numbers;
  n.relaxation_time = s.particle_density * d * d / (18.0 * mu);
  n.stokes = n.relaxation_time / (d / s.gas_velocity);
  n.reynolds = s.gas.density * s.gas_velocity * d / mu;
  n.archimedes = s.gas.density * (s.particle_density - s.gas.density) * s.gravity * d * d * d / (mu * mu);
  n.minimum_fluidization = minimum_fluidization_velocity(d, s.particle_density, s.gas, s.gravity);
  n.terminal_velocity = terminal_velocity(d, s.particle_density, s.gas, s.gravity);
  n.contact_time = contact::contact_time_from_damping(s.normal_stiffness, s.normal_damping, m_eff);
  n.restitution = contact::restitution_from_damping(s.normal_stiffness, s.normal_damping, m_eff);
  n.recommended_time_step =
      contact::recommended_time_step(n.contact_time, recommended_steps_per_contact(n.restitution));
  const double eps_s = 1.0 - s.packed_gas_fraction;
  const double slip = n.minimum_fluidization / s.packed_gas_fraction;
  n.dense_drag_time = s.particle_density * eps_s /
                      drag::beta(s.drag_law, {s.packed_gas_fraction, d, slip}, s.gas);
  n.coupling_time = s.coupling_interval * s.dem_time_step;
  n.cell_to_particle = s.cell_size / d;
  time_step_findings(s, r);
  void_fraction_findings(r);
  drag_findings(r);
  gas_findings(r);
  engine_findings(s, r);
  return r;
}

std::string format_report(const SceneReport &r) {
  const SceneNumbers &n = r.numbers;
  std::ostringstream s;
  s << "Scene numbers\n"
    << "  particle relaxation time tau_p   " << num(n.relaxation_time) << " s\n"
    << "  Stokes number St (seed 000 eq.36) " << num(n.stokes) << "\n"
    << "  particle Reynolds number Re_p     " << num(n.reynolds) << "\n"
    << "  Archimedes number Ar              " << num(n.archimedes) << "\n"
    << "  U_mf (Wen-Yu)                     " << num(n.minimum_fluidization) << " m/s\n"
    << "  terminal velocity u_t             " << num(n.terminal_velocity) << " m/s\n"
    << "  contact time t_c (eq. 26)         " << num(n.contact_time) << " s\n"
    << "  restitution e_n (eq. 25)          " << num(n.restitution) << "\n"
    << "  recommended DEM step t_c/" << num(recommended_steps_per_contact(n.restitution)) << "       "
    << num(n.recommended_time_step) << " s\n"
    << "  drag response time (packed bed)   " << num(n.dense_drag_time) << " s\n"
    << "  coupling time                     " << num(n.coupling_time) << " s\n"
    << "  cell size / particle diameter     " << num(n.cell_to_particle) << "\n"
    << "What the scene needs\n";
  for (const auto &f : r.findings) {
    const char *tag = f.level == Finding::Level::Ok ? "ok    " : f.level == Finding::Level::Advice ? "advice" : "ERROR ";
    s << "  [" << tag << "] " << f.topic << ": " << f.text << "\n";
  }
  return s.str();
}

}  // namespace tfdem
