// The core across MPI ranks (cell_exchange, distributed_coupling): run at 1 and 2 ranks, it
// must give what the serial core gives for all particles on one rank, with particles split
// between ranks one way (by x) and cells the other way (by y), so most particles sit in cells
// another rank owns; or with every cell on every rank (the gas solved whole on each rank).
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <random>

#include "tfdem/cell_exchange.h"
#include "tfdem/distributed_coupling.h"

namespace {

using namespace tfdem;

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int ranks() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// Relative difference scaled by `scale`.
double relative(double a, double b, double scale) { return std::abs(a - b) / scale; }

TEST(CellExchange, SumsAtOwnersAndFetchesBack) {
  const int cells = 50;
  std::vector<int> owner(cells), owned;
  for (int g = 0; g < cells; ++g) owner[g] = (7 * g) % ranks();
  for (int g = 0; g < cells; ++g)
    if (owner[g] == rank()) owned.push_back(g);
  CellExchange exchange(MPI_COMM_WORLD, owner, owned);
  // Every rank touches every third cell, from a rank-dependent start, in descending order.
  std::vector<int> halo;
  for (int g = cells - 1 - rank(); g >= 0; g -= 3) halo.push_back(g);
  exchange.set_halo(halo);
  std::vector<double> values;
  for (int g : halo) values.insert(values.end(), {1.0 * g, 1000.0 + rank()});
  std::vector<double> sums;
  exchange.sum_to_owners(values, 2, sums);
  ASSERT_EQ(sums.size(), 2 * owned.size());
  for (std::size_t l = 0; l < owned.size(); ++l) {
    const int g = owned[l];
    double expected_first = 0.0, expected_second = 0.0;
    for (int r = 0; r < ranks(); ++r)
      if ((cells - 1 - r - g) % 3 == 0 && g <= cells - 1 - r) {
        expected_first += g;
        expected_second += 1000.0 + r;
      }
    EXPECT_EQ(sums[2 * l], expected_first) << "cell " << g;
    EXPECT_EQ(sums[2 * l + 1], expected_second) << "cell " << g;
  }
  std::vector<double> owned_values;
  for (int g : owned) owned_values.push_back(0.5 * g);
  std::vector<double> fetched;
  exchange.fetch_from_owners(owned_values, 1, fetched);
  ASSERT_EQ(fetched.size(), halo.size());
  for (std::size_t h = 0; h < halo.size(); ++h) EXPECT_EQ(fetched[h], 0.5 * halo[h]);

  // What went to other ranks, counted from the halos: set_halo sends each halo cell another
  // rank owns as an int, sum_to_owners its 2 values; fetch_from_owners sends back 1 value for
  // each of my cells in another rank's halo. One message per destination and exchange.
  double sent_to_owners = 0, sent_back = 0;
  std::vector<bool> owners_written(ranks(), false), askers(ranks(), false);
  for (int g : halo)
    if (owner[g] != rank()) {
      ++sent_to_owners;
      owners_written[owner[g]] = true;
    }
  for (int r = 0; r < ranks(); ++r)
    for (int g = cells - 1 - r; r != rank() && g >= 0; g -= 3)
      if (owner[g] == rank()) {
        ++sent_back;
        askers[r] = true;
      }
  const double destinations = std::count(owners_written.begin(), owners_written.end(), true);
  const double sources = std::count(askers.begin(), askers.end(), true);
  EXPECT_EQ(exchange.bytes_sent(), sent_to_owners * (4 + 2 * 8) + sent_back * 8);
  EXPECT_EQ(exchange.messages_sent(), 2 * destinations + sources);
  if (ranks() > 1) EXPECT_GT(exchange.bytes_sent(), 0.0);
}

// Every rank holds every cell (in reversed local order): each rank gets the sum over all
// ranks' halos, the same bits on every rank, and fetching returns its own values.
TEST(CellExchange, EveryRankHoldsTheSumsOfEveryCell) {
  const int cells = 50;
  std::vector<int> owner(cells, CellExchange::kEveryRank), owned;
  for (int g = cells - 1; g >= 0; --g) owned.push_back(g);
  CellExchange exchange(MPI_COMM_WORLD, owner, owned);
  std::vector<int> halo;
  for (int g = cells - 1 - rank(); g >= 0; g -= 3) halo.push_back(g);
  exchange.set_halo(halo);
  EXPECT_EQ(exchange.remote_records(), 0u);
  std::vector<double> values;
  for (int g : halo) values.insert(values.end(), {0.1 * g, 1000.0 + rank()});
  std::vector<double> sums;
  exchange.sum_to_owners(values, 2, sums);
  ASSERT_EQ(sums.size(), 2u * cells);
  for (std::size_t l = 0; l < owned.size(); ++l) {
    const int g = owned[l];
    double expected_first = 0.0, expected_second = 0.0;
    for (int r = 0; r < ranks(); ++r)
      if ((cells - 1 - r - g) % 3 == 0 && g <= cells - 1 - r) {
        expected_first += 0.1 * g;
        expected_second += 1000.0 + r;
      }
    EXPECT_NEAR(sums[2 * l], expected_first, 1e-13) << "cell " << g;
    EXPECT_EQ(sums[2 * l + 1], expected_second) << "cell " << g;
  }
  std::vector<double> first_rank = sums;
  MPI_Bcast(first_rank.data(), static_cast<int>(first_rank.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  for (std::size_t k = 0; k < sums.size(); ++k) EXPECT_EQ(sums[k], first_rank[k]) << "value " << k;
  std::vector<double> owned_values;
  for (int g : owned) owned_values.push_back(0.5 * g + rank());
  std::vector<double> fetched;
  exchange.fetch_from_owners(owned_values, 1, fetched);
  ASSERT_EQ(fetched.size(), halo.size());
  for (std::size_t h = 0; h < halo.size(); ++h) EXPECT_EQ(fetched[h], 0.5 * halo[h] + rank());
  // One sum of every cell's 2 values: each rank's share of the reduction (rank 0: the
  // broadcast), 50 x 2 doubles = 800 bytes in one message; fetching is local. One rank: none.
  EXPECT_EQ(exchange.bytes_sent(), ranks() > 1 ? 800.0 : 0.0);
  EXPECT_EQ(exchange.messages_sent(), ranks() > 1 ? 1.0 : 0.0);
}

TEST(CellExchange, RefusesAMixedOrIncompleteOwnerTable) {
  std::vector<int> mixed(10, CellExchange::kEveryRank);
  mixed[3] = 0;
  std::vector<int> all(10);
  for (int g = 0; g < 10; ++g) all[g] = g;
  EXPECT_THROW(CellExchange(MPI_COMM_WORLD, mixed, all), std::invalid_argument);
  const std::vector<int> every(10, CellExchange::kEveryRank);
  EXPECT_THROW(CellExchange(MPI_COMM_WORLD, every, {0, 1, 2}), std::invalid_argument);
  EXPECT_THROW(CellExchange(MPI_COMM_WORLD, every, {0, 1, 2, 3, 4, 5, 6, 7, 8, 8}), std::invalid_argument);
}

// A 2-D bed of 6 x 8 cells (1 cm, depth 2.5 mm), particles on a jittered lattice with random
// velocities and diameters 2.25-2.75 mm, some overlapping the walls; a smooth gas field.
struct Bed {
  CartesianGrid grid;
  std::vector<double> position, velocity, diameter, density, cell_velocity, cell_gradient, cell_volume;
  Bed() {
    grid.origin = {0, 0, 0};
    grid.spacing = {0.01, 0.01, 0.0025};
    grid.count = {6, 8, 1};
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (double x = 0.001; x < 0.06; x += 0.0029)
      for (double y = 0.001; y < 0.055; y += 0.0031) {
        position.insert(position.end(), {x + 2e-4 * u(rng), y + 2e-4 * u(rng), 0.00125});
        velocity.insert(velocity.end(), {0.05 * u(rng), 0.05 * u(rng), 0.0});
        diameter.push_back(0.0025 * (1.0 + 0.1 * u(rng)));
        density.push_back(2526.0);
      }
    for (int c = 0; c < grid.cell_count(); ++c) {
      cell_velocity.insert(cell_velocity.end(), {0.1 + 0.01 * (c % 3), 1.5 + 0.05 * (c % 4), 0.0});
      cell_gradient.insert(cell_gradient.end(), {10.0 * (c % 2), -9000.0 - 100.0 * (c % 5), 0.0});
    }
    cell_volume = cell_volumes(grid, true, 0.0025);
  }
  ParticleView view() const { return {diameter.size(), position.data(), velocity.data(), diameter.data(), density.data()}; }
};

struct Case {
  VoidFractionMethod void_fraction;
  TransferMethod transfer;
  GasAtParticle gas_velocity = GasAtParticle::Cell;
  drag::Polydispersity polydispersity = drag::Polydispersity::OwnDiameter;
  bool gas_whole_on_every_rank = false;
  bool particles_on_rank_0 = false;  // the other ranks hold none (an empty part of the box)
};

class DistributedCouplingTest : public ::testing::TestWithParam<Case> {};

// Serial reference: the core on one rank with all particles and the whole grid.
struct Reference {
  VoidFraction fraction;
  TransferResult result;
};

Reference serial(const Bed &b, const VoidFractionOptions &vf, const TransferOptions &to) {
  Reference ref;
  const CellWeights w = compute_weights(b.grid, b.view(), vf);
  ref.fraction = map_void_fraction(w, b.view(), b.cell_volume, vf.void_fraction_floor);
  std::vector<double> u_at = average_to_particles(w, b.cell_velocity.data(), 3);
  if (to.gas_velocity == GasAtParticle::Interpolated)  // trilinear from the whole grid's field
    for (std::size_t i = 0; i < b.diameter.size(); ++i)
      interpolate(b.grid, b.cell_velocity.data(), 3, &b.position[3 * i], &u_at[3 * i]);
  const std::vector<double> eps_at = average_to_particles(w, ref.fraction.void_fraction.data(), 1);
  const std::vector<double> grad_at = average_to_particles(w, b.cell_gradient.data(), 3);
  const CellGas cells{b.cell_volume.size(), b.cell_velocity.data(), ref.fraction.void_fraction.data(),
                      b.cell_volume.data()};
  transfer(w, b.view(), cells, {u_at.data(), eps_at.data(), grad_at.data(), nullptr}, to, ref.result);
  return ref;
}

// This rank's share of a bed: cells to ranks by row (y), or every cell on every rank in
// reversed order; particles to ranks by column (x).
struct Partition {
  std::vector<int> owner, owned;
  std::vector<double> volume, velocity, gradient;
  Bed mine;
  std::vector<std::size_t> index;  // each local particle's index in the whole bed
  Partition(const Bed &b, bool whole, bool on_rank_0 = false) : mine(b) {
    const int n = b.grid.cell_count();
    owner.resize(n);
    for (int k = 0; k < n; ++k) {
      const int g = whole ? n - 1 - k : k;
      owner[g] = whole ? CellExchange::kEveryRank : (g / b.grid.count[0]) * ranks() / b.grid.count[1];
      if (!whole && owner[g] != rank()) continue;
      owned.push_back(g);
      volume.push_back(b.cell_volume[g]);
      for (int a = 0; a < 3; ++a) {
        velocity.push_back(b.cell_velocity[3 * g + a]);
        gradient.push_back(b.cell_gradient[3 * g + a]);
      }
    }
    mine.position.clear(), mine.velocity.clear(), mine.diameter.clear(), mine.density.clear();
    for (std::size_t i = 0; i < b.diameter.size(); ++i) {
      const int column = on_rank_0 ? 0 : static_cast<int>(b.position[3 * i] / 0.06 * ranks());
      if (std::min(column, ranks() - 1) != rank()) continue;
      index.push_back(i);
      for (int a = 0; a < 3; ++a) {
        mine.position.push_back(b.position[3 * i + a]);
        mine.velocity.push_back(b.velocity[3 * i + a]);
      }
      mine.diameter.push_back(b.diameter[i]);
      mine.density.push_back(b.density[i]);
    }
  }
};

TEST_P(DistributedCouplingTest, EqualsSerialCore) {
  const Bed b;
  VoidFractionOptions vf;
  vf.method = GetParam().void_fraction;
  vf.two_dimensional = true;
  TransferOptions to;
  to.method = GetParam().transfer;
  to.gas_velocity = GetParam().gas_velocity;
  to.polydispersity = GetParam().polydispersity;
  to.law = drag::Law::ErgunWenYu;
  const Reference ref = serial(b, vf, to);

  const Partition part(b, GetParam().gas_whole_on_every_rank, GetParam().particles_on_rank_0);
  const bool whole = GetParam().gas_whole_on_every_rank;
  const std::vector<int> &owned = part.owned;
  const std::vector<std::size_t> &index = part.index;
  const std::vector<double> &velocity = part.velocity, &gradient = part.gradient;
  const Bed &mine = part.mine;
  DistributedCoupling coupling(MPI_COMM_WORLD, b.grid, part.owner, owned, part.volume, vf, to);
  coupling.map(mine.view());
  coupling.forces(mine.view(), velocity.data(), gradient.data());
  if (ranks() > 1 && !whole && !GetParam().particles_on_rank_0)
    EXPECT_GT(coupling.exchange().remote_records(), 0u) << "no particle in another rank's cell";

  const double eps_tolerance = 1e-13, force_tolerance = 1e-12;  // round-off of reordered sums
  for (std::size_t l = 0; l < owned.size(); ++l) {
    const int g = owned[l];
    EXPECT_NEAR(coupling.void_fraction()[l], ref.fraction.void_fraction[g], eps_tolerance) << "cell " << g;
    const double k_scale = std::max(1.0, std::abs(ref.result.cell_exchange_coefficient[g]));
    EXPECT_LT(relative(coupling.exchange_coefficient()[l], ref.result.cell_exchange_coefficient[g], k_scale), force_tolerance);
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(coupling.solid_velocity()[3 * l + a], ref.result.cell_solid_velocity[3 * g + a], 1e-12);
  }
  double force_scale = 0.0;
  for (double f : ref.result.particle_force) force_scale = std::max(force_scale, std::abs(f));
  for (std::size_t k = 0; k < index.size(); ++k)
    for (int a = 0; a < 3; ++a)
      EXPECT_LT(relative(coupling.particle_force()[3 * k + a], ref.result.particle_force[3 * index[k] + a],
                         force_scale), force_tolerance) << "particle " << index[k];

  const CouplingTotals &t = coupling.totals();
  double particle_volume = 0.0;
  for (double d : b.diameter) particle_volume += sphere_volume(d);
  EXPECT_LT(std::abs(t.particle_volume - particle_volume) / particle_volume, 1e-13);
  EXPECT_LT(std::abs(t.mapped_volume - particle_volume) / particle_volume, 1e-12);  // sum (1-eps)V = sum V_p
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(t.momentum_imbalance[a], ref.result.momentum_imbalance[a], 1e-12 * t.drag_magnitude_sum);
  if (to.method != TransferMethod::PerParticle)  // Newton's third law between the phases
    for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(t.momentum_imbalance[a]), 1e-12 * t.drag_magnitude_sum);
}

INSTANTIATE_TEST_SUITE_P(
    AllMethods, DistributedCouplingTest,
    ::testing::Values(Case{VoidFractionMethod::Centroid, TransferMethod::Averaged},
                      Case{VoidFractionMethod::Divided, TransferMethod::Averaged},
                      Case{VoidFractionMethod::PorousCube, TransferMethod::PerParticle},
                      Case{VoidFractionMethod::Divided, TransferMethod::PerParticleConservative},
                      Case{VoidFractionMethod::Centroid, TransferMethod::PerParticleConservative},
                      Case{VoidFractionMethod::Centroid, TransferMethod::PerParticle, GasAtParticle::Interpolated},
                      Case{VoidFractionMethod::PorousCube, TransferMethod::PerParticleConservative,
                           GasAtParticle::Interpolated},
                      Case{VoidFractionMethod::Divided, TransferMethod::PerParticleConservative, GasAtParticle::Cell,
                           drag::Polydispersity::Beetstra2007},
                      Case{VoidFractionMethod::Centroid, TransferMethod::Averaged, GasAtParticle::Cell,
                           drag::Polydispersity::OwnDiameter, true},
                      Case{VoidFractionMethod::PorousCube, TransferMethod::PerParticle, GasAtParticle::Interpolated,
                           drag::Polydispersity::OwnDiameter, true},
                      Case{VoidFractionMethod::Divided, TransferMethod::PerParticleConservative, GasAtParticle::Cell,
                           drag::Polydispersity::OwnDiameter, true},
                      // ranks with no particles (a pseudo-2-D bed split in y: the freeboard's
                      // ranks), polydisperse drag: their empty halo has no Sauter diameters
                      Case{VoidFractionMethod::Centroid, TransferMethod::PerParticle, GasAtParticle::Cell,
                           drag::Polydispersity::Beetstra2007, true, true},
                      Case{VoidFractionMethod::Centroid, TransferMethod::PerParticle, GasAtParticle::Cell,
                           drag::Polydispersity::Beetstra2007, false, true}));

// With a particle-field filter (a diffusion bandwidth of 1.5 cm on the 6 x 8 cm bed, the
// particle field on blocks of 2 x 2 cells, or both), cells split or whole: every rank's cells
// and particles get what one rank with the whole bed gets; that rank's gas fraction is 1 - the
// serial map's solid volume filtered by ParticleFieldFilter / V_c; the filter keeps the
// solids' volume and, conservative, Newton's third law.
class FilteredCouplingTest : public ::testing::TestWithParam<std::pair<double, std::array<int, 3>>> {};

TEST_P(FilteredCouplingTest, OnRanksEqualsOneRank) {
  const Bed b;
  VoidFractionOptions vf;
  vf.two_dimensional = true;
  vf.diffusion_bandwidth = GetParam().first;
  vf.particle_field_block = GetParam().second;
  const VoidFraction raw = map_void_fraction(compute_weights(b.grid, b.view(), vf), b.view(), b.cell_volume, 0.0);
  std::vector<double> spread_solids = raw.solid_volume, scratch;
  ParticleFieldFilter(b.grid, vf.diffusion_bandwidth, vf.particle_field_block).apply(spread_solids.data(), 1, scratch);
  const int n = b.grid.cell_count();
  std::vector<int> all(n);
  for (int g = 0; g < n; ++g) all[g] = g;
  for (const TransferMethod method : {TransferMethod::PerParticleConservative, TransferMethod::PerParticle})
    for (const bool whole : {false, true}) {
      TransferOptions to;
      to.method = method;
      DistributedCoupling one(MPI_COMM_SELF, b.grid, std::vector<int>(n, 0), all, b.cell_volume, vf, to);
      one.map(b.view());
      one.forces(b.view(), b.cell_velocity.data(), b.cell_gradient.data());
      double largest_change = 0.0;
      for (int g = 0; g < n; ++g) {
        EXPECT_NEAR(one.void_fraction()[g], 1.0 - spread_solids[g] / b.cell_volume[g], 1e-14) << "cell " << g;
        largest_change = std::max(largest_change, std::abs(one.void_fraction()[g] - raw.void_fraction[g]));
      }
      EXPECT_GT(largest_change, 0.05) << "the filter changed no cell's gas fraction";

      const Partition part(b, whole);
      DistributedCoupling coupling(MPI_COMM_WORLD, b.grid, part.owner, part.owned, part.volume, vf, to);
      coupling.map(part.mine.view());
      coupling.forces(part.mine.view(), part.velocity.data(), part.gradient.data());
      for (std::size_t l = 0; l < part.owned.size(); ++l) {
        const int g = part.owned[l];
        EXPECT_NEAR(coupling.void_fraction()[l], one.void_fraction()[g], 1e-14) << "cell " << g;
        EXPECT_LT(relative(coupling.exchange_coefficient()[l], one.exchange_coefficient()[g],
                           std::max(1.0, std::abs(one.exchange_coefficient()[g]))), 1e-12);
        for (int a = 0; a < 3; ++a)
          EXPECT_NEAR(coupling.solid_velocity()[3 * l + a], one.solid_velocity()[3 * g + a], 1e-12);
      }
      double force_scale = 0.0;
      for (double f : one.particle_force()) force_scale = std::max(force_scale, std::abs(f));
      for (std::size_t k = 0; k < part.index.size(); ++k)
        for (int a = 0; a < 3; ++a)
          EXPECT_LT(relative(coupling.particle_force()[3 * k + a], one.particle_force()[3 * part.index[k] + a],
                             force_scale), 1e-12) << "particle " << part.index[k];
      const CouplingTotals &t = coupling.totals();
      EXPECT_LT(std::abs(t.mapped_volume - t.particle_volume) / t.particle_volume, 1e-13);
      if (method == TransferMethod::PerParticleConservative)
        for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(t.momentum_imbalance[a]), 1e-12 * t.drag_magnitude_sum);
    }
}

INSTANTIATE_TEST_SUITE_P(SpreadBlockAndBoth, FilteredCouplingTest,
                         ::testing::Values(std::make_pair(0.015, std::array<int, 3>{1, 1, 1}),
                                           std::make_pair(0.0, std::array<int, 3>{2, 2, 1}),
                                           std::make_pair(0.015, std::array<int, 3>{2, 2, 1})));

// Under the 2-D rule the fluid force has no z component even where the gas data have one
// (round-off of a 2-D gas solution); in 3-D the z component is kept.
TEST(DistributedCoupling, TwoDimensionalRuleKeepsForcesInThePlane) {
  const Bed b;
  const int n = b.grid.cell_count();
  std::vector<int> owner(n), owned;
  std::vector<double> velocity, gradient;
  for (int g = 0; g < n; ++g) {
    owner[g] = g % ranks();
    if (owner[g] != rank()) continue;
    owned.push_back(g);
    velocity.insert(velocity.end(), {0.1, 1.5, 0.3});
    gradient.insert(gradient.end(), {10.0, -9000.0, 50.0});
  }
  Bed mine = b;  // every rank its share of the particles
  mine.position.clear(), mine.velocity.clear(), mine.diameter.clear(), mine.density.clear();
  for (std::size_t i = rank(); i < b.diameter.size(); i += ranks()) {
    mine.position.insert(mine.position.end(), b.position.begin() + 3 * i, b.position.begin() + 3 * i + 3);
    mine.velocity.insert(mine.velocity.end(), b.velocity.begin() + 3 * i, b.velocity.begin() + 3 * i + 3);
    mine.diameter.push_back(b.diameter[i]);
    mine.density.push_back(b.density[i]);
  }
  for (const bool two_dimensional : {true, false}) {
    VoidFractionOptions vf;
    vf.two_dimensional = two_dimensional;
    for (const TransferMethod method : {TransferMethod::Averaged, TransferMethod::PerParticleConservative}) {
      TransferOptions to;
      to.method = method;
      DistributedCoupling coupling(MPI_COMM_WORLD, b.grid, owner, owned,
                                   std::vector<double>(owned.size(), 2.5e-7), vf, to);
      coupling.map(mine.view());
      coupling.forces(mine.view(), velocity.data(), gradient.data());
      double largest_z = 0.0;
      for (std::size_t i = 2; i < coupling.particle_force().size(); i += 3)
        largest_z = std::max(largest_z, std::abs(coupling.particle_force()[i]) +
                                            std::abs(coupling.particle_drag()[i]));
      if (two_dimensional)
        EXPECT_EQ(largest_z, 0.0);
      else
        EXPECT_GT(largest_z, 0.0);
    }
  }
}

TEST(DistributedCoupling, ParticleOutsideTheGridStopsEveryRank) {
  const Bed b;
  const int n = b.grid.cell_count();
  std::vector<int> owner(n), owned;
  for (int g = 0; g < n; ++g) {
    owner[g] = g % ranks();
    if (owner[g] == rank()) owned.push_back(g);
  }
  DistributedCoupling coupling(MPI_COMM_WORLD, b.grid, owner, owned, std::vector<double>(owned.size(), 2.5e-7),
                               VoidFractionOptions{}, TransferOptions{});
  Bed mine = b;
  if (rank() == ranks() - 1) mine.position[1] = 0.2;  // particle 0 above the 8 cm grid
  try {
    coupling.map(mine.view());
    FAIL() << "no error for a particle outside the grid";
  } catch (const std::out_of_range &e) {
    EXPECT_NE(std::string(e.what()).find("particle 0"), std::string::npos) << e.what();
  }
}

}  // namespace

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int failed = RUN_ALL_TESTS();  // every rank reports; a failure on any rank fails the run
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return failed;
}
