// A granular gas cooling: 2197 smooth spheres of 2 mm, e_n = 0.98, solids fraction 0.05, in a
// periodic cube (no walls, whose missing partners near them would slow the cooling by ~4 %),
// followed for 2 s (~200 collisions a particle). Haff's law for smooth inelastic spheres
// (Haff 1983; Brilliantov & Poeschel 2004, ch. 6): dT/dt = -(1 - e^2) nu T / 3 with the
// Enskog collision frequency nu = 4 sigma^2 n g_0 sqrt(pi T / m) and the Carnahan-Starling
// contact value g_0 = (1 - phi/2)/(1 - phi)^3, so T(t) = T_0 / (1 + t/tau)^2 with
// tau = 6 / ((1 - e^2) nu_0), computed here from the initial state. Tolerance 3 %: the first
// Sonine correction to the cooling rate and g_0 are below 1 % at these e_n and phi, the
// uniform initial velocities relax within a few collisions, and N = 2197 leaves ~1 % of
// noise (measured 1.1 %; 0.3 % with 4096 spheres).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tfdem/hard_sphere/event_flight.h"

namespace {

using namespace tfdem::hard_sphere;

TEST(HardSphereGranularGas, CoolsAsHaffsLaw) {
  constexpr int kSide = 13, kCount = kSide * kSide * kSide;
  constexpr double kPi = 3.14159265358979323846;
  const double e = 0.98, d = 2e-3, m = 1e-5, phi = 0.05;
  const double size = std::cbrt(kCount * kPi * d * d * d / 6 / phi);
  WallBox box;
  for (int a = 0; a < 3; ++a) {
    box.upper[a] = size;
    box.wall[a][0] = box.wall[a][1] = false;
    box.periodic[a] = true;
  }
  EventFlight gas(box, 1, {{e, 0, 0}}, {{e, 0, 0}}, 0, 100000);
  std::mt19937 random(15485863);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> v(kCount);
  Vec3 mean;
  for (Vec3 &x : v) mean += (x = {u(random), u(random), u(random)});
  mean = (1.0 / kCount) * mean;  // at rest as a whole: T is the peculiar motion's
  const double spacing = size / kSide;
  int k = 0;
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j)
      for (int l = 0; l < kSide; ++l)
        gas.add({(i + 0.5) * spacing, (j + 0.5) * spacing, (l + 0.5) * spacing}, v[k++] - mean, {}, d / 2, m, 0);
  const auto temperature = [&gas, m] {
    double sum = 0;
    for (const Vec3 &x : gas.velocity) sum += dot(x, x);
    return m * sum / (3.0 * kCount);
  };
  const double t0 = temperature();
  const double nu0 = 4 * d * d * (kCount / (size * size * size)) * (1 - phi / 2) / std::pow(1 - phi, 3) *
                     std::sqrt(kPi * t0 / m);
  const double tau = 6 / ((1 - e * e) * nu0);
  for (int step = 1; step <= 2000; ++step) {
    gas.fly(1e-3);
    if (step % 500 == 0) {
      const double t = step * 1e-3, haff = 1 / std::pow(1 + t / tau, 2);
      EXPECT_NEAR(temperature() / t0 / haff, 1.0, 0.03) << "t = " << t << " s, T/T0 = " << temperature() / t0
                                                        << ", Haff " << haff;
    }
  }
}

}  // namespace
