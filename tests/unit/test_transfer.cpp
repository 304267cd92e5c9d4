// Interphase momentum transfer: seed 000 eq. 28-29 and 33-35; Newton's third law.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tfdem/transfer.h"

namespace {

using namespace tfdem;

const drag::Gas kAir{1.2, 1.8e-5};

struct Bed {
  CartesianGrid grid;
  std::vector<double> position, velocity, diameter, density;
  std::vector<double> cell_velocity, cell_volume;
  ParticleView view() const {
    return {diameter.size(), position.data(), velocity.data(), diameter.data(), density.data()};
  }
};

// A 2-D bed of 6 x 8 cells (1 cm, depth 2.5 mm) holding particles on a jittered lattice, with a
// gas velocity field varying in space and particle velocities either per cell or per particle;
// diameters 2.5 mm, or 2.25-2.75 mm when polydisperse.
Bed make_bed(bool same_velocity_per_cell, unsigned seed, bool polydisperse = true) {
  Bed b;
  b.grid.origin = {0, 0, 0};
  b.grid.spacing = {0.01, 0.01, 0.0025};
  b.grid.count = {6, 8, 1};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double x = 0.0015; x < 0.06; x += 0.003)
    for (double y = 0.0015; y < 0.05; y += 0.003) {
      b.position.insert(b.position.end(), {x + 2e-4 * u(rng), y + 2e-4 * u(rng), 0.00125});
      b.diameter.push_back(0.0025 * (1.0 + (polydisperse ? 0.1 * u(rng) : 0.0)));
      b.density.push_back(2526.0);
    }
  for (std::size_t i = 0; i < b.diameter.size(); ++i) {
    const int c = b.grid.locate(&b.position[3 * i]);
    const double vx = same_velocity_per_cell ? 0.01 * (c % 7) : 0.05 * u(rng);
    const double vy = same_velocity_per_cell ? -0.02 * (c % 5) : 0.05 * u(rng);
    b.velocity.insert(b.velocity.end(), {vx, vy, 0.0});
  }
  for (int c = 0; c < b.grid.cell_count(); ++c)
    b.cell_velocity.insert(b.cell_velocity.end(), {0.1 + 0.01 * (c % 3), 1.5 + 0.05 * (c % 4), 0.0});
  b.cell_volume = cell_volumes(b.grid, true, 0.0025);
  return b;
}

struct Mapped {
  CellWeights weights;
  VoidFraction fraction;
  std::vector<double> gas_velocity_at_particles, gas_fraction_at_particles;
};

Mapped map(const Bed &b, VoidFractionMethod method) {
  VoidFractionOptions o;
  o.method = method;
  o.two_dimensional = true;
  Mapped m;
  m.weights = compute_weights(b.grid, b.view(), o);
  m.fraction = map_void_fraction(m.weights, b.view(), b.cell_volume, 0.0);
  m.gas_velocity_at_particles = average_to_particles(m.weights, b.cell_velocity.data(), 3);
  m.gas_fraction_at_particles = average_to_particles(m.weights, m.fraction.void_fraction.data(), 1);
  return m;
}

// Centroid mapping of a 3-D bed.
Mapped map3d(const Bed &b) {
  Mapped m;
  m.weights = compute_weights(b.grid, b.view(), VoidFractionOptions{});
  m.fraction = map_void_fraction(m.weights, b.view(), b.cell_volume, 0.0);
  m.gas_velocity_at_particles = average_to_particles(m.weights, b.cell_velocity.data(), 3);
  m.gas_fraction_at_particles = average_to_particles(m.weights, m.fraction.void_fraction.data(), 1);
  return m;
}

TransferResult run(const Bed &b, const Mapped &m, TransferMethod method, const double *grad_p = nullptr,
                   drag::Polydispersity polydispersity = drag::Polydispersity::OwnDiameter,
                   drag::Law law = drag::Law::Beetstra) {
  const CellGas cells{static_cast<std::size_t>(b.grid.cell_count()), b.cell_velocity.data(),
                      m.fraction.void_fraction.data(), b.cell_volume.data()};
  const GasAtParticles at{m.gas_velocity_at_particles.data(), m.gas_fraction_at_particles.data(), grad_p, nullptr};
  TransferOptions o;
  o.method = method;
  o.polydispersity = polydispersity;
  o.law = law;
  o.gas = kAir;
  return transfer(m.weights, b.view(), cells, at, o);
}

