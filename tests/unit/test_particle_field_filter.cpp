// The particle-field filter. Diffusion smoothing (Sun & Xiao 2015): the spread of one particle
// against the heat kernel by hand, the lattice's exact variance, the total spread b^2 / 2 of the
// mapping and diffusion on every grid and in blocks, reflecting walls by the method of images,
// conservation, and the refusals of a bandwidth that is not one or is narrower than the cells. The block estimate:
// its weights by hand, a linear field kept, sums kept with and without a spread, the adjoint,
// and the refusal of a block that does not divide the grid.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

#include "tfdem/particle_field_filter.h"

namespace {

using namespace tfdem;

const double kPi = 3.14159265358979323846;

CartesianGrid grid(double h, int nx, int ny, int nz) {
  CartesianGrid g;
  g.origin = {0.0, 0.0, 0.0};
  g.spacing = {h, h, h};
  g.count = {nx, ny, nz};
  return g;
}

// The bandwidth of the diffusion alone, sqrt(b^2 - h^2 / 6): the filter leaves h^2 / 12 of the
// variance b^2 / 2 to the mapping into cells of h (a particle's place in its cell, uniform).
double diffusion_bandwidth(double b, double h) { return std::sqrt(b * b - h * h / 6); }

// One unit at cell `source` of a line of n cells (h = 1 mm), spread with bandwidth b.
std::vector<double> spread_line(int n, int source, double b) {
  std::vector<double> values(n, 0.0), scratch;
  values[source] = 1.0;
  ParticleFieldFilter(grid(1e-3, n, 1, 1), b).apply(values.data(), 1, scratch);
  return values;
}

// Largest |spread - Gaussian| over the peak of the Gaussian, for one unit in the middle of a
// line of cells h = 1 mm, bandwidth b: the Gaussian of the diffusion's bandwidth d has the cell
// value h exp(-x^2/d^2) / (sqrt(pi) d).
double line_error_against_gaussian(double b) {
  const int n = 401, middle = 200;
  const std::vector<double> v = spread_line(n, middle, b);
  const double h = 1e-3;
  b = diffusion_bandwidth(b, h);
  const double peak = h / (std::sqrt(kPi) * b);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = (i - middle) * h;
    worst = std::max(worst, std::abs(v[i] - peak * std::exp(-x * x / (b * b))));
  }
  return worst / peak;
}

