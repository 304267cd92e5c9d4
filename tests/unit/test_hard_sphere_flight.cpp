// Event-driven flight (seed 001 Fig. 5, eqs. 44-47) on cases worked by hand or with a law that
// holds exactly: a head-on pair and a wall bounce placed by hand; an elastic, smooth gas keeps
// its kinetic energy to round-off and ends with no overlap; an inelastic one in a box without
// walls keeps its momentum and loses energy; three spheres in a line with e_n = 0.05 < 7 - 4
// sqrt(3) collapse (McNamara & Young 1992: infinitely many collisions in a finite time; in
// double precision the relative speeds reach round-off after ~41), which a bound of 10 a
// particle stops, and the TC model (elastic within t_c of a collision) keeps to 3. The
// neighbour lists lose no pair: a gas with spheres fast enough to leave their anchor's sphere
// many times within one flow step collides exactly as an all-pairs search without lists does.
#include <gtest/gtest.h>

#include <cfenv>
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

// The TC model on a wall collision placed by hand (elastic_within 1 s, so every collision of
// this step is within it): a sphere of radius 1 mm and mass m at x = 0.005 m moving at (-1,
// 0.5, 0) m/s against the wall x = 0, law e_n = 0.5, mu = 0.05, beta_0 = 0.4 (seed 001 eqs.
// 17-21, a wall of infinite mass: m_ab = m). Elastic and smooth: (1, 0.5, 0), no spin. Keeping
// friction, e_n = 1: J_n = 2 m; sticking would need mu J_n >= (2/7)(1.4)(0.5) m = 0.2 m, and
// mu J_n = 0.1 m, so it slides: J_t = -0.1 m along y, v = (1, 0.4, 0); the spin I dw =
// -R n x J with I = 0.4 m R^2, n x J = (0, 0, -0.1 m): w_z = 0.1 / (0.4 R) = 250 rad/s.
TEST(HardSphereFlight, TcModelIsElasticAndSmoothOrKeepsFriction) {
  for (const bool keep : {false, true}) {
    EventFlight f = flight(box(0.1), {0.5, 0.05, 0.4}, 1.0);
    f.set_tc_keeps_friction(keep);
    f.add({0.005, 0.05, 0.05}, {-1, 0.5, 0}, {}, 1e-3, 1e-5, 0);
    f.last_collision[0] = 0;
    const FlightCounts c = f.fly(0.01);
    EXPECT_EQ(c.wall, 1);
    EXPECT_EQ(c.elastic, 1);
    EXPECT_DOUBLE_EQ(f.velocity[0].x, 1.0) << "keep " << keep;
    EXPECT_NEAR(f.velocity[0].y, keep ? 0.4 : 0.5, 1e-15) << "keep " << keep;
    EXPECT_NEAR(f.spin[0].z, keep ? 250 : 0, 1e-10) << "keep " << keep;
  }
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
    const std::string what = e.what();
    EXPECT_EQ(what.find("31 collisions of 3 particles"), 0u) << what;
    EXPECT_NE(what.find("inelastic collapse"), std::string::npos) << what;
    EXPECT_NE(what.find("a higher max_collisions_per_particle"), std::string::npos) << what;  // the bound is 10
  }
  EventFlight tc = line_of_three(1e-6);
  const FlightCounts c = tc.fly(0.02);
  EXPECT_EQ(c.pair, 3);
  EXPECT_GT(c.elastic, 0);
  EXPECT_LT(deepest_overlap(tc), 1e-12);
}

// A rough gas (e_n 0.7, mu 0.3, beta_0 0.4), periodic, in which the TC model makes every
// collision elastic (elastic_within 1 s): smooth, it keeps its energy to round-off; keeping
// friction, it loses energy through the tangential impulses alone, keeps its momentum and
// collides on without collapse. 512 spheres of 2 mm in (2.5 cm)^3 (solids fraction 0.137,
// Carnahan-Starling g_0 1.46), each velocity component uniform in (-1, 1) m/s (<v^2> = 1 m^2/s^2):
// the Enskog rate 4 n sigma^2 g_0 sqrt(pi <v^2> / 3) is 780 per sphere and second, 20,000
// collisions over the 0.1 s: at least half of them asked of the smooth gas; the rough one
// cools as it collides (its rate falls with the square root of its temperature), so a tenth.
TEST(HardSphereFlight, TcModelKeepingFrictionDissipatesWithoutCollapse) {
  for (const bool keep : {false, true}) {
    WallBox periodic = box(0.025, false);
    for (bool &axis : periodic.periodic) axis = true;
    EventFlight f = flight(periodic, {0.7, 0.3, 0.4}, 1.0, 100000);
    f.set_tc_keeps_friction(keep);
    fill(f, 8, 0.025, 32452843);
    for (std::size_t i = 0; i < f.size(); ++i) f.last_collision[i] = 0;
    Vec3 p0;
    for (std::size_t i = 0; i < f.size(); ++i) p0 += f.mass[i] * f.velocity[i];
    const double e0 = kinetic_energy(f);
    long collisions = 0, elastic = 0;
    for (int step = 0; step < 20; ++step) {
      const FlightCounts c = f.fly(0.005);
      collisions += c.pair;
      elastic += c.elastic;
    }
    Vec3 p;
    for (std::size_t i = 0; i < f.size(); ++i) p += f.mass[i] * f.velocity[i];
    EXPECT_GT(collisions, keep ? 2000 : 10000) << "keep " << keep;
    EXPECT_EQ(elastic, collisions) << "keep " << keep;
    EXPECT_NEAR(p.x, p0.x, 1e-18);
    EXPECT_NEAR(p.y, p0.y, 1e-18);
    if (keep)
      EXPECT_LT(kinetic_energy(f), 0.95 * e0);
    else
      EXPECT_NEAR(kinetic_energy(f) / e0, 1.0, 1e-11);
    EXPECT_LT(deepest_overlap(f), 1e-12);
  }
}

