// Drag closures: seed 000 eq. 29-31, seed 001 eq. 3-6, Di Felice (1994), Koch & Hill (2001).
// Expected values are numbers worked out from the published formulas (the arithmetic in each
// test's comment), independent of the implementation.
#include <gtest/gtest.h>

#include "tfdem/drag.h"

namespace {

using namespace tfdem::drag;

const Gas kAir{1.2, 1.8e-5};
constexpr double kD = 2.5e-3;  // uniform-bed particle diameter (m)

// Stokes drag of a lone sphere as beta/eps_s, by hand: 18 mu/d^2 = 18 * 1.8e-5 / (2.5e-3)^2
// = 3.24e-4 / 6.25e-6 = 51.84 kg/m^3/s.
constexpr double kStokes = 51.84;

// A state in the Stokes limit: lone particle (eps_s = 1e-9), Re ~ 1e-8.
State stokes_state() {
  const double eps_g = 1.0 - 1e-9;
  const double slip = 1e-8 * kAir.viscosity / (eps_g * kAir.density * kD);
  return {eps_g, kD, slip};
}

// Every closure but min(Ergun, Wen-Yu) reduces to Stokes drag 3 pi mu d (u - v) for a lone
// particle at Re -> 0, i.e. beta/eps_s -> kStokes = 51.84 kg/m^3/s (by hand above). Di Felice's
// C_D -> 4.8^2/Re = 23.04/Re instead of 24/Re: 0.96 * 51.84 = 49.7664 kg/m^3/s. Relative
// tolerance 1e-4 (a 1 % error fails): the leading corrections are 3/sqrt(2) sqrt(eps_s) ~ 7e-5
// (Koch-Hill, Hill-Koch-Ladd), 0.15 Re^0.687 ~ 5e-7 (Wen-Yu), 2 * 0.63 sqrt(Re)/4.8 ~ 3e-5 (Di Felice).
TEST(Drag, StokesLimitOfEachLaw) {
  for (Law law : {Law::ErgunWenYu, Law::ErgunWenYuReview, Law::HillKochLadd, Law::Beetstra, Law::KochHill}) {
    EXPECT_NEAR(beta_per_solid_fraction(law, stokes_state(), kAir), kStokes, 1e-4 * kStokes) << law_name(law);
  }
  EXPECT_NEAR(beta_per_solid_fraction(Law::DiFelice, stokes_state(), kAir), 49.7664, 1e-4 * 49.7664);
}

// Stokes' sphere by hand, a 50 um glass bead (2500 kg/m^3) in air: 18 mu/d^2 = 3.24e-4 /
// 2.5e-9 = 129600 kg/m^3/s. Its terminal velocity (Stokes 1851) u_t = (rho_p - rho_g) g d^2 /
// (18 mu) = 2498.8 * 9.81 * 2.5e-9 / 3.24e-4 = 6.128307e-5 / 3.24e-4 = 0.18914528 m/s, where the
// drag per particle volume (beta/eps_s) u_t balances the net weight per volume 2498.8 * 9.81 =
// 24513.228 N/m^3.
TEST(Drag, StokesDragBalancesWeightAtStokesTerminalVelocity) {
  const double stokes_50um = stokes_beta_per_solid_fraction(5e-5, kAir);
  EXPECT_NEAR(stokes_50um, 129600.0, 1e-12 * 129600.0);
  EXPECT_NEAR(stokes_50um * 0.18914528, 24513.228, 1e-7 * 24513.228);
}

// Values at general states computed outside this code (a separate Python implementation of
// the published formulas, d = 2.5 mm, air): Ergun (1952) at eps_g = 0.45, slip 0.8 m/s;
// Hill, Koch & Ladd (seed 001 eq. 5, A divided by eps_s above eps_g = 0.6, see drag.h) at
// eps_g = 0.5 and 0.7; Koch & Hill (2001), beta = 18 mu eps_g^2 eps_s/d^2 (F0 + F3 Re/2), at
// eps_g = 0.7 and 0.5; Di Felice (1994), f = C_D rho pi d^2/8 eps_g^2 |u-v|^2 eps_g^-chi,
// at eps_g = 0.7 (slip 0.8) and 0.45 (slip 0.3). Relative tolerance 1e-9 (printed digits).
TEST(Drag, HandComputedValuesAtGeneralStates) {
  struct Point {
    Law law;
    double void_fraction, slip, beta;
  };
  for (const Point &p : {Point{Law::ErgunWenYuReview, 0.45, 0.8, 660.0}, Point{Law::MinErgunWenYu, 0.45, 0.8, 660.0},
                         Point{Law::HillKochLadd, 0.5, 0.8, 457.1448}, Point{Law::HillKochLadd, 0.7, 0.8, 167.603904789},
                         Point{Law::KochHill, 0.7, 0.8, 167.556884381}, Point{Law::KochHill, 0.5, 0.8, 456.9912},
                         Point{Law::DiFelice, 0.7, 0.8, 163.463605405}, Point{Law::DiFelice, 0.45, 0.3, 372.452759349}})
    EXPECT_NEAR(beta(p.law, {p.void_fraction, kD, p.slip}, kAir), p.beta, 1e-9 * p.beta)
        << law_name(p.law) << " at eps_g " << p.void_fraction;
}

// Documented: min(Ergun, Wen-Yu) takes Ergun in the dilute low-Re limit, far below Stokes. By
// hand at the Stokes state (eps_s = 1e-9, |u - v| = 1e-8 mu / (eps_g rho d) = 6e-11 m/s):
// beta/eps_s = 150 eps_s mu / (eps_g d^2) + 1.75 rho |u - v| / d = 4.32e-7 + 840 * 6e-11 =
// 4.824e-7 kg/m^3/s, 1e-8 of kStokes. Tolerance 2e-7 relative: eps_s = 1 - (1 - 1e-9) in
// doubles is 1e-9 only to within half an ulp of 1 (5.6e-17), i.e. 5.6e-8 relative.
TEST(Drag, MinErgunWenYuMissesStokesLimitAsDocumented) {
  const double min_law = beta_per_solid_fraction(Law::MinErgunWenYu, stokes_state(), kAir);
  EXPECT_NEAR(min_law, 4.824e-7, 2e-7 * 4.824e-7);
  EXPECT_LT(min_law, 1e-3 * kStokes);
}

// By hand: Re = eps_g rho |u - v| d / mu = 0.9 * 1.2 * 1.0 * 2.5e-3 / 1.8e-5 = 2.7e-3 / 1.8e-5
// = 150 (the superficial 1.2 * 2.5e-3 / 1.8e-5 = 166.67 would fail).
TEST(Drag, ReynoldsNumberUsesGasFraction) { EXPECT_NEAR(reynolds({0.9, kD, 1.0}, kAir), 150.0, 1e-12 * 150.0); }

// Schiller-Naumann C_D = 24/Re (1 + 0.15 Re^0.687) by hand: Re = 10: 10^0.687 = 4.864072,
// C_D = 2.4 * (1 + 0.7296108) = 4.151066. Just below Re = 1000: 1000^0.687 = 10^2.061 =
// 115.0800, C_D = 0.024 * (1 + 17.26201) = 0.4382881; at and above 1000 the law's Newton value
// (0.43 of seed 000 eq. 31, 0.44 of seed 001 eq. 4): jumps of -1.89 % and +0.39 %.
TEST(Drag, DragCoefficientIsSchillerNaumannBelowRe1000AndNewtonValueAbove) {
  EXPECT_NEAR(drag_coefficient(10.0, 0.44), 4.151066, 1e-6 * 4.151066);
  EXPECT_NEAR(drag_coefficient(1000.0 * (1 - 1e-12), 0.44), 0.4382881, 1e-6 * 0.4382881);
  EXPECT_EQ(drag_coefficient(1000.0, 0.43), 0.43);
  EXPECT_EQ(drag_coefficient(1000.0, 0.44), 0.44);
  EXPECT_EQ(drag_coefficient(5000.0, 0.43), 0.43);
}

// Wen-Yu in the Newton regime tells the paper's law (C_D = 0.43, eps_g^-2.7, seed 000 eq.
// 30-31) from the review's (0.44, eps_g^-2.65, seed 001 eq. 4), 1.8 % apart. By hand at eps_g =
// 0.9 and Re = 2000: |u - v| = Re mu / (eps_g rho d) = 0.036 / 0.0027 = 13.33333 m/s, eps_g rho
// |u - v| / d = 14.4 / 2.5e-3 = 5760, beta = 3/4 C_D eps_s 5760 eps_g^-n: paper 0.75 * 0.43 *
// 576 * 0.9^-2.7 = 185.76 * 1.329062 = 246.8865, review 0.75 * 0.44 * 576 * 0.9^-2.65 = 190.08 *
// 1.322079 = 251.3007 kg/m^3/s.
TEST(Drag, NewtonRegimeWenYuUsesEachLawsDragCoefficientAndExponent) {
  const State newton{0.9, kD, 2000.0 * kAir.viscosity / (0.9 * kAir.density * kD)};
  EXPECT_NEAR(beta(Law::ErgunWenYu, newton, kAir), 246.8865, 1e-6 * 246.8865);
  EXPECT_NEAR(beta(Law::ErgunWenYuReview, newton, kAir), 251.3007, 1e-6 * 251.3007);
}

// Seed 000 eq. 30 by hand at a slip of 1 m/s. Ergun at eps_g = 0.5: beta = 150 eps_s^2 mu /
// (eps_g d^2) + 1.75 eps_s rho |u - v| / d = 6.75e-4 / 3.125e-6 + 1.05 / 2.5e-3 = 216 + 420 = 636.
// Wen-Yu at eps_g = 0.9: Re = 150, 150^0.687 = 31.25897, C_D = 0.16 * (1 + 4.688846) =
// 0.9102153, beta = 3/4 C_D eps_s eps_g rho |u - v| / d eps_g^-n = 0.75 * 0.9102153 * 0.1 * 432
// * 0.9^-n = 29.49098 * 1.329062 (n = 2.7) = 39.19534, and * 1.322079 (n = 2.65, the review's
// exponent; C_D is the same below Re = 1000) = 38.98940 kg/m^3/s.
TEST(Drag, PaperLawHandComputedPoints) {
  EXPECT_NEAR(beta(Law::ErgunWenYu, {0.5, kD, 1.0}, kAir), 636.0, 1e-12 * 636.0);
  EXPECT_NEAR(beta(Law::ErgunWenYu, {0.9, kD, 1.0}, kAir), 39.19534, 1e-6 * 39.19534);
  EXPECT_NEAR(beta(Law::ErgunWenYuReview, {0.9, kD, 1.0}, kAir), 38.98940, 1e-6 * 38.98940);
}

// The paper's switch at eps_g = 0.8 is a jump, by hand at a bubbling-bed slip of 1 m/s. Just
// below, Ergun: 150 * 0.04 * 1.8e-5 / (0.8 * 6.25e-6) + 1.75 * 0.2 * 1.2 / 2.5e-3 = 21.6 + 168 =
// 189.6. At 0.8, Wen-Yu: Re = 0.8 * 1.2 * 2.5e-3 / 1.8e-5 = 133.3333, Re^0.687 = 28.82922, C_D =
// 0.18 * (1 + 4.324383) = 0.9583890, beta = 0.75 * 0.9583890 * 0.2 * 384 * 0.8^-2.7 = 55.20320 *
// 1.826657 = 100.8373 kg/m^3/s (47 % below).
TEST(Drag, PaperSwitchAtPointEightJumpsAsDocumented) {
  EXPECT_NEAR(beta(Law::ErgunWenYu, {0.8 - 1e-12, kD, 1.0}, kAir), 189.6, 1e-9 * 189.6);
  EXPECT_NEAR(beta(Law::ErgunWenYu, {0.8, kD, 1.0}, kAir), 100.8373, 1e-6 * 100.8373);
}

// min(Ergun, Wen-Yu) is continuous at 0.8 (both branches are continuous there).
TEST(Drag, MinErgunWenYuIsContinuousAtSwitch) {
  for (double u : {0.01, 0.3, 1.0, 5.0}) {
    const double below = beta(Law::MinErgunWenYu, {0.8 - 1e-9, kD, u}, kAir);
    const double above = beta(Law::MinErgunWenYu, {0.8 + 1e-9, kD, u}, kAir);
    EXPECT_NEAR(above / below, 1.0, 1e-6) << "slip " << u;
  }
}

// Hill-Koch-Ladd's A switches at eps_g = 0.6 from 18 eps_g^3 F0/eps_s = 178.2 to 180: a 1 %
// jump in the viscous term. Koch-Hill's F0 switches at eps_s = 0.4 from 18.33 to 18.52 (1 %).
TEST(Drag, LatticeBoltzmannLawsNearlyContinuousAtTheirSwitches) {
  for (double u : {1e-4, 0.5}) {
    const double hkl_lo = beta(Law::HillKochLadd, {0.6 - 1e-12, kD, u}, kAir);
    const double hkl_hi = beta(Law::HillKochLadd, {0.6 + 1e-12, kD, u}, kAir);
    EXPECT_NEAR(hkl_hi / hkl_lo, 1.0, 0.015);
    const double kh_lo = beta(Law::KochHill, {0.6 - 1e-12, kD, u}, kAir);
    const double kh_hi = beta(Law::KochHill, {0.6 + 1e-12, kD, u}, kAir);
    EXPECT_NEAR(kh_hi / kh_lo, 1.0, 0.015);
  }
}

// Beetstra by hand at eps_g = 0.6, Re = 50 (slip 0.5 m/s) and in a packed bed (eps_g = 0.4,
// Re = 200, slip 3 m/s) from Beetstra, van der Hoef & Kuipers (2007) in their own
// normalisation, as MFiX codes it (DRAG_BVK): F = 10 phi/eps^2 + eps^2 (1 + 1.5 sqrt(phi)) +
// 0.413 Re/(24 eps^2) (1/eps + 3 eps phi + 8.4 Re^-0.343)/(1 + 10^(3 phi) Re^-(1 + 4 phi)/2),
// beta/eps_s = 18 mu eps F / d^2 = 51.84 eps F.
//   eps 0.6: F = 11.11111 + 0.701526 + 2.390046 * 4.582162 / (1 + 15.84893 * 0.00618499)
//            = 11.11111 + 0.701526 + 10.95158 / 1.098025 = 21.78652, beta/eps_s = 31.104 F = 677.6480;
//   eps 0.4: F = 37.5 + 0.3459032 + 21.51042 * 4.584665 / (1 + 63.09573 * 1.225319e-4)
//            = 37.5 + 0.3459032 + 98.61805 / 1.007731 = 135.7074, beta/eps_s = 20.736 F = 2814.028.
TEST(Drag, BeetstraHandComputedPoints) {
  EXPECT_NEAR(beta_per_solid_fraction(Law::Beetstra, {0.6, kD, 0.5}, kAir), 677.6480, 1e-6 * 677.6480);
  EXPECT_NEAR(beta_per_solid_fraction(Law::Beetstra, {0.4, kD, 3.0}, kAir), 2814.028, 1e-6 * 2814.028);
}

// Dense packed bed: every Ergun-type law gives beta/eps_s > Stokes (hindered settling).
TEST(Drag, DenseBedDragExceedsStokes) {
  for (std::size_t i = 0; i < law_names().size(); ++i) {
    const Law law = static_cast<Law>(i);
    EXPECT_GT(beta_per_solid_fraction(law, {0.45, kD, 0.5}, kAir), kStokes) << law_name(law);
  }
}

TEST(Drag, NamesRoundTripAndUnknownNameListsValidOnes) {
  for (const auto &name : law_names()) EXPECT_EQ(law_name(law_from_name(name)), name);
  try {
    law_from_name("beetstr");
    FAIL() << "no exception";
  } catch (const std::invalid_argument &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("did you mean 'beetstra'?"), std::string::npos) << what;
    EXPECT_NE(what.find("'koch_hill'"), std::string::npos) << what;
  }
}

