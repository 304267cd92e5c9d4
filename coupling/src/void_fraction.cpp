#include "tfdem/void_fraction.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tfdem/suggest.h"

namespace tfdem {
namespace {

// Sample point of the divided method: offset in units of d_p and its share of the volume.
struct SamplePoint {
  double offset[3];
  double weight;
};

// Lattice of n^3 (3-D) or n^2 (2-D) points over the sphere of unit diameter.
std::vector<SamplePoint> sphere_samples(int n, bool two_dimensional) {
  std::vector<SamplePoint> points;
  const double r2 = 0.25;
  double total = 0.0;
  const int nz = two_dimensional ? 1 : n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < nz; ++k) {
        const double x = (i + 0.5) / n - 0.5, y = (j + 0.5) / n - 0.5;
        const double z = two_dimensional ? 0.0 : (k + 0.5) / n - 0.5;
        const double rho2 = x * x + y * y + z * z;
        if (rho2 > r2) continue;
        const double w = two_dimensional ? std::sqrt(r2 - rho2) : 1.0;  // chord in z for 2-D
        points.push_back({{x, y, z}, w});
        total += w;
      }
  for (auto &p : points) p.weight /= total;
  return points;
}

[[noreturn]] void outside(std::size_t index, const double *p, const CartesianGrid &grid) {
  std::ostringstream msg;
  msg << "particle " << index << " at (" << p[0] << ", " << p[1] << ", " << p[2]
      << ") m is outside the mesh [" << grid.origin[0] << ", " << grid.upper(0) << "] x ["
      << grid.origin[1] << ", " << grid.upper(1) << "] x [" << grid.origin[2] << ", "
      << grid.upper(2) << "] m";
  throw std::out_of_range(msg.str());
}

// Append (cell, weight) to the current row, merging with an existing entry of that cell.
void add_share(CellWeights &w, std::size_t row_start, int cell, double weight) {
  for (std::size_t k = row_start; k < w.cells.size(); ++k)
    if (w.cells[k] == cell) {
      w.weights[k] += weight;
      return;
    }
  w.cells.push_back(cell);
  w.weights.push_back(weight);
}

void centroid(const CartesianGrid &grid, const ParticleView &particles, CellWeights &w) {
  w.offsets.resize(particles.count + 1);
  w.cells.resize(particles.count);
  w.weights.assign(particles.count, 1.0);
  for (std::size_t p = 0; p < particles.count; ++p) {
    const double *x = particles.position + 3 * p;
    const int cell = grid.locate(x);
    if (cell < 0) outside(p, x, grid);
    w.cells[p] = cell;
    w.offsets[p + 1] = p + 1;
  }
}

// True when the sphere's bounding box lies in the cell of its centre (in 2-D: in x and y).
bool sphere_in_one_cell(const CartesianGrid &grid, const double *x, double radius, bool two_d) {
  const int axes = two_d ? 2 : 3;
  for (int a = 0; a < axes; ++a)
    if (grid.clamped_index(a, x[a] - radius) != grid.clamped_index(a, x[a] + radius)) return false;
  return true;
}

void clear(CellWeights &w, std::size_t particle_count) {
  w.offsets.clear();
  w.offsets.reserve(particle_count + 1);
  w.offsets.push_back(0);
  w.cells.clear();
  w.weights.clear();
}

void divided(const CartesianGrid &grid, const ParticleView &particles, int n, bool two_d, CellWeights &w) {
  const std::vector<SamplePoint> samples = sphere_samples(n, two_d);
  clear(w, particles.count);
  for (std::size_t p = 0; p < particles.count; ++p) {
    const double *x = particles.position + 3 * p;
    if (grid.locate(x) < 0) outside(p, x, grid);
    const double d = particles.diameter[p];
    const std::size_t row = w.cells.size();
    if (sphere_in_one_cell(grid, x, 0.5 * d, two_d)) {
      w.cells.push_back(grid.locate(x));
      w.weights.push_back(1.0);
      w.offsets.push_back(w.cells.size());
      continue;
    }
    for (const auto &s : samples) {
      int idx[3];
      for (int a = 0; a < 3; ++a) idx[a] = grid.clamped_index(a, x[a] + d * s.offset[a]);
      add_share(w, row, grid.flat(idx[0], idx[1], idx[2]), s.weight);
    }
    w.offsets.push_back(w.cells.size());
  }
}

// Overlap lengths of [lo, hi] with the cells along one axis, clipped to the domain.
int axis_overlaps(const CartesianGrid &grid, int axis, double lo, double hi, int *first, double *len) {
  const int i0 = grid.clamped_index(axis, lo), i1 = grid.clamped_index(axis, hi);
  for (int i = i0; i <= i1; ++i) {
    const double cell_lo = grid.origin[axis] + i * grid.spacing[axis];
    len[i - i0] = std::max(0.0, std::min(hi, cell_lo + grid.spacing[axis]) - std::max(lo, cell_lo));
  }
  *first = i0;
  return i1 - i0 + 1;
}

void porous_cube(const CartesianGrid &grid, const ParticleView &particles, double a, bool two_d, CellWeights &w) {
  clear(w, particles.count);
  constexpr int kMaxSpan = 64;
  for (std::size_t p = 0; p < particles.count; ++p) {
    const double *x = particles.position + 3 * p;
    if (grid.locate(x) < 0) outside(p, x, grid);
    const double half = 0.5 * a * particles.diameter[p];
    int first[3], n[3];
    double len[3][kMaxSpan];
    for (int ax = 0; ax < 3; ++ax) {
      if (two_d && ax == 2) {
        first[2] = grid.clamped_index(2, x[2]);
        n[2] = 1;
        len[2][0] = 1.0;
        continue;
      }
      if (2.0 * half / grid.spacing[ax] + 2.0 > kMaxSpan)
        throw std::invalid_argument("porous cube spans more than 62 cells: refine less or reduce a");
      n[ax] = axis_overlaps(grid, ax, x[ax] - half, x[ax] + half, &first[ax], len[ax]);
    }
    double total = 0.0;
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j)
        for (int k = 0; k < n[2]; ++k) total += len[0][i] * len[1][j] * len[2][k];
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j)
        for (int k = 0; k < n[2]; ++k) {
          const double share = len[0][i] * len[1][j] * len[2][k] / total;
          if (share > 0.0) {
            w.cells.push_back(grid.flat(first[0] + i, first[1] + j, first[2] + k));
            w.weights.push_back(share);
          }
        }
    w.offsets.push_back(w.cells.size());
  }
}

}  // namespace