// Elastic, smooth, equal spheres in a walled box moved by searching every pair and wall for
// the earliest contact (no lists, no cells, no heap): the reference for the lists below.
struct AllPairsGas {
  std::vector<Vec3> x, v;
  double radius, size;
  long pair = 0, wall = 0;

  void fly(double dt) {
    double now = 0;
    for (;;) {
      double first = dt - now;
      int a = -1, b = -1;  // b < 0: wall on axis -1 - b
      for (std::size_t i = 0; i < x.size(); ++i) {
        for (std::size_t j = i + 1; j < x.size(); ++j) {
          const Vec3 r = x[i] - x[j], u = v[i] - v[j];
          const double rb = dot(r, u), c = dot(r, r) - 4 * radius * radius, disc = rb * rb - dot(u, u) * c;
          if (rb >= 0 || disc <= 0) continue;
          const double t = c / (-rb + std::sqrt(disc));
          if (t < first) first = t, a = static_cast<int>(i), b = static_cast<int>(j);
        }
        for (int axis = 0; axis < 3; ++axis) {
          const double t = v[i][axis] < 0 ? (x[i][axis] - radius) / -v[i][axis]
                           : v[i][axis] > 0 ? (size - radius - x[i][axis]) / v[i][axis] : dt;
          if (t < first) first = t, a = static_cast<int>(i), b = -1 - axis;
        }
      }
      for (std::size_t i = 0; i < x.size(); ++i) x[i] += first * v[i];
      now += first;
      if (a < 0) return;
      if (b < 0) {
        v[a][-1 - b] = -v[a][-1 - b];
        ++wall;
      } else {  // equal masses: the normal components swap
        const Vec3 r = x[a] - x[b];
        const Vec3 n = (1 / norm(r)) * r;
        const double exchange = dot(v[a] - v[b], n);
        v[a] -= exchange * n;
        v[b] += exchange * n;
        ++pair;
      }
    }
  }
};

// 60 spheres of 2 mm in a 12 mm box (solids fraction 0.15) at up to 1 m/s, two of them at
// 30 m/s: in one flow step of 2 ms these cross the box five times and leave their anchor's
// sphere (radius 0.2 mm) hundreds of times. Same collisions, same end positions.
TEST(HardSphereFlight, ListsLoseNoPairAgainstAnAllPairsSearch) {
  const double size = 0.012, radius = 1e-3;
  EventFlight f = flight(box(size), {1, 0, 0});
  AllPairsGas reference{{}, {}, radius, size};
  std::mt19937 random(104729);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4 && reference.x.size() < 60; ++k) {
        const Vec3 x{(i + 0.5) * size / 4, (j + 0.5) * size / 4, (k + 0.5) * size / 4};
        Vec3 v{u(random), u(random), u(random)};
        if (reference.x.size() < 2) v = (30 / norm(v)) * v;
        f.add(x, v, {}, radius, 1e-5, 0);
        reference.x.push_back(x);
        reference.v.push_back(v);
      }
  const FlightCounts c = f.fly(2e-3);
  reference.fly(2e-3);
  EXPECT_GT(c.lists_renewed, 200);
  EXPECT_GT(reference.pair, 100);
  EXPECT_EQ(c.pair, reference.pair);
  EXPECT_EQ(c.wall, reference.wall);
  double farthest = 0;
  for (std::size_t i = 0; i < f.size(); ++i) farthest = std::max(farthest, norm(f.position[i] - reference.x[i]));
  EXPECT_LT(farthest, 1e-9);
  EXPECT_LT(deepest_overlap(f), 1e-12);
}

// A bed emptied through its outlets flies on: no lists, no cells, the clock advances. The
// floating-point traps are on, as OpenFOAM's (FOAM_SIGFPE): the lists' cells were sized from
// the largest sphere, none, and a division by zero stopped the solver.
TEST(HardSphereFlight, AnEmptiedBedFliesOn) {
  feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
  EventFlight f = flight(box(0.1), {0.9, 0.1, 0.5});
  f.add({0.040, 0.05, 0.05}, {1, 0, 0}, {}, 1e-3, 1e-5, 0);
  f.add({0.050, 0.05, 0.05}, {-1, 0, 0}, {}, 1e-3, 1e-5, 0);
  f.fly(0.01);
  f.remove({0, 1});
  const FlightCounts c = f.fly(0.01);
  fedisableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
  EXPECT_EQ(c.pair + c.wall, 0);
  EXPECT_DOUBLE_EQ(f.clock(), 0.02);
}


}  // namespace
