#include "tfdem/cell_exchange.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace tfdem {

namespace {

// Displacements (prefix sums) of `counts` scaled by `components`.
std::vector<int> displacements(const std::vector<int> &counts, int components, std::vector<int> &scaled) {
  scaled.resize(counts.size());
  std::vector<int> offsets(counts.size(), 0);
  for (std::size_t r = 0; r < counts.size(); ++r) {
    scaled[r] = counts[r] * components;
    if (r > 0) offsets[r] = offsets[r - 1] + scaled[r - 1];
  }
  return offsets;
}

}  // namespace

bool CellExchange::replicated_table(const std::vector<int> &owner_of_cell) {
  const auto every = std::count(owner_of_cell.begin(), owner_of_cell.end(), kEveryRank);
  if (every > 0 && static_cast<std::size_t>(every) < owner_of_cell.size())
    throw std::invalid_argument("CellExchange: the owner table gives " + std::to_string(every) + " of " +
                                std::to_string(owner_of_cell.size()) +
                                " cells to every rank; either all cells are on every rank or each on one");
  return every > 0;
}

CellExchange::CellExchange(MPI_Comm comm, std::vector<int> owner_of_cell, const std::vector<int> &owned_cells)
    : owner_of_cell_(std::move(owner_of_cell)),
      owned_count_(owned_cells.size()),
      replicated_(replicated_table(owner_of_cell_)) {
  MPI_Comm_dup(comm, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  local_of_cell_.assign(owner_of_cell_.size(), -1);
  const int mine = replicated_ ? kEveryRank : rank_;
  for (std::size_t l = 0; l < owned_cells.size(); ++l) {
    const int g = owned_cells[l];
    if (g < 0 || static_cast<std::size_t>(g) >= owner_of_cell_.size() || owner_of_cell_[g] != mine ||
        local_of_cell_[g] >= 0)
      throw std::invalid_argument("CellExchange: rank " + std::to_string(rank_) + " lists cell " +
                                  std::to_string(g) + " that the owner table does not give it (or twice)");
    local_of_cell_[g] = static_cast<int>(l);
  }
  if (replicated_ && owned_count_ != owner_of_cell_.size())
    throw std::invalid_argument("CellExchange: every rank holds every cell, but rank " + std::to_string(rank_) +
                                " lists " + std::to_string(owned_count_) + " of " +
                                std::to_string(owner_of_cell_.size()));
  send_counts_.assign(size_, 0);
  receive_counts_.assign(size_, 0);
}

CellExchange::~CellExchange() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Comm_free(&comm_);
}

void CellExchange::set_halo(const std::vector<int> &halo_cells) {
  halo_size_ = halo_cells.size();
  for (int g : halo_cells)
    if (g < 0 || static_cast<std::size_t>(g) >= owner_of_cell_.size())
      throw std::out_of_range("CellExchange: halo cell " + std::to_string(g) + " is not a grid cell");
  if (replicated_) {
    halo_cells_ = halo_cells;
    remote_records_ = 0;
    return;
  }
  std::fill(send_counts_.begin(), send_counts_.end(), 0);
  for (int g : halo_cells) ++send_counts_[owner_of_cell_[g]];
  std::vector<int> next(size_, 0);
  for (int r = 1; r < size_; ++r) next[r] = next[r - 1] + send_counts_[r - 1];
  send_order_.resize(halo_cells.size());
  for (std::size_t h = 0; h < halo_cells.size(); ++h) send_order_[next[owner_of_cell_[halo_cells[h]]]++] = static_cast<int>(h);

  MPI_Alltoall(send_counts_.data(), 1, MPI_INT, receive_counts_.data(), 1, MPI_INT, comm_);
  std::vector<int> send_cells(halo_cells.size());
  for (std::size_t k = 0; k < send_order_.size(); ++k) send_cells[k] = halo_cells[send_order_[k]];
  std::vector<int> send_scaled, receive_scaled;
  const std::vector<int> send_offsets = displacements(send_counts_, 1, send_scaled);
  const std::vector<int> receive_offsets = displacements(receive_counts_, 1, receive_scaled);
  const int received = std::accumulate(receive_counts_.begin(), receive_counts_.end(), 0);
  std::vector<int> receive_cells(received);
  MPI_Alltoallv(send_cells.data(), send_scaled.data(), send_offsets.data(), MPI_INT, receive_cells.data(),
                receive_scaled.data(), receive_offsets.data(), MPI_INT, comm_);
  count_sent(send_scaled, sizeof(int));
  received_local_.resize(received);
  for (int k = 0; k < received; ++k) received_local_[k] = local_of_cell_[receive_cells[k]];
  remote_records_ = static_cast<std::size_t>(received - receive_counts_[rank_]);
}

