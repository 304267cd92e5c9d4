// Event-driven flight (seed 001 Fig. 5, eqs. 44-47) on cases worked by hand or with a law that
// holds exactly: a head-on pair and a wall bounce placed by hand; an elastic, smooth gas keeps
// its kinetic energy to round-off and ends with no overlap; an inelastic one in a box without
// walls keeps its momentum and loses energy; three spheres in a line with e_n = 0.05 < 7 - 4
// sqrt(3) collapse (McNamara & Young 1992: infinitely many collisions in a finite time; in
// double precision the relative speeds reach round-off after ~41), which a bound of 10 a
// particle stops, and the TC model (elastic within t_c of a collision) keeps to 3.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "tfdem/hard_sphere/event_flight.h"

namespace {

using namespace tfdem::hard_sphere;

WallBox box(double size, bool walls = true) {
  WallBox b;
  for (int a = 0; a < 3; ++a) {
    b.lower[a] = 0;
    b.upper[a] = size;
    b.wall[a][0] = b.wall[a][1] = walls;
  }
  return b;
}

EventFlight flight(const WallBox &b, CollisionLaw law, double elastic_within = 0, long bound = 1000) {
  return EventFlight(b, 1, {law}, {law}, elastic_within, bound);
}

// Spheres of 2 mm at x = 0.040 and 0.050 m closing at 1 m/s each: they touch when the gap of
// 8 mm is closed, after 4 ms, at x = 0.044 and 0.046; elastic and equal, they swap
// velocities; at 10 ms each is 6 mm back out: x = 0.038 and 0.052.
TEST(HardSphereFlight, HeadOnPairByHand) {
  EventFlight f = flight(box(0.1), {1, 0, 0});
  f.add({0.040, 0.05, 0.05}, {1, 0, 0}, {}, 1e-3, 1e-5, 0);
  f.add({0.050, 0.05, 0.05}, {-1, 0, 0}, {}, 1e-3, 1e-5, 0);
  const FlightCounts c = f.fly(0.01);
  EXPECT_EQ(c.pair, 1);
  EXPECT_NEAR(f.position[0].x, 0.038, 1e-15);
  EXPECT_NEAR(f.position[1].x, 0.052, 1e-15);
  EXPECT_DOUBLE_EQ(f.velocity[0].x, -1);
  EXPECT_NEAR(f.impulse[0].x, -2e-5, 1e-20);  // m dv on the first sphere
  EXPECT_DOUBLE_EQ(f.clock(), 0.01);
}

// A sphere of radius 1 mm at x = 0.005 m moving at -1 m/s against the wall x = 0 with
// e_n = 0.5: it touches after 4 ms, leaves at 0.5 m/s, and is 3 mm out (x = 0.004) at 10 ms.
TEST(HardSphereFlight, WallBounceByHand) {
  EventFlight f = flight(box(0.1), {0.5, 0, 0});
  f.add({0.005, 0.05, 0.05}, {-1, 0, 0}, {}, 1e-3, 1e-5, 0);
  const FlightCounts c = f.fly(0.01);
  EXPECT_EQ(c.wall, 1);
  EXPECT_NEAR(f.position[0].x, 0.004, 1e-15);
  EXPECT_DOUBLE_EQ(f.velocity[0].x, 0.5);
}

// Random spheres on a lattice of a 5 cm box with random velocities.
void fill(EventFlight &f, int per_side, double size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const double spacing = size / per_side;
  for (int i = 0; i < per_side; ++i)
    for (int j = 0; j < per_side; ++j)
      for (int k = 0; k < per_side; ++k)
        f.add({(i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing}, {u(random), u(random), u(random)}, {},
              1e-3, 1e-5, 0);
}

double kinetic_energy(const EventFlight &f) {
  double e = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    e += 0.5 * f.mass[i] * dot(f.velocity[i], f.velocity[i]) +
         0.5 * 0.4 * f.mass[i] * f.radius[i] * f.radius[i] * dot(f.spin[i], f.spin[i]);
  return e;
}

double deepest_overlap(const EventFlight &f) {
  double deepest = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t j = i + 1; j < f.size(); ++j)
      deepest = std::max(deepest, f.radius[i] + f.radius[j] - norm(f.position[i] - f.position[j]));
  return deepest;
}

TEST(HardSphereFlight, ElasticSmoothGasKeepsItsEnergy) {
  EventFlight f = flight(box(0.05), {1, 0, 0});
  fill(f, 8, 0.05, 15485863);  // 512 spheres of 2 mm, solids fraction 0.017
  const double e0 = kinetic_energy(f);
  long collisions = 0;
  for (int step = 0; step < 100; ++step) {
    const FlightCounts c = f.fly(0.01);
    collisions += c.pair;
  }
  EXPECT_GT(collisions, 10000);
  EXPECT_NEAR(kinetic_energy(f) / e0, 1.0, 1e-11);
  EXPECT_LT(deepest_overlap(f), 1e-12);
}

TEST(HardSphereFlight, InelasticRoughGasWithoutWallsKeepsItsMomentum) {
  EventFlight f = flight(box(0.025, false), {0.7, 0.3, 0.4});
  fill(f, 8, 0.025, 32452843);  // spacing 3.1 mm: solids fraction 0.14
  Vec3 p0;
  for (std::size_t i = 0; i < f.size(); ++i) p0 += f.mass[i] * f.velocity[i];
  const double e0 = kinetic_energy(f);
  for (int step = 0; step < 20; ++step) f.fly(0.005);
  Vec3 p;
  for (std::size_t i = 0; i < f.size(); ++i) p += f.mass[i] * f.velocity[i];
  EXPECT_NEAR(p.x, p0.x, 1e-18);
  EXPECT_NEAR(p.y, p0.y, 1e-18);
  EXPECT_NEAR(p.z, p0.z, 1e-18);
  EXPECT_LT(kinetic_energy(f), 0.9 * e0);
}

// Three spheres on a line, the outer two closing on the middle one at rest.
EventFlight line_of_three(double elastic_within) {
  EventFlight f = flight(box(0.1, false), {0.05, 0, 0}, elastic_within, 10);
  f.add({0.040, 0.05, 0.05}, {1, 0, 0}, {}, 1e-3, 1e-5, 0);
  f.add({0.050, 0.05, 0.05}, {0, 0, 0}, {}, 1e-3, 1e-5, 0);
  f.add({0.060, 0.05, 0.05}, {-1, 0, 0}, {}, 1e-3, 1e-5, 0);
  return f;
}

TEST(HardSphereFlight, InelasticCollapseIsStoppedAndTheTcModelPreventsIt) {
  EventFlight collapsing = line_of_three(0);
  try {
    collapsing.fly(0.02);
    FAIL() << "no collapse";
  } catch (const std::runtime_error &e) {
    EXPECT_NE(std::string(e.what()).find("inelastic collapse: 31 collisions of 3 particles"), std::string::npos)
        << e.what();
  }
  EventFlight tc = line_of_three(1e-6);
  const FlightCounts c = tc.fly(0.02);
  EXPECT_EQ(c.pair, 3);
  EXPECT_GT(c.elastic, 0);
  EXPECT_LT(deepest_overlap(tc), 1e-12);
}

}  // namespace
