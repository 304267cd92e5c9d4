// Hard-sphere collisions (seed 001 eqs. 11-21) against values worked by hand: a head-on pair,
// an oblique sticking one (beta_0 = 0 stops the contact points' slip, eq. 19), an oblique
// sliding one (J_t = -mu J_n), a spinning sphere on a floor; energy kept for e_n = 1 with a
// smooth (mu = 0) or a perfectly rough (beta_0 = 1) contact, lost otherwise; momentum and the
// angular momentum about the contact point always kept.
#include <gtest/gtest.h>

#include "tfdem/hard_sphere/collision.h"

namespace {

using namespace tfdem::hard_sphere;

constexpr double kTol = 1e-12;

Sphere sphere(Vec3 v, Vec3 w = {}, double radius = 1e-3, double mass = 2e-6) { return {v, w, radius, mass}; }

double energy(const Sphere &s) {
  return 0.5 * s.mass * dot(s.velocity, s.velocity) + 0.5 * 0.4 * s.mass * s.radius * s.radius * dot(s.spin, s.spin);
}

void expect_vec(const Vec3 &got, const Vec3 &want, double tol = kTol) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

// Equal spheres, a moving at -1 m/s onto b at rest along n = +x (b to a), e_n = 0.9:
// m_ab = m/2, J_n = 1.9 m/2 = 0.95 m, so v_a = -0.05, v_b = -0.95 m/s.
TEST(HardSphereCollision, HeadOnByHand) {
  Sphere a = sphere({-1, 0, 0}), b = sphere({0, 0, 0});
  const Impulse j = collide(a, b, {1, 0, 0}, {0.9, 0.3, 0.4});
  expect_vec(j.on_a, {0.95 * 2e-6, 0, 0});
  expect_vec(a.velocity, {-0.05, 0, 0});
  expect_vec(b.velocity, {-0.95, 0, 0});
  expect_vec(a.spin, {0, 0, 0});
}

// Separating spheres are left alone.
TEST(HardSphereCollision, SeparatingPairUntouched) {
  Sphere a = sphere({1, 0, 0}), b = sphere({0, 0, 0});
  const Impulse j = collide(a, b, {1, 0, 0}, {0.9, 0.3, 0.4});
  expect_vec(j.on_a, {0, 0, 0});
  expect_vec(a.velocity, {1, 0, 0});
}

// Oblique: v_a = (-1, 0.2, 0) onto b at rest, n = +x. Normal: J_n = 0.95 m as above. Slip
// 0.2 m/s along t = +y; sticking needs mu J_n >= (2/7)(1 + beta_0) m_ab 0.2 = 0.02857 m with
// beta_0 = 0 and m_ab = m/2: mu = 0.5 gives 0.475 m, so J_t = -0.02857 m, and the contact
// points' tangential relative velocity vanishes (eq. 19); mu = 0.02 gives 0.019 m < 0.02857 m,
// so it slides: J_t = -mu J_n = -0.019 m.
TEST(HardSphereCollision, ObliqueStickingAndSliding) {
  const double m = 2e-6;
  Sphere a = sphere({-1, 0.2, 0}), b = sphere({0, 0, 0});
  Impulse j = collide(a, b, {1, 0, 0}, {0.9, 0.5, 0.0});
  EXPECT_TRUE(j.sticking);
  expect_vec(j.on_a, {0.95 * m, -2.0 / 7.0 * 0.5 * m * 0.2, 0});
  const Vec3 n = {1, 0, 0};
  const Vec3 slip = (a.velocity - b.velocity) - cross(a.radius * a.spin + b.radius * b.spin, n);
  EXPECT_NEAR(slip.y, 0, kTol);
  EXPECT_NEAR(slip.x, 0.9, kTol);  // e_n: 0.9 of the approach speed, now separating

  a = sphere({-1, 0.2, 0}), b = sphere({0, 0, 0});
  j = collide(a, b, n, {0.9, 0.02, 0.0});
  EXPECT_FALSE(j.sticking);
  expect_vec(j.on_a, {0.95 * m, -0.02 * 0.95 * m, 0});
}

// A sphere sliding at (1, -2, 0) m/s, no spin, onto a floor (n = +y), e_n = 0.8, mu = 0.1,
// beta_0 = 0.3: J_n = 1.8 m 2 = 3.6 m; sticking would need 2/7 1.3 m = 0.3714 m > mu J_n =
// 0.36 m, so it slides: v = (1 - 0.36, -2 + 3.6, 0) = (0.64, 1.6, 0) and the friction at the
// contact point (0, -R, 0) spins it: dw_z = -0.36 m R / (0.4 m R^2) = -0.9 / R.
TEST(HardSphereCollision, SlidingOnAFloorByHand) {
  Sphere a = sphere({1, -2, 0});
  const Impulse j = collide_with_wall(a, {0, 1, 0}, {0.8, 0.1, 0.3});
  EXPECT_FALSE(j.sticking);
  expect_vec(a.velocity, {0.64, 1.6, 0});
  expect_vec(a.spin, {0, 0, -0.9 / a.radius}, 1e-9);
}

// Elastic and smooth, elastic and perfectly rough: kinetic energy (translation + rotation)
// kept; momentum always kept, and the angular momentum about the contact point.
TEST(HardSphereCollision, ConservationLaws) {
  const Vec3 n = {0.6, 0.8, 0};
  const CollisionLaw laws[] = {{1, 0, 0}, {1, 10, 1}, {0.7, 0.2, 0.35}};
  for (int k = 0; k < 3; ++k) {
    Sphere a = sphere({-0.3, -1.1, 0.2}, {10, -20, 5}), b = sphere({0.4, 0.1, -0.1}, {-3, 7, 2}, 1.5e-3, 5e-6);
    const double e0 = energy(a) + energy(b);
    const Vec3 p0 = a.mass * a.velocity + b.mass * b.velocity;
    // angular momentum about the contact point c (origin there): r_a = R_a n, r_b = -R_b n
    const auto angular = [&n](const Sphere &s, double side) {
      return cross(side * s.radius * n, s.mass * s.velocity) + 0.4 * s.mass * s.radius * s.radius * s.spin;
    };
    const Vec3 l0 = angular(a, 1) + angular(b, -1);
    collide(a, b, n, laws[k]);
    expect_vec(a.mass * a.velocity + b.mass * b.velocity, p0, 1e-18);
    expect_vec(angular(a, 1) + angular(b, -1), l0, 1e-20);
    if (k < 2)
      EXPECT_NEAR((energy(a) + energy(b)) / e0, 1.0, 1e-12) << "law " << k;
    else
      EXPECT_LT(energy(a) + energy(b), e0);
  }
}

}  // namespace
