// Analyses behind the paper's figures (seed 000 Fig. 5-13, seed 001 eq. 49).
#ifndef TFDEM_ANALYSIS_H
#define TFDEM_ANALYSIS_H

#include <cstddef>
#include <utility>
#include <vector>

#include "tfdem/particles.h"
#include "tfdem/void_fraction.h"

namespace tfdem::analysis {

// Pairs (i < j) of touching particles: overlap (d_i + d_j)/2 - |r_i - r_j| > 0 (seed 000
// eq. 17), found with a bin grid of the largest diameter (O(N)).
std::vector<std::pair<std::size_t, std::size_t>> contact_pairs(const ParticleView &particles);

// N_c of every particle: its number of touching neighbours (seed 000, Fig. 6).
std::vector<int> coordination_numbers(std::size_t particle_count,
                                      const std::vector<std::pair<std::size_t, std::size_t>> &pairs);

// Bulk coordination number: mean N_c over all particles (seed 000 Fig. 5).
double bulk_coordination_number(const std::vector<int> &coordination);

// Multicontact ratio: particles with N_c > 1 over particles with N_c >= 1 (seed 000
// Fig. 11); 0 when no particle touches another.
double multicontact_ratio(const std::vector<int> &coordination);

// Mean particle height: arithmetic mean of the coordinate along `axis` above `base`
// (seed 000 Fig. 9).
double mean_height(const ParticleView &particles, int axis, double base);

// Per-cell force maps of seed 000 Fig. 7 and 12: sums of |contact force| and |drag force| of
// the particles whose centre is in the cell, each divided by its weight m_i g, and their
// ratio (contact / drag; -1 where the drag sum is zero, as the paper's legend).
struct ForceMaps {
  std::vector<double> contact, drag, ratio;
};
ForceMaps force_maps(const ParticleView &particles, const int *cell_of_particle, std::size_t cell_count,
                     const double *contact_force, const double *drag_force, double gravity);

// Degree of segregation s = (S - 1)/(S_max - 1), S = <h_small>/<h_large>,
// S_max = (x_large + 1)/x_large with x_large the volume fraction of large particles
// (seed 001 eq. 49): 0 mixed, 1 segregated. `is_large` flags each particle.
double segregation_degree(const ParticleView &particles, const std::vector<bool> &is_large, int axis, double base);

// Granular temperature per cell, theta = <|v - v_sm|^2> / 3 (seed 000 eq. 6), volume-
// weighted with the mapping weights; 0 in empty cells.
std::vector<double> granular_temperature(const CellWeights &weights, const ParticleView &particles,
                                         std::size_t cell_count);

// Time average of a cell field: sum of field * dt over sum of dt.
class TimeAverage {
 public:
  // Add one sample of `field` (size fixed by the first sample) held for duration dt.
  void add(const std::vector<double> &field, double dt);
  // The average so far; throws std::logic_error before any sample.
  std::vector<double> mean() const;
  double duration() const { return duration_; }

 private:
  std::vector<double> sum_;
  double duration_ = 0.0;
};

}  // namespace tfdem::analysis

#endif
