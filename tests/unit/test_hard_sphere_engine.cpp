// The hard-sphere engine behind the coupler's interface, against analytic motion and its own
// restart: a sphere falling under gravity and a held force (kick-drift-kick is exact for a
// constant force between collisions); one dropped on a floor rebounds to e_n^2 of its drop,
// off by at most what the step leaves on the rebound speed (an impact tau into a step of dt
// leaves the speed at the step's end off by (1 + e) g (dt/2 - tau), so the apex by at most
// (1 + e) g dt / (e v) of itself); a run resumed from its restart file equals the straight
// run bit for bit; particles removed by ID; collision laws that do not fit the types refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "tfdem/hard_sphere/engine.h"

namespace {

using namespace tfdem;
using tfdem::hard_sphere::HardSphereEngine;
using tfdem::hard_sphere::HardSphereOptions;

const double kGravity[3] = {0, -9.81, 0};

HardSphereOptions laws(double e) {
  HardSphereOptions o;
  o.restitution = o.wall_restitution = {e};
  o.tangential_restitution = o.wall_tangential_restitution = {0.33};
  o.friction = o.wall_friction = {0.1};
  o.elastic_within = 0;
  return o;
}

std::string data_file(const std::string &name, const std::string &atoms, int count, int types = 1,
                      const std::string &velocities = "") {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << "test bed\n\n" << count << " atoms\n" << types << " atom types\n\n"
                      << "0 0.1 xlo xhi\n0 0.5 ylo yhi\n0 0.01 zlo zhi\n\nAtoms # granular\n\n" << atoms
                      << (velocities.empty() ? "" : "\nVelocities\n\n" + velocities);
  return path;
}

// A sphere at rest at y = 0.4 m, the fluid force holding a third of its weight: it falls
// with 2 g / 3; after 0.2 s in 1 ms steps, y = 0.4 - g t^2 / 3 and v = -2 g t / 3 exactly
// (to round-off), it has not reached the floor.
TEST(HardSphereEngine, FallsAsAConstantForceMoves) {
  HardSphereEngine engine(laws(0.9), data_file("fall.data", "1 1 0.002 2500 0.05 0.4 0.005\n", 1), kGravity);
  const double m = engine.masses()[0];
  engine.set_fluid_force({0, m * 9.81 / 3, 0});
  for (int k = 0; k < 200; ++k) engine.advance(1e-3, false);
  EXPECT_NEAR(engine.positions()[1], 0.4 - 9.81 * 0.04 / 3, 1e-13);
  EXPECT_NEAR(engine.velocities()[1], -2 * 9.81 * 0.2 / 3, 1e-12);
  EXPECT_NEAR(engine.time(), 0.2, 1e-15);
  EXPECT_EQ(engine.step(), 200);
}

// Dropped from 0.1 m (its bottom 0.1 m above the floor) with e_n = 0.8: it rebounds to
// 0.64 x 0.1 m, within (1 + e) g dt / (e v) of it, v = sqrt(2 g 0.1) = 1.40 m/s (measured
// -0.89 % at 1 ms against 1.6 %, -0.27 % at 0.2 ms against 0.32 %).
TEST(HardSphereEngine, ReboundsFromAFloorToENSquaredOfItsDrop) {
  for (const double dt : {1e-3, 2e-4}) {
    HardSphereEngine engine(laws(0.8), data_file("drop.data", "1 1 0.002 2500 0.05 0.101 0.005\n", 1), kGravity);
    double highest = 0, time = 0;
    bool bounced = false;
    for (; time < 0.5; time += dt) {
      engine.advance(dt, false);
      const double bottom = engine.positions()[1] - 0.001;
      if (engine.velocities()[1] > 0) bounced = true;
      if (bounced) highest = std::max(highest, bottom);
    }
    const double impact = std::sqrt(2 * 9.81 * 0.1);
    EXPECT_NEAR(highest / (0.64 * 0.1), 1.0, 1.8 * 9.81 * dt / (0.8 * impact)) << "dt " << dt;
  }
}

// Two spheres on the floor overlapping by 0.2 mm and sunk 0.1 mm into it (as a soft packing
// leaves them), the second drifting away at 1 mm/s, and a third thrown at them at 0.2 m/s
// that strikes after the checkpoint and drives the pair together again while they still
// overlap, with five more thrown sideways in turns: stopped after 0.05 s and resumed from the
// restart file, the next 0.05 s end exactly where the straight run's do (the pair's contact
// distance and the floor's reach kept as tolerated).
TEST(HardSphereEngine, ResumesBitForBit) {
  const double x[8] = {0.05, 0.0538, 0.0688, 0.01, 0.015, 0.02, 0.025, 0.03};
  const double y[8] = {0.0019, 0.0019, 0.0025, 0.003, 0.008, 0.013, 0.003, 0.008};
  const double u[8] = {0, 0.001, -0.2, 0.2, -0.2, 0.2, -0.2, 0.2};
  std::string atoms, velocities;
  for (int k = 0; k < 8; ++k) {
    char line[128];
    std::snprintf(line, sizeof line, "%d 1 0.004 2500 %g %g 0.005\n", k + 1, x[k], y[k]);
    atoms += line;
    std::snprintf(line, sizeof line, "%d %g 0 0 0 0 0\n", k + 1, u[k]);
    velocities += line;
  }
  const std::string file = data_file("box.data", atoms, 8, 1, velocities);
  HardSphereEngine straight(laws(0.9), file, kGravity), first(laws(0.9), file, kGravity);
  EXPECT_EQ(straight.overlaps().pairs, 1u);
  EXPECT_EQ(straight.overlaps().walls, 2u);
  const std::vector<double> force(24, 1e-5);
  straight.set_fluid_force(force);
  first.set_fluid_force(force);
  for (int k = 0; k < 50; ++k) {
    straight.advance(1e-3, false);
    first.advance(1e-3, false);
  }
  const std::string restart = ::testing::TempDir() + "box.restart";
  ASSERT_TRUE(first.write_restart(restart));
  ASSERT_TRUE(straight.write_restart(restart + ".straight"));  // a straight run checkpoints too
  DemResume resume;
  resume.restart_file = restart;
  resume.step = first.step();
  HardSphereEngine resumed(laws(0.9), file, kGravity, &resume);
  for (int k = 0; k < 50; ++k) {
    straight.advance(1e-3, false);
    resumed.advance(1e-3, false);  // with the held forces the restart file kept
  }
  EXPECT_GT(straight.totals().pair + straight.totals().wall, 10);
  for (int i = 0; i < 24; ++i) {
    EXPECT_EQ(resumed.positions()[i], straight.positions()[i]) << i;
    EXPECT_EQ(resumed.velocities()[i], straight.velocities()[i]) << i;
  }
  EXPECT_EQ(resumed.step(), 100);
  EXPECT_EQ(resumed.time(), straight.time());
}

// A LIGGGHTS data file declares its walls' atom type too (2 types, the particles all of
// type 1): the laws cover the particles' types, so one law fits and the engine has one type.
TEST(HardSphereEngine, TakesTheLawsOfTheParticlesTypes) {
  const std::string file = data_file("walltype.data", "1 1 0.002 2500 0.02 0.2 0.005\n2 1 0.002 2500 0.06 0.2 0.005\n", 2, 2);
  HardSphereOptions o = laws(0.9);
  o.restitution = {0.9};
  HardSphereEngine engine(o, file, kGravity);
  EXPECT_EQ(engine.type_count(), 1);
}

TEST(HardSphereEngine, RemovesByIdAndRefusesLawsThatDoNotFit) {
  HardSphereEngine engine(laws(0.9), data_file("two.data", "7 1 0.002 2500 0.02 0.2 0.005\n9 1 0.002 2500 0.06 0.2 0.005\n", 2),
                          kGravity);
  engine.remove_particles({7});
  ASSERT_EQ(engine.local_count(), 1u);
  EXPECT_EQ(engine.tags()[0], 9);
  EXPECT_EQ(engine.positions()[0], 0.06);
  HardSphereOptions three = laws(0.9);
  three.restitution = {0.9, 0.8, 0.7};
  try {
    HardSphereEngine bad(three, data_file("types.data", "1 1 0.002 2500 0.02 0.2 0.005\n1 2 0.002 2500 0.06 0.2 0.005\n", 2, 2),
                         kGravity);
    FAIL() << "accepted";
  } catch (const std::runtime_error &e) {
    EXPECT_NE(std::string(e.what()).find("dem.hard_sphere.restitution does not fit: it gives 3 values where one, or 4"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
