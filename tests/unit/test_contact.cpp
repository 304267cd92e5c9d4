// Contact relations: seed 001 eq. 16, 27, 41, 43; seed 000 eq. 25-26, Table 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tfdem/contact.h"

namespace {

using namespace tfdem::contact;
constexpr double kPi = 3.14159265358979323846;

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
// practice uses (E = 10 MPa, nu = 0.3) at 1 and 10 m/s: the formula's duration equals the
// integrated one within 0.5 % (the constant 2.868 is rounded) and falls as v^(-1/5).
TEST(Contact, HertzContactTimeMatchesIntegratedCollision) {
  const double e_star = effective_modulus(1e7, 0.3, 1e7, 0.3);
  EXPECT_NEAR(e_star, 1e7 / (2.0 * (1.0 - 0.09)), 1e-6);
  const double radius = 0.5 * 0.002, m = 0.5 * sphere_mass(0.004, 2700.0);
  for (const double v : {1.0, 10.0})
    EXPECT_NEAR(hertz_contact_time(e_star, radius, m, v) / integrate_hertz_collision(e_star, radius, m, v), 1.0, 5e-3);
  EXPECT_NEAR(hertz_contact_time(e_star, radius, m, 10.0) / hertz_contact_time(e_star, radius, m, 1.0),
              std::pow(10.0, -0.2), 1e-12);
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

TEST(Contact, EffectiveMassOfEqualSpheresIsHalfAndWallIsParticleMass) {
  EXPECT_DOUBLE_EQ(effective_mass(2.0, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(effective_mass(3.0, std::numeric_limits<double>::infinity()), 3.0);
  EXPECT_DOUBLE_EQ(effective_mass(1.0, 3.0), 1.0 * 3.0 / 4.0);
}

TEST(Contact, SphereMassIsDensityTimesPiDCubedOverSix) {
  EXPECT_DOUBLE_EQ(sphere_mass(0.004, 2700.0), 2700.0 * kPi * 0.004 * 0.004 * 0.004 / 6.0);
}

TEST(Contact, DampingAndRestitutionAreInverse) {
  const double k = 800.0, m = 4.5e-5;
  for (double e : {0.1, 0.5, 0.86, 0.97, 0.999}) {
    const double eta = normal_damping(k, e, m);
    EXPECT_NEAR(restitution_from_damping(k, eta, m), e, 1e-12) << "e_n = " << e;
    EXPECT_NEAR(contact_time_from_damping(k, eta, m), contact_time(k, e, m), 1e-15);
  }
}

TEST(Contact, ZeroRestitutionIsCriticalDamping) {
  EXPECT_DOUBLE_EQ(normal_damping(800.0, 0.0, 1e-4), 2.0 * std::sqrt(800.0 * 1e-4));
  EXPECT_EQ(restitution_from_damping(800.0, 2.0 * std::sqrt(800.0 * 1e-4) * 1.01, 1e-4), 0.0);
}

TEST(Contact, ElasticContactTimeIsHalfPeriod) {
  const double k = 800.0, m = 1e-4;
  EXPECT_NEAR(contact_time(k, 1.0, m), kPi * std::sqrt(m / k), 1e-15);
}

// Numerical round trip: the requested e_n within 0.5 %, the predicted t_c within 1 %.
TEST(Contact, IntegratedCollisionReturnsRequestedRestitutionAndContactTime) {
  const double k = 800.0;
  const double m = effective_mass(sphere_mass(0.004, 2700.0), sphere_mass(0.004, 2700.0));
  for (double e : {0.3, 0.7, 0.86, 0.97}) {
    const double eta = normal_damping(k, e, m);
    const CollisionResult r = integrate_collision(k, eta, m, 1.0);
    EXPECT_NEAR(r.restitution / e, 1.0, 5e-3) << "e_n = " << e;
    EXPECT_NEAR(r.duration / contact_time(k, e, m), 1.0, 1e-2) << "e_n = " << e;
  }
}

// Seed 000 Table 1 damping is absolute: 0.018 N s/m (jet bed) and 0.00177 N s/m (uniform bed)
// with k_n = 800 N/m give e_n ~ 0.86 and ~ 0.97 (SPEC.md), computed here from eq. 25-26.
TEST(Contact, PaperTableOneDampingGivesExpectedRestitution) {
  const double m_jet = effective_mass(sphere_mass(0.004, 2700.0), sphere_mass(0.004, 2700.0));
  const double m_uniform = effective_mass(sphere_mass(0.0025, 2526.0), sphere_mass(0.0025, 2526.0));
  const double gamma_jet = 0.018 / m_jet;
  const double tc_jet = kPi / std::sqrt(800.0 / m_jet - gamma_jet * gamma_jet / 4.0);
  EXPECT_NEAR(restitution_from_damping(800.0, 0.018, m_jet), std::exp(-gamma_jet * tc_jet / 2.0), 1e-14);
  EXPECT_NEAR(restitution_from_damping(800.0, 0.018, m_jet), 0.86, 0.005);
  EXPECT_NEAR(restitution_from_damping(800.0, 0.00177, m_uniform), 0.97, 0.005);
}

TEST(Contact, TangentialStiffnessGivesEqualContactTimes) {
  const double kn = 800.0, en = 0.86, beta0 = 0.4, m = 4.5e-5;
  const double kt = tangential_stiffness(kn, en, beta0);
  const double log_b = std::log(beta0);
  const double tc_t = std::sqrt(2.0 / 7.0 * m * (kPi * kPi + log_b * log_b) / kt);  // eq. 42
  EXPECT_NEAR(tc_t, contact_time(kn, en, m), 1e-15);
  EXPECT_NEAR(tangential_stiffness(kn, 1.0, 1.0), 2.0 / 7.0 * kn, 1e-12);
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
