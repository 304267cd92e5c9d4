// One coupling step of the core across MPI ranks: particles on the ranks the DEM put them,
// cells on the ranks the gas solver put them. Each rank maps its own particles onto the
// global grid, sends the per-cell sums of the cells they touch to those cells' owners
// (CellExchange), and fetches back the completed cell data it needs for its particles'
// forces. No rank ever holds other ranks' particles. With one rank this is transfer().
// When every rank holds every cell (owner table all CellExchange::kEveryRank: the gas solved
// whole on each rank) the cell sums reach every rank, each rank completes every cell, and
// the cells' part of the totals is counted once (rank 0's).
//
// Per step: map() (void fraction on owned cells) then forces() (particle fluid forces,
// seed 000 eq. 28, and the gas sink K, U_s on owned cells, for the method of the options).
// With a particle-field filter (void_fraction.h's diffusion bandwidth or particle-field block,
// particle_field_filter.h) the completed cell sums are filtered before they are used: the
// solids' sums before the gas fraction, the drag sums of the conservative transfer before the
// gas sink. The filter needs the whole grid: cells split over ranks are gathered on every
// rank for it (one sum over ranks of the grid's sums per field), so every rank filters the
// same array as one rank does. The gas velocity the particles' drag takes goes through the
// filter's adjoint (for the spread alone the same kernel: it is symmetric), so a particle's
// drag answers to the gas over b as the gas's drag sink is spread over b, and the power the
// particles take, sum_i f_i . u_i, is the power the gas gives, sum_c V_c s_c . u_c.
// Without it the particles sample the gas's cell-scale velocity, which the spread sink cannot
// damp: the fixed bed on cells of 0.8 d (test coupled.packed_bed_fine_cells) grew columns of
// 0.49 and 0.65 m/s side by side and took 9 % less drag in its interior. The gas itself keeps
// its own velocity in the sink, K_c (u_c - U_s,c).
// Under the 2-D rule (one particle layer, gas one cell deep in z) the fluid force has no z
// component: the gas has none, and the round-off z parts of a 2-D gas solution (~1e-14 of
// the force) would push particles out of their layer, whose in-plane contacts then amplify
// the offset until particles leave the mesh.
#ifndef TFDEM_DISTRIBUTED_COUPLING_H
#define TFDEM_DISTRIBUTED_COUPLING_H

#include <mpi.h>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "tfdem/cell_exchange.h"
#include "tfdem/particle_field_filter.h"
#include "tfdem/grid.h"
#include "tfdem/particles.h"
#include "tfdem/transfer.h"
#include "tfdem/void_fraction.h"

namespace tfdem {

// Totals over all ranks from the last step.
struct CouplingTotals {
  std::size_t floored_cells = 0;     // cells where the gas-fraction floor was used
  double floored_solid_volume = 0.0;  // the solids in them (VoidFraction's)
  double removed_solid_volume = 0.0;  // the solids the floored map leaves out
  double lowest_unfloored = 1.0;     // smallest eps before the floor
  int lowest_cell = -1;              // global grid cell holding it (-1 when all cells are empty)
  double particle_volume = 0.0;      // sum_i V_i
  double mapped_volume = 0.0;        // sum_c (1 - eps_c) V_c
  std::array<double, 3> momentum_imbalance{};  // sum_i eps_g f_d,i - sum_c V_c K_c (u_c - U_s,c)
  double drag_magnitude_sum = 0.0;   // sum_i |eps_g f_d,i|
  // sum_i V_i grad p(x_i) - sum_c (1 - eps_c) V_c grad p_c: the particles' pressure-gradient
  // force against its reaction in the gas (the solids volume of the map, filtered when the
  // filter is on, times the cells' grad p); 0 to round-off when grad p reaches the particles
  // through the map's and the filter's adjoints
  std::array<double, 3> pressure_force_imbalance{};
  double pressure_force_magnitude_sum = 0.0;  // sum_i V_i |grad p(x_i)|
};

class DistributedCoupling {
 public:
  // `grid`: the global grid; `owner_of_cell[g]`: rank owning grid cell g (or kEveryRank for
  // all cells); `owned_cells`:
  // this rank's grid cells in its local order, with their volumes `owned_volume`.
  DistributedCoupling(MPI_Comm comm, const CartesianGrid &grid, std::vector<int> owner_of_cell,
                      const std::vector<int> &owned_cells, std::vector<double> owned_volume,
                      const VoidFractionOptions &void_fraction, const TransferOptions &transfer);