double relative_imbalance(const TransferResult &r) {
  return std::sqrt(r.momentum_imbalance[0] * r.momentum_imbalance[0] +
                   r.momentum_imbalance[1] * r.momentum_imbalance[1] +
                   r.momentum_imbalance[2] * r.momentum_imbalance[2]) / r.drag_magnitude_sum;
}

// When all particles of a cell move together (one diameter, centroid mapping, gas velocity of
// the cell at the particle), eq. 29 and eq. 33-35 give each particle the same drag.
TEST(Transfer, AveragedEqualsPerParticleWhenCellParticlesMoveTogether) {
  const Bed b = make_bed(true, 1, false);
  const Mapped m = map(b, VoidFractionMethod::Centroid);
  const TransferResult averaged = run(b, m, TransferMethod::Averaged);
  const TransferResult per_particle = run(b, m, TransferMethod::PerParticle);
  for (std::size_t k = 0; k < averaged.particle_drag.size(); ++k)
    EXPECT_NEAR(per_particle.particle_drag[k], averaged.particle_drag[k], 1e-12 * averaged.drag_magnitude_sum / b.diameter.size());
  EXPECT_LT(relative_imbalance(per_particle), 1e-12);
}

// Newton's third law to 1e-12 relative: the gas loses exactly the particles' drag, for the
// averaged and the conservative per-particle methods, with every mapping method.
TEST(Transfer, ConservativeMethodsBalanceMomentum) {
  const Bed b = make_bed(false, 2);
  for (auto vf : {VoidFractionMethod::Centroid, VoidFractionMethod::Divided, VoidFractionMethod::PorousCube}) {
    const Mapped m = map(b, vf);
    for (auto method : {TransferMethod::Averaged, TransferMethod::PerParticleConservative}) {
      const TransferResult r = run(b, m, method);
      EXPECT_GT(r.drag_magnitude_sum, 0.0);
      EXPECT_LT(relative_imbalance(r), 1e-12) << transfer_method_names()[static_cast<int>(method)];
    }
  }
}

// V_p of a 2.5 mm sphere: pi/6 * 1.5625e-8 = 8.18123086872342e-9 m^3.
constexpr double kVp = 8.18123086872342e-9;

// Two cells by hand (centroid mapping, 2.5 mm spheres, Ergun): cell 0 (volume 8 V_p) holds
// particles 1 and 2 at rest and rising at 0.4 m/s under gas at (0, 1, 0) m/s; cell 1 (4 V_p)
// holds particle 3 rising at 0.6 m/s under gas at (0.3, 1, 0) m/s. The cell volumes are set for
// eps_g = 0.75 in both (the grid's 4 mm cubes only locate the particles), so Ergun (seed 000
// eq. 30) gives beta/eps_s = 150 * 0.25 * 1.8e-5 / (0.75 * 6.25e-6) + 1.75 * 1.2 / 2.5e-3 |s|
// = 144 + 840 |s| kg/m^3/s at slip s.
Bed two_cell_bed() {
  Bed b;
  b.grid.origin = {0, 0, 0};
  b.grid.spacing = {0.004, 0.004, 0.004};
  b.grid.count = {2, 1, 1};
  b.position = {0.00125, 0.00125, 0.00125, 0.00275, 0.00275, 0.00275, 0.006, 0.002, 0.002};
  b.velocity = {0.0, 0.0, 0.0, 0.0, 0.4, 0.0, 0.0, 0.6, 0.0};
  b.diameter = {0.0025, 0.0025, 0.0025};
  b.density = {2526.0, 2526.0, 2526.0};
  b.cell_velocity = {0.0, 1.0, 0.0, 0.3, 1.0, 0.0};
  b.cell_volume = {8.0 * kVp, 4.0 * kVp};
  return b;
}

