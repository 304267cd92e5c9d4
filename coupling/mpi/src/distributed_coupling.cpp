#include "tfdem/distributed_coupling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tfdem {

namespace {

// Per owned cell, what a particle rank fetches: u_g (3), eps_g, K_c, U_s,c (3), solid volume,
// V_c, grad p (3), Sauter diameter.
constexpr int kStateComponents = 14;

// Throw the same std::out_of_range on every rank when `message` is set on any of them (the
// lowest such rank's message), so no rank is left waiting in a collective call.
void throw_if_any_rank_failed(MPI_Comm comm, const std::string &message) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int mine = message.empty() ? size : rank;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  std::string text = message;
  text.resize(length);
  MPI_Bcast(text.data(), length, MPI_CHAR, first, comm);
  throw std::out_of_range(text);
}

}  // namespace

DistributedCoupling::DistributedCoupling(MPI_Comm comm, const CartesianGrid &grid, std::vector<int> owner_of_cell,
                                         const std::vector<int> &owned_cells, std::vector<double> owned_volume,
                                         const VoidFractionOptions &void_fraction, const TransferOptions &transfer)
    : comm_(comm),
      grid_(grid),
      exchange_(comm, std::move(owner_of_cell), owned_cells),
      owned_cells_(owned_cells),
      owned_volume_(std::move(owned_volume)),
      void_fraction_(void_fraction),
      transfer_(transfer) {
  if (owned_volume_.size() != owned_cells.size())
    throw std::invalid_argument("DistributedCoupling: one volume per owned cell expected");
  if (void_fraction_.filters())
    filter_.emplace(grid_, void_fraction_.diffusion_bandwidth, void_fraction_.particle_field_block);
  scratch_.assign(grid_.cell_count(), -1);
  exchange_coefficient_.assign(owned_volume_.size(), 0.0);
  solid_velocity_.assign(3 * owned_volume_.size(), 0.0);
}

bool DistributedCoupling::adds_cell_totals() const {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  return !exchange_.every_rank_holds_every_cell() || rank == 0;
}

void DistributedCoupling::sum_over_ranks(double *values, int count) const {
  MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, MPI_SUM, comm_);
}

void DistributedCoupling::filter_owned(std::vector<double> &owned, int components, bool adjoint) {
  if (!filter_) return;
  grid_sums_.assign(static_cast<std::size_t>(components) * grid_.cell_count(), 0.0);
  for (std::size_t c = 0; c < owned_cells_.size(); ++c)
    std::copy_n(&owned[components * c], components, &grid_sums_[components * static_cast<std::size_t>(owned_cells_[c])]);
  if (!exchange_.every_rank_holds_every_cell())  // one owner per cell: the others add zeros
    sum_over_ranks(grid_sums_.data(), static_cast<int>(grid_sums_.size()));
  if (adjoint)
    filter_->apply_adjoint(grid_sums_.data(), components, filter_scratch_);
  else
    filter_->apply(grid_sums_.data(), components, filter_scratch_);
  for (std::size_t c = 0; c < owned_cells_.size(); ++c)
    std::copy_n(&grid_sums_[components * static_cast<std::size_t>(owned_cells_[c])], components, &owned[components * c]);
}

void DistributedCoupling::map(const ParticleView &particles) {
  std::string failure;
  try {
    compute_weights(grid_, particles, void_fraction_, weights_);
  } catch (const std::out_of_range &e) {
    failure = e.what();
  }
  throw_if_any_rank_failed(comm_, failure);
  if (interpolates_gas_velocity()) add_interpolation_stencils(grid_, particles, weights_);
  halo_cells_ = compact_cells(weights_, scratch_);
  exchange_.set_halo(halo_cells_);
  accumulate_solid_sums(weights_, particles, halo_cells_.size(), halo_sums_);
  exchange_.sum_to_owners(halo_sums_, kSolidSumComponents, owned_sums_);
  filter_owned(owned_sums_, kSolidSumComponents);
  map_void_fraction_from_sums(owned_sums_, owned_volume_, void_fraction_.void_fraction_floor, gas_);

  totals_.particle_volume = 0.0;
  for (std::size_t i = 0; i < particles.count; ++i) totals_.particle_volume += sphere_volume(particles.diameter[i]);
  totals_.mapped_volume = 0.0;
  double floored_volumes[2] = {0.0, 0.0};
  if (adds_cell_totals()) {
    for (std::size_t c = 0; c < owned_volume_.size(); ++c) totals_.mapped_volume += gas_.solid_volume[c];
    floored_volumes[0] = gas_.floored_solid_volume;
    floored_volumes[1] = gas_.removed_solid_volume;
  }
  double volumes[4] = {totals_.particle_volume, totals_.mapped_volume, floored_volumes[0], floored_volumes[1]};
  sum_over_ranks(volumes, 4);
  totals_.particle_volume = volumes[0];
  totals_.mapped_volume = volumes[1];
  totals_.floored_solid_volume = volumes[2];
  totals_.removed_solid_volume = volumes[3];
  unsigned long floored = adds_cell_totals() ? gas_.floored_cells : 0;
  MPI_Allreduce(MPI_IN_PLACE, &floored, 1, MPI_UNSIGNED_LONG, MPI_SUM, comm_);
  totals_.floored_cells = floored;
  struct {
    double value;
    int cell;
  } lowest{gas_.lowest_unfloored, gas_.lowest_cell < 0 ? -1 : owned_cells_[gas_.lowest_cell]};
  MPI_Allreduce(MPI_IN_PLACE, &lowest, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm_);
  totals_.lowest_unfloored = lowest.value;
  totals_.lowest_cell = lowest.cell;
}