void CellExchange::count_sent(const std::vector<int> &scaled, std::size_t value_bytes) {
  for (int r = 0; r < size_; ++r)
    if (r != rank_ && scaled[r] > 0) {
      bytes_sent_ += double(scaled[r]) * double(value_bytes);
      ++messages_sent_;
    }
}

void CellExchange::exchange(const std::vector<double> &send, const std::vector<int> &send_records,
                            std::vector<double> &receive, const std::vector<int> &receive_records, int components) {
  std::vector<int> send_scaled, receive_scaled;
  const std::vector<int> send_offsets = displacements(send_records, components, send_scaled);
  const std::vector<int> receive_offsets = displacements(receive_records, components, receive_scaled);
  receive.resize(std::accumulate(receive_scaled.begin(), receive_scaled.end(), std::size_t{0}));
  MPI_Alltoallv(send.data(), send_scaled.data(), send_offsets.data(), MPI_DOUBLE, receive.data(),
                receive_scaled.data(), receive_offsets.data(), MPI_DOUBLE, comm_);
  count_sent(send_scaled, sizeof(double));
}

void CellExchange::sum_to_owners(const std::vector<double> &halo_values, int components,
                                 std::vector<double> &owned_values) {
  if (halo_values.size() != halo_size_ * components)
    throw std::invalid_argument("CellExchange::sum_to_owners: halo values are not for the halo of set_halo");
  if (replicated_) {
    sum_on_every_rank(halo_values, components, owned_values);
    return;
  }
  send_buffer_.resize(halo_values.size());
  for (std::size_t k = 0; k < send_order_.size(); ++k)
    for (int a = 0; a < components; ++a) send_buffer_[components * k + a] = halo_values[components * send_order_[k] + a];
  exchange(send_buffer_, send_counts_, receive_buffer_, receive_counts_, components);
  owned_values.assign(owned_count_ * components, 0.0);
  for (std::size_t k = 0; k < received_local_.size(); ++k)
    for (int a = 0; a < components; ++a)
      owned_values[components * received_local_[k] + a] += receive_buffer_[components * k + a];
}

void CellExchange::fetch_from_owners(const std::vector<double> &owned_values, int components,
                                     std::vector<double> &halo_values) {
  if (owned_values.size() != owned_count_ * components)
    throw std::invalid_argument("CellExchange::fetch_from_owners: owned values are not one record per owned cell");
  if (replicated_) {
    halo_values.resize(halo_size_ * components);
    for (std::size_t h = 0; h < halo_size_; ++h)
      for (int a = 0; a < components; ++a)
        halo_values[components * h + a] = owned_values[components * local_of_cell_[halo_cells_[h]] + a];
    return;
  }
  receive_buffer_.resize(received_local_.size() * components);
  for (std::size_t k = 0; k < received_local_.size(); ++k)
    for (int a = 0; a < components; ++a)
      receive_buffer_[components * k + a] = owned_values[components * received_local_[k] + a];
  exchange(receive_buffer_, receive_counts_, send_buffer_, send_counts_, components);
  halo_values.resize(halo_size_ * components);
  for (std::size_t k = 0; k < send_order_.size(); ++k)
    for (int a = 0; a < components; ++a) halo_values[components * send_order_[k] + a] = send_buffer_[components * k + a];
}

void CellExchange::sum_on_every_rank(const std::vector<double> &halo_values, int components,
                                     std::vector<double> &owned_values) {
  const std::size_t values = owner_of_cell_.size() * components;
  send_buffer_.assign(values, 0.0);
  for (std::size_t h = 0; h < halo_size_; ++h)
    for (int a = 0; a < components; ++a)
      send_buffer_[components * halo_cells_[h] + a] += halo_values[components * h + a];
  receive_buffer_.resize(values);
  MPI_Reduce(send_buffer_.data(), receive_buffer_.data(), static_cast<int>(values), MPI_DOUBLE, MPI_SUM, 0, comm_);
  MPI_Bcast(receive_buffer_.data(), static_cast<int>(values), MPI_DOUBLE, 0, comm_);
  if (size_ > 1) {
    bytes_sent_ += double(values) * sizeof(double);
    ++messages_sent_;
  }
  owned_values.resize(values);
  for (std::size_t g = 0; g < owner_of_cell_.size(); ++g)
    for (int a = 0; a < components; ++a)
      owned_values[components * local_of_cell_[g] + a] = receive_buffer_[components * g + a];
}

}  // namespace tfdem