// Per-particle drag of two_cell_bed by hand (eq. 29, f = V_p (144 + 840 |s|) s): slips 1, 0.6
// and (0.3, 0.4) m/s give (144 + 840) * 1 = 984 V_p, (144 + 504) * 0.6 = 388.8 V_p and
// (144 + 420) * (0.3, 0.4) = (169.2, 225.6) V_p, sum of magnitudes 984 + 388.8 + 282 = 1654.8 V_p.
void expect_two_cell_particle_drag(const TransferResult &r) {
  const double expected[9] = {0.0, 984.0 * kVp, 0.0, 0.0, 388.8 * kVp, 0.0, 169.2 * kVp, 225.6 * kVp, 0.0};
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(r.particle_drag[k], expected[k], 1e-12 * 984.0 * kVp) << k;
  EXPECT_NEAR(r.drag_magnitude_sum, 1654.8 * kVp, 1e-12 * 1654.8 * kVp);
}

// The paper's method 2 is not conservative when particles of a cell move differently; its
// imbalance by hand on two_cell_bed. The gas side is eq. 33-35: cell 0's solids move at v_sm =
// (0, 0.2, 0), slip 0.8, beta = 0.25 * (144 + 672) = 204, sink 8 V_p * 204 * 0.8 = 1305.6 V_p;
// cell 1: v_sm = (0, 0.6, 0), beta = 0.25 * 564 = 141, sink 4 V_p * 141 * (0.3, 0.4) =
// (169.2, 225.6) V_p, its particle's drag. Imbalance = particles' drag - sink = (0, 984 + 388.8
// - 1305.6, 0) V_p = (0, 67.2, 0) V_p = (0, 5.497787e-7, 0) N (the viscous parts cancel: 840 *
// (1^2 + 0.6^2 - 2 * 0.8^2) = 840 * 0.08 = 67.2), 4.06 % of the drag magnitude sum.
TEST(Transfer, PaperPerParticleImbalanceOfTwoCellsByHand) {
  const Bed b = two_cell_bed();
  const TransferResult r =
      run(b, map3d(b), TransferMethod::PerParticle, nullptr, drag::Polydispersity::OwnDiameter, drag::Law::ErgunWenYu);
  expect_two_cell_particle_drag(r);
  EXPECT_NEAR(r.cell_exchange_coefficient[0], 204.0, 1e-12 * 204.0);
  EXPECT_NEAR(r.cell_exchange_coefficient[1], 141.0, 1e-12 * 141.0);
  const double solid_velocity[6] = {0.0, 0.2, 0.0, 0.0, 0.6, 0.0};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(r.cell_solid_velocity[k], solid_velocity[k], 1e-14) << k;
  EXPECT_NEAR(r.momentum_imbalance[0], 0.0, 1e-14 * r.drag_magnitude_sum);
  EXPECT_NEAR(r.momentum_imbalance[1], 67.2 * kVp, 1e-12 * 67.2 * kVp);
  EXPECT_NEAR(r.momentum_imbalance[2], 0.0, 1e-14 * r.drag_magnitude_sum);
  EXPECT_NEAR(relative_imbalance(r), 67.2 / 1654.8, 1e-12);
}

