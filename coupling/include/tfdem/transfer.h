// Interphase momentum transfer between particles and gas cells (seed 000 eq. 28-35).
//
// Methods:
//  - averaged (seed 000 eq. 33-35, the paper's method 1): per cell, beta from the cell's
//    eps and the slip to the solids' mean velocity v_sm (eq. 35); the cell's drag
//    V_c beta (u_g - v_sm) is shared by its particles in proportion to their volume, i.e.
//    every particle gets the same drag per unit volume. Conserves momentum exactly.
//  - per_particle (eq. 29, method 2): each particle's drag uses its own velocity and the gas
//    velocity and eps at its location; the gas still gets eq. 33, as the paper does, so
//    momentum is NOT conserved: the imbalance is reported.
//  - per_particle_conservative: particles as per_particle; the gas gets exactly minus the sum
//    of the particle drags (Newton's third law), in semi-implicit form.
// Gas side in semi-implicit form: the gas loses K_c (u_g - U_s) per unit volume, with K_c
// (kg/m^3/s) treated implicitly and U_s an effective particle velocity; at the gas velocity
// of the coupling step, sum_c V_c K_c (u_c - U_s,c) is the total drag on the particles
// (exactly, for the conservative methods).
// Fluid force on a particle, eq. 28: -V_i grad p + V_i div tau (optional) + eps_g f_d,i,
// where eps_g f_d,i = V_i beta / eps_s (u_g - v_i) is the drag of drag.h.
#ifndef TFDEM_TRANSFER_H
#define TFDEM_TRANSFER_H

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "tfdem/drag.h"
#include "tfdem/particles.h"
#include "tfdem/void_fraction.h"