TEST(ParticleFieldFilter, OneParticleSpreadsAsTheHeatKernel) {
  // 41^3 cells of 1 mm, bandwidth 8 mm (sigma = b/sqrt(2) = 5.7 cells, the walls 3.6 sigma away):
  // the cell values against the Gaussian (pi d^2)^(-3/2) exp(-r^2/d^2) V_c of the diffusion's
  // bandwidth d (diffusion_bandwidth). The lattice kernel per axis is exp(-2T/h^2) I_i(2T/h^2)
  // with T/h^2 = 16 less 1/24; at the centre it exceeds the Gaussian by 1/(8 * 2T/h^2) = 0.4 %
  // (the Bessel function's asymptotic series), 1.2 % in 3-D.
  const int n = 41, c = 20;
  const double h = 1e-3, b = diffusion_bandwidth(8e-3, h);
  const CartesianGrid g = grid(h, n, n, n);
  std::vector<double> values(g.cell_count(), 0.0), scratch;
  values[g.flat(c, c, c)] = 1.0;
  ParticleFieldFilter(g, 8e-3).apply(values.data(), 1, scratch);
  const double peak = h * h * h / std::pow(kPi * b * b, 1.5);
  double worst = 0.0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double r2 = h * h * ((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
        worst = std::max(worst, std::abs(values[g.flat(i, j, k)] - peak * std::exp(-r2 / (b * b))));
      }
  EXPECT_LT(worst / peak, 0.014);
  EXPECT_GT(values[g.flat(c, c, c)] / peak, 1.0);  // the lattice's peak is the higher one
  EXPECT_NEAR(std::accumulate(values.begin(), values.end(), 0.0), 1.0, 1e-12);
}

TEST(ParticleFieldFilter, ApproachesTheGaussianAsTheCellsShrink) {
  // The lattice kernel's departure from the Gaussian is O(h^2 / b^2): doubling b/h divides
  // it by about 4 (the centre's 1/(8 * 2T/h^2): 0.39 %, 0.098 %, 0.024 %).
  const double e8 = line_error_against_gaussian(8e-3), e16 = line_error_against_gaussian(16e-3),
               e32 = line_error_against_gaussian(32e-3);
  EXPECT_NEAR(e8, 1.0 / (8 * (32 - 1.0 / 12)), 0.2e-3);
  EXPECT_NEAR(e8 / e16, 4.0, 0.2);
  EXPECT_NEAR(e16 / e32, 4.0, 0.2);
}

TEST(ParticleFieldFilter, DiffusionLeavesTheCellsTheirTwelfth) {
  // The lattice heat kernel's variance is 2T for any h (a random walk of rate 1/h^2 per
  // direction and steps h): the diffusion alone spreads a cell's content by b^2 / 2 - h^2 / 12;
  // the walls are 200 cells (35 sigma) away.
  const int n = 401, middle = 200;
  const double h = 1e-3, b = 8e-3;
  const std::vector<double> v = spread_line(n, middle, b);
  double mean = 0.0, variance = 0.0;
  for (int i = 0; i < n; ++i) mean += v[i] * (i - middle) * h;
  for (int i = 0; i < n; ++i) variance += v[i] * std::pow((i - middle) * h - mean, 2);
  EXPECT_NEAR(mean, 0.0, 1e-15);
  EXPECT_NEAR(variance / (b * b / 2 - h * h / 12), 1.0, 1e-12);
}

// A particle's total spread along a line of cells of h in blocks of k, bandwidth b: one unit
// mapped to the cell holding its centre, filtered, and the second moment of the result about
// the centre, averaged over `places` centres spread evenly across a block in the line's middle
// (the mapping as the coupling does it, with no formula for the cells' share).
double total_spread(double h, int k, double b, int places) {
  const int n = static_cast<int>(std::lround(0.6 / h));  // 0.6 m: the walls > 10 b away
  const int first = (n / 2 / k) * k;                        // the block in the middle
  const ParticleFieldFilter filter(grid(h, n, 1, 1), b, {k, 1, 1});
  std::vector<double> values(n), scratch;
  double sum = 0.0;
  for (int m = 0; m < places; ++m) {
    const double x = (first + (m + 0.5) * k / places) * h;
    std::fill(values.begin(), values.end(), 0.0);
    values[static_cast<int>(std::floor(x / h))] = 1.0;
    filter.apply(values.data(), 1, scratch);
    for (int i = 0; i < n; ++i) sum += values[i] * std::pow((i + 0.5) * h - x, 2);
  }
  return sum / places;
}

TEST(ParticleFieldFilter, TotalSpreadIsHalfTheBandwidthSquaredOnEveryGrid) {
  // b = 2.4 cm on cells of 0.5, 1 and 2 cm, and on 0.5 cm cells in blocks of 2 and 4: the
  // mapping and the diffusion together spread a particle by b^2 / 2 = 2.88 cm^2 per axis on
  // every grid (the average over 2000 places across a block, whose even sampling errs by
  // (k h / 2000)^2 / 12, below 1e-8 of it).
  const double b = 0.024, target = b * b / 2;
  for (const double h : {0.005, 0.01, 0.02})
    EXPECT_NEAR(total_spread(h, 1, b, 2000) / target, 1.0, 1e-7) << "cells of " << h << " m";
  for (const int k : {2, 4}) EXPECT_NEAR(total_spread(0.005, k, b, 2000) / target, 1.0, 1e-7) << "blocks of " << k;
  // Diffusion to b^2 / 2 on top of the mapping would make the coarse grid's kernel wider:
  // by (2 cm)^2 / 12 = 0.33 cm^2, 12 % of b^2 / 2.
  const double uncompensated = total_spread(0.02, 1, std::sqrt(b * b + 0.02 * 0.02 / 6), 2000);
  EXPECT_NEAR(uncompensated - target, 0.02 * 0.02 / 12, 1e-9);
}

TEST(ParticleFieldFilter, WallsReflectAsTheMethodOfImages) {
  // A unit two cells from the wall at x = 0 is what an unbounded line gives with an image
  // source mirrored across the wall's face (cell -1 - s); nothing leaves through the wall (the
  // far walls are 97 and 150 cells, 23 and 35 sigma, away).
  const int n = 100, s = 2, far = 301, middle = 150;
  const double b = 6e-3;
  const std::vector<double> walled = spread_line(n, s, b), open = spread_line(far, middle, b);
  for (int i = 0; i < 30; ++i) {
    const double images = open[middle + i - s] + open[middle + i + s + 1];
    EXPECT_NEAR(walled[i], images, 1e-14) << "cell " << i;
  }
  EXPECT_NEAR(std::accumulate(walled.begin(), walled.end(), 0.0), 1.0, 1e-13);
}

TEST(ParticleFieldFilter, KeepsEachFieldsSumAndSign) {
  // A random field of three components on 7 x 9 x 5 cells: each component's sum unchanged to
  // round-off, nothing negative; a uniform field stays uniform.
  const CartesianGrid g = grid(2e-3, 7, 9, 5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> values(3 * g.cell_count()), scratch;
  for (double &v : values) v = u(rng) < 0.3 ? u(rng) : 0.0;
  double before[3] = {0, 0, 0}, after[3] = {0, 0, 0};
  for (std::size_t c = 0; c < values.size(); ++c) before[c % 3] += values[c];
  const ParticleFieldFilter smoothing(g, 5e-3);
  smoothing.apply(values.data(), 3, scratch);
  for (std::size_t c = 0; c < values.size(); ++c) {
    after[c % 3] += values[c];
    EXPECT_GE(values[c], 0.0);
  }
  for (int m = 0; m < 3; ++m) EXPECT_NEAR(after[m] / before[m], 1.0, 1e-14);
  std::vector<double> uniform(g.cell_count(), 0.25);
  smoothing.apply(uniform.data(), 1, scratch);
  for (double v : uniform) EXPECT_NEAR(v, 0.25, 1e-15);
}

TEST(ParticleFieldFilter, SpreadsAlongEachAxisAloneAndNotAcrossOneCell) {
  // On 12 x 10 x 1 cells, a field that varies along x only keeps every y-line alike and each
  // x-line equal to the 1-D spread; the one-cell depth (the 2-D rule's) is not spread.
  const int nx = 12, ny = 10;
  const double b = 4e-3;
  const CartesianGrid g = grid(1e-3, nx, ny, 1);
  std::vector<double> values(g.cell_count()), line(nx), scratch;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) values[g.flat(i, j, 0)] = line[i] = (i == 3 ? 1.0 : 0.0) + 0.1 * i;
  ParticleFieldFilter(g, b).apply(values.data(), 1, scratch);
  ParticleFieldFilter(grid(1e-3, nx, 1, 1), b).apply(line.data(), 1, scratch);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) EXPECT_NEAR(values[g.flat(i, j, 0)], line[i], 1e-14) << i << ", " << j;
}

