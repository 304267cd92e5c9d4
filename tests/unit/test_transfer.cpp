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

// V of a 2 mm sphere: pi/6 * 8e-9 = 4.18879020478639e-9 m^3.
constexpr double kV2mm = 4.18879020478639e-9;

// The averaged method (seed 000 eq. 33-35, Ergun of eq. 30) on one cell by hand: a 2 mm
// particle moving at (-0.4, 0.4, 0) m/s and a 4 mm one (8 V_2mm) at (0.5, 1.3, 0) m/s under gas
// at (1, 2, 0) m/s, the cell's volume 22.5 V_2mm for eps_g = 1 - 9 / 22.5 = 0.6. Eq. 35: v_sm =
// ((-0.4, 0.4) + 8 (0.5, 1.3)) / 9 = (3.6, 10.8) / 9 = (0.4, 1.2) m/s (the number mean would be
// (0.05, 0.85)), slip (0.6, 0.8), |s| = 1 m/s; Sauter mean <d> = (8 + 64) / (4 + 16) mm = 3.6 mm.
// Ergun: beta/eps_s = 150 * 0.4 * 1.8e-5 / (0.6 * 1.296e-5) + 1.75 * 1.2 * 1 / 3.6e-3 =
// 138.8889 + 583.3333 = 722.22222 kg/m^3/s, so K_c = beta = 0.4 * 722.2222 = 288.88889. The
// cell's drag V_c K_c (0.6, 0.8) is shared by volume, V_i / (9 V_2mm) * 22.5 V_2mm * 288.8889 =
// 722.2222 V_i per unit slip: (433.33333, 577.77778) V_2mm and (3466.6667, 4622.2222) V_2mm.
TEST(Transfer, AveragedDragOfABinaryCellByHand) {
  Bed b;
  b.grid.origin = {0, 0, 0};
  b.grid.spacing = {0.01, 0.01, 0.01};
  b.grid.count = {1, 1, 1};
  b.position = {0.003, 0.003, 0.005, 0.007, 0.007, 0.005};
  b.velocity = {-0.4, 0.4, 0.0, 0.5, 1.3, 0.0};
  b.diameter = {0.002, 0.004};
  b.density = {2500.0, 2500.0};
  b.cell_velocity = {1.0, 2.0, 0.0};
  b.cell_volume = {22.5 * kV2mm};
  const TransferResult r =
      run(b, map3d(b), TransferMethod::Averaged, nullptr, drag::Polydispersity::OwnDiameter, drag::Law::ErgunWenYu);
  const double solid_velocity[3] = {0.4, 1.2, 0.0};
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(r.cell_solid_velocity[a], solid_velocity[a], 1e-14) << a;
  EXPECT_NEAR(r.cell_exchange_coefficient[0], 288.88889, 1e-6 * 288.88889);
  const double expected[6] = {433.33333 * kV2mm, 577.77778 * kV2mm, 0.0, 3466.6667 * kV2mm, 4622.2222 * kV2mm, 0.0};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(r.particle_drag[k], expected[k], 1e-6 * 433.33333 * kV2mm) << k;
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

// V_p of a 3 mm sphere: pi/6 * 2.7e-8 = 1.41371669411541e-8 m^3.
constexpr double kV3mm = 1.41371669411541e-8;

// A lone 3 mm particle falling at 0.5 m/s through still gas in a cell of 100 V_p (eps_g = 0.99,
// Wen-Yu's branch of seed 000 eq. 30), its drag of eq. 29 by hand: Re = 0.99 * 1.2 * 0.5 * 3e-3
// / 1.8e-5 = 99, 99^0.687 = exp(0.687 * 4.595120) = 23.49640, eq. 31: C_D = 24 (1 + 0.15 *
// 23.49640) / 99 = 24 * 4.524460 / 99 = 1.096839; 3/4 C_D eps_g rho |s| / d = 148.5 * 1.096839 =
// 162.8806, eps_g^-2.7 = exp(2.7 * 0.01005034) = 1.027507, beta/eps_s = 162.8806 * 1.027507 =
// 167.36100 kg/m^3/s; drag V_p * 167.3610 * 0.5 = 83.680501 V_p = 1.183005e-6 N upward. The gas
// side (eq. 33 with the cell's one particle, v_sm = v) has K_c = eps_s beta/eps_s = 0.01 *
// 167.3610 = 1.6736100 kg/m^3/s.
TEST(Transfer, LoneParticleWenYuDragByHand) {
  Bed b;
  b.grid.origin = {0, 0, 0};
  b.grid.spacing = {0.1, 0.1, 0.1};
  b.grid.count = {1, 1, 1};
  b.position = {0.05, 0.05, 0.05};
  b.velocity = {0.0, -0.5, 0.0};
  b.diameter = {0.003};
  b.density = {2500.0};
  b.cell_velocity = {0.0, 0.0, 0.0};
  b.cell_volume = {100.0 * kV3mm};
  const TransferResult r = run(b, map3d(b), TransferMethod::PerParticle, nullptr, drag::Polydispersity::OwnDiameter,
                               drag::Law::ErgunWenYu);
  EXPECT_NEAR(r.particle_drag[1], 83.680501 * kV3mm, 1e-6 * 83.680501 * kV3mm);
  EXPECT_EQ(r.particle_drag[0], 0.0);
  EXPECT_EQ(r.particle_drag[2], 0.0);
  EXPECT_NEAR(r.cell_exchange_coefficient[0], 1.6736100, 1e-6 * 1.6736100);
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

// V of a 1 mm sphere: pi/6 * 1e-9 = 5.23598775598299e-10 m^3.
constexpr double kV1mm = 5.23598775598299e-10;

// A binary cell by hand (Beetstra et al. 2007, drag.h): a 1 mm and a 2 mm particle (V_1mm and
// 8 V_1mm) at rest under gas at 1.2 m/s upward, the cell's volume 30 V_1mm for eps_g = 1 - 9 /
// 30 = 0.7 (Ergun's branch, seed 000 eq. 30). Ergun at the Sauter mean <d> = (1 + 8) / (1 + 4)
// mm = 1.8 mm: beta/eps_s = 150 * 0.3 * 1.8e-5 / (0.7 * 3.24e-6) + 1.75 * 1.2 * 1.2 / 1.8e-3 =
// 357.1429 + 1400 = 1757.143 kg/m^3/s, times (eps y + eps_s y^2 + 0.064 eps y^3) / ((1 + 0.064
// eps) y^2) at y = d/<d>: y = 5/9, (0.3888889 + 0.09259259 + 0.007681756) / (1.0448 *
// 0.3086420) = 0.4891632 / 0.3224691 = 1.516930; y = 10/9, (0.7777778 + 0.3703704 + 0.06145405)
// / (1.0448 * 1.234568) = 1.209602 / 1.289877 = 0.9377659. Drag 1757.143 * 1.516930 * 1.2 =
// 3198.5561 V_1mm and 8 * 1757.143 * 0.9377659 * 1.2 = 15818.771 V_1mm upward, with either
// per-particle method. Conservative gas side: K_c = 1757.143 * (1.516930 + 8 * 0.9377659) / 30
// = 1757.143 * 9.019057 / 30 = 528.25907 kg/m^3/s, U_s = 1.2 - (3198.556 + 15818.77) / (30 *
// 528.2591) = 0 m/s, sink 30 V_1mm * 528.2591 * 1.2 = 19017.327 V_1mm, the two drags' sum.
TEST(Transfer, PolydisperseDragOfABinaryCellByHand) {
  Bed b;
  b.grid.origin = {0, 0, 0};
  b.grid.spacing = {0.0035, 0.0035, 0.0035};
  b.grid.count = {1, 1, 1};
  b.position = {0.001, 0.001, 0.001, 0.0022, 0.0022, 0.0022};
  b.velocity = {0, 0, 0, 0, 0, 0};
  b.diameter = {0.001, 0.002};
  b.density = {2500.0, 2500.0};
  b.cell_velocity = {0.0, 1.2, 0.0};
  b.cell_volume = {30.0 * kV1mm};
  const Mapped m = map3d(b);
  for (auto method : {TransferMethod::PerParticle, TransferMethod::PerParticleConservative}) {
    const TransferResult r = run(b, m, method, nullptr, drag::Polydispersity::Beetstra2007, drag::Law::ErgunWenYu);
    EXPECT_NEAR(r.particle_drag[1], 3198.5561 * kV1mm, 1e-6 * 3198.5561 * kV1mm);
    EXPECT_NEAR(r.particle_drag[4], 15818.771 * kV1mm, 1e-6 * 15818.771 * kV1mm);
    EXPECT_EQ(r.particle_drag[0], 0.0);
  }
  const TransferResult r = run(b, m, TransferMethod::PerParticleConservative, nullptr,
                               drag::Polydispersity::Beetstra2007, drag::Law::ErgunWenYu);
  EXPECT_NEAR(r.cell_exchange_coefficient[0], 528.25907, 1e-6 * 528.25907);
  EXPECT_NEAR(r.cell_solid_velocity[1], 0.0, 1e-14);
  const double sink = b.cell_volume[0] * r.cell_exchange_coefficient[0] * (1.2 - r.cell_solid_velocity[1]);
  EXPECT_NEAR(sink, 19017.327 * kV1mm, 1e-6 * 19017.327 * kV1mm);
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
