#include "tfdemForceRecord.H"
#include "tfdemRanks.H"
#include "IOmanip.H"

#include <mpi.h>

#include <chrono>
#include <cstdint>

#include "tfdem/particle_engine.h"

namespace
{

double slowestRank(double seconds)
{
    MPI_Allreduce(MPI_IN_PLACE, &seconds, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return seconds;
}

} // End anonymous namespace


Foam::TfdemForceRecord::TfdemForceRecord(const fileName& file)
{
    if (file.empty())
    {
        return;
    }
    const fileName path(file + "." + Foam::name(TfdemRanks::rank()));
    out_.open(path, std::ios::binary);
    if (!out_)
    {
        FatalErrorInFunction
            << "-recordForces: cannot write " << path << exit(FatalError);
    }
}


void Foam::TfdemForceRecord::write
(
    const tfdem::ParticleEngine& dem,
    const std::vector<double>& force
)
{
    if (!out_.is_open())
    {
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    const std::uint64_t n = dem.local_count();
    out_.write(reinterpret_cast<const char*>(&n), sizeof(n));
    out_.write(reinterpret_cast<const char*>(dem.tags()), n*sizeof(int));
    out_.write(reinterpret_cast<const char*>(force.data()), 3*n*sizeof(double));
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}


void Foam::TfdemForceRecord::report(const tfdem::ParticleEngine& dem) const
{
    double positionSum[3] = {0, 0, 0};
    for (std::size_t i = 0; i < 3*dem.local_count(); ++i)
    {
        positionSum[i % 3] += dem.positions()[i];
    }
    MPI_Allreduce(MPI_IN_PLACE, positionSum, 3, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    const int digits = Info().precision(17);  // compared bit for bit with the replay
    Info<< "TFDEM positions: sum of x, y, z over particles = " << positionSum[0] << " "
        << positionSum[1] << " " << positionSum[2] << endl;
    Info().precision(digits);
    if (out_.is_open())
    {
        Info<< "TFDEM record: forces written in "
            << slowestRank(seconds_) << " s (not in the split below)"
            << endl;
    }
}