std::string refusal(const CartesianGrid &g, double b, std::array<int, 3> block = {1, 1, 1}) {
  try {
    ParticleFieldFilter smoothing(g, b, block);
  } catch (const std::invalid_argument &e) {
    return e.what();
  }
  return "";
}

TEST(ParticleFieldFilter, RefusesABandwidthThatIsNotOne) {
  const CartesianGrid g = grid(1e-2, 15, 45, 1);  // 15 x 45 cm, one cell deep
  for (double b : {-0.01, std::nan("")}) {
    const std::string message = refusal(g, b);
    EXPECT_NE(message.find("coupling.void_fraction.diffusion_bandwidth"), std::string::npos) << message;
    EXPECT_NE(message.find("above 0 in metres"), std::string::npos) << message;
  }
  const std::string wide = refusal(g, 0.2);
  EXPECT_NE(wide.find("larger than the domain along x (0.15 m)"), std::string::npos) << wide;
  EXPECT_EQ(refusal(g, 0.05), "");  // wider than the one-cell depth (1 cm): that axis is not spread
  // Narrower than the cells: mapping into 2 cm cells spreads by (2 cm)^2 / 12 = 3.33e-5 m^2,
  // more than b^2 / 2 for b = 8 mm; the least bandwidth is sqrt(2 * 3.33e-5) = 8.16 mm
  const std::string narrow = refusal(grid(0.02, 10, 10, 1), 0.008);
  EXPECT_NE(narrow.find("narrower than the cells along x"), std::string::npos) << narrow;
  EXPECT_NE(narrow.find("at least 0.00816497 m"), std::string::npos) << narrow;
  EXPECT_EQ(refusal(grid(0.02, 10, 10, 1), 0.0082), "");
}

