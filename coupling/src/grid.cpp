#include "tfdem/grid.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tfdem {

void CartesianGrid::validate() const {
  for (int a = 0; a < 3; ++a) {
    if (!(spacing[a] > 0.0))
      throw std::invalid_argument("grid spacing along axis " + std::to_string(a) + " must be > 0");
    if (count[a] < 1)
      throw std::invalid_argument("grid cell count along axis " + std::to_string(a) + " must be >= 1");
  }
}

int CartesianGrid::clamped_index(int axis, double x) const {
  const int i = static_cast<int>(std::floor((x - origin[axis]) / spacing[axis]));
  return i < 0 ? 0 : (i >= count[axis] ? count[axis] - 1 : i);
}

int CartesianGrid::locate(const double *p) const {
  for (int a = 0; a < 3; ++a)
    if (p[a] < origin[a] || p[a] > upper(a)) return -1;
  return flat(clamped_index(0, p[0]), clamped_index(1, p[1]), clamped_index(2, p[2]));
}

}  // namespace tfdem
