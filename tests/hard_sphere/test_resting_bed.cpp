// A bed at rest on a floor, the external force entering as seed 001's impulse per flow step
// (half a step's gravity kick before the flight, half after): 200 spheres of 2 mm, e_n 0.9,
// dropped from a loose lattice into a 12 mm square column, 1 s in flow steps of 1e-4 s. Once
// settled (from 0.5 s) it must neither collapse (the collisions per flow step growing) nor gain
// energy. Each step's kick sets the resting spheres moving at g dt / 2 against their
// supports, so the bed collides at a steady rate, which the TC model's elastic_within sets:
// `tfdem_hard_sphere_tests --gtest_also_run_disabled_tests --gtest_filter='*Resting*'`
// prints the rate for 0 (no TC model), 1e-6, 1e-5 (the default) and 1e-4 s.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "tfdem/hard_sphere/event_flight.h"

namespace {

using namespace tfdem::hard_sphere;

constexpr double kG = 9.81, kRadius = 1e-3, kStep = 1e-4;

struct Settled {
  double energy_half = 0, energy_end = 0;  // J: kinetic, rotational and potential
  double collisions_early = 0, collisions_late = 0;  // per particle per flow step, 0.5-0.6 s, 0.9-1 s
  double weight_height = 0;  // J: the bed's m g d, the scale of its potential energy
};

double energy(const EventFlight &f) {
  double e = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    e += f.mass[i] * (0.5 * dot(f.velocity[i], f.velocity[i]) + kG * f.position[i].y) +
         0.5 * 0.4 * f.mass[i] * f.radius[i] * f.radius[i] * dot(f.spin[i], f.spin[i]);
  return e;
}

Settled settle(double elastic_within) {
  WallBox box;
  box.upper[0] = box.upper[2] = 0.012;
  box.upper[1] = 0.04;
  const CollisionLaw law{0.9, 0.1, 0.33};
  EventFlight f(box, 1, {law}, {law}, elastic_within, 1000);
  std::mt19937 random(7919);
  std::uniform_real_distribution<double> jitter(-1e-4, 1e-4);
  const double m = 2526 * 4.0 / 3.0 * 3.14159265358979323846 * kRadius * kRadius * kRadius;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        f.add({1.2e-3 + 2.4e-3 * i + jitter(random), 1.2e-3 + 2.4e-3 * k, 1.2e-3 + 2.4e-3 * j + jitter(random)}, {},
              {}, kRadius, m, 0);
  Settled s;
  s.weight_height = f.size() * m * kG * 2 * kRadius;
  const int steps = static_cast<int>(std::lround(1.0 / kStep));
  for (int n = 1; n <= steps; ++n) {
    for (Vec3 &v : f.velocity) v.y -= 0.5 * kStep * kG;
    const FlightCounts c = f.fly(kStep);
    for (Vec3 &v : f.velocity) v.y -= 0.5 * kStep * kG;
    const double per_particle = double(c.pair + c.wall) / f.size() / (0.1 / kStep);
    if (n > steps / 2 && n <= 6 * steps / 10) s.collisions_early += per_particle;
    if (n > 9 * steps / 10) s.collisions_late += per_particle;
    if (n == steps / 2) s.energy_half = energy(f);
  }
  s.energy_end = energy(f);
  return s;
}

TEST(HardSphereRestingBed, NeitherCollapsesNorGainsEnergy) {
  const Settled s = settle(1e-5);
  EXPECT_LT(s.collisions_late, 1.2 * s.collisions_early) << s.collisions_early << " then " << s.collisions_late;
  EXPECT_LT(s.energy_end - s.energy_half, 1e-5 * s.weight_height)
      << (s.energy_end - s.energy_half) / s.weight_height << " of the bed's m g d";
}

TEST(HardSphereRestingBed, DISABLED_CollisionRateAgainstTheTcTime) {
  for (double tc : {0.0, 1e-6, 1e-5, 1e-4}) {
    const Settled s = settle(tc);
    std::printf("elastic_within %g s: collisions per particle per flow step %.2f (0.5-0.6 s), %.2f (0.9-1 s); "
                "E(1 s) - E(0.5 s) = %.2g of the bed's m g d\n",
                tc, s.collisions_early, s.collisions_late, (s.energy_end - s.energy_half) / s.weight_height);
  }
}

}  // namespace
