// What the particle fields pass through between the mapping and their use: a linear operator F
// on the cells' particle sums (solid volume, their momentum and Sauter sums, the conservative
// transfer's drag sums), separable per axis of the uniform Cartesian gas grid. Two parts,
// either or both (coupling.void_fraction):
//
// - particle_field_block: [k_x, k_y, k_z]: the particle field estimated on a grid of its own,
//   blocks of k_x x k_y x k_z gas cells, and interpolated back. A block's sum is its cells'
//   (the mapping on the coarse grid), then each gas cell takes its share V_c/V_block of the
//   block density interpolated linearly between block centres to the cell's centre (a wall's
//   ghost block mirrors its neighbour). Per axis: fine cell i at s = (i + 1/2)/k - 1/2 block
//   widths takes (1 - f) of block floor(s) and f of the next, f = s - floor(s); each block's
//   weights over its fine cells sum to k, so sums are kept. The separation test of grid
//   dependence: the gas solved on fine cells, the particles' field and what they see of the
//   gas on the coarse ones.
// - diffusion_bandwidth: b (m): every particle's fields spread to the same total kernel on every
//   grid, of variance b^2 / 2 per axis (the Gaussian (pi b^2)^(-3/2) exp(-|x|^2 / b^2) of Sun &
//   Xiao 2015, "Diffusion-based coarse graining in hybrid continuum-discrete solvers", Int. J.
//   Multiphase Flow 77, 142-157, eq. 10-12; Capecelatro & Desjardins 2013's two-step filter;
//   CFDEMcoupling's constDiffSmoothing solves the same equation). The mapping into cells of
//   width h already spreads a particle, on average over where it sits in its cell, by h^2 / 12
//   per axis (more with blocks: deposition_variance), so that much less is left to diffusion:
//   the (block) field is spread by d(phi)/dtau = laplacian(phi), no flux through the walls, over
//   the pseudo-time T_a = (b^2 / 2 - deposition_variance) / 2 along each axis. Without this a
//   coarse grid's kernel is wider than b (at b = 1.2 cm, 1.05 cm^2 on 2 cm cells against 0.74
//   on 0.5 cm ones). Matching the variance, not a fixed deposition width in metres (Capecelatro
//   & Desjardins), keeps the one-cell mapping and costs nothing; the kernels then differ only
//   in higher moments, O(h^4), the box's against the heat kernel's. Solved exactly in
//   pseudo-time: the discrete Laplacian with zero-flux walls is a sum of one per axis, which
//   commute, so exp(T L) = exp(T_x L_x) exp(T_y L_y) exp(T_z L_z), each the n x n matrix
//   sum_k exp(-T mu_k) v_k v_k^T of the 1-D Neumann Laplacian's eigenpairs (the DCT-II basis
//   v_k(i) = cos(pi k (i + 1/2) / n), mu_k = (4 / h^2) sin^2(pi k / (2 n))), whose spread has
//   variance exactly 2 T on the grid (the lattice heat kernel's). A bandwidth with b^2 / 2
//   below the mapping's own variance is refused.
//
// Per axis F = P H R (R: block sums, H: the heat kernel on the blocks, P: the interpolation),
// every column summing to 1 and every entry >= 0: sums over cells are kept to round-off, and no
// value becomes negative. The gas fields the particles see (velocity, pressure gradient) go
// through the adjoint F^T (the heat kernel is symmetric; the block part is not), so the power
// the particles take, sum_i f_i . u_i, is the power the gas gives, and their pressure-gradient
// force the reaction of the filtered solids in the gas. Entries below 1e-18 of their row's largest are
// skipped (a band of about +-5 b about each cell). An axis of one cell (the 2-D rule's depth)
// is neither blocked nor spread. Cost per field component: n_x + n_y + n_z multiply-adds per
// cell at most (the band's widths).
#ifndef TFDEM_PARTICLE_FIELD_FILTER_H
#define TFDEM_PARTICLE_FIELD_FILTER_H

#include <array>
#include <vector>

#include "tfdem/grid.h"

namespace tfdem {

// exp(time L) of the 1-D Laplacian with zero-flux ends on n cells of width `spacing` (row major,
// n x n): entry (i, j) is what cell i holds after `time` of what was in cell j.
std::vector<double> neumann_heat_kernel(int n, double spacing, double time);

// The variance (m^2) per axis that mapping a particle into cells of `spacing`, in blocks of
// `block`, adds to its spread, averaged over where it sits in its cell: the block's width w =
// block * spacing, uniform, w^2 / 12, plus the interpolation back to the cells, sum_i P_i s_i^2
// over the cells' centres s_i from the block's (0 for block 1). Exact on an unbounded grid.
double deposition_variance(double spacing, int block);

// The block estimate P R on n cells in blocks of `block` (n a multiple of it; row major n x n):
// entry (i, j) is what cell i holds of what was in cell j.
std::vector<double> block_estimate_kernel(int n, int block);

class ParticleFieldFilter {
 public:
  // `bandwidth` b (m; 0 for no spread), `block` gas cells per particle-field cell along x, y,
  // z. Throws std::invalid_argument naming coupling.void_fraction.diffusion_bandwidth or
  // particle_field_block when b is negative or not a number, wider than the domain along an
  // axis of more than one cell (the field would be all but uniform along it), or a block is
  // not a whole divisor of the cells along its axis.
  ParticleFieldFilter(const CartesianGrid &grid, double bandwidth, std::array<int, 3> block = {1, 1, 1});

  double bandwidth() const { return bandwidth_; }
  // T_a = (b^2 / 2 - deposition_variance) / 2 along axis a (m^2, the pseudo-time of a unit
  // diffusivity); 0 along an axis not spread.
  double pseudo_time(int axis) const { return pseudo_time_[axis]; }
  // F, then F^T, applied to `components` interleaved values per cell (grid order,
  // cell_count() records) in place; `scratch` is resized and reused.
  void apply(double *values, int components, std::vector<double> &scratch) const;
  void apply_adjoint(double *values, int components, std::vector<double> &scratch) const;

 private:
  // One axis's n x n matrix (row major; empty: the identity) and each row's band of columns
  // whose entries exceed 1e-18 of its largest.
  struct AxisOperator {
    std::vector<double> matrix;
    std::vector<int> first, last;
  };
  static AxisOperator banded(std::vector<double> matrix, int n);
  void apply(const std::array<AxisOperator, 3> &axes, double *values, int components,
             std::vector<double> &scratch) const;

  CartesianGrid grid_;
  double bandwidth_;
  std::array<double, 3> pseudo_time_{};
  std::array<AxisOperator, 3> forward_, adjoint_;
};

}  // namespace tfdem

#endif