// The conservative method on two_cell_bed: each cell's gas sink V_c K_c (u_c - U_s,c) equals
// its particles' drag by hand, (0, 984 + 388.8, 0) V_p = (0, 1372.8, 0) V_p in cell 0 and
// (169.2, 225.6, 0) V_p in cell 1, so the imbalance is zero to round-off. K_c = sum_i V_i
// beta_i/eps_s,i / V_c: cell 0 (984 + 648) V_p / 8 V_p = 204, cell 1 564 / 4 = 141 kg/m^3/s;
// U_s,c = u_c - drag / (V_c K_c): cell 0 1 - 1372.8 / 1632 = 0.1588235 (2.7/17), cell 1
// (0.3, 1) - (169.2, 225.6) / 564 = (0, 0.6) m/s, the particle's velocity.
TEST(Transfer, ConservativeGasSinkPerCellOfTwoCellsByHand) {
  const Bed b = two_cell_bed();
  const TransferResult r = run(b, map3d(b), TransferMethod::PerParticleConservative, nullptr,
                               drag::Polydispersity::OwnDiameter, drag::Law::ErgunWenYu);
  expect_two_cell_particle_drag(r);
  EXPECT_NEAR(r.cell_exchange_coefficient[0], 204.0, 1e-12 * 204.0);
  EXPECT_NEAR(r.cell_exchange_coefficient[1], 141.0, 1e-12 * 141.0);
  const double solid_velocity[6] = {0.0, 2.7 / 17.0, 0.0, 0.0, 0.6, 0.0};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(r.cell_solid_velocity[k], solid_velocity[k], 1e-14) << k;
  const double sink[6] = {0.0, 1372.8 * kVp, 0.0, 169.2 * kVp, 225.6 * kVp, 0.0};
  for (int c = 0; c < 2; ++c)
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(b.cell_volume[c] * r.cell_exchange_coefficient[c] *
                      (b.cell_velocity[3 * c + a] - r.cell_solid_velocity[3 * c + a]),
                  sink[3 * c + a], 1e-12 * 1372.8 * kVp)
          << "cell " << c << " component " << a;
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(r.momentum_imbalance[a], 0.0, 1e-14 * r.drag_magnitude_sum) << a;
}

// Averaged gas side: K_c = beta(eps_c, Sauter d, |u_c - v_sm|), U_s = v_sm of eq. 35.
TEST(Transfer, AveragedGasSideUsesEquation35MeanVelocity) {
  Bed b;
  b.grid.origin = {0, 0, 0};
  b.grid.spacing = {0.01, 0.01, 0.01};
  b.grid.count = {1, 1, 1};
  b.position = {0.003, 0.003, 0.005, 0.007, 0.007, 0.005};
  b.velocity = {0.1, 0.0, 0.0, -0.2, 0.3, 0.0};
  b.diameter = {0.002, 0.004};
  b.density = {2500.0, 2500.0};
  b.cell_velocity = {1.0, 2.0, 0.0};
  b.cell_volume = {1e-6};
  const Mapped m = map(b, VoidFractionMethod::Centroid);
  const TransferResult r = run(b, m, TransferMethod::Averaged);
  const double v1 = sphere_volume(0.002), v2 = sphere_volume(0.004);
  const double vx = (v1 * 0.1 - v2 * 0.2) / (v1 + v2), vy = v2 * 0.3 / (v1 + v2);
  EXPECT_NEAR(r.cell_solid_velocity[0], vx, 1e-15);
  EXPECT_NEAR(r.cell_solid_velocity[1], vy, 1e-15);
  const double eps = 1.0 - (v1 + v2) / 1e-6;
  const double sauter = (8e-9 + 64e-9) / (4e-6 + 16e-6);
  const double slip = std::hypot(1.0 - vx, 2.0 - vy);
  // Beetstra et al. (2007) written out in their normalisation: beta = 18 mu eps eps_s F / d^2
  const double es = 1.0 - eps, re = eps * kAir.density * slip * sauter / kAir.viscosity;
  const double f = 10.0 * es / (eps * eps) + eps * eps * (1.0 + 1.5 * std::sqrt(es)) +
                   0.413 * re / (24.0 * eps * eps) * (1.0 / eps + 3.0 * eps * es + 8.4 * std::pow(re, -0.343)) /
                       (1.0 + std::pow(10.0, 3.0 * es) * std::pow(re, -(1.0 + 4.0 * es) / 2.0));
  const double beetstra = 18.0 * kAir.viscosity * eps * es * f / (sauter * sauter);
  EXPECT_NEAR(r.cell_exchange_coefficient[0], beetstra, 1e-12 * beetstra);
  // each particle gets the same drag per unit volume
  EXPECT_NEAR(r.particle_drag[0] / v1, r.particle_drag[3] / v2, 1e-9 * std::abs(r.particle_drag[3] / v2));
}