// Beetstra et al. (2007) bracket eps y + eps_s y^2 + 0.064 eps y^3 over its y = 1 value, per y^2.
TEST(Drag, PolydisperseFactorByHand) {
  for (double eps : {0.4, 0.6, 0.9}) EXPECT_NEAR(polydisperse_factor(eps, 1.0), 1.0, 1e-15) << eps;
  // eps = 0.6, y = 1.5: (0.9 + 0.9 + 0.1296) / (1.0384 * 2.25)
  EXPECT_NEAR(polydisperse_factor(0.6, 1.5), 1.9296 / (1.0384 * 2.25), 1e-15);
  // eps = 0.6, y = 0.5: (0.3 + 0.1 + 0.0048) / (1.0384 * 0.25); a small particle gets more drag
  // per volume than at <d> (the bracket falls slower than y^2).
  EXPECT_NEAR(polydisperse_factor(0.6, 0.5), 0.4048 / (1.0384 * 0.25), 1e-15);
  EXPECT_GT(polydisperse_factor(0.6, 0.5), 1.0);
  EXPECT_EQ(polydispersity_from_name("beetstra_2007"), Polydispersity::Beetstra2007);
  EXPECT_THROW(polydispersity_from_name("beetstra"), std::invalid_argument);
}

TEST(Drag, InvalidStateIsRejected) {
  EXPECT_THROW(beta(Law::Beetstra, {0.0, kD, 1.0}, kAir), std::invalid_argument);
  EXPECT_THROW(beta(Law::Beetstra, {1.2, kD, 1.0}, kAir), std::invalid_argument);
  EXPECT_THROW(beta(Law::Beetstra, {0.5, -kD, 1.0}, kAir), std::invalid_argument);
}

}  // namespace
