// tfdem-liggghts: LIGGGHTS with TFDEM's fix styles registered; same command line as `liggghts`.
#include <mpi.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "input.h"
#include "lammps.h"
#include "tfdem_liggghts.h"

namespace {

// The file given after -in/-i, or empty when the script comes from standard input.
std::string input_script_path(int argc, char **argv) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "-in") == 0 || std::strcmp(argv[i], "-i") == 0) return argv[i + 1];
  return {};
}

}  // namespace

int main(int argc, char **argv) {
  // LIGGGHTS writes its screen to stdout and stops on an error with MPI_Abort, which does not
  // flush it: line by line, so the error reaches a log file too (not only a terminal)
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const std::string script = input_script_path(argc, argv);
  if (!script.empty() && !std::ifstream(script).good()) {
    if (rank == 0)
      std::fprintf(stderr, "tfdem-liggghts: DEM input script '%s' not found or not readable\n",
                   script.c_str());
    MPI_Finalize();
    return 2;
  }
  auto *lmp = new LAMMPS_NS::LAMMPS(argc, argv, MPI_COMM_WORLD);
  tfdem::register_fix_styles(lmp);
  lmp->input->file();
  delete lmp;
  MPI_Finalize();
  return 0;
}