std::vector<std::size_t> DistributedCoupling::particles_in_cell(int g) const {
  std::vector<std::size_t> found;
  for (std::size_t p = 0; p < weights_.particle_count(); ++p)
    for (std::size_t k = weights_.offsets[p]; k < weights_.offsets[p + 1]; ++k)
      if (halo_cells_[weights_.cells[k]] == g && weights_.weights[k] > 0.0) {
        found.push_back(p);
        break;
      }
  return found;
}

bool DistributedCoupling::interpolates_gas_velocity() const {
  return transfer_.gas_velocity == GasAtParticle::Interpolated && transfer_.method != TransferMethod::Averaged;
}

std::vector<double> DistributedCoupling::interpolated_velocity(const ParticleView &particles) {
  grid_velocity_.resize(3 * static_cast<std::size_t>(grid_.cell_count()));
  for (std::size_t h = 0; h < halo_cells_.size(); ++h)
    for (int a = 0; a < 3; ++a) grid_velocity_[3 * halo_cells_[h] + a] = halo_.velocity[3 * h + a];
  std::vector<double> out(3 * particles.count);
  for (std::size_t i = 0; i < particles.count; ++i)
    interpolate(grid_, grid_velocity_.data(), 3, particles.position + 3 * i, &out[3 * i]);
  return out;
}

void DistributedCoupling::pack_owned_state(const double *gas_velocity, const double *pressure_gradient) {
  const std::size_t owned = owned_volume_.size();
  owned_state_.resize(kStateComponents * owned);
  for (std::size_t c = 0; c < owned; ++c) {
    double *s = &owned_state_[kStateComponents * c];
    for (int a = 0; a < 3; ++a) {
      s[a] = gas_velocity[3 * c + a];
      s[5 + a] = solid_velocity_[3 * c + a];
      s[10 + a] = pressure_gradient ? pressure_gradient[3 * c + a] : 0.0;
    }
    s[3] = gas_.void_fraction[c];
    s[4] = exchange_coefficient_[c];
    s[8] = gas_.solid_volume[c];
    s[9] = owned_volume_[c];
    s[13] = sauter_diameter_[c];
  }
}

void DistributedCoupling::unpack_halo_state() {
  const std::size_t halo = halo_cells_.size();
  for (auto *field : {&halo_.void_fraction, &halo_.exchange_coefficient, &halo_.solid_volume, &halo_.volume,
                      &halo_.sauter_diameter})
    field->resize(halo);
  for (auto *field : {&halo_.velocity, &halo_.solid_velocity, &halo_.gradient}) field->resize(3 * halo);
  for (std::size_t c = 0; c < halo; ++c) {
    const double *s = &halo_state_[kStateComponents * c];
    for (int a = 0; a < 3; ++a) {
      halo_.velocity[3 * c + a] = s[a];
      halo_.solid_velocity[3 * c + a] = s[5 + a];
      halo_.gradient[3 * c + a] = s[10 + a];
    }
    halo_.void_fraction[c] = s[3];
    halo_.exchange_coefficient[c] = s[4];
    halo_.solid_volume[c] = s[8];
    halo_.volume[c] = s[9];
    halo_.sauter_diameter[c] = s[13];
  }
}

void DistributedCoupling::drop_thin_direction() {
  for (std::size_t i = 2; i < result_.particle_force.size(); i += 3) {
    result_.particle_force[i] = 0.0;
    result_.particle_drag[i] = 0.0;
  }
  result_.momentum_imbalance[2] = 0.0;  // the particle part: sum of the drags' z components
}

