// The particles a coupled run starts from, checked before the DEM moves them: values that are
// not numbers, centres that coincide (LIGGGHTS divides by the distance between them and stops
// on a floating-point exception), and the overlaps the packing holds, whose stored elastic
// energy throws a squeezed bed apart as soon as it runs.
#ifndef TFDEM_PACKING_CHECK_H
#define TFDEM_PACKING_CHECK_H

#include <cstddef>
#include <utility>
#include <vector>

#include "tfdem/particles.h"

namespace tfdem {

struct PackingCheck {
  // Indices of particles with a NaN or infinite position, velocity or diameter
  std::vector<std::size_t> not_finite;
  // Pairs (i < j) whose centres lie closer than kCoincident of the smaller diameter
  std::vector<std::pair<std::size_t, std::size_t>> coincident;
  // Every overlapping pair: depth (d_i + d_j)/2 - |x_i - x_j| > 0 (seed 000 eq. 17)
  struct Overlap {
    std::size_t a = 0, b = 0;
    double depth = 0;
  };
  std::vector<Overlap> overlaps;
};

constexpr double kCoincident = 1e-9;

// Non-finite particles are left out of the pair search (their pairs are meaningless).
PackingCheck check_packing(const ParticleView &particles);

}  // namespace tfdem

#endif