TEST(ParticleFieldFilter, WithoutBandwidthOrBlockChangesNothing) {
  const CartesianGrid g = grid(2e-3, 4, 6, 1);
  std::vector<double> values(g.cell_count()), scratch;
  for (std::size_t c = 0; c < values.size(); ++c) values[c] = 0.1 * c;
  const std::vector<double> before = values;
  ParticleFieldFilter(g, 0.0).apply(values.data(), 1, scratch);
  EXPECT_EQ(values, before);
}

TEST(ParticleFieldFilter, BlockSharesByHand) {
  // 4 cells in blocks of 2: a unit in cell 0 is block 0's sum S0 = 1. Cell centres sit at
  // s = -1/4, 1/4, 3/4, 5/4 block widths from block 0's centre: cell 0 between the wall's
  // mirror ghost (= S0) and S0, so S0/2; cell 1: (3/4 S0 + 1/4 S1)/2 = 0.375; cell 2:
  // (1/4 S0 + 3/4 S1)/2 = 0.125; cell 3: S1/2 = 0.
  EXPECT_EQ(block_estimate_kernel(4, 1), std::vector<double>({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}));
  std::vector<double> line = {1.0, 0.0, 0.0, 0.0}, scratch;
  ParticleFieldFilter(grid(1e-2, 4, 1, 1), 0.0, {2, 1, 1}).apply(line.data(), 1, scratch);
  const double expected[4] = {0.5, 0.375, 0.125, 0.0};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(line[i], expected[i], 1e-16) << "cell " << i;
  // Blocks of 3: the middle cell sits at its block's centre and takes a third of its sum.
  std::vector<double> three(9, 0.0);
  three[4] = 1.0;
  ParticleFieldFilter(grid(1e-2, 9, 1, 1), 0.0, {3, 1, 1}).apply(three.data(), 1, scratch);
  const double thirds[9] = {0, 0, 1.0 / 9, 2.0 / 9, 1.0 / 3, 2.0 / 9, 1.0 / 9, 0, 0};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(three[i], thirds[i], 1e-15) << "cell " << i;
}

TEST(ParticleFieldFilter, BlockKeepsALinearFieldAwayFromTheWalls) {
  // Cell sums of the density 1 + 30 x (x in m) on 24 x 12 cells of 5 mm in blocks of 4 x 3: a
  // block's mean is its centre's density and the linear interpolation is exact for a linear
  // field, so every cell more than a block from a wall along x gets its own sum back.
  const double h = 5e-3;
  const CartesianGrid g = grid(h, 24, 12, 1);
  std::vector<double> values(g.cell_count()), scratch;
  const auto density = [&](int i) { return 1.0 + 30.0 * (i + 0.5) * h; };
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 24; ++i) values[g.flat(i, j, 0)] = density(i) * h * h * h;
  ParticleFieldFilter(g, 0.0, {4, 3, 1}).apply(values.data(), 1, scratch);
  for (int j = 0; j < 12; ++j)
    for (int i = 4; i < 20; ++i)
      EXPECT_NEAR(values[g.flat(i, j, 0)] / (h * h * h), density(i), 1e-12) << i << ", " << j;
  // ... and at a wall the mirror ghost makes the field flat over the outer half block: the
  // wall cell gets its block's mean, 1 + 30 * 2 h.
  EXPECT_NEAR(values[g.flat(0, 5, 0)] / (h * h * h), 1.0 + 30.0 * 2 * h, 1e-12);
}

