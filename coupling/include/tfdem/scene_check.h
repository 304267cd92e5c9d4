// Scene check: the dimensionless numbers of a gas-particle scene and the models, time steps
// and void-fraction method it needs ("model only what a scene needs").
#ifndef TFDEM_SCENE_CHECK_H
#define TFDEM_SCENE_CHECK_H

#include <string>
#include <vector>

#include "tfdem/drag.h"

namespace tfdem {

// The DEM step rule, stated once for the scene check and the solver's start-up check. The
// speed-against-error sweeps (bench/README.md, "DEM step") compared each bed's statistics
// (Delta p, its fluctuation and frequency, mean height, solids map) with a run at t_c/150:
// - the jet bed (e_n = 0.86) stays within noise down to t_c/37;
// - the bubbling bed (e_n = 0.97) does at t_c/57, while at t_c/37 its Delta p fluctuation is
//   3.2 sigma above the reference.
// Between the two measured restitutions the rule is linear in e_n; outside them it takes the
// nearer bed's value (unmeasured there). Why the weakly damped bed needs the finer step is not
// established: one collision's restitution error is under 0.1 % at t_c/37. A restitution that
// is not known (a Hertz contact given by its coefficientRestitution) gets the finer step.
// Fewer than 10 steps per contact do not resolve a contact at all (an error).
struct StepsPerContactAt {
  double restitution;
  double steps;
};
constexpr StepsPerContactAt kJetBedStepRule{0.86, 37.0};
constexpr StepsPerContactAt kBubblingBedStepRule{0.97, 57.0};
constexpr double kMinimumStepsPerContact = 10.0;
constexpr double kUnknownRestitution = -1.0;

// DEM steps per contact the rule above recommends for normal restitution e_n (< 0: unknown).
double recommended_steps_per_contact(double restitution);

// What is wrong with DEM step dt for contacts of duration t_c (infinite: overdamped) and
// restitution e_n, with the fix; "" when dt <= t_c/10.
std::string dem_step_problem(double contact_time, double dt, double restitution = kUnknownRestitution);

// The rule's advice when dt resolves a contact with fewer steps than it recommends; "" when not.
std::string dem_step_advice(double contact_time, double dt, double restitution);

// The gas step rule, from the same sweeps ("Gas step"): the jet bed's statistics stayed within
// noise of a reference whose largest cell Courant number was 0.32 at every gas step up to one
// whose largest Courant number (in the jet's cells, interstitial gas velocity) reached 3.2:
// the particles' drag response (about 1 s in that bed) is slow next to a gas step of 1 ms,
// and the implicit momentum equation stays stable. Longer steps were not measured, so the
// solver warns above it; the jet tutorial runs at about 2.5. It bounds the Courant number
// only: the bubbling bed at a 2 ms step (Courant 1.75) read its Delta p fluctuation 2.6 sigma
// off its reference, so each tutorial keeps the gas step its own sweep put on the front.
constexpr double kLargestMeasuredCourantNumber = 3.2;

// What is wrong with a gas step whose largest cell Courant number reached `courant`, with the
// fix; "" within the rule above.
std::string gas_step_problem(double courant, double gas_step);

struct Scene {
  double particle_diameter = 0.0;      // d_p (m)
  double particle_density = 0.0;       // rho_p (kg/m^3)
  drag::Gas gas{1.2, 1.8e-5};
  double gravity = 9.81;               // |g| (m/s^2)
  double gas_velocity = 0.0;           // characteristic (superficial inflow) gas velocity (m/s)
  double cell_size = 0.0;              // smallest in-plane cell size (m)
  double normal_stiffness = 0.0;       // k_n (N/m)
  double normal_damping = 0.0;         // eta_n, absolute (N s/m)
  double dem_time_step = 0.0;          // (s)
  long coupling_interval = 1;          // DEM steps per gas step
  drag::Law drag_law = drag::Law::ErgunWenYu;
  double packed_gas_fraction = 0.4;    // eps_g of the settled bed
};

struct SceneNumbers {
  double relaxation_time;         // tau_p = rho_p d^2 / (18 mu) (seed 000 after eq. 36)
  double stokes;                  // St = tau_p / (d / v_g) (seed 000 eq. 36)
  double reynolds;                // Re_p = rho_g v_g d / mu
  double archimedes;              // Ar = rho_g (rho_p - rho_g) g d^3 / mu^2
  double minimum_fluidization;    // U_mf (Wen-Yu): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7
  double terminal_velocity;       // single sphere, C_D of seed 000 eq. 31 (0.44 above Re 1000)
  double contact_time;            // t_c of seed 000 eq. 26, particle-particle
  double restitution;             // e_n of seed 000 eq. 25
  double recommended_time_step;   // t_c / recommended_steps_per_contact(e_n)
  double dense_drag_time;         // rho_p eps_s / beta in the packed bed at U_mf: drag response time
  double coupling_time;           // coupling_interval * dem_time_step
  double cell_to_particle;        // cell_size / d_p
};

struct Finding {
  enum class Level { Ok, Advice, Error } level;
  std::string topic;
  std::string text;
};

struct SceneReport {
  SceneNumbers numbers;
  std::vector<Finding> findings;
  bool has_errors() const;
};

// Minimum fluidization velocity by Wen and Yu (1966).
double minimum_fluidization_velocity(double diameter, double particle_density, const drag::Gas &gas, double gravity);
// Terminal velocity of a lone sphere with the standard drag curve (Schiller-Naumann below
// Re = 1000, C_D = 0.44 above), found by bisection to 1e-12 relative.
double terminal_velocity(double diameter, double particle_density, const drag::Gas &gas, double gravity);

// Numbers and findings for `scene`; throws std::invalid_argument on non-positive inputs.
SceneReport check_scene(const Scene &scene);

// Human-readable report.
std::string format_report(const SceneReport &report);

}  // namespace tfdem

#endif
