// Contact relations: seed 001 eq. 16, 27, 41, 43; seed 000 eq. 25-26, Table 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tfdem/contact.h"

namespace {

using namespace tfdem::contact;

struct CollisionResult {
  double restitution;
  double duration;
};

// Head-on collision m x'' = -k x - eta x' from overlap 0 at approach speed v0, integrated
// with velocity Verlet until the overlap returns to 0 (linear interpolation of the crossing).
CollisionResult integrate_collision(double k, double eta, double m, double v0) {
  const double dt = contact_time_from_damping(k, eta, m) / 20000.0;
  double x = 0.0, v = v0, t = 0.0;
  double a = (-k * x - eta * v) / m;
  while (true) {
    const double x_old = x, v_old = v, t_old = t;
    const double v_half = v + 0.5 * dt * a;
    x += dt * v_half;
    const double a_guess = (-k * x - eta * v_half) / m;
    v = v_half + 0.5 * dt * a_guess;
    a = (-k * x - eta * v) / m;
    t += dt;
    if (x < 0.0 && t > dt) {
      const double s = x_old / (x_old - x);
      return {-(v_old + s * (v - v_old)) / v0, t_old + s * dt};
    }
  }
}

// Elastic Hertz collision m x'' = -(4/3) E* sqrt(R*) x^(3/2) from overlap 0 at speed v0,
// integrated as above: its duration.
double integrate_hertz_collision(double modulus, double radius, double m, double v0) {
  const double c = 4.0 / 3.0 * modulus * std::sqrt(radius) / m;
  const auto acceleration = [c](double x) { return x > 0.0 ? -c * std::pow(x, 1.5) : 0.0; };
  const double dt = hertz_contact_time(modulus, radius, m, v0) / 20000.0;
  double x = 0.0, v = v0, t = 0.0, a = 0.0;
  while (true) {
    const double x_old = x, t_old = t;
    v += 0.5 * dt * a;
    x += dt * v;
    a = acceleration(x);
    v += 0.5 * dt * a;
    t += dt;
    if (x < 0.0) return t_old + x_old / (x_old - x) * dt;
  }
}

// Two spheres of the jet bed's beads (d = 4 mm, 2700 kg/m^3) with a softened modulus as DEM
// practice uses (E = 10 MPa, nu = 0.3) at 1 and 10 m/s. By hand, 1/E* = 2 (1 - 0.3^2) / 1e7 =
// 1.82e-7 1/Pa, E* = 5494505.49 Pa. The formula's duration equals the integrated one within
// 5e-4 (the constant 2.868 is rounded from 2.8683, 1e-4) and falls as v^(-1/5): 10^-0.2 = 0.6309573.
TEST(Contact, HertzContactTimeMatchesIntegratedCollision) {
  const double e_star = effective_modulus(1e7, 0.3, 1e7, 0.3);
  EXPECT_NEAR(e_star, 5494505.49, 1e-2);
  const double radius = 0.5 * 0.002, m = 0.5 * sphere_mass(0.004, 2700.0);
  for (const double v : {1.0, 10.0})
    EXPECT_NEAR(hertz_contact_time(e_star, radius, m, v) / integrate_hertz_collision(e_star, radius, m, v), 1.0, 5e-4);
  EXPECT_NEAR(hertz_contact_time(e_star, radius, m, 10.0) / hertz_contact_time(e_star, radius, m, 1.0), 0.6309573,
              1e-7);
}

// Deepest overlap of an elastic collision x'' = acceleration(x) from 0 at speed v0 (velocity
// Verlet; the overlap peaks where the velocity changes sign).
template <typename Acceleration>
double integrated_peak_overlap(Acceleration acceleration, double v0, double dt) {
  double x = 0.0, v = v0, a = 0.0, peak = 0.0;
  while (v > 0.0) {
    v += 0.5 * dt * a;
    x += dt * v;
    a = acceleration(x);
    v += 0.5 * dt * a;
    peak = std::max(peak, x);
  }
  return peak;
}

// The uniform bed's spheres (seed 000 Table 1: k_n 800 N/m, 2.5 mm, 2526 kg/m^3) meeting at
// 3 m/s, and the Hertz pair above at 1 and 10 m/s: the formulas' deepest overlap equals the
// integrated collision's within 1e-4.
TEST(Contact, ImpactOverlapMatchesIntegratedCollision) {
  const double m = 0.5 * sphere_mass(0.0025, 2526.0), k = 800.0;
  const double linear = integrated_peak_overlap([&](double x) { return -k * x / m; }, 3.0,
                                                contact_time_from_damping(k, 0.0, m) / 1e5);
  EXPECT_NEAR(linear_impact_overlap(k, m, 3.0) / linear, 1.0, 1e-4);
  EXPECT_EQ(linear_impact_overlap(k, m, 0.0), 0.0);
  const double e_star = effective_modulus(1e7, 0.3, 1e7, 0.3), radius = 0.001, mh = 0.5 * sphere_mass(0.004, 2700.0);
  const double c = 4.0 / 3.0 * e_star * std::sqrt(radius) / mh;
  for (const double v : {1.0, 10.0}) {
    const double peak = integrated_peak_overlap([c](double x) { return x > 0.0 ? -c * std::pow(x, 1.5) : 0.0; }, v,
                                                hertz_contact_time(e_star, radius, mh, v) / 1e5);
    EXPECT_NEAR(hertz_impact_overlap(e_star, radius, mh, v) / peak, 1.0, 1e-4);
  }
}

// By hand: (1/2 + 1/2)^-1 = 1, a wall leaves the particle's 3, (1/1 + 1/3)^-1 = 3/4 = 0.75.
TEST(Contact, EffectiveMassOfEqualSpheresIsHalfAndWallIsParticleMass) {
  EXPECT_DOUBLE_EQ(effective_mass(2.0, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(effective_mass(3.0, std::numeric_limits<double>::infinity()), 3.0);
  EXPECT_DOUBLE_EQ(effective_mass(1.0, 3.0), 0.75);
}

// The jet bed's bead by hand: 0.004^3 = 6.4e-8 m^3, * 2700 = 1.728e-4, * pi/6 (0.5235988) =
// 9.047787e-5 kg.
TEST(Contact, SphereMassIsDensityTimesPiDCubedOverSix) {
  EXPECT_NEAR(sphere_mass(0.004, 2700.0), 9.047787e-5, 1e-6 * 9.047787e-5);
}

// Seed 001 eq. 27 and 41 by hand for k_n = 800 N/m, e_n = 0.86, m_ab = 4.5e-5 kg: ln 0.86 =
// -0.1508229, pi^2 + ln^2 e_n = 9.869604 + 0.02274754 = 9.892352, sqrt(m_ab k_n) = sqrt(0.036) =
// 0.1897367; eta_n = 2 * 0.1508229 * 0.1897367 / sqrt(9.892352) = 0.05723328 / 3.145211 =
// 0.01819696 N s/m, t_c = sqrt(4.5e-5 * 9.892352 / 800) = sqrt(5.564448e-7) = 7.459523e-4 s.
TEST(Contact, NormalDampingAndContactTimeByHand) {
  EXPECT_NEAR(normal_damping(800.0, 0.86, 4.5e-5), 0.01819696, 1e-6 * 0.01819696);
  EXPECT_NEAR(contact_time(800.0, 0.86, 4.5e-5), 7.459523e-4, 1e-6 * 7.459523e-4);
  EXPECT_NEAR(contact_time_from_damping(800.0, 0.01819696, 4.5e-5), 7.459523e-4, 1e-6 * 7.459523e-4);
}

TEST(Contact, DampingAndRestitutionAreInverse) {
  const double k = 800.0, m = 4.5e-5;
  for (double e : {0.1, 0.5, 0.86, 0.97, 0.999}) {
    const double eta = normal_damping(k, e, m);
    EXPECT_NEAR(restitution_from_damping(k, eta, m), e, 1e-12) << "e_n = " << e;
    EXPECT_NEAR(contact_time_from_damping(k, eta, m), contact_time(k, e, m), 1e-15);
  }
}

// Critical damping by hand for k_n = 800 N/m, m = 1e-4 kg: 2 sqrt(k m) = 2 sqrt(0.08) =
// 0.5656854 N s/m; 1 % more than that is overdamped (no rebound), 1 % less still rebounds.
TEST(Contact, ZeroRestitutionIsCriticalDamping) {
  EXPECT_NEAR(normal_damping(800.0, 0.0, 1e-4), 0.5656854, 1e-6 * 0.5656854);
  EXPECT_EQ(restitution_from_damping(800.0, 0.5656854 * 1.01, 1e-4), 0.0);
  EXPECT_GT(restitution_from_damping(800.0, 0.5656854 * 0.99, 1e-4), 0.0);
}

// Half the undamped period by hand for k_n = 800 N/m, m = 1e-4 kg: pi sqrt(1e-4 / 800) =
// pi * 3.535534e-4 = 1.110721e-3 s.
TEST(Contact, ElasticContactTimeIsHalfPeriod) {
  EXPECT_NEAR(contact_time(800.0, 1.0, 1e-4), 1.110721e-3, 1e-6 * 1.110721e-3);
}

// Numerical round trip: the requested e_n and the predicted t_c within 1e-4 (the integration's
// error, 20000 steps per contact, is at most 2e-5).
TEST(Contact, IntegratedCollisionReturnsRequestedRestitutionAndContactTime) {
  const double k = 800.0;
  const double m = effective_mass(sphere_mass(0.004, 2700.0), sphere_mass(0.004, 2700.0));
  for (double e : {0.3, 0.7, 0.86, 0.97}) {
    const double eta = normal_damping(k, e, m);
    const CollisionResult r = integrate_collision(k, eta, m, 1.0);
    EXPECT_NEAR(r.restitution / e, 1.0, 1e-4) << "e_n = " << e;
    EXPECT_NEAR(r.duration / contact_time(k, e, m), 1.0, 1e-4) << "e_n = " << e;
  }
}

// Seed 000 Table 1 damping is absolute: 0.018 N s/m (jet bed) and 0.00177 N s/m (uniform bed)
// with k_n = 800 N/m give e_n ~ 0.86 and ~ 0.97 (SPEC.md). Eq. 25-26 by hand, gamma = eta/m_ab,
// t_c = pi / sqrt(k/m_ab - gamma^2/4), e_n = exp(-gamma t_c / 2):
//   jet, m_ab = 2700 pi/12 0.004^3 = 4.523893e-5 kg: gamma = 397.8874 1/s, k/m_ab = 1.768388e7,
//     gamma^2/4 = 39578.59, omega = 4200.512 1/s, t_c = 7.479070e-4 s, gamma t_c/2 = 0.1487914,
//     e_n = 0.8617489;
//   uniform, m_ab = 2526 pi/12 0.0025^3 = 1.033289e-5 kg: gamma = 171.2976 1/s, k/m_ab =
//     7.742264e7, gamma^2/4 = 7335.717, omega = 8798.597 1/s, t_c = 3.570561e-4 s,
//     gamma t_c/2 = 0.03058143, e_n = 0.9698815.
TEST(Contact, PaperTableOneDampingGivesExpectedRestitution) {
  const double m_jet = 4.523893e-5, m_uniform = 1.033289e-5;
  EXPECT_NEAR(effective_mass(sphere_mass(0.004, 2700.0), sphere_mass(0.004, 2700.0)), m_jet, 1e-6 * m_jet);
  EXPECT_NEAR(effective_mass(sphere_mass(0.0025, 2526.0), sphere_mass(0.0025, 2526.0)), m_uniform, 1e-6 * m_uniform);
  EXPECT_NEAR(contact_time_from_damping(800.0, 0.018, m_jet), 7.479070e-4, 1e-6 * 7.479070e-4);
  EXPECT_NEAR(restitution_from_damping(800.0, 0.018, m_jet), 0.8617489, 1e-6);
  EXPECT_NEAR(contact_time_from_damping(800.0, 0.00177, m_uniform), 3.570561e-4, 1e-6 * 3.570561e-4);
  EXPECT_NEAR(restitution_from_damping(800.0, 0.00177, m_uniform), 0.9698815, 1e-6);
}

// Seed 001 eq. 43 and 30 by hand for k_n = 800 N/m, e_n = 0.86, beta_0 = 0.4, m_ab = 4.5e-5 kg:
// ln 0.4 = -0.9162907, pi^2 + ln^2 0.4 = 9.869604 + 0.8395887 = 10.70919; k_t = 800 (2/7)
// 10.70919 / 9.892352 = 228.5714 * 1.082573 = 247.4453 N/m (and 1600/7 = 228.5714 N/m when both
// restitutions are 1); eta_t = 2 * 0.9162907 sqrt(2/7 m_ab k_t) / sqrt(10.70919) = 1.832581 *
// 0.05640425 / 3.272490 = 0.03158615 N s/m. The consequence checked by integration: the
// tangential oscillator (2/7) m_ab x'' = -k_t x - eta_t x' rebounds at beta_0 = 0.4 after the
// normal contact time 7.459523e-4 s (NormalDampingAndContactTimeByHand), within 1e-4.
TEST(Contact, TangentialStiffnessGivesEqualContactTimes) {
  const double kn = 800.0, en = 0.86, beta0 = 0.4, m = 4.5e-5;
  const double kt = tangential_stiffness(kn, en, beta0);
  EXPECT_NEAR(kt, 247.4453, 1e-6 * 247.4453);
  EXPECT_NEAR(tangential_stiffness(kn, 1.0, 1.0), 228.5714, 1e-6 * 228.5714);
  const double eta_t = tangential_damping(kt, beta0, m);
  EXPECT_NEAR(eta_t, 0.03158615, 1e-6 * 0.03158615);
  const CollisionResult r = integrate_collision(kt, eta_t, 2.0 / 7.0 * m, 1.0);
  EXPECT_NEAR(r.restitution, 0.4, 1e-4 * 0.4);
  EXPECT_NEAR(r.duration, 7.459523e-4, 1e-4 * 7.459523e-4);
}

TEST(Contact, RecommendedStepIsContactTimeOverN) {
  EXPECT_DOUBLE_EQ(recommended_time_step(7.5e-4, 50.0), 1.5e-5);
}

TEST(Contact, InvalidArgumentsAreRejected) {
  EXPECT_THROW(normal_damping(800.0, 1.2, 1e-4), std::invalid_argument);
  EXPECT_THROW(normal_damping(-1.0, 0.5, 1e-4), std::invalid_argument);
  EXPECT_THROW(sphere_mass(-0.001, 2500.0), std::invalid_argument);
  EXPECT_THROW(tangential_stiffness(800.0, 0.0, 0.5), std::invalid_argument);
}

}  // namespace
