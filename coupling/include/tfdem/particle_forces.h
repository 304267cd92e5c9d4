// Forces on single particles that do not depend on the gas solution.
#ifndef TFDEM_PARTICLE_FORCES_H
#define TFDEM_PARTICLE_FORCES_H

namespace tfdem {

// Force that cancels the fraction f of a particle's weight: F = -f m g (N).
// f = 1 makes a particle float under gravity g, f = 0.5 leaves it an acceleration g/2.
inline void scaled_weight_counterforce(double mass, const double gravity[3], double fraction,
                                       double force[3]) {
  for (int k = 0; k < 3; ++k) force[k] = -fraction * mass * gravity[k];
}

}  // namespace tfdem

#endif
