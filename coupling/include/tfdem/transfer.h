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
  const double *gas_fraction = nullptr;  // eps_g as mapped (after any floor)
  const double *volume = nullptr;        // V_cell (m^3)
};

// Gas data at each particle (3 per particle), e.g. from interpolate() or average_to_particles().
struct GasAtParticles {
  const double *velocity = nullptr;                   // u_g at the particle
  const double *gas_fraction = nullptr;               // eps_g at the particle (1 per particle)
  const double *pressure_gradient = nullptr;          // grad p (Pa/m); nullptr = none
  const double *viscous_stress_divergence = nullptr;  // div tau (Pa/m); nullptr = neglected
};

struct TransferOptions {
  TransferMethod method = TransferMethod::Averaged;
  drag::Law law = drag::Law::ErgunWenYu;
  drag::Gas gas{1.2, 1.8e-5};
};

struct TransferResult {
  std::vector<double> particle_drag;   // eps_g f_d per particle (N), 3N
  std::vector<double> particle_force;  // eq. 28 total fluid force (N), 3N
  std::vector<double> cell_coefficient;     // K_c (kg/m^3/s)
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

// Weighted average of a cell field at each particle, sum_c w_ic phi_c (seed 001 eq. 38 with
// the mapping weights); `components` values per cell and per particle.
std::vector<double> average_to_particles(const CellWeights &weights, const double *cell_field,
                                         int components);

}  // namespace tfdem

#endif
