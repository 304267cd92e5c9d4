// Diffusion smoothing of particle fields (Sun & Xiao 2015): the spread of one particle against
// the heat kernel by hand, the lattice's exact variance, reflecting walls by the method of
// images, conservation, and the refusals of a bandwidth that is not one.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

#include "tfdem/diffusion_smoothing.h"

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

// One unit at cell `source` of a line of n cells (h = 1 mm), spread with bandwidth b.
std::vector<double> spread_line(int n, int source, double b) {
  std::vector<double> values(n, 0.0), scratch;
  values[source] = 1.0;
  DiffusionSmoothing(grid(1e-3, n, 1, 1), b).spread(values.data(), 1, scratch);
  return values;
}

// Largest |spread - Gaussian| over the peak of the Gaussian, for one unit in the middle of a
// line of cells h = 1 mm, bandwidth b: the Gaussian's cell value is h exp(-x^2/b^2) / (sqrt(pi) b).
double line_error_against_gaussian(double b) {
  const int n = 401, middle = 200;
  const std::vector<double> v = spread_line(n, middle, b);
  const double h = 1e-3, peak = h / (std::sqrt(kPi) * b);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = (i - middle) * h;
    worst = std::max(worst, std::abs(v[i] - peak * std::exp(-x * x / (b * b))));
  }
  return worst / peak;
}

TEST(DiffusionSmoothing, OneParticleSpreadsAsTheHeatKernel) {
  // 41^3 cells of 1 mm, bandwidth 8 mm (sigma = b/sqrt(2) = 5.7 cells, the walls 3.6 sigma away):
  // the cell values against the Gaussian (pi b^2)^(-3/2) exp(-r^2/b^2) V_c. The lattice kernel
  // per axis is exp(-2T/h^2) I_i(2T/h^2) with T/h^2 = 16; at the centre it exceeds the
  // Gaussian by 1/(8 * 2T/h^2) = 0.4 % (the Bessel function's asymptotic series), 1.2 % in 3-D.
  const int n = 41, c = 20;
  const double h = 1e-3, b = 8e-3;
  const CartesianGrid g = grid(h, n, n, n);
  std::vector<double> values(g.cell_count(), 0.0), scratch;
  values[g.flat(c, c, c)] = 1.0;
  DiffusionSmoothing(g, b).spread(values.data(), 1, scratch);
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

TEST(DiffusionSmoothing, ApproachesTheGaussianAsTheCellsShrink) {
  // The lattice kernel's departure from the Gaussian is O(h^2 / b^2): doubling b/h divides
  // it by about 4 (the centre's 1/(8 * 2T/h^2): 0.39 %, 0.098 %, 0.024 %).
  const double e8 = line_error_against_gaussian(8e-3), e16 = line_error_against_gaussian(16e-3),
               e32 = line_error_against_gaussian(32e-3);
  EXPECT_NEAR(e8, 1.0 / (8 * 32), 0.2e-3);
  EXPECT_NEAR(e8 / e16, 4.0, 0.2);
  EXPECT_NEAR(e16 / e32, 4.0, 0.2);
}

TEST(DiffusionSmoothing, VarianceIsExactlyHalfTheBandwidthSquared) {
  // The lattice heat kernel's variance is 2T = b^2 / 2 for any h (a random walk of rate 1/h^2
  // per direction and steps h); the walls are 200 cells (35 sigma) away.
  const int n = 401, middle = 200;
  const double h = 1e-3, b = 8e-3;
  const std::vector<double> v = spread_line(n, middle, b);
  double mean = 0.0, variance = 0.0;
  for (int i = 0; i < n; ++i) mean += v[i] * (i - middle) * h;
  for (int i = 0; i < n; ++i) variance += v[i] * std::pow((i - middle) * h - mean, 2);
  EXPECT_NEAR(mean, 0.0, 1e-15);
  EXPECT_NEAR(variance / (b * b / 2), 1.0, 1e-12);
}

TEST(DiffusionSmoothing, WallsReflectAsTheMethodOfImages) {
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

TEST(DiffusionSmoothing, KeepsEachFieldsSumAndSign) {
  // A random field of three components on 7 x 9 x 5 cells: each component's sum unchanged to
  // round-off, nothing negative; a uniform field stays uniform.
  const CartesianGrid g = grid(2e-3, 7, 9, 5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> values(3 * g.cell_count()), scratch;
  for (double &v : values) v = u(rng) < 0.3 ? u(rng) : 0.0;
  double before[3] = {0, 0, 0}, after[3] = {0, 0, 0};
  for (std::size_t c = 0; c < values.size(); ++c) before[c % 3] += values[c];
  const DiffusionSmoothing smoothing(g, 5e-3);
  smoothing.spread(values.data(), 3, scratch);
  for (std::size_t c = 0; c < values.size(); ++c) {
    after[c % 3] += values[c];
    EXPECT_GE(values[c], 0.0);
  }
  for (int m = 0; m < 3; ++m) EXPECT_NEAR(after[m] / before[m], 1.0, 1e-14);
  std::vector<double> uniform(g.cell_count(), 0.25);
  smoothing.spread(uniform.data(), 1, scratch);
  for (double v : uniform) EXPECT_NEAR(v, 0.25, 1e-15);
}

TEST(DiffusionSmoothing, SpreadsAlongEachAxisAloneAndNotAcrossOneCell) {
  // On 12 x 10 x 1 cells, a field that varies along x only keeps every y-line alike and each
  // x-line equal to the 1-D spread; the one-cell depth (the 2-D rule's) is not spread.
  const int nx = 12, ny = 10;
  const double b = 4e-3;
  const CartesianGrid g = grid(1e-3, nx, ny, 1);
  std::vector<double> values(g.cell_count()), line(nx), scratch;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) values[g.flat(i, j, 0)] = line[i] = (i == 3 ? 1.0 : 0.0) + 0.1 * i;
  DiffusionSmoothing(g, b).spread(values.data(), 1, scratch);
  DiffusionSmoothing(grid(1e-3, nx, 1, 1), b).spread(line.data(), 1, scratch);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) EXPECT_NEAR(values[g.flat(i, j, 0)], line[i], 1e-14) << i << ", " << j;
}

std::string refusal(const CartesianGrid &g, double b) {
  try {
    DiffusionSmoothing smoothing(g, b);
  } catch (const std::invalid_argument &e) {
    return e.what();
  }
  return "";
}

TEST(DiffusionSmoothing, RefusesABandwidthThatIsNotOne) {
  const CartesianGrid g = grid(1e-2, 15, 45, 1);  // 15 x 45 cm, one cell deep
  for (double b : {0.0, -0.01, std::nan("")}) {
    const std::string message = refusal(g, b);
    EXPECT_NE(message.find("coupling.void_fraction.diffusion_bandwidth"), std::string::npos) << message;
    EXPECT_NE(message.find("above 0 in metres"), std::string::npos) << message;
  }
  const std::string wide = refusal(g, 0.2);
  EXPECT_NE(wide.find("larger than the domain along x (0.15 m)"), std::string::npos) << wide;
  EXPECT_EQ(refusal(g, 0.05), "");  // wider than the one-cell depth (1 cm): that axis is not spread
}

}  // namespace