TEST(ParticleFieldFilter, BlockWithOrWithoutSpreadKeepsSumsSignAndAdjoint) {
  // A random field of three components on 8 x 9 x 5 cells in blocks of 2 x 3 x 1, with no
  // spread and with b = 6 mm: each sum unchanged, nothing negative; the adjoint is the
  // transpose (<F x, y> = <x, F^T y> for random x, y) and keeps a uniform velocity uniform (a
  // particle in a uniform gas sees it).
  const CartesianGrid g = grid(2e-3, 8, 9, 5);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double b : {0.0, 6e-3}) {
    const ParticleFieldFilter filter(g, b, {2, 3, 1});
    std::vector<double> values(3 * g.cell_count()), scratch;
    for (double &v : values) v = u(rng) < 0.3 ? u(rng) : 0.0;
    double before[3] = {0, 0, 0}, after[3] = {0, 0, 0};
    for (std::size_t c = 0; c < values.size(); ++c) before[c % 3] += values[c];
    filter.apply(values.data(), 3, scratch);
    for (std::size_t c = 0; c < values.size(); ++c) {
      after[c % 3] += values[c];
      EXPECT_GE(values[c], 0.0);
    }
    for (int m = 0; m < 3; ++m) EXPECT_NEAR(after[m] / before[m], 1.0, 1e-14) << "b " << b;

    std::vector<double> x(g.cell_count()), y(g.cell_count());
    for (double &v : x) v = u(rng) - 0.5;
    for (double &v : y) v = u(rng) - 0.5;
    std::vector<double> fx = x, fty = y;
    filter.apply(fx.data(), 1, scratch);
    filter.apply_adjoint(fty.data(), 1, scratch);
    double left = 0.0, right = 0.0, scale = 0.0;
    for (int c = 0; c < g.cell_count(); ++c) {
      left += fx[c] * y[c];
      right += x[c] * fty[c];
      scale += std::abs(fx[c] * y[c]);
    }
    EXPECT_LT(std::abs(left - right), 1e-14 * scale) << "b " << b;
    EXPECT_GT(std::abs(left - std::inner_product(x.begin(), x.end(), y.begin(), 0.0)), 1e-3 * scale)
        << "the filter left the field as it was";
    std::vector<double> uniform(3 * g.cell_count());
    for (std::size_t c = 0; c < uniform.size(); ++c) uniform[c] = 0.5 + c % 3;
    filter.apply_adjoint(uniform.data(), 3, scratch);
    for (std::size_t c = 0; c < uniform.size(); ++c) EXPECT_NEAR(uniform[c], 0.5 + c % 3, 1e-14);
  }
}

TEST(ParticleFieldFilter, RefusesABlockThatDoesNotDivideTheGrid) {
  const CartesianGrid g = grid(1e-2, 15, 45, 1);
  const std::string four = refusal(g, 0.0, {1, 4, 1});
  EXPECT_NE(four.find("coupling.void_fraction.particle_field_block: 4 gas cells along y is not a whole divisor of "
                      "the gas grid's 45 cells there: give one of 1 3 5 9 15 45"),
            std::string::npos)
      << four;
  const std::string deep = refusal(g, 0.0, {3, 3, 2});
  EXPECT_NE(deep.find("2 gas cells along z is not a whole divisor of the gas grid's 1 cells there: give one of 1 "),
            std::string::npos)
      << deep;
  EXPECT_NE(refusal(g, 0.0, {0, 1, 1}).find("0 gas cells along x"), std::string::npos);
  EXPECT_EQ(refusal(g, 0.05, {3, 5, 1}), "");
}

}  // namespace
