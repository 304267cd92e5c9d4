// Void fraction mapping: seed 000 eq. 34 (centroid), seed 001 eq. 33-37 (porous cube),
// divided volume, the 2-D rule, the gas-fraction floor and interpolation.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "tfdem/void_fraction.h"

namespace {

using namespace tfdem;

struct Cloud {
  std::vector<double> position, velocity, diameter, density;
  ParticleView view() const {
    return {diameter.size(), position.data(), velocity.data(), diameter.data(), density.data()};
  }
  void add(double x, double y, double z, double d) {
    position.insert(position.end(), {x, y, z});
    velocity.insert(velocity.end(), {0.0, 0.0, 0.0});
    diameter.push_back(d);
    density.push_back(2500.0);
  }
};

CartesianGrid grid(double dx, double dy, double dz, int nx, int ny, int nz) {
  CartesianGrid g;
  g.origin = {0.0, 0.0, 0.0};
  g.spacing = {dx, dy, dz};
  g.count = {nx, ny, nz};
  return g;
}

// Non-overlapping particles on a jittered lattice filling the box, the outermost ones
// sticking out of the walls (centres within d/2 of them), plus one centred on a corner.
Cloud lattice_cloud(const CartesianGrid &g, double spacing, double d_min, double d_max, bool flat, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double jitter = 0.5 * (spacing - d_max);
  Cloud c;
  const double z_mid = 0.5 * g.upper(2);
  for (double x = 0.3 * spacing; x < g.upper(0); x += spacing)
    for (double y = 0.3 * spacing; y < g.upper(1); y += spacing)
      for (double z = flat ? z_mid : 0.3 * spacing; z < g.upper(2); z += flat ? g.upper(2) : spacing) {
        const double jx = std::min(x + jitter * (2 * u(rng) - 1), g.upper(0));
        const double jy = std::min(y + jitter * (2 * u(rng) - 1), g.upper(1));
        c.add(std::max(jx, 0.0), std::max(jy, 0.0), z, d_min + (d_max - d_min) * u(rng));
      }
  c.add(g.upper(0), g.upper(1), flat ? z_mid : g.upper(2), 0.5 * d_max);
  return c;
}

double total_particle_volume(const Cloud &c) {
  double v = 0.0;
  for (double d : c.diameter) v += sphere_volume(d);
  return v;
}

double mapped_solid_volume(const VoidFraction &f, const std::vector<double> &cell_volume) {
  double v = 0.0;
  for (std::size_t i = 0; i < cell_volume.size(); ++i) v += (1.0 - f.void_fraction[i]) * cell_volume[i];
  return v;
}

VoidFractionOptions options(VoidFractionMethod m, bool two_d = false, double a = 1.0) {
  VoidFractionOptions o;
  o.method = m;
  o.two_dimensional = two_d;
  o.cube_factor = a;
  return o;
}

const char *name(VoidFractionMethod m) { return void_fraction_method_names()[static_cast<int>(m)].c_str(); }

// Every method conserves volume: sum_c solid_volume_c = sum_i V_i to 1e-12 relative, with
// particles sticking out of walls and cells larger (10 mm) and smaller (2 mm) than particles
// (1.5-4 mm). Where no cell is over-filled (eps >= 0, floor unused) this is the identity
// sum_c (1 - eps_c) V_c = sum_i V_i. In 2 mm cells, centroid over-fills cells, and so does
// divided (a cell inside a 4 mm sphere holds ~27 of the ~113 sample points, ~1 % more than
// its volume): those cells are counted by the floor; the porous cube (a = 1.2, cube solid
// fraction pi/(6 a^3) = 0.30, seed 001 eq. 36) never over-fills.
TEST(VoidFraction, MappedVolumeEqualsParticleVolumeForEveryMethod3D) {
  for (auto m : {VoidFractionMethod::Centroid, VoidFractionMethod::Divided, VoidFractionMethod::PorousCube}) {
    for (double cell : {0.01, 0.002}) {
      const CartesianGrid g = grid(cell, cell, cell, static_cast<int>(0.06 / cell), static_cast<int>(0.05 / cell),
                                   static_cast<int>(0.04 / cell));
      const Cloud c = lattice_cloud(g, 0.0045, 0.0015, 0.004, false, 7);
      const auto vol = cell_volumes(g, false, 0.0);
      const VoidFraction f = map_void_fraction(compute_weights(g, c.view(), options(m, false, 1.2)), c.view(), vol, 0.0);
      const double solid = std::accumulate(f.solid_volume.begin(), f.solid_volume.end(), 0.0);
      EXPECT_NEAR(solid / total_particle_volume(c), 1.0, 1e-12) << name(m) << ", cell " << cell;
      if (m != VoidFractionMethod::PorousCube && cell < 0.004) {
        EXPECT_GT(f.floored_cells, 0u) << name(m) << " in cells smaller than particles over-fills cells";
        continue;
      }
      EXPECT_EQ(f.floored_cells, 0u) << name(m) << ", cell " << cell;
      EXPECT_NEAR(mapped_solid_volume(f, vol) / total_particle_volume(c), 1.0, 1e-12) << name(m) << ", cell " << cell;
    }
  }
}

// Same under the paper's 2-D rule: one layer, cell depth = d_p.
TEST(VoidFraction, MappedVolumeEqualsParticleVolumeUnderTwoDimensionalRule) {
  const double dp = 0.0025;
  for (auto m : {VoidFractionMethod::Centroid, VoidFractionMethod::Divided, VoidFractionMethod::PorousCube}) {
    for (double cell : {0.01, 0.004}) {
      const CartesianGrid g = grid(cell, cell, dp, static_cast<int>(0.15 / cell), static_cast<int>(0.1 / cell), 1);
      const Cloud c = lattice_cloud(g, 0.003, dp, dp, true, 11);
      const auto vol = cell_volumes(g, true, dp);
      const VoidFraction f = map_void_fraction(compute_weights(g, c.view(), options(m, true, 0.9)), c.view(), vol, 0.0);
      const double solid = std::accumulate(f.solid_volume.begin(), f.solid_volume.end(), 0.0);
      EXPECT_NEAR(solid / total_particle_volume(c), 1.0, 1e-12) << name(m) << ", cell " << cell;
      EXPECT_EQ(f.floored_cells, 0u) << name(m) << ", cell " << cell;
      EXPECT_NEAR(mapped_solid_volume(f, vol) / total_particle_volume(c), 1.0, 1e-12) << name(m) << ", cell " << cell;
    }
  }
}

// Seed 000 eq. 34: one particle alone in a cell gives eps_s = V_p / V_cell.
TEST(VoidFraction, CentroidSingleParticle) {
  const CartesianGrid g = grid(0.01, 0.01, 0.01, 3, 3, 3);
  Cloud c;
  c.add(0.015, 0.012, 0.018, 0.004);
  const auto vol = cell_volumes(g, false, 0.0);
  const VoidFraction f = map_void_fraction(compute_weights(g, c.view(), options(VoidFractionMethod::Centroid)), c.view(), vol, 0.0);
  EXPECT_DOUBLE_EQ(f.void_fraction[g.flat(1, 1, 1)], 1.0 - sphere_volume(0.004) / 1e-6);
  EXPECT_EQ(f.void_fraction[g.flat(0, 0, 0)], 1.0);
}

// The floor's account, by hand: three 8 mm spheres in one 1 cm cube (centroid) fill it to
// eps = 1 - 3 V_p / V_cell = 0.196 < 0.3; the floored cell holds 3 V_p of solids, and the map
// leaves out 3 V_p - (1 - 0.3) V_cell of them; the cell beside, with one sphere, is not floored.
TEST(VoidFraction, FloorCountsTheSolidsItTouchesAndLeavesOut) {
  const CartesianGrid g = grid(0.01, 0.01, 0.01, 2, 1, 1);
  Cloud c;
  for (const double y : {0.003, 0.005, 0.007}) c.add(0.005, y, 0.005, 0.008);
  c.add(0.015, 0.005, 0.005, 0.008);
  const auto vol = cell_volumes(g, false, 0.0);
  const double vp = M_PI * 0.008 * 0.008 * 0.008 / 6.0;
  const VoidFraction f = map_void_fraction(compute_weights(g, c.view(), options(VoidFractionMethod::Centroid)), c.view(), vol, 0.3);
  EXPECT_EQ(f.floored_cells, 1u);
  EXPECT_DOUBLE_EQ(f.void_fraction[g.flat(0, 0, 0)], 0.3);
  EXPECT_NEAR(f.lowest_unfloored, 1.0 - 3 * vp / 1e-6, 1e-14);
  EXPECT_NEAR(f.floored_solid_volume, 3 * vp, 1e-20);
  EXPECT_NEAR(f.removed_solid_volume, 3 * vp - 0.7e-6, 1e-20);
  EXPECT_NEAR(f.void_fraction[g.flat(1, 0, 0)], 1.0 - vp / 1e-6, 1e-14);
}

// Seed 001 eq. 36-37: a cube inside one cell puts all of V_p there; a 2-D cube centred on a
// corner of four cells gives each a quarter.
TEST(VoidFraction, PorousCubeSharesAreOverlapFractions) {
  const double dp = 0.0025;
  const CartesianGrid g = grid(0.01, 0.01, dp, 2, 2, 1);
  Cloud c;
  c.add(0.005, 0.005, 0.5 * dp, dp);
  c.add(0.01, 0.01, 0.5 * dp, dp);
  const CellWeights w = compute_weights(g, c.view(), options(VoidFractionMethod::PorousCube, true, 1.0));
  ASSERT_EQ(w.offsets[1] - w.offsets[0], 1u);
  EXPECT_EQ(w.cells[0], g.flat(0, 0, 0));
  ASSERT_EQ(w.offsets[2] - w.offsets[1], 4u);
  for (std::size_t k = w.offsets[1]; k < w.offsets[2]; ++k) EXPECT_NEAR(w.weights[k], 0.25, 1e-15);
}

// A cube shifted by s along x from a face shares (a d/2 + s)/(a d) and (a d/2 - s)/(a d).
TEST(VoidFraction, PorousCubeSplitAcrossOneFace) {
  const double dp = 0.004, a = 1.1, s = 0.0007;
  const CartesianGrid g = grid(0.01, 0.01, 0.01, 2, 1, 1);
  Cloud c;
  c.add(0.01 + s, 0.005, 0.005, dp);
  const CellWeights w = compute_weights(g, c.view(), options(VoidFractionMethod::PorousCube, false, a));
  ASSERT_EQ(w.cells.size(), 2u);
  EXPECT_NEAR(w.weights[0], (0.5 * a * dp - s) / (a * dp), 1e-14);
  EXPECT_NEAR(w.weights[1], (0.5 * a * dp + s) / (a * dp), 1e-14);
}

// Every method maps a bed and its mirror image (x -> W - x) to mirrored cells: no side is
// favoured, in the interior or at the walls (the 1 x 1 cm cells of the jet bed's fine grid,
// 4 mm particles under the 2-D rule, cubes of 2.5 and 5 d_p reaching through the walls).
TEST(VoidFraction, MirroredBedMapsToMirroredCells) {
  const double dp = 0.004;
  const CartesianGrid g = grid(0.01, 0.01, dp, 15, 20, 1);
  const Cloud c = lattice_cloud(g, 0.0045, dp, dp, true, 7);
  Cloud mirror = c;
  for (std::size_t i = 0; i < c.diameter.size(); ++i) mirror.position[3 * i] = g.upper(0) - c.position[3 * i];
  std::vector<double> cell_volume(g.cell_count(), 0.01 * 0.01 * dp);
  for (auto m : {VoidFractionMethod::Centroid, VoidFractionMethod::Divided, VoidFractionMethod::PorousCube})
    for (double a : {2.5, 5.0}) {
      const VoidFractionOptions o = options(m, true, a);
      const VoidFraction f = map_void_fraction(compute_weights(g, c.view(), o), c.view(), cell_volume, 0.0);
      const VoidFraction fm = map_void_fraction(compute_weights(g, mirror.view(), o), mirror.view(), cell_volume, 0.0);
      for (int j = 0; j < g.count[1]; ++j)
        for (int i = 0; i < g.count[0]; ++i)
          EXPECT_NEAR(f.solid_volume[g.flat(i, j, 0)], fm.solid_volume[g.flat(g.count[0] - 1 - i, j, 0)], 1e-18)
              << name(m) << " a = " << a << " cell " << i << ", " << j;
    }
}

// Divided: a particle far from faces stays in its cell; one centred on a face splits 50/50.
TEST(VoidFraction, DividedSplitsSymmetricallyAcrossAFace) {
  const CartesianGrid g = grid(0.01, 0.01, 0.01, 2, 1, 1);
  Cloud c;
  c.add(0.005, 0.005, 0.005, 0.004);
  c.add(0.01, 0.005, 0.005, 0.004);
  const CellWeights w = compute_weights(g, c.view(), options(VoidFractionMethod::Divided));
  EXPECT_EQ(w.offsets[1], 1u);
  ASSERT_EQ(w.offsets[2] - w.offsets[1], 2u);
  EXPECT_NEAR(w.weights[1], 0.5, 1e-14);
  EXPECT_NEAR(w.weights[2], 0.5, 1e-14);
}

// The floor replaces values below it and every replacement is counted.
TEST(VoidFraction, FloorIsAppliedAndCounted) {
  const CartesianGrid g = grid(0.003, 0.003, 0.003, 2, 1, 1);
  Cloud c;
  for (int i = 0; i < 3; ++i) c.add(0.0015, 0.0015, 0.0015, 0.0025);  // eps_s = 3 V_p / V_cell = 0.91
  const auto vol = cell_volumes(g, false, 0.0);
  const VoidFraction f = map_void_fraction(compute_weights(g, c.view(), options(VoidFractionMethod::Centroid)), c.view(), vol, 0.3);
  EXPECT_EQ(f.floored_cells, 1u);
  EXPECT_DOUBLE_EQ(f.void_fraction[0], 0.3);
  EXPECT_DOUBLE_EQ(f.lowest_unfloored, 1.0 - 3.0 * sphere_volume(0.0025) / 2.7e-8);
  EXPECT_DOUBLE_EQ(f.void_fraction[1], 1.0);
  EXPECT_THROW(map_void_fraction(compute_weights(g, c.view(), options(VoidFractionMethod::Centroid)), c.view(), vol, 1.0),
               std::invalid_argument);
}

TEST(VoidFraction, ParticleOutsideMeshIsNamed) {
  const CartesianGrid g = grid(0.01, 0.01, 0.01, 2, 2, 2);
  Cloud c;
  c.add(0.005, 0.005, 0.005, 0.002);
  c.add(0.005, 0.025, 0.005, 0.002);
  for (auto m : {VoidFractionMethod::Centroid, VoidFractionMethod::Divided, VoidFractionMethod::PorousCube}) {
    try {
      compute_weights(g, c.view(), options(m));
      FAIL() << "no exception";
    } catch (const std::out_of_range &e) {
      EXPECT_NE(std::string(e.what()).find("particle 1 at (0.005, 0.025, 0.005) m is outside the mesh"), std::string::npos)
          << e.what();
    }
  }
  const int cells[] = {0, -1};
  EXPECT_THROW(centroid_weights(cells, 2), std::out_of_range);
}

TEST(VoidFraction, CubeFactorBelowSeed001Eq35IsRejected) {
  EXPECT_NEAR(minimum_cube_factor(), std::cbrt(3.14159265358979323846 / 6.0), 1e-15);
  const CartesianGrid g = grid(0.01, 0.01, 0.01, 1, 1, 1);
  Cloud c;
  c.add(0.005, 0.005, 0.005, 0.002);
  EXPECT_THROW(compute_weights(g, c.view(), options(VoidFractionMethod::PorousCube, false, 0.8)), std::invalid_argument);
}

TEST(VoidFraction, MethodNamesAndSuggestions) {
  EXPECT_EQ(void_fraction_method_from_name("porous_cube"), VoidFractionMethod::PorousCube);
  try {
    void_fraction_method_from_name("centriod");
    FAIL() << "no exception";
  } catch (const std::invalid_argument &e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'centroid'?"), std::string::npos);
  }
}

// Interpolation reproduces a linear field exactly, interior and boundary half-cells, 3-D and 2-D.
TEST(Interpolation, ExactForLinearFields) {
  for (const CartesianGrid &g : {grid(0.01, 0.02, 0.015, 5, 4, 3), grid(0.01, 0.01, 0.0025, 6, 9, 1)}) {
    std::vector<double> field(2 * g.cell_count());
    auto linear = [](const double *x, double *v) {
      v[0] = 1.5 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2];
      v[1] = -0.7 + 4.0 * x[1];
    };
    for (int k = 0; k < g.count[2]; ++k)
      for (int j = 0; j < g.count[1]; ++j)
        for (int i = 0; i < g.count[0]; ++i) {
          double x[3] = {g.centre(0, i), g.centre(1, j), g.centre(2, k)};
          if (g.count[2] == 1) x[2] = 0.0;
          linear(x, &field[2 * g.flat(i, j, k)]);
        }
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int n = 0; n < 200; ++n) {
      double p[3] = {u(rng) * g.upper(0), u(rng) * g.upper(1), g.count[2] == 1 ? 0.0 : u(rng) * g.upper(2)};
      double got[2], expected[2];
      interpolate(g, field.data(), 2, p, got);
      linear(p, expected);
      EXPECT_NEAR(got[0], expected[0], 1e-12);
      EXPECT_NEAR(got[1], expected[1], 1e-12);
    }
  }
}

}  // namespace
