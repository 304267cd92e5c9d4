#include "tfdem/diffusion_smoothing.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>

namespace tfdem {

namespace {

const char *const kKey = "coupling.void_fraction.diffusion_bandwidth";
const double kNegligible = 1e-18;  // of a kernel row's largest entry: left out of the band
const double kPi = 3.14159265358979323846;

std::string refusal(double bandwidth, const std::string &why) {
  std::ostringstream s;
  s << kKey << ": " << bandwidth << " m " << why;
  return s.str();
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

DiffusionSmoothing::DiffusionSmoothing(const CartesianGrid &grid, double bandwidth)
    : grid_(grid), bandwidth_(bandwidth) {
  grid_.validate();
  if (!(bandwidth > 0.0) || !std::isfinite(bandwidth))
    throw std::invalid_argument(refusal(bandwidth, "is not a bandwidth: give a length above 0 in metres "
                                                   "(3-6 particle diameters smooths the field of a bed)"));
  static const char *const axis_name[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    if (grid_.count[a] < 2) continue;
    const double extent = grid_.spacing[a] * grid_.count[a];
    if (bandwidth > extent) {
      std::ostringstream why;
      why << "is larger than the domain along " << axis_name[a] << " (" << extent
          << " m): the field would be all but uniform across it; give a bandwidth below " << extent
          << " m (3-6 particle diameters)";
      throw std::invalid_argument(refusal(bandwidth, why.str()));
    }
    const int n = grid_.count[a];
    kernel_[a] = neumann_heat_kernel(n, grid_.spacing[a], pseudo_time());
    band_first_[a].assign(n, 0);
    band_last_[a].assign(n, n - 1);
    for (int i = 0; i < n; ++i) {
      const double *row = &kernel_[a][static_cast<std::size_t>(i) * n];
      const double cut = kNegligible * *std::max_element(row, row + n);
      while (row[band_first_[a][i]] < cut) ++band_first_[a][i];
      while (row[band_last_[a][i]] < cut) --band_last_[a][i];
    }
  }
}

void DiffusionSmoothing::spread(double *values, int components, std::vector<double> &scratch) const {
  const std::size_t cells = static_cast<std::size_t>(grid_.cell_count());
  const std::size_t stride[3] = {1, static_cast<std::size_t>(grid_.count[0]),
                                 static_cast<std::size_t>(grid_.count[0]) * grid_.count[1]};
  scratch.resize(cells * components);
  for (int a = 0; a < 3; ++a) {
    if (kernel_[a].empty()) continue;
    const int n = grid_.count[a];
    const double *kernel = kernel_[a].data();
    const std::size_t step = stride[a] * components;  // between a line's neighbours, in values
    for (std::size_t c = 0; c < cells; ++c) {
      const int i = static_cast<int>((c / stride[a]) % n);  // c's index along the axis
      const std::size_t line = c - i * stride[a];           // the line's first cell
      const double *row = &kernel[static_cast<std::size_t>(i) * n];
      const int first = band_first_[a][i], last = band_last_[a][i];
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