  // Collective: weights of this rank's particles, and eps_g of the owned cells. Throws
  // std::out_of_range (on the rank holding it) for a particle outside the grid.
  void map(const ParticleView &particles);
  // Collective, after map() with the same particles: `gas_velocity` (3 per owned cell) and,
  // when not null, `pressure_gradient` (3 per owned cell, then eq. 28 includes -V_i grad p).
  void forces(const ParticleView &particles, const double *gas_velocity, const double *pressure_gradient);

  // Per owned cell, after map(): eps_g; after forces(): K_c and U_s,c (3 per cell).
  const std::vector<double> &void_fraction() const { return gas_.void_fraction; }
  const std::vector<double> &exchange_coefficient() const { return exchange_coefficient_; }
  const std::vector<double> &solid_velocity() const { return solid_velocity_; }
  // Per local particle, after forces(): eq. 28 fluid force and its drag part eps_g f_d (3 per
  // particle each).
  const std::vector<double> &particle_force() const { return result_.particle_force; }
  const std::vector<double> &particle_drag() const { return result_.particle_drag; }
  // Local particles (indices into the last map()'s view) with a share in global grid cell g.
  std::vector<std::size_t> particles_in_cell(int g) const;
  const CouplingTotals &totals() const { return totals_; }
  const CellExchange &exchange() const { return exchange_; }

 private:
  // Whether this rank's cells enter the totals (each cell counted once over the ranks).
  bool adds_cell_totals() const;
  // Sum over ranks of `values` in place.
  void sum_over_ranks(double *values, int count) const;
  // The particle-field filter (or, `adjoint`, its transpose) of `components` values per owned
  // cell (local order), in place.
  void filter_owned(std::vector<double> &owned, int components, bool adjoint = false);
  // One record of kStateComponents per owned cell, for the particle ranks to fetch.
  void pack_owned_state(const double *gas_velocity, const double *pressure_gradient);
  // Split the fetched halo records into the per-field arrays of halo_.
  void unpack_halo_state();
  // 2-D rule: zero the thin-direction (z) component of every particle's drag and force.
  void drop_thin_direction();
  // Per-particle transfer with gas_velocity interpolated (the weights then carry each
  // particle's interpolation stencil with weight 0, so the halo holds it).
  bool interpolates_gas_velocity() const;
  std::vector<double> interpolated_velocity(const ParticleView &particles);

  // Completed cell data of the halo cells, one field per array (storage reused every step).
  struct HaloCells {
    std::vector<double> velocity, void_fraction, exchange_coefficient, solid_velocity, solid_volume, volume, gradient,
        sauter_diameter;
  };

  MPI_Comm comm_;
  CartesianGrid grid_;
  CellExchange exchange_;
  std::vector<int> owned_cells_;
  std::vector<double> owned_volume_;
  VoidFractionOptions void_fraction_;
  TransferOptions transfer_;
  std::optional<ParticleFieldFilter> filter_;  // with a diffusion bandwidth or a particle-field block
  std::vector<double> grid_sums_, filter_scratch_, seen_velocity_, seen_gradient_;
  // sum_i V_i grad p(x_i), sum_c (1 - eps_c) V_c grad p_c subtracted (3), sum_i V_i |grad p(x_i)|
  void pressure_force_balance(const ParticleView &particles, const std::vector<double> &gradient_at,
                              const double *pressure_gradient, double *out) const;

  CellWeights weights_;
  std::vector<int> scratch_, halo_cells_;
  std::vector<double> grid_velocity_;  // halo gas velocities on the global grid (interpolation)
  std::vector<double> halo_sums_, owned_sums_, halo_state_, owned_state_;
  VoidFraction gas_;
  std::vector<double> exchange_coefficient_, solid_velocity_, sauter_diameter_;
  HaloCells halo_;
  TransferResult result_;
  CouplingTotals totals_;
};

}  // namespace tfdem

#endif