namespace tfdem {

enum class TransferMethod { Averaged, PerParticle, PerParticleConservative };

// Names accepted in configuration files, in enum order.
const std::vector<std::string> &transfer_method_names();
// The method called `name`; throws std::invalid_argument listing the valid names.
TransferMethod transfer_method_from_name(const std::string &name);

// Gas data per cell (cell_count entries; vectors 3 per cell).
struct CellGas {
  std::size_t cell_count = 0;
  const double *velocity = nullptr;      // u_g
  const double *void_fraction = nullptr;  // eps_g as mapped (after any floor)
  const double *volume = nullptr;        // V_cell (m^3)
};

// Gas data at each particle (3 per particle), e.g. from interpolate() or average_to_particles().
struct GasAtParticles {
  const double *velocity = nullptr;                   // u_g at the particle
  const double *void_fraction = nullptr;               // eps_g at the particle (1 per particle)
  const double *pressure_gradient = nullptr;          // grad p (Pa/m); nullptr = none
  const double *viscous_stress_divergence = nullptr;  // div tau (Pa/m); nullptr = neglected
};

// Gas velocity seen by a particle in the per-particle methods ("v_g^i, the gas velocity at the
// location of particle i", seed 000 eq. 29): the mapping-weighted mean of the cells the
// particle is mapped to (with centroid mapping: its cell's value), or trilinear interpolation
// between cell centres at the particle's centre (void_fraction.h interpolate()).
enum class GasAtParticle { Cell, Interpolated };
const std::vector<std::string> &gas_at_particle_names();

struct TransferOptions {
  TransferMethod method = TransferMethod::Averaged;
  GasAtParticle gas_velocity = GasAtParticle::Cell;
  drag::Law law = drag::Law::ErgunWenYu;
  // Size dependence in a mixture; Beetstra2007 needs a per-particle method.
  drag::Polydispersity polydispersity = drag::Polydispersity::OwnDiameter;
  drag::Gas gas{1.2, 1.8e-5};
};

struct TransferResult {
  std::vector<double> particle_drag;   // eps_g f_d per particle (N), 3N
  std::vector<double> particle_force;  // eq. 28 total fluid force (N), 3N
  std::vector<double> cell_exchange_coefficient;     // K_c (kg/m^3/s)
  std::vector<double> cell_solid_velocity;  // U_s,c (m/s), 3 per cell
  // sum of particle drags minus the drag the gas loses, at the coupling-step gas velocity (N)
  std::array<double, 3> momentum_imbalance{};
  double drag_magnitude_sum = 0.0;  // sum_i |eps_g f_d,i| (N), scale for the imbalance
};

// Drag and fluid forces on particles and the gas sink, by `options.method`, into `out` (its
// storage is reused between coupling steps).
void transfer(const CellWeights &weights, const ParticleView &particles, const CellGas &cells,
              const GasAtParticles &at_particles, const TransferOptions &options, TransferResult &out);
TransferResult transfer(const CellWeights &weights, const ParticleView &particles, const CellGas &cells,
                        const GasAtParticles &at_particles, const TransferOptions &options);

// ---------------------------------------------------------------------------------------
// Staged form of transfer(), for particles and cells held by different MPI ranks (the
// cell_exchange layer moves the per-cell arrays). Cell indices are those of `weights`
// (e.g. compact indices after compact_cells()); transfer() is these stages on one rank.
//   1. particle side: accumulate_solid_sums (additive over ranks, summed at cell owners);
//   2. cell side: map_void_fraction_from_sums and, unless conservative, averaged_cell_drag;
//   3. particle side, with the completed cell data of its cells: particle_drag_and_force;
//   4. conservative only: accumulate_conservative_sums (additive) then conservative_cell_drag.

// Per-cell particle sums of stage 1, kSolidSumComponents values per cell: solid volume
// sum_i w_ic V_i (eq. 34 numerator), sum_i w_ic V_i v_i (3, eq. 35 numerator), and the
// Sauter-mean sums sum_i w_ic d_i^3, sum_i w_ic d_i^2.
constexpr int kSolidSumComponents = 6;
void accumulate_solid_sums(const CellWeights &weights, const ParticleView &particles, std::size_t cell_count,
                           std::vector<double> &sums);

// Gas fraction per cell from completed solid sums (as map_void_fraction).
void map_void_fraction_from_sums(const std::vector<double> &sums, const std::vector<double> &cell_volume,
                                double floor, VoidFraction &out);

// Averaged gas sink (eq. 33, 35) from completed solid sums: K_c = beta_c and U_s,c = v_sm,c
// (zero in cells without particles); `exchange_coefficient` 1 and `solid_velocity` 3 per cell.
void averaged_cell_drag(const std::vector<double> &sums, const CellGas &cells, const TransferOptions &options,
                        double *exchange_coefficient, double *solid_velocity);

// Completed cell data a particle's drag needs (cell_count entries; vectors 3 per cell).
struct CellSolidsState {
  CellGas gas;
  const double *solid_volume = nullptr;    // sum_i w_ic V_i over all particles
  const double *exchange_coefficient = nullptr;     // K_c of averaged_cell_drag (averaged method)
  const double *solid_velocity = nullptr;  // v_sm,c of averaged_cell_drag (averaged method)
  const double *sauter_diameter = nullptr;  // <d>_c of sauter_diameters (polydisperse drag)
};

// Sauter mean diameter <d>_c = sum w d^3 / sum w d^2 per cell from completed solid sums
// (0 in cells without particles).
void sauter_diameters(const std::vector<double> &sums, std::size_t cell_count, double *sauter_diameter);

// Stage 3: eps_g f_d (out.particle_drag) and the eq. 28 force (out.particle_force) of each
// particle, sum_i |eps_g f_d,i| and sum_i eps_g f_d,i (out.momentum_imbalance, the particle
// part). Returns V_i beta_i / eps_s,i per particle for the per-particle methods (empty for
// averaged).
std::vector<double> particle_drag_and_force(const CellWeights &weights, const ParticleView &particles,
                                            const CellSolidsState &cells, const GasAtParticles &at_particles,
                                            const TransferOptions &options, TransferResult &out);

// Conservative sums per cell, kConservativeSumComponents values: sum_i w_ic V_i beta_i/eps_s,i
// and sum_i w_ic eps_g f_d,i (3).
constexpr int kConservativeSumComponents = 4;
void accumulate_conservative_sums(const CellWeights &weights, const std::vector<double> &particle_exchange_coefficient,
                                  const std::vector<double> &particle_drag, std::size_t cell_count,
                                  std::vector<double> &sums);

// Conservative gas sink from completed sums: K_c = sum / V_c and U_s,c such that
// V_c K_c (u_c - U_s,c) = sum_i w_ic eps_g f_d,i exactly.
void conservative_cell_drag(const std::vector<double> &sums, const CellGas &cells, double *exchange_coefficient,
                            double *solid_velocity);

// Drag the gas loses, sum_c V_c K_c (u_c - U_s,c) (N).
std::array<double, 3> gas_drag_sink(const CellGas &cells, const double *exchange_coefficient, const double *solid_velocity);

// Weighted average of a cell field at each particle, sum_c w_ic phi_c (seed 001 eq. 38 with
// the mapping weights); `components` values per cell and per particle.
std::vector<double> average_to_particles(const CellWeights &weights, const double *cell_field,
                                         int components);

}  // namespace tfdem

#endif
