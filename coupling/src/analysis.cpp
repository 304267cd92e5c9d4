#include "tfdem/analysis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace tfdem::analysis {
namespace {

double norm3(const double *v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// Key of an integer bin triple for the hash grid.
long long bin_key(long long i, long long j, long long k) {
  constexpr long long kSpan = 1 << 20;
  return (i + kSpan / 2) + kSpan * ((j + kSpan / 2) + kSpan * (k + kSpan / 2));
}

bool touching(const ParticleView &p, std::size_t a, std::size_t b) {
  const double *x = p.position + 3 * a, *y = p.position + 3 * b;
  const double dx = x[0] - y[0], dy = x[1] - y[1], dz = x[2] - y[2];
  const double reach = 0.5 * (p.diameter[a] + p.diameter[b]);
  return dx * dx + dy * dy + dz * dz < reach * reach;
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> contact_pairs(const ParticleView &p) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  if (p.count == 0) return pairs;
  const double bin = *std::max_element(p.diameter, p.diameter + p.count);
  std::unordered_map<long long, std::vector<std::size_t>> bins;
  std::vector<long long> ijk(3 * p.count);
  for (std::size_t i = 0; i < p.count; ++i) {
    for (int a = 0; a < 3; ++a) ijk[3 * i + a] = static_cast<long long>(std::floor(p.position[3 * i + a] / bin));
    bins[bin_key(ijk[3 * i], ijk[3 * i + 1], ijk[3 * i + 2])].push_back(i);
  }
  for (std::size_t i = 0; i < p.count; ++i)
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj)
        for (int dk = -1; dk <= 1; ++dk) {
          const auto found = bins.find(bin_key(ijk[3 * i] + di, ijk[3 * i + 1] + dj, ijk[3 * i + 2] + dk));
          if (found == bins.end()) continue;
          for (std::size_t j : found->second)
            if (j > i && touching(p, i, j)) pairs.emplace_back(i, j);
        }
  return pairs;
}

std::vector<int> coordination_numbers(std::size_t n, const std::vector<std::pair<std::size_t, std::size_t>> &pairs) {
  std::vector<int> nc(n, 0);
  for (const auto &[i, j] : pairs) {
    ++nc.at(i);
    ++nc.at(j);
  }
  return nc;
}

double bulk_coordination_number(const std::vector<int> &nc) {
  if (nc.empty()) return 0.0;
  double sum = 0.0;
  for (int c : nc) sum += c;
  return sum / nc.size();
}

double multicontact_ratio(const std::vector<int> &nc) {
  const auto in_contact = std::count_if(nc.begin(), nc.end(), [](int c) { return c >= 1; });
  const auto multi = std::count_if(nc.begin(), nc.end(), [](int c) { return c > 1; });
  return in_contact == 0 ? 0.0 : static_cast<double>(multi) / in_contact;
}

double mean_height(const ParticleView &p, int axis, double base) {
  if (p.count == 0) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < p.count; ++i) sum += p.position[3 * i + axis] - base;
  return sum / p.count;
}

void ContactCounts::add(const ContactCounts &o) {
  particles += o.particles;
  contacts += o.contacts;
  in_contact += o.in_contact;
  multi += o.multi;
}

double ContactCounts::bulk_coordination() const { return particles > 0.0 ? contacts / particles : 0.0; }

double ContactCounts::multicontact() const { return in_contact > 0.0 ? multi / in_contact : 0.0; }

ContactCounts contact_counts(const int *nc, std::size_t count) {
  ContactCounts c;
  c.particles = static_cast<double>(count);
  for (std::size_t i = 0; i < count; ++i) {
    c.contacts += nc[i];
    c.in_contact += nc[i] >= 1 ? 1.0 : 0.0;
    c.multi += nc[i] > 1 ? 1.0 : 0.0;
  }
  return c;
}

void add_force_sums(const ParticleView &p, const int *cell_of_particle, const double *force, double gravity,
                    std::vector<double> &sums) {
  const std::size_t cell_count = sums.size() / 3;
  for (std::size_t i = 0; i < p.count; ++i) {
    const int c = cell_of_particle[i];
    if (c < 0 || static_cast<std::size_t>(c) >= cell_count) throw std::out_of_range("force map: particle in no cell");
    const double weight = sphere_volume(p.diameter[i]) * p.density[i] * gravity;
    for (int a = 0; a < 3; ++a) sums[3 * c + a] += force[3 * i + a] / weight;
  }
}

