// Void fraction (gas volume fraction) from particles, and the particle-to-cell weights that
// every transfer between particles and cells reuses.
//
// Methods (chosen per case):
//  - centroid: each particle's whole volume goes to the cell holding its centre (seed 000
//    eq. 34: eps_s = sum_i V_i / V_cell). Cheap; noisy and unsafe when cells are not several
//    particle diameters wide.
//  - divided: the particle's volume is split over the cells it overlaps, by a lattice of
//    sample points inside the sphere (equal weights in 3-D; in 2-D, weights proportional to
//    the sphere's chord through the thin direction).
//  - porous_cube: Link et al., seed 001 eq. 33-37: the particle is a porous cube of side
//    d_cube = a d_p (eq. 34), a >= (pi/6)^(1/3) ~ 0.806 (eq. 35); f_cell^i is the fraction of
//    the cube inside each cell, exact on a Cartesian grid (eq. 37: eps_g = 1 - eps_cube sum f).
// 2-D rule of seed 000 (after eq. 35): one particle layer, cell depth = d_p; the thin
// direction (z) is not split.
// Parts of a particle outside the domain (a particle touching a wall) are given to the
// inside cells in proportion, so sum_cells (1 - eps) V_cell = sum_i V_i always holds.
#ifndef TFDEM_VOID_FRACTION_H
#define TFDEM_VOID_FRACTION_H

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "tfdem/grid.h"
#include "tfdem/particles.h"

namespace tfdem {

enum class VoidFractionMethod { Centroid, Divided, PorousCube };

// Names accepted in configuration files, in enum order.
const std::vector<std::string> &void_fraction_method_names();
// The method called `name`; throws std::invalid_argument listing the valid names.
VoidFractionMethod void_fraction_method_from_name(const std::string &name);

// Smallest porous-cube factor a, seed 001 eq. 35: the cube holds the sphere's volume.
double minimum_cube_factor();

struct VoidFractionOptions {
  VoidFractionMethod method = VoidFractionMethod::Centroid;
  double cube_factor = 1.0;           // a of seed 001 eq. 34
  int divided_points_per_diameter = 6;  // sample lattice of the divided method (even: none on a face)
  bool two_dimensional = false;       // seed 000's one-layer rule
  double void_fraction_floor = 0.0;    // eps_g never below this (0 = no floor)
  // particle_field_filter.h's filter of the cell sums: b (m) of the diffusion spread (0 = none),
  // and the gas cells per particle-field cell along x, y, z (1, 1, 1: the gas cells)
  double diffusion_bandwidth = 0.0;
  std::array<int, 3> particle_field_block{1, 1, 1};
  bool filters() const {
    return diffusion_bandwidth > 0.0 || particle_field_block != std::array<int, 3>{1, 1, 1};
  }
};

// Particle-to-cell weights in compressed rows: particle p's share w of its volume goes to
// cells[k] with weights[k] for k in [offsets[p], offsets[p+1]); each row sums to 1.
struct CellWeights {
  std::vector<std::size_t> offsets{0};
  std::vector<int> cells;
  std::vector<double> weights;
  std::size_t particle_count() const { return offsets.size() - 1; }
};

// Weights of `options.method` for particles on `grid`, written into `out` (its storage is
// reused between coupling steps). Throws std::out_of_range naming the first particle whose
// centre is outside the grid.
void compute_weights(const CartesianGrid &grid, const ParticleView &particles,
                     const VoidFractionOptions &options, CellWeights &out);
CellWeights compute_weights(const CartesianGrid &grid, const ParticleView &particles,
                            const VoidFractionOptions &options);

// Centroid weights from cell indices found by the caller (e.g. OpenFOAM's findCell on an
// unstructured mesh); throws std::out_of_range for a negative index.
CellWeights centroid_weights(const int *cell_of_particle, std::size_t count);

// Per-cell result of mapping particle volume.
struct VoidFraction {
  std::vector<double> solid_volume;  // sum_i w_ic V_i (m^3)
  std::vector<double> void_fraction;  // max(1 - solid_volume / V_cell, floor)
  std::size_t floored_cells = 0;     // cells where the floor replaced a lower value
  double floored_solid_volume = 0.0;  // sum of solid_volume over those cells (m^3): the
                                      // particles whose drag sees eps = floor
  double removed_solid_volume = 0.0;  // sum over them of solid_volume - (1 - floor) V_cell:
                                      // the solids the floored map leaves out (m^3)
  double lowest_unfloored = 1.0;     // smallest 1 - solid_volume / V_cell before the floor
  int lowest_cell = -1;              // the cell holding it (-1 when every cell is empty)
};

// Solid volume and gas fraction per cell into `out`; cell_volume has one entry per cell.
void map_void_fraction(const CellWeights &weights, const ParticleView &particles,
                      const std::vector<double> &cell_volume, double floor, VoidFraction &out);
VoidFraction map_void_fraction(const CellWeights &weights, const ParticleView &particles,
                             const std::vector<double> &cell_volume, double floor);

// Gas fraction max(1 - out.solid_volume / V_cell, floor) per cell from out.solid_volume
// (already filled), with the floor statistics.
void void_fraction_from_solid_volume(const std::vector<double> &cell_volume, double floor, VoidFraction &out);
// Renumber weights.cells to 0 .. n-1 over the n distinct cells used, in order of first use,
// and return the original index of each. `scratch` (one entry per original cell, all -1, or
// empty: it is then sized to the largest index) is left all -1 again, so the pass is O(weights).
std::vector<int> compact_cells(CellWeights &weights, std::vector<int> &scratch);
// Cell volumes of `grid`: V = dx dy dz; under the 2-D rule the depth is `depth_2d` (= d_p).
std::vector<double> cell_volumes(const CartesianGrid &grid, bool two_dimensional, double depth_2d);

// Value at point p of a cell-centred field with `components` values per cell, by
// trilinear interpolation between cell centres, extrapolated linearly in the half cells at
// the domain boundary: exact for fields linear in x, y, z. Axes with one cell are constant.
void interpolate(const CartesianGrid &grid, const double *cell_field, int components,
                 const double *p, double *out);
// The cells and weights interpolate() uses at point p (up to 8); returns how many.
int interpolation_stencil(const CartesianGrid &grid, const double *p, int cells[8], double weights[8]);
// Each particle's row extended by the cells of its interpolation stencil with weight 0, so a
// rank that fetches the gas data of its weights' cells can interpolate at its particles;
// every weighted sum is unchanged.
void add_interpolation_stencils(const CartesianGrid &grid, const ParticleView &particles, CellWeights &weights);

}  // namespace tfdem

#endif
