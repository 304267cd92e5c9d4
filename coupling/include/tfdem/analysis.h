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

// Contact statistics of a set of particles from their N_c, additive over sets (MPI ranks).
struct ContactCounts {
  double particles = 0.0;   // particles counted
  double contacts = 0.0;    // sum of N_c (each touching pair counted once per particle)
  double in_contact = 0.0;  // particles with N_c >= 1
  double multi = 0.0;       // particles with N_c > 1
  void add(const ContactCounts &other);
  // Bulk coordination number, sum N_c / N (seed 000 Fig. 5); 0 without particles.
  double bulk_coordination() const;
  // Multicontact ratio, N(N_c > 1) / N(N_c >= 1) (seed 000 Fig. 11); 0 when none touches.
  double multicontact() const;
};
ContactCounts contact_counts(const int *coordination, std::size_t count);

// Per-cell sums of seed 000 Fig. 7 and 12, scaled by particle weight: S_c += f_i / (m_i g)
// over the particles i whose centre is in cell c (cell_of_particle[i]); 3 values per cell
// in `sums`, which must hold 3 cell_count values (added to, so ranks can each add theirs).
void add_force_sums(const ParticleView &particles, const int *cell_of_particle, const double *force, double gravity,
                    std::vector<double> &sums);

// The paper's maps from completed sums: |S_c| of the contact and the drag sums (the
// magnitude of the cell's summed force, not the sum of magnitudes) and their ratio
// contact / drag (-1 where the drag sum is zero, as the paper's legend).
struct ForceMaps {
  std::vector<double> contact, drag, ratio;
};
ForceMaps force_maps(const std::vector<double> &contact_sums, const std::vector<double> &drag_sums);

// Degree of segregation of a bidisperse bed (seed 001 eq. 49): s = (S - 1)/(S_max - 1),
// S = <h_small>/<h_large>, S_max = (x_large + 1)/x_large with x_large the volume fraction of
// large particles: 0 mixed, 1 segregated (small on top). Particles with d > size_threshold are
// large; h is the height along `axis` above `base`. The sums are additive over ranks:
// heights, volumes and counts of the small then the large particles.
struct SegregationSums {
  double height_small = 0.0, height_large = 0.0;
  double volume_small = 0.0, volume_large = 0.0;
  double count_small = 0.0, count_large = 0.0;
  static constexpr int kComponents = 6;
  double *data() { return &height_small; }
  const double *data() const { return &height_small; }
};
SegregationSums segregation_sums(const ParticleView &particles, double size_threshold, int axis, double base);
// s from completed sums; throws std::invalid_argument when one size is absent.
double segregation_degree(const SegregationSums &sums);

// Per-cell velocity moments behind the granular temperature, kVelocityMoments values per
// cell: sum w V_i, sum w V_i v_i (3), sum w V_i |v_i|^2 over the particles i in the cell with
// their mapping weights w and volumes V_i. Added to `moments` (kVelocityMoments cell_count
// values), so that ranks can each add theirs and sum them.
constexpr int kVelocityMoments = 5;
void add_velocity_moments(const CellWeights &weights, const ParticleView &particles, std::vector<double> &moments);

// Granular temperature per cell from summed moments, theta = <|v - v_sm|^2> / 3 (seed 000
// eq. 6, the kinetic theory's Theta): volume-weighted <|v|^2> - |v_sm|^2 over 3; 0 in empty
// cells. A cell with one particle has theta 0 (no fluctuation about its own mean).
std::vector<double> granular_temperature(const std::vector<double> &moments);

// The same on one rank: the moments of `particles` on `cell_count` cells.
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
