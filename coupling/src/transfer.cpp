#include "tfdem/transfer.h"

#include <cmath>
#include <stdexcept>

#include "tfdem/suggest.h"

namespace tfdem {
namespace {

double norm3(const double *v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// Per-cell particle statistics: solid volume (eq. 34 numerator), volume-weighted velocity sum
// (eq. 35 numerator) and the Sauter-mean diameter sums.
struct CellSolids {
  std::vector<double> volume, momentum, d3, d2;
  explicit CellSolids(std::size_t n) : volume(n, 0.0), momentum(3 * n, 0.0), d3(n, 0.0), d2(n, 0.0) {}
};

CellSolids accumulate_solids(const CellWeights &w, const ParticleView &p, std::size_t cell_count) {
  CellSolids s(cell_count);
  for (std::size_t i = 0; i < p.count; ++i) {
    const double d = p.diameter[i], v = sphere_volume(d);
    for (std::size_t k = w.offsets[i]; k < w.offsets[i + 1]; ++k) {
      const int c = w.cells[k];
      const double wv = w.weights[k] * v;
      s.volume[c] += wv;
      for (int a = 0; a < 3; ++a) s.momentum[3 * c + a] += wv * p.velocity[3 * i + a];
      s.d3[c] += w.weights[k] * d * d * d;
      s.d2[c] += w.weights[k] * d * d;
    }
  }
  return s;
}

// Averaged gas sink (eq. 33 with eq. 35): K_c = beta_c, U_s,c = v_sm,c.
void averaged_gas_side(const CellSolids &s, const CellGas &cells, const TransferOptions &o, TransferResult &r) {
  for (std::size_t c = 0; c < cells.cell_count; ++c) {
    if (s.volume[c] <= 0.0) continue;
    double v_sm[3], slip[3];
    for (int a = 0; a < 3; ++a) {
      v_sm[a] = s.momentum[3 * c + a] / s.volume[c];
      slip[a] = cells.velocity[3 * c + a] - v_sm[a];
      r.cell_solid_velocity[3 * c + a] = v_sm[a];
    }
    const double sauter = s.d3[c] / s.d2[c];
    r.cell_coefficient[c] = drag::beta(o.law, {cells.gas_fraction[c], sauter, norm3(slip)}, o.gas);
  }
}

// Averaged particle drag: the cell's drag V_c K_c (u_c - v_sm) shared by volume.
void averaged_particle_side(const CellWeights &w, const ParticleView &p, const CellSolids &s,
                            const CellGas &cells, TransferResult &r) {
  for (std::size_t i = 0; i < p.count; ++i) {
    const double v = sphere_volume(p.diameter[i]);
    for (std::size_t k = w.offsets[i]; k < w.offsets[i + 1]; ++k) {
      const int c = w.cells[k];
      const double share = w.weights[k] * v / s.volume[c] * cells.volume[c] * r.cell_coefficient[c];
      for (int a = 0; a < 3; ++a)
        r.particle_drag[3 * i + a] += share * (cells.velocity[3 * c + a] - r.cell_solid_velocity[3 * c + a]);
    }
  }
}

// Per-particle drag (eq. 29): V_i beta_i / eps_s,i (u_g,i - v_i); returns V_i beta_i/eps_s,i per particle.
std::vector<double> per_particle_drag(const ParticleView &p, const GasAtParticles &g, const TransferOptions &o,
                                      TransferResult &r) {
  std::vector<double> coefficient(p.count);
  for (std::size_t i = 0; i < p.count; ++i) {
    double slip[3];
    for (int a = 0; a < 3; ++a) slip[a] = g.velocity[3 * i + a] - p.velocity[3 * i + a];
    const double d = p.diameter[i];
    coefficient[i] = sphere_volume(d) * drag::beta_per_solid_fraction(o.law, {g.gas_fraction[i], d, norm3(slip)}, o.gas);
    for (int a = 0; a < 3; ++a) r.particle_drag[3 * i + a] = coefficient[i] * slip[a];
  }
  return coefficient;
}

// Conservative gas sink: K_c = sum_i w_ic V_i beta_i/eps_s,i / V_c and U_s,c chosen so that
// V_c K_c (u_c - U_s,c) = sum_i w_ic f_i exactly.
void conservative_gas_side(const CellWeights &w, const std::vector<double> &coefficient, const CellGas &cells,
                           TransferResult &r) {
  std::vector<double> force_sum(3 * cells.cell_count, 0.0);
  for (std::size_t i = 0; i < coefficient.size(); ++i)
    for (std::size_t k = w.offsets[i]; k < w.offsets[i + 1]; ++k) {
      const int c = w.cells[k];
      r.cell_coefficient[c] += w.weights[k] * coefficient[i];
      for (int a = 0; a < 3; ++a) force_sum[3 * c + a] += w.weights[k] * r.particle_drag[3 * i + a];
    }
  for (std::size_t c = 0; c < cells.cell_count; ++c) {
    if (r.cell_coefficient[c] <= 0.0) continue;
    const double total = r.cell_coefficient[c];  // sum of V_i beta_i/eps_s,i shares (N s/m)
    r.cell_coefficient[c] = total / cells.volume[c];
    for (int a = 0; a < 3; ++a)
      r.cell_solid_velocity[3 * c + a] = cells.velocity[3 * c + a] - force_sum[3 * c + a] / total;
  }
}

// Fluid force of eq. 28 and the momentum bookkeeping.
void finish(const ParticleView &p, const CellGas &cells, const GasAtParticles &g, TransferResult &r) {
  r.particle_force = r.particle_drag;
  for (std::size_t i = 0; i < p.count; ++i) {
    const double v = sphere_volume(p.diameter[i]);
    for (int a = 0; a < 3; ++a) {
      if (g.pressure_gradient) r.particle_force[3 * i + a] -= v * g.pressure_gradient[3 * i + a];
      if (g.viscous_stress_divergence) r.particle_force[3 * i + a] += v * g.viscous_stress_divergence[3 * i + a];
      r.momentum_imbalance[a] += r.particle_drag[3 * i + a];
    }
    r.drag_magnitude_sum += norm3(&r.particle_drag[3 * i]);
  }
  for (std::size_t c = 0; c < cells.cell_count; ++c)
    for (int a = 0; a < 3; ++a)
      r.momentum_imbalance[a] -= cells.volume[c] * r.cell_coefficient[c] *
                                 (cells.velocity[3 * c + a] - r.cell_solid_velocity[3 * c + a]);
}

}  // namespace

const std::vector<std::string> &transfer_method_names() {
  static const std::vector<std::string> names = {"averaged", "per_particle", "per_particle_conservative"};
  return names;
}

TransferMethod transfer_method_from_name(const std::string &name) {
  return static_cast<TransferMethod>(index_of_name(name, transfer_method_names(), "transfer method"));
}

void transfer(const CellWeights &weights, const ParticleView &particles, const CellGas &cells,
              const GasAtParticles &at_particles, const TransferOptions &options, TransferResult &r) {
  if (weights.particle_count() != particles.count)
    throw std::invalid_argument("transfer: weights are for a different number of particles");
  r.momentum_imbalance = {0.0, 0.0, 0.0};
  r.drag_magnitude_sum = 0.0;
  r.particle_drag.assign(3 * particles.count, 0.0);
  r.cell_coefficient.assign(cells.cell_count, 0.0);
  r.cell_solid_velocity.assign(3 * cells.cell_count, 0.0);
  if (options.method == TransferMethod::PerParticleConservative) {
    conservative_gas_side(weights, per_particle_drag(particles, at_particles, options, r), cells, r);
  } else {
    const CellSolids solids = accumulate_solids(weights, particles, cells.cell_count);
    averaged_gas_side(solids, cells, options, r);
    if (options.method == TransferMethod::Averaged)
      averaged_particle_side(weights, particles, solids, cells, r);
    else
      per_particle_drag(particles, at_particles, options, r);
  }
  finish(particles, cells, at_particles, r);
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
