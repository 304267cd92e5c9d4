#include "tfdem/transfer.h"

#include <cmath>
#include <stdexcept>

#include "tfdem/suggest.h"

namespace tfdem {
namespace {

double norm3(const double *v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// Sauter mean diameter sum w d^3 / sum w d^2 of one cell's solid sums (0 when empty).
double sauter_of(const double *sums) { return sums[5] > 0.0 ? sums[4] / sums[5] : 0.0; }

// Averaged particle drag: the cell's drag V_c K_c (u_c - v_sm) shared by volume.
void averaged_particle_drag(const CellWeights &w, const ParticleView &p, const CellSolidsState &cells,
                            TransferResult &r) {
  const CellGas &gas = cells.gas;
  for (std::size_t i = 0; i < p.count; ++i) {
    const double v = sphere_volume(p.diameter[i]);
    for (std::size_t k = w.offsets[i]; k < w.offsets[i + 1]; ++k) {
      const int c = w.cells[k];
      const double share = w.weights[k] * v / cells.solid_volume[c] * gas.volume[c] * cells.exchange_coefficient[c];
      for (int a = 0; a < 3; ++a)
        r.particle_drag[3 * i + a] += share * (gas.velocity[3 * c + a] - cells.solid_velocity[3 * c + a]);
    }
  }
}

// beta_i/eps_s of particle i (diameter d) seeing gas fraction eps and slip speed `slip`; under
// Beetstra2007 the law is evaluated at the local Sauter mean `sauter` and corrected for y = d/<d>.
double particle_beta_per_solid_fraction(const TransferOptions &o, double eps, double d, double sauter, double slip) {
  if (o.polydispersity == drag::Polydispersity::OwnDiameter)
    return drag::beta_per_solid_fraction(o.law, {eps, d, slip}, o.gas);
  return drag::beta_per_solid_fraction(o.law, {eps, sauter, slip}, o.gas) * drag::polydisperse_factor(eps, d / sauter);
}

// Per-particle drag (eq. 29): V_i beta_i / eps_s,i (u_g,i - v_i); returns V_i beta_i/eps_s,i per particle.
std::vector<double> per_particle_drag(const CellWeights &w, const ParticleView &p, const CellSolidsState &cells,
                                      const GasAtParticles &g, const TransferOptions &o, TransferResult &r) {
  const bool polydisperse = o.polydispersity != drag::Polydispersity::OwnDiameter;
  if (polydisperse && p.count > 0 && !cells.sauter_diameter)
    throw std::invalid_argument("transfer: polydisperse drag needs the cells' Sauter diameters");
  const std::vector<double> sauter = polydisperse ? average_to_particles(w, cells.sauter_diameter, 1) : std::vector<double>();
  std::vector<double> exchange_coefficient(p.count);
  for (std::size_t i = 0; i < p.count; ++i) {
    double slip[3];
    for (int a = 0; a < 3; ++a) slip[a] = g.velocity[3 * i + a] - p.velocity[3 * i + a];
    const double d = p.diameter[i];
    exchange_coefficient[i] = sphere_volume(d) * particle_beta_per_solid_fraction(
                                                     o, g.void_fraction[i], d, polydisperse ? sauter[i] : d, norm3(slip));
    for (int a = 0; a < 3; ++a) r.particle_drag[3 * i + a] = exchange_coefficient[i] * slip[a];
  }
  return exchange_coefficient;
}

// Fluid force of eq. 28 and the particle part of the momentum bookkeeping.
void particle_force(const ParticleView &p, const GasAtParticles &g, TransferResult &r) {
  r.particle_force = r.particle_drag;
  r.momentum_imbalance = {0.0, 0.0, 0.0};
  r.drag_magnitude_sum = 0.0;
  for (std::size_t i = 0; i < p.count; ++i) {
    const double v = sphere_volume(p.diameter[i]);
    for (int a = 0; a < 3; ++a) {
      if (g.pressure_gradient) r.particle_force[3 * i + a] -= v * g.pressure_gradient[3 * i + a];
      if (g.viscous_stress_divergence) r.particle_force[3 * i + a] += v * g.viscous_stress_divergence[3 * i + a];
      r.momentum_imbalance[a] += r.particle_drag[3 * i + a];
    }
    r.drag_magnitude_sum += norm3(&r.particle_drag[3 * i]);
  }
}

}  // namespace

const std::vector<std::string> &transfer_method_names() {
  static const std::vector<std::string> names = {"averaged", "per_particle", "per_particle_conservative"};
  return names;
}

const std::vector<std::string> &gas_at_particle_names() {
  static const std::vector<std::string> names = {"cell", "interpolated"};
  return names;
}

TransferMethod transfer_method_from_name(const std::string &name) {
  return static_cast<TransferMethod>(index_of_name(name, transfer_method_names(), "transfer method"));
}

void accumulate_solid_sums(const CellWeights &w, const ParticleView &p, std::size_t cell_count,
                           std::vector<double> &sums) {
  constexpr int n = kSolidSumComponents;
  sums.assign(n * cell_count, 0.0);
  for (std::size_t i = 0; i < p.count; ++i) {
    const double d = p.diameter[i], v = sphere_volume(d);
    for (std::size_t k = w.offsets[i]; k < w.offsets[i + 1]; ++k) {
      double *s = &sums[n * w.cells[k]];
      const double wv = w.weights[k] * v;
      s[0] += wv;
      for (int a = 0; a < 3; ++a) s[1 + a] += wv * p.velocity[3 * i + a];
      s[4] += w.weights[k] * d * d * d;
      s[5] += w.weights[k] * d * d;
    }
  }
}

void map_void_fraction_from_sums(const std::vector<double> &sums, const std::vector<double> &cell_volume,
                                double floor, VoidFraction &out) {
  const std::size_t n = cell_volume.size();
  if (sums.size() != kSolidSumComponents * n)
    throw std::invalid_argument("map_void_fraction_from_sums: sums are for a different number of cells");
  out.solid_volume.resize(n);
  for (std::size_t c = 0; c < n; ++c) out.solid_volume[c] = sums[kSolidSumComponents * c];
  void_fraction_from_solid_volume(cell_volume, floor, out);
}

void averaged_cell_drag(const std::vector<double> &sums, const CellGas &cells, const TransferOptions &o,
                        double *exchange_coefficient, double *solid_velocity) {
  for (std::size_t c = 0; c < cells.cell_count; ++c) {
    const double *s = &sums[kSolidSumComponents * c];
    exchange_coefficient[c] = 0.0;
    for (int a = 0; a < 3; ++a) solid_velocity[3 * c + a] = 0.0;
    if (s[0] <= 0.0) continue;
    double slip[3];
    for (int a = 0; a < 3; ++a) {
      solid_velocity[3 * c + a] = s[1 + a] / s[0];
      slip[a] = cells.velocity[3 * c + a] - solid_velocity[3 * c + a];
    }
    exchange_coefficient[c] = drag::beta(o.law, {cells.void_fraction[c], sauter_of(s), norm3(slip)}, o.gas);
  }
}

void sauter_diameters(const std::vector<double> &sums, std::size_t cell_count, double *sauter_diameter) {
  for (std::size_t c = 0; c < cell_count; ++c) sauter_diameter[c] = sauter_of(&sums[kSolidSumComponents * c]);
}

std::vector<double> particle_drag_and_force(const CellWeights &weights, const ParticleView &particles,
                                            const CellSolidsState &cells, const GasAtParticles &at_particles,
                                            const TransferOptions &options, TransferResult &r) {
  if (weights.particle_count() != particles.count)
    throw std::invalid_argument("transfer: weights are for a different number of particles");
  r.particle_drag.assign(3 * particles.count, 0.0);
  std::vector<double> exchange_coefficient;
  if (options.method == TransferMethod::Averaged)
    averaged_particle_drag(weights, particles, cells, r);
  else
    exchange_coefficient = per_particle_drag(weights, particles, cells, at_particles, options, r);
  particle_force(particles, at_particles, r);
  return exchange_coefficient;
}

void accumulate_conservative_sums(const CellWeights &w, const std::vector<double> &particle_exchange_coefficient,
                                  const std::vector<double> &particle_drag, std::size_t cell_count,
                                  std::vector<double> &sums) {
  constexpr int n = kConservativeSumComponents;
  sums.assign(n * cell_count, 0.0);
  for (std::size_t i = 0; i < particle_exchange_coefficient.size(); ++i)
    for (std::size_t k = w.offsets[i]; k < w.offsets[i + 1]; ++k) {
      double *s = &sums[n * w.cells[k]];
      s[0] += w.weights[k] * particle_exchange_coefficient[i];
      for (int a = 0; a < 3; ++a) s[1 + a] += w.weights[k] * particle_drag[3 * i + a];
    }
}

void conservative_cell_drag(const std::vector<double> &sums, const CellGas &cells, double *exchange_coefficient,
                            double *solid_velocity) {
  for (std::size_t c = 0; c < cells.cell_count; ++c) {
    const double *s = &sums[kConservativeSumComponents * c];
    const double total = s[0];  // sum of V_i beta_i/eps_s,i shares (N s/m)
    exchange_coefficient[c] = 0.0;
    for (int a = 0; a < 3; ++a) solid_velocity[3 * c + a] = 0.0;
    if (total <= 0.0) continue;
    exchange_coefficient[c] = total / cells.volume[c];
    for (int a = 0; a < 3; ++a) solid_velocity[3 * c + a] = cells.velocity[3 * c + a] - s[1 + a] / total;
  }
}

std::array<double, 3> gas_drag_sink(const CellGas &cells, const double *exchange_coefficient, const double *solid_velocity) {
  std::array<double, 3> sink{0.0, 0.0, 0.0};
  for (std::size_t c = 0; c < cells.cell_count; ++c)
    for (int a = 0; a < 3; ++a)
      sink[a] += cells.volume[c] * exchange_coefficient[c] * (cells.velocity[3 * c + a] - solid_velocity[3 * c + a]);
  return sink;
}

void transfer(const CellWeights &weights, const ParticleView &particles, const CellGas &cells,
              const GasAtParticles &at_particles, const TransferOptions &options, TransferResult &r) {
  if (weights.particle_count() != particles.count)
    throw std::invalid_argument("transfer: weights are for a different number of particles");
  const std::size_t n = cells.cell_count;
  r.cell_exchange_coefficient.assign(n, 0.0);
  r.cell_solid_velocity.assign(3 * n, 0.0);
  std::vector<double> sums;
  accumulate_solid_sums(weights, particles, n, sums);
  const bool conservative = options.method == TransferMethod::PerParticleConservative;
  if (!conservative) averaged_cell_drag(sums, cells, options, r.cell_exchange_coefficient.data(), r.cell_solid_velocity.data());
  std::vector<double> solid_volume(n), sauter(n);
  for (std::size_t c = 0; c < n; ++c) solid_volume[c] = sums[kSolidSumComponents * c];
  sauter_diameters(sums, n, sauter.data());
  const CellSolidsState state{cells, solid_volume.data(), r.cell_exchange_coefficient.data(),
                              r.cell_solid_velocity.data(), sauter.data()};
  const std::vector<double> exchange_coefficient =
      particle_drag_and_force(weights, particles, state, at_particles, options, r);
  if (conservative) {
    accumulate_conservative_sums(weights, exchange_coefficient, r.particle_drag, n, sums);
    conservative_cell_drag(sums, cells, r.cell_exchange_coefficient.data(), r.cell_solid_velocity.data());
  }
  const std::array<double, 3> sink = gas_drag_sink(cells, r.cell_exchange_coefficient.data(), r.cell_solid_velocity.data());
  for (int a = 0; a < 3; ++a) r.momentum_imbalance[a] -= sink[a];
}

TransferResult transfer(const CellWeights &weights, const ParticleView &particles, const CellGas &cells,
                        const GasAtParticles &at_particles, const TransferOptions &options) {
  TransferResult r;
  transfer(weights, particles, cells, at_particles, options, r);
  return r;
}

std::vector<double> average_to_particles(const CellWeights &weights, const double *cell_field, int components) {
  const std::size_t n = weights.particle_count();
  std::vector<double> out(components * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = weights.offsets[i]; k < weights.offsets[i + 1]; ++k)
      for (int a = 0; a < components; ++a)
        out[components * i + a] += weights.weights[k] * cell_field[components * weights.cells[k] + a];
  return out;
}

}  // namespace tfdem