// Eq. 28: the fluid force adds -V_p grad p to the drag.
TEST(Transfer, FluidForceAddsPressureGradientForce) {
  const Bed b = make_bed(false, 4);
  const Mapped m = map(b, VoidFractionMethod::PorousCube);
  std::vector<double> grad_p;
  for (std::size_t i = 0; i < b.diameter.size(); ++i) grad_p.insert(grad_p.end(), {100.0, -15000.0, 0.0});
  const TransferResult r = run(b, m, TransferMethod::PerParticle, grad_p.data());
  for (std::size_t i = 0; i < b.diameter.size(); ++i) {
    const double v = sphere_volume(b.diameter[i]);
    EXPECT_NEAR(r.particle_force[3 * i + 0] - r.particle_drag[3 * i + 0], -v * 100.0, 1e-15);
    EXPECT_NEAR(r.particle_force[3 * i + 1] - r.particle_drag[3 * i + 1], v * 15000.0, 1e-15);
  }
}

// A lone particle (eps -> 1) in still gas with the paper's law: eq. 29 with C_D of eq. 31,
// f = V_p (3/4) C_D eps_g rho |u - v| / d eps_g^-2.7 (u - v).
TEST(Transfer, LoneParticleDragFollowsEquation29) {
  Bed b;
  b.grid.origin = {0, 0, 0};
  b.grid.spacing = {0.1, 0.1, 0.1};
  b.grid.count = {1, 1, 1};
  b.position = {0.05, 0.05, 0.05};
  b.velocity = {0.0, -0.5, 0.0};
  b.diameter = {0.003};
  b.density = {2500.0};
  b.cell_velocity = {0.0, 0.0, 0.0};
  b.cell_volume = {1e-3};
  const Mapped m = map(b, VoidFractionMethod::Centroid);
  const CellGas cells{1, b.cell_velocity.data(), m.fraction.void_fraction.data(), b.cell_volume.data()};
  const GasAtParticles at{m.gas_velocity_at_particles.data(), m.gas_fraction_at_particles.data(), nullptr, nullptr};
  TransferOptions o;
  o.method = TransferMethod::PerParticle;
  o.law = drag::Law::ErgunWenYu;
  o.gas = kAir;
  const TransferResult r = transfer(m.weights, b.view(), cells, at, o);
  const double eps = 1.0 - sphere_volume(0.003) / 1e-3;
  const double re = eps * 1.2 * 0.5 * 0.003 / 1.8e-5;
  const double cd = 24.0 * (1.0 + 0.15 * std::pow(re, 0.687)) / re;
  const double expected = sphere_volume(0.003) * 0.75 * cd * eps * 1.2 * 0.5 / 0.003 * std::pow(eps, -2.7) * 0.5;
  EXPECT_NEAR(r.particle_drag[1], expected, 1e-12 * expected);
  EXPECT_EQ(r.particle_drag[0], 0.0);
}

// Beetstra et al.'s (2007) polydisperse drag reduces to the monodisperse law for equal sizes.
TEST(Transfer, PolydisperseDragReducesToMonodisperseForEqualSizes) {
  const Bed b = make_bed(false, 5, false);
  for (auto vf : {VoidFractionMethod::Centroid, VoidFractionMethod::PorousCube}) {
    const Mapped m = map(b, vf);
    for (auto method : {TransferMethod::PerParticle, TransferMethod::PerParticleConservative}) {
      const TransferResult own = run(b, m, method);
      const TransferResult poly = run(b, m, method, nullptr, drag::Polydispersity::Beetstra2007);
      for (std::size_t k = 0; k < own.particle_drag.size(); ++k)
        EXPECT_NEAR(poly.particle_drag[k], own.particle_drag[k], 1e-12 * std::abs(own.particle_drag[k]) + 1e-30);
    }
  }
}

