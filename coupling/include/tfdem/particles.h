// Flat views of particle and cell data shared by the coupling core's modules.
#ifndef TFDEM_PARTICLES_H
#define TFDEM_PARTICLES_H

#include <cstddef>

namespace tfdem {

// Read-only view of N particles: positions and velocities are 3N arrays (x0 y0 z0 x1 ...),
// diameters and densities N arrays, all SI. Nothing is owned.
struct ParticleView {
  std::size_t count = 0;
  const double *position = nullptr;
  const double *velocity = nullptr;
  const double *diameter = nullptr;
  const double *density = nullptr;
};

constexpr double kPi = 3.14159265358979323846;

// Volume of a sphere of diameter d: pi d^3 / 6.
inline double sphere_volume(double diameter) { return kPi * diameter * diameter * diameter / 6.0; }

}  // namespace tfdem

#endif
