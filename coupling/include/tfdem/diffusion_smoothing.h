// Diffusion smoothing of the particle fields on the gas grid: a particle field whose spread is
// set in metres, not by the cells (Sun & Xiao 2015, "Diffusion-based coarse graining in hybrid
// continuum-discrete solvers", Int. J. Multiphase Flow 77, 142-157; Capecelatro & Desjardins
// 2013's second filter step; CFDEMcoupling's constDiffSmoothing solves the same equation).
//
// Each per-cell sum phi_c of the particles (solid volume, their momentum, the drag sums) is
// taken as a density phi_c / V_c and advanced by the diffusion equation d(phi)/dtau =
// laplacian(phi) over the pseudo-time T = b^2 / 4, with no flux through the domain's walls.
// On an unbounded domain that is the convolution with the Gaussian of bandwidth b,
// (pi b^2)^(-3/2) exp(-|x|^2 / b^2) (Sun & Xiao eq. 10-12: b = sqrt(4 T)), whose standard
// deviation along each axis is b / sqrt(2).
//
// Here the equation is solved exactly in pseudo-time on the uniform Cartesian grid: the
// discrete Laplacian with zero-flux walls is a sum of one per axis, which commute, so
// exp(T L) = exp(T L_x) exp(T L_y) exp(T L_z), each the n x n matrix sum_k exp(-T mu_k) v_k v_k^T
// of the 1-D Neumann Laplacian's eigenpairs (the DCT-II basis v_k(i) = cos(pi k (i + 1/2) / n),
// mu_k = (4 / h^2) sin^2(pi k / (2 n))). Every column of each matrix sums to 1 and every entry
// is >= 0: sums over cells are kept to round-off, and no value becomes negative. Entries
// below 1e-18 of their row's largest are skipped (a band of about +-5 b about each cell). On the grid the
// spread has variance exactly 2 T = b^2 / 2 per axis (the lattice heat kernel's); the Gaussian
// is its limit for cells much smaller than b. An axis of one cell (the 2-D rule's depth, a
// pseudo-2-D bed one cell deep) is not spread. Cost per field component: n_x + n_y + n_z
// multiply-adds per cell at most (the band's widths, when b is smaller than the domain).
#ifndef TFDEM_DIFFUSION_SMOOTHING_H
#define TFDEM_DIFFUSION_SMOOTHING_H

#include <array>
#include <vector>

#include "tfdem/grid.h"

namespace tfdem {

// exp(time L) of the 1-D Laplacian with zero-flux ends on n cells of width `spacing` (row major,
// n x n): entry (i, j) is what cell i holds after `time` of what was in cell j.
std::vector<double> neumann_heat_kernel(int n, double spacing, double time);

class DiffusionSmoothing {
 public:
  // Throws std::invalid_argument (naming coupling.void_fraction.diffusion_bandwidth) when
  // `bandwidth` is not a positive length or exceeds the domain along an axis of more than one
  // cell (the field would be all but uniform along it).
  DiffusionSmoothing(const CartesianGrid &grid, double bandwidth);

  double bandwidth() const { return bandwidth_; }
  // T = b^2 / 4 (m^2, the pseudo-time of a unit diffusivity).
  double pseudo_time() const { return bandwidth_ * bandwidth_ / 4; }
  // Spread `components` interleaved values per cell (grid order, cell_count() records) in
  // place; `scratch` is resized and reused.
  void spread(double *values, int components, std::vector<double> &scratch) const;

 private:
  CartesianGrid grid_;
  double bandwidth_;
  std::array<std::vector<double>, 3> kernel_;  // per axis; empty for an axis of one cell
  // Per axis and row i: the columns [band_first, band_last] where row i's entries exceed
  // kNegligible of its largest (the rest, below ~1e-18 of a cell's content, are skipped)
  std::array<std::vector<int>, 3> band_first_, band_last_;
};

}  // namespace tfdem

#endif
