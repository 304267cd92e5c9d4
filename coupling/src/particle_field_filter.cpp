#include "tfdem/particle_field_filter.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>

namespace tfdem {

namespace {

const char *const kBandwidthKey = "coupling.void_fraction.diffusion_bandwidth";
const char *const kBlockKey = "coupling.void_fraction.particle_field_block";
const char *const kAxisName[3] = {"x", "y", "z"};
const double kNegligible = 1e-18;  // of a kernel row's largest entry: left out of the band
const double kPi = 3.14159265358979323846;

std::string refusal(double bandwidth, const std::string &why) {
  std::ostringstream s;
  s << kBandwidthKey << ": " << bandwidth << " m " << why;
  return s.str();
}

void check_block(const CartesianGrid &grid, const std::array<int, 3> &block) {
  for (int a = 0; a < 3; ++a) {
    const int n = grid.count[a], k = block[a];
    if (k >= 1 && n % k == 0) continue;
    std::ostringstream s;
    s << kBlockKey << ": " << k << " gas cells along " << kAxisName[a] << " is not a whole divisor of the gas grid's "
      << n << " cells there: give one of";
    for (int d = 1; d <= n; ++d)
      if (n % d == 0) s << " " << d;
    s << " (1: the particle field on the gas cells)";
    throw std::invalid_argument(s.str());
  }
}

// n x n row major product of (rows x inner) and (inner x n).
std::vector<double> product(const std::vector<double> &a, const std::vector<double> &b, int rows, int inner, int n) {
  std::vector<double> out(static_cast<std::size_t>(rows) * n, 0.0);
  for (int i = 0; i < rows; ++i)
    for (int m = 0; m < inner; ++m) {
      const double aim = a[static_cast<std::size_t>(i) * inner + m];
      if (aim == 0.0) continue;
      for (int j = 0; j < n; ++j) out[static_cast<std::size_t>(i) * n + j] += aim * b[static_cast<std::size_t>(m) * n + j];
    }
  return out;
}

// P (n x m) / k: fine cell i's share of each block's sum, the linear interpolation between
// block centres divided by the block's k cells; a wall's ghost block mirrors its neighbour.
std::vector<double> block_interpolation(int n, int block) {
  const int blocks = n / block;
  std::vector<double> p(static_cast<std::size_t>(n) * blocks, 0.0);
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) / block - 0.5;
    const int below = static_cast<int>(std::floor(s));
    const double f = s - below;
    p[static_cast<std::size_t>(i) * blocks + std::max(below, 0)] += (1.0 - f) / block;
    p[static_cast<std::size_t>(i) * blocks + std::min(below + 1, blocks - 1)] += f / block;
  }
  return p;
}

// R (m x n): a block's sum of its cells.
std::vector<double> block_sums(int n, int block) {
  const int blocks = n / block;
  std::vector<double> r(static_cast<std::size_t>(blocks) * n, 0.0);
  for (int j = 0; j < n; ++j) r[static_cast<std::size_t>(j / block) * n + j] = 1.0;
  return r;
}

std::vector<double> transposed(const std::vector<double> &matrix, int n) {
  std::vector<double> t(matrix.size());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) t[static_cast<std::size_t>(j) * n + i] = matrix[static_cast<std::size_t>(i) * n + j];
  return t;
}

}  // namespace

double deposition_variance(double spacing, int block) {
  // Fine cell m's centre sits (m + 1/2) / k - 1/2 block widths from block 0's centre and takes
  // max(0, 1 - |offset|) / k of that block (block_interpolation); nothing beyond one block away.
  const double width = block * spacing;
  double interpolation = 0.0;
  for (int m = -block; m < 2 * block; ++m) {
    const double offset = (m + 0.5) / block - 0.5;
    interpolation += std::max(0.0, 1.0 - std::abs(offset)) / block * offset * offset;
  }
  return width * width / 12.0 + interpolation * width * width;
}

namespace {

// The pseudo-time of the diffusion along `axis` that brings the mapping's own variance there up
// to b^2 / 2; throws naming the least bandwidth when the mapping alone spreads more.
double diffusion_time(double bandwidth, double spacing, int block, int axis) {
  const double deposited = deposition_variance(spacing, block);
  const double time = (bandwidth * bandwidth / 2.0 - deposited) / 2.0;
  if (time >= 0.0) return time;
  std::ostringstream why;
  why << "is narrower than the cells along " << kAxisName[axis] << ": mapping into " << (block > 1 ? "blocks" : "cells")
      << " of " << block * spacing << " m already spreads a particle by a variance of " << deposited
      << " m^2 there, more than b^2 / 2; give a bandwidth of at least " << std::sqrt(2.0 * deposited)
      << " m (3-6 particle diameters), or leave it out";
  throw std::invalid_argument(refusal(bandwidth, why.str()));
}

}  // namespace

