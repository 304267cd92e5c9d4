// Gas-particle drag closures: the interphase momentum transfer coefficient beta (kg/m^3/s).
//
// Conventions (seed 000 eq. 28-29, seed 001 eq. 1): the drag force on particle i is
//   f_i = V_i beta / eps_s (u_g - v_i),
// and the force on the gas per unit volume is beta (u_g - v_s). Every closure below has a
// factor eps_s, so each returns beta / eps_s (kg/m^3/s), which stays finite for a lone
// particle (eps_s -> 0); multiply by eps_s for beta. Reynolds number (both seeds):
//   Re = eps_g rho_g |u_g - v| d_p / mu_g.
// Dimensionless form used by seed 001: F = beta d_p^2 / mu_g.
#ifndef TFDEM_DRAG_H
#define TFDEM_DRAG_H

#include <string>
#include <vector>

namespace tfdem::drag {

// Gas density (kg/m^3) and dynamic viscosity (Pa s).
struct Gas {
  double density;
  double viscosity;
};

// Local state seen by one particle (or a cell's mean particle).
struct State {
  double void_fraction;  // eps_g, in (0, 1]
  double diameter;      // d_p (m)
  double slip_speed;    // |u_g - v_p| (m/s)
};

enum class Law {
  // Seed 000 eq. 30-31 as the paper writes it (Tsuji/MFIX): Ergun for eps_g < 0.8, Wen-Yu
  // with eps_g^-2.7 for eps_g >= 0.8, C_D = 0.43 for Re >= 1000. beta jumps at eps_g = 0.8.
  ErgunWenYu,
  // Seed 001 eq. 3-4: the review's variant, eps_g^-2.65 and C_D = 0.44. Its eq. 3 prints the
  // inertial Ergun term as 1.75 eps_s Re, eps_g times Ergun's with its Re = eps_g rho |u-v|
  // d/mu: taken as a misprint, Ergun's law (as seed 000 eq. 30) is used. Jumps at 0.8.
  ErgunWenYuReview,
  // Seed 001, text after eq. 4: the lesser of eq. 3 and eq. 4 everywhere (no jump). At low
  // Re in dilute regions Ergun is the lesser, so it does NOT reach the Stokes limit.
  MinErgunWenYu,
  // Seed 001 eq. 5 (Hill, Koch & Ladd 2001, LB data, stated for Re > 40). A for eps_g > 0.6
  // is divided by eps_s so that A eps_s^2/eps_g -> 18 eps_s (Stokes) as eps_s -> 0 and A is
  // continuous (178 vs 180) at eps_g = 0.6, as in the original correlation.
  HillKochLadd,
  // Seed 001 eq. 6 (Beetstra, van der Hoef & Kuipers 2007, monodisperse), Re up to 1000, with
  // the 1/eps_g of the original's inertial term that the seed's print drops (drag.cpp).
  Beetstra,
  // Di Felice (1994): f = C_D rho pi d^2/8 eps_g^2 |u-v|(u-v) eps_g^-chi,
  // C_D = (0.63 + 4.8/sqrt(Re))^2, chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2).
  // Low-Re limit is 0.96 Stokes (4.8^2/24). As in CFDEMcoupling.
  DiFelice,
  // Koch & Hill (2001) as in MFiX/CFDEMcoupling (Benyahia et al. 2006 without the high-Re
  // blend): beta = 18 mu eps_g^2 eps_s F / d^2, F = F0 + F3 Re / 2,
  // F0 = (1 + 3 sqrt(eps_s/2) + 135/64 eps_s ln eps_s + 16.14 eps_s) /
  //      (1 + 0.681 eps_s - 8.48 eps_s^2 + 8.16 eps_s^3)       for eps_s < 0.4,
  //      10 eps_s / eps_g^3                                       otherwise,
  // F3 = 0.0673 + 0.212 eps_s + 0.0232 / eps_g^5.
  KochHill,
};

// Names accepted in configuration files, in Law order.
const std::vector<std::string> &law_names();

// The law called `name`; throws std::invalid_argument listing the valid names.
Law law_from_name(const std::string &name);

// The configuration name of a law.
const std::string &law_name(Law law);

// Particle Reynolds number Re = eps_g rho_g |u_g - v| d_p / mu_g.
double reynolds(const State &state, const Gas &gas);

// Single-sphere drag coefficient of seed 000 eq. 31 / seed 001 eq. 4 (Schiller-Naumann
// below Re = 1000, `newton_value` above). Re must be > 0.
double drag_coefficient(double reynolds, double newton_value);

// beta / eps_s (kg/m^3/s) of `law` at `state`.
double beta_per_solid_fraction(Law law, const State &state, const Gas &gas);

// beta (kg/m^3/s) = eps_s * beta_per_solid_fraction.
double beta(Law law, const State &state, const Gas &gas);

// Stokes drag of a lone sphere expressed as beta / eps_s: 18 mu / d^2.
double stokes_beta_per_solid_fraction(double diameter, const Gas &gas);

// How a particle's drag depends on its size in a mixture (per-particle transfers only).
enum class Polydispersity {
  // The monodisperse law at the particle's own diameter d_i ("standard drag", seed 001 §5).
  OwnDiameter,
  // Beetstra, van der Hoef & Kuipers (2007), AIChE J. 53, 489, and its erratum
  // (AIChE J. 53, 3020), the relation seed 001 §5 tests against Goldschmidt's experiment:
  //   F_i = F(eps_g, <Re>) * (eps_g y_i + eps_s y_i^2 + 0.064 eps_g y_i^3) / (1 + 0.064 eps_g),
  //   y_i = d_i/<d>, <d> = sum d^3 / sum d^2 (the local Sauter mean), <Re> with <d>,
  // F_i = f_i / (3 pi mu d_i eps_g |u-v|), F the monodisperse law chosen by `Law`. As printed
  // the bracket is 1 + 0.064 eps_g at y_i = 1, so equal sizes would get up to 6.4 % more drag
  // than the monodisperse law the correction multiplies; dividing by its y_i = 1 value keeps the
  // size dependence and makes the relation reduce exactly to the monodisperse law (MFiX instead
  // drops the y^3 term for its first solids phase). Fitted for 0.1 <= eps_s <= 0.6,
  // 1/4 <= y <= 4 (binary arrays, Re <= 1000).
  Beetstra2007,
};

// Names accepted in configuration files, in Polydispersity order.
const std::vector<std::string> &polydispersity_names();
Polydispersity polydispersity_from_name(const std::string &name);

// Factor on beta/eps_s evaluated at the Sauter mean <d> (and <Re>) that gives particle i's
// beta_i/eps_s under Beetstra2007: f_i = V_i (beta/eps_s)(<d>) * factor * (u - v), i.e.
// factor = (eps_g y + eps_s y^2 + 0.064 eps_g y^3) / ((1 + 0.064 eps_g) y^2), y = d_i/<d>.
double polydisperse_factor(double void_fraction, double size_ratio);

}  // namespace tfdem::drag

#endif
