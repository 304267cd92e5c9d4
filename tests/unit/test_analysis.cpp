// Analyses of seed 000 Fig. 5-13 and seed 001 eq. 49, against hand-built configurations.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tfdem/analysis.h"

namespace {

using namespace tfdem;
using namespace tfdem::analysis;

struct Cloud {
  std::vector<double> position, velocity, diameter, density;
  ParticleView view() const {
    return {diameter.size(), position.data(), velocity.data(), diameter.data(), density.data()};
  }
  void add(double x, double y, double z, double d, double vx = 0.0) {
    position.insert(position.end(), {x, y, z});
    velocity.insert(velocity.end(), {vx, 0.0, 0.0});
    diameter.push_back(d);
    density.push_back(2500.0);
  }
};

// A chain of four touching spheres and one loner: N_c = 1 2 2 1 0, bulk 6/5, multicontact 2/4.
TEST(Analysis, ChainCoordinationAndMulticontact) {
  Cloud c;
  const double d = 0.004;
  for (int i = 0; i < 4; ++i) c.add(i * 0.99 * d, 0.0, 0.0, d);
  c.add(0.1, 0.1, 0.0, d);
  const auto nc = coordination_numbers(5, contact_pairs(c.view()));
  EXPECT_EQ(nc, (std::vector<int>{1, 2, 2, 1, 0}));
  EXPECT_DOUBLE_EQ(bulk_coordination_number(nc), 6.0 / 5.0);
  EXPECT_DOUBLE_EQ(multicontact_ratio(nc), 2.0 / 4.0);
  EXPECT_DOUBLE_EQ(multicontact_ratio({0, 0}), 0.0);
}

// Binned search equals the all-pairs search on a random polydisperse cloud.
TEST(Analysis, ContactPairsMatchBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Cloud c;
  for (int i = 0; i < 400; ++i) c.add(0.05 * u(rng), 0.05 * u(rng), 0.02 * u(rng), 0.002 + 0.003 * u(rng));
  const auto pairs = contact_pairs(c.view());
  std::size_t brute = 0;
  for (std::size_t i = 0; i < 400; ++i)
    for (std::size_t j = i + 1; j < 400; ++j) {
      const double dx = c.position[3 * i] - c.position[3 * j], dy = c.position[3 * i + 1] - c.position[3 * j + 1],
                   dz = c.position[3 * i + 2] - c.position[3 * j + 2];
      if (std::sqrt(dx * dx + dy * dy + dz * dz) < 0.5 * (c.diameter[i] + c.diameter[j])) ++brute;
    }
  EXPECT_EQ(pairs.size(), brute);
  EXPECT_GT(brute, 50u);
}

// A hexagonal layer with 0.1 % overlap: the central particle has N_c = 6.
TEST(Analysis, HexagonalLayerCentreHasSixContacts) {
  Cloud c;
  const double d = 0.0025, s = 0.999 * d;
  for (int row = -2; row <= 2; ++row)
    for (int col = -2; col <= 2; ++col) c.add((col + 0.5 * (row & 1)) * s, row * s * std::sqrt(3.0) / 2.0, 0.0, d);
  const auto nc = coordination_numbers(c.diameter.size(), contact_pairs(c.view()));
  EXPECT_EQ(nc[12], 6);  // row 0, col 0
}

TEST(Analysis, MeanHeight) {
  Cloud c;
  c.add(0.0, 0.01, 0.0, 0.002);
  c.add(0.0, 0.04, 0.0, 0.002);
  EXPECT_DOUBLE_EQ(mean_height(c.view(), 1, 0.0), 0.025);
  EXPECT_DOUBLE_EQ(mean_height(c.view(), 1, 0.01), 0.015);
}

// Sums of |f| / (m g) per cell and their ratio; -1 where the drag sum is zero.
// Cell 0 holds two particles whose contact forces are (3, 4, 0) and (0, 0, 5) weights and
// whose drags are (0, 1, 0) and (0.5, 0, 0) weights: the cell's summed contact force is
// (3, 4, 5), |.| = sqrt(50) (the sum of magnitudes would be 10), the summed drag (0.5, 1, 0),
// |.| = sqrt(1.25). Cell 1's only particle is twice as heavy (density doubled): a contact
// force of 2 light-particle weights is 1 of its own weight.
TEST(Analysis, ForceMapsAreMagnitudesOfCellSums) {
  Cloud c;
  c.add(0.0, 0.0, 0.0, 0.004);
  c.add(0.0, 0.0, 0.0, 0.004);
  c.add(0.0, 0.0, 0.0, 0.004);
  c.density[2] = 5000.0;
  const int cells[] = {0, 0, 1};
  const double w = sphere_volume(0.004) * 2500.0 * 9.81;
  const double contact[] = {3 * w, 4 * w, 0, 0, 0, 5 * w, 2 * w, 0, 0};
  const double drag[] = {0, w, 0, 0.5 * w, 0, 0, 0, 0, 0};
  std::vector<double> contact_sums(6, 0.0), drag_sums(6, 0.0);
  add_force_sums(c.view(), cells, contact, 9.81, contact_sums);
  add_force_sums(c.view(), cells, drag, 9.81, drag_sums);
  const ForceMaps m = force_maps(contact_sums, drag_sums);
  EXPECT_NEAR(m.contact[0], std::sqrt(50.0), 1e-12);
  EXPECT_NEAR(m.drag[0], std::sqrt(1.25), 1e-12);
  EXPECT_NEAR(m.ratio[0], std::sqrt(50.0 / 1.25), 1e-12);
  EXPECT_NEAR(m.contact[1], 1.0, 1e-12);
  EXPECT_EQ(m.ratio[1], -1.0);
}

// Sums added by two "ranks" (halves of the particles) equal the sums of all at once: the
// maps are additive before the magnitude is taken.
TEST(Analysis, ForceSumsAddOverParticleSets) {
  Cloud all, first, second;
  const double f[] = {1e-4, -2e-4, 3e-5, -5e-5, 1e-4, 0.0, 2e-4, 2e-4, -1e-4, 0.0, 0.0, 7e-5};
  const int cells[] = {0, 1, 1, 0};
  for (int i = 0; i < 4; ++i) {
    all.add(0.0, 0.0, 0.0, 0.003);
    (i < 2 ? first : second).add(0.0, 0.0, 0.0, 0.003);
  }
  std::vector<double> whole(6, 0.0), split(6, 0.0);
  add_force_sums(all.view(), cells, f, 9.81, whole);
  add_force_sums(first.view(), cells, f, 9.81, split);
  add_force_sums(second.view(), cells + 2, f + 6, 9.81, split);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(split[k], whole[k], 1e-15);
  // sum over cells = sum over particles of f_i / (m_i g), each axis
  const double weight = sphere_volume(0.003) * 2500.0 * 9.81;
  for (int a = 0; a < 3; ++a) {
    double over_particles = 0.0;
    for (int i = 0; i < 4; ++i) over_particles += f[3 * i + a] / weight;
    EXPECT_NEAR(whole[a] + whole[3 + a], over_particles, 1e-12 * std::abs(over_particles) + 1e-15);
  }
}

// N_c = 1 2 2 1 0 (the chain above) split over two "ranks" as {1, 2} and {2, 1, 0}.
TEST(Analysis, ContactCountsAddOverRanks) {
  const int a[] = {1, 2}, b[] = {2, 1, 0};
  ContactCounts counts = contact_counts(a, 2);
  counts.add(contact_counts(b, 3));
  EXPECT_DOUBLE_EQ(counts.bulk_coordination(), 6.0 / 5.0);
  EXPECT_DOUBLE_EQ(counts.multicontact(), 2.0 / 4.0);
  EXPECT_DOUBLE_EQ(ContactCounts().bulk_coordination(), 0.0);
  EXPECT_DOUBLE_EQ(ContactCounts().multicontact(), 0.0);
}

// Seed 001 eq. 49 limits. Segregated: the large particles (volume fraction x_L) fill the
// bottom x_L H of the column, the small ones the rest, each evenly spaced, so <h_L> = x_L H/2,
// <h_S> = (1 + x_L) H/2 and S = S_max: s = 1. Mixed: both spread over the whole column: s = 0.
TEST(Analysis, SegregationDegreeLimits) {
  const double ds = 0.0015, dl = 0.0025, height = 0.15;
  const int n_large = 300, n_small = 463;  // x_L ~ 0.75 as in seed 001's experiment
  const double vl = n_large * sphere_volume(dl), vs = n_small * sphere_volume(ds);
  const double x_large = vl / (vl + vs);
  Cloud segregated, mixed;
  for (int k = 0; k < n_large; ++k) {
    segregated.add(0.0, x_large * height * (k + 0.5) / n_large, 0.0, dl);
    mixed.add(0.0, height * (k + 0.5) / n_large, 0.0, dl);
  }
  for (int k = 0; k < n_small; ++k) {
    segregated.add(0.0, height * (x_large + (1.0 - x_large) * (k + 0.5) / n_small), 0.0, ds);
    mixed.add(0.0, height * (k + 0.5) / n_small, 0.0, ds);
  }
  const double threshold = 0.5 * (ds + dl);
  EXPECT_NEAR(segregation_degree(segregation_sums(segregated.view(), threshold, 1, 0.0)), 1.0, 1e-12);
  EXPECT_NEAR(segregation_degree(segregation_sums(mixed.view(), threshold, 1, 0.0)), 0.0, 1e-12);
  // Inverted (large on top, small below): S = <h_S>/<h_L> = (1 - x_L)/(2 - x_L) < 1, s < 0.
  Cloud inverted;
  for (int k = 0; k < n_small; ++k) inverted.add(0.0, (1.0 - x_large) * height * (k + 0.5) / n_small, 0.0, ds);
  for (int k = 0; k < n_large; ++k)
    inverted.add(0.0, height * ((1.0 - x_large) + x_large * (k + 0.5) / n_large), 0.0, dl);
  const double ratio = (1.0 - x_large) / (2.0 - x_large), ratio_max = (x_large + 1.0) / x_large;
  EXPECT_NEAR(segregation_degree(segregation_sums(inverted.view(), threshold, 1, 0.0)),
              (ratio - 1.0) / (ratio_max - 1.0), 1e-12);
  // Sums over two halves of the particles (as two ranks hold them) add up to the whole bed's.
  Cloud halves[2];
  for (std::size_t i = 0; i < segregated.diameter.size(); ++i)
    halves[i % 2].add(0.0, segregated.position[3 * i + 1], 0.0, segregated.diameter[i]);
  SegregationSums total = segregation_sums(halves[0].view(), threshold, 1, 0.0);
  const SegregationSums other = segregation_sums(halves[1].view(), threshold, 1, 0.0);
  for (int k = 0; k < SegregationSums::kComponents; ++k) total.data()[k] += other.data()[k];
  EXPECT_NEAR(segregation_degree(total), 1.0, 1e-12);
  EXPECT_THROW(segregation_degree(segregation_sums(Cloud().view(), threshold, 1, 0.0)), std::invalid_argument);
}

// Two equal particles moving at +u and -u in one cell: v_sm = 0, theta = u^2 / 3 (seed 000 eq. 6).
TEST(Analysis, GranularTemperatureOfOpposedPair) {
  Cloud c;
  c.add(0.002, 0.002, 0.0, 0.002, 0.3);
  c.add(0.006, 0.002, 0.0, 0.002, -0.3);
  c.add(0.015, 0.002, 0.0, 0.002, 0.7);  // alone in cell 1: theta = 0
  const int cells[] = {0, 0, 1};
  const CellWeights w = centroid_weights(cells, 3);
  const auto theta = granular_temperature(w, c.view(), 2);
  EXPECT_NEAR(theta[0], 0.09 / 3.0, 1e-15);
  EXPECT_NEAR(theta[1], 0.0, 1e-15);
}

// Split over two ranks, the summed moments give the one-rank theta: by hand, cell 0 holds
// +0.3, -0.3 and +0.6 m/s (x) of equal spheres: v_sm = 0.2, <|v|^2> = (0.09 + 0.09 + 0.36) / 3
// = 0.18, theta = (0.18 - 0.04) / 3; a second size weighs by volume (8x at twice d).
TEST(Analysis, GranularTemperatureFromMomentsOfRanks) {
  Cloud first, second;
  first.add(0.002, 0.002, 0.0, 0.002, 0.3);
  first.add(0.004, 0.002, 0.0, 0.002, -0.3);
  second.add(0.006, 0.002, 0.0, 0.002, 0.6);
  const int first_cells[] = {0, 0}, second_cells[] = {0};
  std::vector<double> moments(kVelocityMoments * 2, 0.0);
  add_velocity_moments(centroid_weights(first_cells, 2), first.view(), moments);
  add_velocity_moments(centroid_weights(second_cells, 1), second.view(), moments);
  const std::vector<double> theta = granular_temperature(moments);
  EXPECT_NEAR(theta[0], (0.18 - 0.04) / 3.0, 1e-15);
  EXPECT_EQ(theta[1], 0.0);  // empty
  Cloud mixed;  // d and 2d at +u and -u: v_sm = (u - 8u) / 9, <|v|^2> = u^2
  mixed.add(0.002, 0.002, 0.0, 0.002, 0.5);
  mixed.add(0.006, 0.002, 0.0, 0.004, -0.5);
  const int mixed_cells[] = {0, 0};
  EXPECT_NEAR(granular_temperature(centroid_weights(mixed_cells, 2), mixed.view(), 1)[0],
              (0.25 - std::pow(0.5 * 7.0 / 9.0, 2)) / 3.0, 1e-15);
}

TEST(Analysis, TimeAverageWeightsByDuration) {
  TimeAverage avg;
  EXPECT_THROW(avg.mean(), std::logic_error);
  avg.add({1.0, 2.0}, 0.1);
  avg.add({3.0, 2.0}, 0.3);
  EXPECT_NEAR(avg.mean()[0], (0.1 + 0.9) / 0.4, 1e-15);
  EXPECT_NEAR(avg.mean()[1], 2.0, 1e-15);
  EXPECT_THROW(avg.add({1.0}, 0.1), std::invalid_argument);
}

}  // namespace