std::vector<double> neumann_heat_kernel(int n, double spacing, double time) {
  const std::size_t size = static_cast<std::size_t>(n);
  std::vector<double> basis(size * size);  // v_k(i), orthonormal: row k
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      basis[k * size + i] = std::sqrt(k == 0 ? 1.0 / n : 2.0 / n) * std::cos(kPi * k * (i + 0.5) / n);
  std::vector<double> kernel(size * size, 0.0);
  for (int k = 0; k < n; ++k) {
    const double s = std::sin(kPi * k / (2.0 * n));
    const double decay = std::exp(-time * 4.0 / (spacing * spacing) * s * s);
    const double *v = &basis[k * size];
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) kernel[i * size + j] += decay * v[i] * v[j];
  }
  return kernel;
}

std::vector<double> block_estimate_kernel(int n, int block) {
  return product(block_interpolation(n, block), block_sums(n, block), n, n / block, n);
}

ParticleFieldFilter::AxisOperator ParticleFieldFilter::banded(std::vector<double> matrix, int n) {
  AxisOperator axis{std::move(matrix), std::vector<int>(n, 0), std::vector<int>(n, n - 1)};
  for (int i = 0; i < n; ++i) {
    const double *row = &axis.matrix[static_cast<std::size_t>(i) * n];
    const double cut = kNegligible * *std::max_element(row, row + n);
    while (row[axis.first[i]] < cut) ++axis.first[i];
    while (row[axis.last[i]] < cut) --axis.last[i];
  }
  return axis;
}

ParticleFieldFilter::ParticleFieldFilter(const CartesianGrid &grid, double bandwidth, std::array<int, 3> block)
    : grid_(grid), bandwidth_(bandwidth) {
  grid_.validate();
  if (!(bandwidth >= 0.0) || !std::isfinite(bandwidth))
    throw std::invalid_argument(refusal(bandwidth, "is not a bandwidth: give a length above 0 in metres "
                                                   "(3-6 particle diameters smooths the field of a bed)"));
  check_block(grid_, block);
  for (int a = 0; a < 3; ++a) {
    const int n = grid_.count[a], k = block[a], blocks = n / k;
    const double extent = grid_.spacing[a] * n;
    if (n > 1 && bandwidth > extent) {
      std::ostringstream why;
      why << "is larger than the domain along " << kAxisName[a] << " (" << extent
          << " m): the field would be all but uniform across it; give a bandwidth below " << extent
          << " m (3-6 particle diameters)";
      throw std::invalid_argument(refusal(bandwidth, why.str()));
    }
    const bool spreads = bandwidth > 0.0 && blocks > 1;
    if (!spreads && k == 1) continue;
    std::vector<double> matrix;
    if (spreads) pseudo_time_[a] = diffusion_time(bandwidth, grid_.spacing[a], k, a);
    if (!spreads)
      matrix = block_estimate_kernel(n, k);
    else if (k == 1)
      matrix = neumann_heat_kernel(n, grid_.spacing[a], pseudo_time_[a]);
    else
      matrix = product(block_interpolation(n, k),
                       product(neumann_heat_kernel(blocks, k * grid_.spacing[a], pseudo_time_[a]),
                               block_sums(n, k), blocks, blocks, n),
                       n, blocks, n);
    adjoint_[a] = banded(transposed(matrix, n), n);
    forward_[a] = banded(std::move(matrix), n);
  }
}

void ParticleFieldFilter::apply(double *values, int components, std::vector<double> &scratch) const {
  apply(forward_, values, components, scratch);
}

void ParticleFieldFilter::apply_adjoint(double *values, int components, std::vector<double> &scratch) const {
  apply(adjoint_, values, components, scratch);
}

void ParticleFieldFilter::apply(const std::array<AxisOperator, 3> &axes, double *values, int components,
                                std::vector<double> &scratch) const {
  const std::size_t cells = static_cast<std::size_t>(grid_.cell_count());
  const std::size_t stride[3] = {1, static_cast<std::size_t>(grid_.count[0]),
                                 static_cast<std::size_t>(grid_.count[0]) * grid_.count[1]};
  scratch.resize(cells * components);
  for (int a = 0; a < 3; ++a) {
    const AxisOperator &axis = axes[a];
    if (axis.matrix.empty()) continue;
    const int n = grid_.count[a];
    const std::size_t step = stride[a] * components;  // between a line's neighbours, in values
    for (std::size_t c = 0; c < cells; ++c) {
      const int i = static_cast<int>((c / stride[a]) % n);  // c's index along the axis
      const std::size_t line = c - i * stride[a];           // the line's first cell
      const double *row = &axis.matrix[static_cast<std::size_t>(i) * n];
      const int first = axis.first[i], last = axis.last[i];
      for (int m = 0; m < components; ++m) {
        const double *in = &values[line * components + m];
        double sum = 0.0;
        for (int j = first; j <= last; ++j) sum += row[j] * in[j * step];
        scratch[c * components + m] = sum;
      }
    }
    std::copy(scratch.begin(), scratch.end(), values);
  }
}

}  // namespace tfdem
