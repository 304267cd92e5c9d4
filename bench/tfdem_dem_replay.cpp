// tfdem-dem-replay: the DEM part of a coupled run alone. It runs the same DEM script in the
// same way the coupler does (LIGGGHTS in-process, `run N post no` per coupling
// interval) with the particle fluid forces that `tfdemFoam -recordForces` wrote, so the
// particles go through the same steps and contacts without the gas or the coupling. Prints
// its wall time and the sum of particle coordinates that tfdemFoam prints at its end.
//
// Usage: tfdem-dem-replay <DEM script> <record prefix> <coupling interval> <intervals>
#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dem_instance.h"

namespace {

// One coupling step of the record: atom IDs and their forces on this rank.
struct ForceRecord {
  std::vector<int> tags;
  std::vector<double> forces;
};

ForceRecord read_record(std::ifstream &in, const std::string &path, long step) {
  std::uint64_t n = 0;
  if (!in.read(reinterpret_cast<char *>(&n), sizeof(n)))
    throw std::runtime_error(path + ": ends before coupling step " + std::to_string(step));
  ForceRecord r;
  r.tags.resize(n);
  r.forces.resize(3 * n);
  in.read(reinterpret_cast<char *>(r.tags.data()), n * sizeof(int));
  in.read(reinterpret_cast<char *>(r.forces.data()), 3 * n * sizeof(double));
  if (!in) throw std::runtime_error(path + ": truncated at coupling step " + std::to_string(step));
  return r;
}

// Set the recorded forces; the particles must be the recorded ones in the recorded order,
// which holds as long as the replay follows the coupled run exactly.
void apply(const ForceRecord &r, tfdem::DemInstance &dem, long step) {
  if (r.tags.size() != dem.local_count())
    throw std::runtime_error("replay diverged at coupling step " + std::to_string(step) + ": " +
                             std::to_string(dem.local_count()) + " local particles, record has " +
                             std::to_string(r.tags.size()));
  for (std::size_t i = 0; i < r.tags.size(); ++i)
    if (dem.tags()[i] != r.tags[i])
      throw std::runtime_error("replay diverged at coupling step " + std::to_string(step) +
                               ": particle order differs from the record");
  dem.set_fluid_force(r.forces);
}

// A positive whole number from argument `name`, or std::invalid_argument naming it.
long positive_count(const char *name, const char *text) {
  char *end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || value <= 0)
    throw std::invalid_argument(std::string(name) + " must be a positive whole number, got '" + text + "'");
  return value;
}

int replay(int argc, char **argv, int rank) {
  if (argc != 5) {
    if (rank == 0)
      std::fprintf(stderr, "usage: tfdem-dem-replay <DEM script> <record prefix> <coupling interval> <intervals>\n");
    return 2;
  }
  const std::string script = argv[1], path = std::string(argv[2]) + "." + std::to_string(rank);
  const long interval = positive_count("<coupling interval>", argv[3]);
  const long intervals = positive_count("<intervals>", argv[4]);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read force record " + path);
  tfdem::DemInstance dem(MPI_COMM_WORLD, script, "log.replay");
  double read_seconds = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (long step = 0; step < intervals; ++step) {
    const auto read_start = std::chrono::steady_clock::now();
    const ForceRecord r = read_record(in, path, step);
    read_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - read_start).count();
    apply(r, dem, step);
    dem.run(interval);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double sums[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < 3 * dem.local_count(); ++i) sums[i % 3] += dem.positions()[i];
  MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  double times[2] = {wall - read_seconds, read_seconds};
  MPI_Allreduce(MPI_IN_PLACE, times, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (rank == 0) {
    std::printf("TFDEM replay: DEM %.6g s for %ld intervals of %ld steps (record reading %.3g s, not included)\n",
                times[0], intervals, interval, times[1]);
    std::printf("TFDEM positions: sum of x, y, z over particles = %.17g %.17g %.17g\n", sums[0], sums[1], sums[2]);
  }
  return 0;
}

}  // namespace

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int status = 0;
  try {
    status = replay(argc, argv, rank);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "tfdem-dem-replay (rank %d): %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return status;
}