const std::vector<std::string> &void_fraction_method_names() {
  static const std::vector<std::string> names = {"centroid", "divided", "porous_cube"};
  return names;
}

VoidFractionMethod void_fraction_method_from_name(const std::string &name) {
  return static_cast<VoidFractionMethod>(index_of_name(name, void_fraction_method_names(), "void fraction method"));
}

double minimum_cube_factor() { return std::cbrt(kPi / 6.0); }

void compute_weights(const CartesianGrid &grid, const ParticleView &particles,
                     const VoidFractionOptions &options, CellWeights &out) {
  grid.validate();
  switch (options.method) {
    case VoidFractionMethod::Centroid:
      return centroid(grid, particles, out);
    case VoidFractionMethod::Divided:
      if (options.divided_points_per_diameter < 1)
        throw std::invalid_argument("divided_points_per_diameter must be >= 1");
      return divided(grid, particles, options.divided_points_per_diameter, options.two_dimensional, out);
    case VoidFractionMethod::PorousCube:
      if (options.cube_factor < minimum_cube_factor() * (1.0 - 1e-12))
        throw std::invalid_argument("porous cube factor a = " + std::to_string(options.cube_factor) +
                                    " is below (pi/6)^(1/3) = 0.806 (seed 001 eq. 35)");
      return porous_cube(grid, particles, options.cube_factor, options.two_dimensional, out);
  }
  throw std::invalid_argument("unknown void fraction method");
}

CellWeights compute_weights(const CartesianGrid &grid, const ParticleView &particles,
                            const VoidFractionOptions &options) {
  CellWeights w;
  compute_weights(grid, particles, options, w);
  return w;
}

CellWeights centroid_weights(const int *cell_of_particle, std::size_t count) {
  CellWeights w;
  w.offsets.reserve(count + 1);
  w.cells.assign(cell_of_particle, cell_of_particle + count);
  w.weights.assign(count, 1.0);
  for (std::size_t p = 0; p < count; ++p) {
    if (w.cells[p] < 0)
      throw std::out_of_range("particle " + std::to_string(p) + " is in no cell of the mesh");
    w.offsets.push_back(p + 1);
  }
  return w;
}

void void_fraction_from_solid_volume(const std::vector<double> &cell_volume, double floor, VoidFraction &out) {
  if (!(floor >= 0.0 && floor < 1.0))
    throw std::invalid_argument("gas fraction floor must be in [0, 1), got " + std::to_string(floor));
  out.floored_cells = 0;
  out.floored_solid_volume = 0.0;
  out.removed_solid_volume = 0.0;
  out.lowest_unfloored = 1.0;
  out.lowest_cell = -1;
  out.void_fraction.resize(cell_volume.size());
  for (std::size_t c = 0; c < cell_volume.size(); ++c) {
    const double eps = 1.0 - out.solid_volume[c] / cell_volume[c];
    if (eps < out.lowest_unfloored) {
      out.lowest_unfloored = eps;
      out.lowest_cell = static_cast<int>(c);
    }
    if (eps < floor) {
      ++out.floored_cells;
      out.floored_solid_volume += out.solid_volume[c];
      out.removed_solid_volume += out.solid_volume[c] - (1.0 - floor) * cell_volume[c];
    }
    out.void_fraction[c] = std::max(eps, floor);
  }
}