void DistributedCoupling::forces(const ParticleView &particles, const double *gas_velocity,
                                 const double *pressure_gradient) {
  const std::size_t owned = owned_volume_.size(), halo = halo_cells_.size();
  const CellGas owned_gas{owned, gas_velocity, gas_.void_fraction.data(), owned_volume_.data()};
  const bool conservative = transfer_.method == TransferMethod::PerParticleConservative;
  if (conservative) {  // K and U_s come after the particle drags; none fetched before
    std::fill(exchange_coefficient_.begin(), exchange_coefficient_.end(), 0.0);
    std::fill(solid_velocity_.begin(), solid_velocity_.end(), 0.0);
  } else {
    averaged_cell_drag(owned_sums_, owned_gas, transfer_, exchange_coefficient_.data(), solid_velocity_.data());
  }
  sauter_diameter_.resize(owned);
  sauter_diameters(owned_sums_, owned, sauter_diameter_.data());
  // The gas fields the particles see: under the filter through its adjoint, as the map's
  // weights carry them to the particles, so that what the gas loses to the filtered solids
  // the particles receive (the filter spreads extensive sums, its adjoint samples fields)
  const double *seen_velocity = gas_velocity, *seen_gradient = pressure_gradient;
  if (filter_) {
    seen_velocity_.assign(gas_velocity, gas_velocity + 3 * owned);
    filter_owned(seen_velocity_, 3, true);
    seen_velocity = seen_velocity_.data();
    if (pressure_gradient) {
      seen_gradient_.assign(pressure_gradient, pressure_gradient + 3 * owned);
      filter_owned(seen_gradient_, 3, true);
      seen_gradient = seen_gradient_.data();
    }
  }
  pack_owned_state(seen_velocity, seen_gradient);
  exchange_.fetch_from_owners(owned_state_, kStateComponents, halo_state_);

  unpack_halo_state();
  const CellSolidsState state{{halo, halo_.velocity.data(), halo_.void_fraction.data(), halo_.volume.data()},
                              halo_.solid_volume.data(), halo_.exchange_coefficient.data(), halo_.solid_velocity.data(),
                              halo_.sauter_diameter.data()};
  const std::vector<double> velocity_at = interpolates_gas_velocity()
                                               ? interpolated_velocity(particles)
                                               : average_to_particles(weights_, halo_.velocity.data(), 3);
  const std::vector<double> void_fraction_at = average_to_particles(weights_, halo_.void_fraction.data(), 1);
  const std::vector<double> gradient_at =
      pressure_gradient ? average_to_particles(weights_, halo_.gradient.data(), 3) : std::vector<double>();
  const GasAtParticles at{velocity_at.data(), void_fraction_at.data(),
                          pressure_gradient ? gradient_at.data() : nullptr, nullptr};
  const std::vector<double> particle_exchange_coefficient =
      particle_drag_and_force(weights_, particles, state, at, transfer_, result_);
  if (void_fraction_.two_dimensional) drop_thin_direction();

  if (conservative) {
    accumulate_conservative_sums(weights_, particle_exchange_coefficient, result_.particle_drag, halo, halo_sums_);
    exchange_.sum_to_owners(halo_sums_, kConservativeSumComponents, owned_sums_);
    filter_owned(owned_sums_, kConservativeSumComponents);
    conservative_cell_drag(owned_sums_, owned_gas, exchange_coefficient_.data(), solid_velocity_.data());
  }
  const std::array<double, 3> sink = adds_cell_totals()
                                         ? gas_drag_sink(owned_gas, exchange_coefficient_.data(), solid_velocity_.data())
                                         : std::array<double, 3>{};
  double balance[8];
  for (int a = 0; a < 3; ++a) balance[a] = result_.momentum_imbalance[a] - sink[a];
  balance[3] = result_.drag_magnitude_sum;
  pressure_force_balance(particles, gradient_at, pressure_gradient, &balance[4]);
  sum_over_ranks(balance, 8);
  for (int a = 0; a < 3; ++a) totals_.momentum_imbalance[a] = balance[a];
  totals_.drag_magnitude_sum = balance[3];
  for (int a = 0; a < 3; ++a) totals_.pressure_force_imbalance[a] = balance[4 + a];
  totals_.pressure_force_magnitude_sum = balance[7];
}

void DistributedCoupling::pressure_force_balance(const ParticleView &particles, const std::vector<double> &gradient_at,
                                                 const double *pressure_gradient, double *out) const {
  std::fill(out, out + 4, 0.0);
  if (!pressure_gradient) return;
  const int axes = void_fraction_.two_dimensional ? 2 : 3;  // the thin direction's forces are dropped
  for (std::size_t i = 0; i < particles.count; ++i) {
    const double volume = sphere_volume(particles.diameter[i]);
    for (int a = 0; a < axes; ++a) out[a] += volume * gradient_at[3 * i + a];
    out[3] += volume * std::hypot(gradient_at[3 * i], gradient_at[3 * i + 1], gradient_at[3 * i + 2]);
  }
  for (std::size_t c = 0; c < owned_volume_.size(); ++c)
    for (int a = 0; a < axes; ++a) out[a] -= gas_.solid_volume[c] * pressure_gradient[3 * c + a];
}

}  // namespace tfdem
