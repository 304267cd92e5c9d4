// The MPI layer of the coupling core: moves per-cell arrays between the ranks that hold
// particles and the ranks that own the cells they touch. Only the cells a rank's particles
// touch travel (a sparse halo), never all particles or all cells: each coupling step a rank
// sums its particles' contributions into its halo cells, sends each halo cell's values to
// the cell's owner (sum_to_owners), and fetches the owners' completed values back
// (fetch_from_owners). With one rank both are copies.
//
// When every rank holds every cell (the gas solved whole on each rank, owner table all
// kEveryRank), the halos' sums are added on rank 0 and broadcast, so every rank holds
// bit-identical cell data (the ranks' copies of the gas solution then stay identical), and
// fetching is a local copy.
#ifndef TFDEM_CELL_EXCHANGE_H
#define TFDEM_CELL_EXCHANGE_H

#include <mpi.h>

#include <cstddef>
#include <vector>

namespace tfdem {

class CellExchange {
 public:
  // Owner-table entry of a cell every rank holds.
  static constexpr int kEveryRank = -1;

  // `owner_of_cell[g]`: rank owning global cell g (the same table on every rank), or
  // kEveryRank for all cells; `owned_cells`: the global index of each of this rank's cells,
  // in its local order (every cell once when all are kEveryRank).
  CellExchange(MPI_Comm comm, std::vector<int> owner_of_cell, const std::vector<int> &owned_cells);
  CellExchange(const CellExchange &) = delete;
  CellExchange &operator=(const CellExchange &) = delete;
  ~CellExchange();

  // Collective: this rank's particles touch the global cells `halo_cells` (distinct); the
  // halo arrays below have one record per entry, in this order.
  void set_halo(const std::vector<int> &halo_cells);
  // Collective: add each halo cell's `components` values into its owner's `owned_values`
  // (components per owned cell, local order; zeroed first). Contributions are added in
  // rank order, so the result does not depend on message timing.
  void sum_to_owners(const std::vector<double> &halo_values, int components, std::vector<double> &owned_values);
  // Collective: each halo cell's `components` values from its owner's `owned_values`.
  void fetch_from_owners(const std::vector<double> &owned_values, int components, std::vector<double> &halo_values);

  std::size_t owned_count() const { return owned_count_; }
  std::size_t halo_count() const { return halo_size_; }
  // Halo records received from other ranks in the last set_halo (a measure of traffic; 0
  // when every rank holds every cell).
  std::size_t remote_records() const { return remote_records_; }
  bool every_rank_holds_every_cell() const { return replicated_; }
  // What this rank has sent other ranks since construction: payload bytes (cell values and
  // halo cell indices; with every cell on every rank, its share of the reduction to rank 0,
  // or rank 0's broadcast) and messages (one per destination rank and exchange; a reduction
  // or broadcast counts one)
  double bytes_sent() const { return bytes_sent_; }
  double messages_sent() const { return messages_sent_; }

 private:
  // Owner table all kEveryRank (true), or ranks only (false); anything else throws.
  static bool replicated_table(const std::vector<int> &owner_of_cell);
  // sum_to_owners when every rank holds every cell: summed on rank 0, broadcast.
  void sum_on_every_rank(const std::vector<double> &halo_values, int components, std::vector<double> &owned_values);
  // Alltoallv of `components` doubles per record.
  void exchange(const std::vector<double> &send, const std::vector<int> &send_records,
                std::vector<double> &receive, const std::vector<int> &receive_records, int components);

  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
  std::vector<int> owner_of_cell_;
  std::vector<int> local_of_cell_;  // local index of each global cell owned here, else -1
  std::size_t owned_count_ = 0;
  std::size_t halo_size_ = 0;
  std::size_t remote_records_ = 0;
  std::vector<int> send_order_;       // halo entries grouped by owner rank
  std::vector<int> send_counts_;      // records per destination rank
  std::vector<int> receive_counts_;   // records per source rank
  std::vector<int> received_local_;   // owned local cell of each received record
  std::vector<double> send_buffer_, receive_buffer_;
  bool replicated_ = false;
  std::vector<int> halo_cells_;  // when replicated: the halo's global cells
  double bytes_sent_ = 0, messages_sent_ = 0;
  // Count what `scaled` (values per destination rank) sends to other ranks
  void count_sent(const std::vector<int> &scaled, std::size_t value_bytes);
};

}  // namespace tfdem

#endif