// A binary cell by hand: one 1.5 mm and one 2.5 mm particle at rest in a 3.5 mm cube, gas at
// 1.2 m/s upward, Ergun (dense branch, seed 000 eq. 30) at the Sauter mean <d>, times
// (eps y + eps_s y^2 + 0.064 eps y^3) / ((1 + 0.064 eps) y^2), y = d/<d> (Beetstra et al. 2007).
TEST(Transfer, PolydisperseDragOfABinaryCellByHand) {
  Bed b;
  b.grid.origin = {0, 0, 0};
  b.grid.spacing = {0.0035, 0.0035, 0.0035};
  b.grid.count = {1, 1, 1};
  b.position = {0.001, 0.001, 0.001, 0.0022, 0.0022, 0.0022};
  b.velocity = {0, 0, 0, 0, 0, 0};
  b.diameter = {0.0015, 0.0025};
  b.density = {2500.0, 2500.0};
  b.cell_velocity = {0.0, 1.2, 0.0};
  b.cell_volume = {0.0035 * 0.0035 * 0.0035};
  const Mapped m = map3d(b);
  const double pi = std::acos(-1.0);
  const double v1 = pi / 6 * 3.375e-9, v2 = pi / 6 * 15.625e-9;
  const double eps = 1.0 - (v1 + v2) / 4.2875e-8, es = 1.0 - eps;
  ASSERT_LT(eps, 0.8);  // Ergun's branch
  const double sauter = (3.375e-9 + 15.625e-9) / (2.25e-6 + 6.25e-6);
  const double ergun = 150.0 * es * 1.8e-5 / (eps * sauter * sauter) + 1.75 * 1.2 * 1.2 / sauter;  // beta/eps_s
  const double y1 = 0.0015 / sauter, y2 = 0.0025 / sauter;
  const double f1 = (eps * y1 + es * y1 * y1 + 0.064 * eps * y1 * y1 * y1) / ((1 + 0.064 * eps) * y1 * y1);
  const double f2 = (eps * y2 + es * y2 * y2 + 0.064 * eps * y2 * y2 * y2) / ((1 + 0.064 * eps) * y2 * y2);
  for (auto method : {TransferMethod::PerParticle, TransferMethod::PerParticleConservative}) {
    const TransferResult r = run(b, m, method, nullptr, drag::Polydispersity::Beetstra2007, drag::Law::ErgunWenYu);
    EXPECT_NEAR(r.particle_drag[1], v1 * ergun * f1 * 1.2, 1e-12 * v1 * ergun * f1 * 1.2);
    EXPECT_NEAR(r.particle_drag[4], v2 * ergun * f2 * 1.2, 1e-12 * v2 * ergun * f2 * 1.2);
    EXPECT_EQ(r.particle_drag[0], 0.0);
  }
  // The conservative gas sink is minus the sum of these two drags.
  const TransferResult r = run(b, m, TransferMethod::PerParticleConservative, nullptr,
                               drag::Polydispersity::Beetstra2007, drag::Law::ErgunWenYu);
  const double sink = b.cell_volume[0] * r.cell_exchange_coefficient[0] * (1.2 - r.cell_solid_velocity[1]);
  EXPECT_NEAR(sink, (v1 * f1 + v2 * f2) * ergun * 1.2, 1e-12 * sink);
}

// Newton's third law for a mixture under polydisperse drag with every mapping method.
TEST(Transfer, PolydisperseConservativeTransferBalancesMomentum) {
  const Bed b = make_bed(false, 6);
  for (auto vf : {VoidFractionMethod::Centroid, VoidFractionMethod::Divided, VoidFractionMethod::PorousCube}) {
    const TransferResult r = run(b, map(b, vf), TransferMethod::PerParticleConservative, nullptr,
                                 drag::Polydispersity::Beetstra2007);
    EXPECT_GT(r.drag_magnitude_sum, 0.0);
    EXPECT_LT(relative_imbalance(r), 1e-12);
  }
}

TEST(Transfer, MethodNames) {
  EXPECT_EQ(transfer_method_from_name("per_particle_conservative"), TransferMethod::PerParticleConservative);
  EXPECT_THROW(transfer_method_from_name("avg"), std::invalid_argument);
}

}  // namespace