ForceMaps force_maps(const std::vector<double> &contact_sums, const std::vector<double> &drag_sums) {
  if (contact_sums.size() != drag_sums.size() || contact_sums.size() % 3 != 0)
    throw std::invalid_argument("force_maps: contact and drag sums need 3 values for each cell");
  const std::size_t cell_count = contact_sums.size() / 3;
  ForceMaps m;
  m.contact.resize(cell_count);
  m.drag.resize(cell_count);
  m.ratio.resize(cell_count);
  for (std::size_t c = 0; c < cell_count; ++c) {
    m.contact[c] = norm3(&contact_sums[3 * c]);
    m.drag[c] = norm3(&drag_sums[3 * c]);
    m.ratio[c] = m.drag[c] > 0.0 ? m.contact[c] / m.drag[c] : -1.0;
  }
  return m;
}

SegregationSums segregation_sums(const ParticleView &p, double size_threshold, int axis, double base) {
  SegregationSums s;
  for (std::size_t i = 0; i < p.count; ++i) {
    const double h = p.position[3 * i + axis] - base, v = sphere_volume(p.diameter[i]);
    if (p.diameter[i] > size_threshold) {
      s.height_large += h;
      s.volume_large += v;
      s.count_large += 1.0;
    } else {
      s.height_small += h;
      s.volume_small += v;
      s.count_small += 1.0;
    }
  }
  return s;
}

double segregation_degree(const SegregationSums &s) {
  if (s.count_small <= 0.0 || s.count_large <= 0.0)
    throw std::invalid_argument("segregation needs small and large particles");
  const double ratio = (s.height_small / s.count_small) / (s.height_large / s.count_large);
  const double x_large = s.volume_large / (s.volume_large + s.volume_small);
  const double ratio_max = (x_large + 1.0) / x_large;
  return (ratio - 1.0) / (ratio_max - 1.0);
}

void add_velocity_moments(const CellWeights &w, const ParticleView &p, std::vector<double> &moments) {
  for (std::size_t i = 0; i < p.count; ++i) {
    const double v = sphere_volume(p.diameter[i]);
    const double *u = p.velocity + 3 * i;
    const double speed_sq = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    for (std::size_t k = w.offsets[i]; k < w.offsets[i + 1]; ++k) {
      double *m = &moments[kVelocityMoments * static_cast<std::size_t>(w.cells[k])];
      const double wv = w.weights[k] * v;
      m[0] += wv;
      for (int a = 0; a < 3; ++a) m[1 + a] += wv * u[a];
      m[4] += wv * speed_sq;
    }
  }
}

std::vector<double> granular_temperature(const std::vector<double> &moments) {
  const std::size_t cells = moments.size() / kVelocityMoments;
  std::vector<double> theta(cells, 0.0);
  for (std::size_t c = 0; c < cells; ++c) {
    const double *m = &moments[kVelocityMoments * c];
    if (m[0] <= 0.0) continue;
    const double mean_sq = (m[1] * m[1] + m[2] * m[2] + m[3] * m[3]) / (m[0] * m[0]);
    theta[c] = std::max(0.0, m[4] / m[0] - mean_sq) / 3.0;  // <|v|^2> - |v_sm|^2
  }
  return theta;
}

std::vector<double> granular_temperature(const CellWeights &w, const ParticleView &p, std::size_t cell_count) {
  std::vector<double> moments(kVelocityMoments * cell_count, 0.0);
  add_velocity_moments(w, p, moments);
  return granular_temperature(moments);
}

void TimeAverage::add(const std::vector<double> &field, double dt) {
  if (sum_.empty()) sum_.assign(field.size(), 0.0);
  if (field.size() != sum_.size()) throw std::invalid_argument("TimeAverage: field size changed");
  if (!(dt > 0.0)) throw std::invalid_argument("TimeAverage: dt must be > 0");
  for (std::size_t i = 0; i < field.size(); ++i) sum_[i] += field[i] * dt;
  duration_ += dt;
}

std::vector<double> TimeAverage::mean() const {
  if (duration_ <= 0.0) throw std::logic_error("TimeAverage: no sample yet");
  std::vector<double> out(sum_);
  for (double &v : out) v /= duration_;
  return out;
}

}  // namespace tfdem::analysis