void map_void_fraction(const CellWeights &weights, const ParticleView &particles,
                      const std::vector<double> &cell_volume, double floor, VoidFraction &out) {
  out.solid_volume.assign(cell_volume.size(), 0.0);
  for (std::size_t p = 0; p < particles.count; ++p) {
    const double volume = sphere_volume(particles.diameter[p]);
    for (std::size_t k = weights.offsets[p]; k < weights.offsets[p + 1]; ++k)
      out.solid_volume[weights.cells[k]] += weights.weights[k] * volume;
  }
  void_fraction_from_solid_volume(cell_volume, floor, out);
}

std::vector<int> compact_cells(CellWeights &weights, std::vector<int> &scratch) {
  if (scratch.empty() && !weights.cells.empty())
    scratch.assign(*std::max_element(weights.cells.begin(), weights.cells.end()) + 1, -1);
  std::vector<int> original;
  for (int &c : weights.cells) {
    if (c < 0 || static_cast<std::size_t>(c) >= scratch.size())
      throw std::out_of_range("compact_cells: cell " + std::to_string(c) + " outside the scratch of " +
                              std::to_string(scratch.size()) + " cells");
    if (scratch[c] < 0) {
      scratch[c] = static_cast<int>(original.size());
      original.push_back(c);
    }
    c = scratch[c];
  }
  for (int c : original) scratch[c] = -1;
  return original;
}

VoidFraction map_void_fraction(const CellWeights &weights, const ParticleView &particles,
                             const std::vector<double> &cell_volume, double floor) {
  VoidFraction out;
  map_void_fraction(weights, particles, cell_volume, floor, out);
  return out;
}

std::vector<double> cell_volumes(const CartesianGrid &grid, bool two_dimensional, double depth_2d) {
  grid.validate();
  const double v = two_dimensional ? grid.spacing[0] * grid.spacing[1] * depth_2d : grid.cell_volume();
  if (!(v > 0.0)) throw std::invalid_argument("2-D cell depth (particle diameter) must be > 0");
  return std::vector<double>(grid.cell_count(), v);
}

int interpolation_stencil(const CartesianGrid &grid, const double *p, int cells[8], double weights[8]) {
  int base[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    if (grid.count[a] == 1) {
      base[a] = 0;
      t[a] = 0.0;
      continue;
    }
    const double s = (p[a] - grid.origin[a]) / grid.spacing[a] - 0.5;
    base[a] = std::clamp(static_cast<int>(std::floor(s)), 0, grid.count[a] - 2);
    t[a] = s - base[a];
  }
  int n = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const int di = corner & 1, dj = (corner >> 1) & 1, dk = (corner >> 2) & 1;
    if ((di && grid.count[0] == 1) || (dj && grid.count[1] == 1) || (dk && grid.count[2] == 1)) continue;
    weights[n] = (di ? t[0] : 1.0 - t[0]) * (dj ? t[1] : 1.0 - t[1]) * (dk ? t[2] : 1.0 - t[2]);
    cells[n++] = grid.flat(base[0] + di, base[1] + dj, base[2] + dk);
  }
  return n;
}

void interpolate(const CartesianGrid &grid, const double *cell_field, int components,
                 const double *p, double *out) {
  int cells[8];
  double weights[8];
  const int n = interpolation_stencil(grid, p, cells, weights);
  for (int c = 0; c < components; ++c) out[c] = 0.0;
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < components; ++c) out[c] += weights[k] * cell_field[components * cells[k] + c];
}

void add_interpolation_stencils(const CartesianGrid &grid, const ParticleView &particles, CellWeights &w) {
  CellWeights out;
  out.offsets.reserve(w.offsets.size());
  for (std::size_t p = 0; p < w.particle_count(); ++p) {
    for (std::size_t k = w.offsets[p]; k < w.offsets[p + 1]; ++k) {
      out.cells.push_back(w.cells[k]);
      out.weights.push_back(w.weights[k]);
    }
    int cells[8];
    double unused[8];
    const int n = interpolation_stencil(grid, particles.position + 3 * p, cells, unused);
    for (int k = 0; k < n; ++k) {
      out.cells.push_back(cells[k]);
      out.weights.push_back(0.0);
    }
    out.offsets.push_back(out.cells.size());
  }
  w = std::move(out);
}

}  // namespace tfdem
