// Uniform Cartesian grid of cells, numbered as a single blockMesh hex block: x fastest,
// then y, then z (cell = i + nx (j + ny k)).
#ifndef TFDEM_GRID_H
#define TFDEM_GRID_H

#include <array>

namespace tfdem {

struct CartesianGrid {
  std::array<double, 3> origin{};   // lower corner (m)
  std::array<double, 3> spacing{};  // cell size per axis (m)
  std::array<int, 3> count{};       // cells per axis

  // Throw std::invalid_argument unless spacings and counts are positive.
  void validate() const;
  int cell_count() const { return count[0] * count[1] * count[2]; }
  double cell_volume() const { return spacing[0] * spacing[1] * spacing[2]; }
  // Upper corner along `axis`.
  double upper(int axis) const { return origin[axis] + spacing[axis] * count[axis]; }
  // Index of the cell containing point p, or -1 outside; faces belong to the upper cell,
  // the domain's upper faces to the last cell.
  int locate(const double *p) const;
  // Cell index along `axis` containing coordinate x, clamped into [0, count - 1].
  int clamped_index(int axis, double x) const;
  // Flat cell index of (i, j, k).
  int flat(int i, int j, int k) const { return i + count[0] * (j + count[1] * k); }
  // Centre of cell index i along `axis`.
  double centre(int axis, int i) const { return origin[axis] + (i + 0.5) * spacing[axis]; }
};

}  // namespace tfdem

#endif
