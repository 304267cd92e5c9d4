#include "tfdemRanks.H"

#include <mpi.h>

#include <cstring>
#include <vector>

namespace
{

// Every rank's `count` values, concatenated in rank order, on every rank (MPI_COMM_WORLD)
template<class Type>
std::vector<Type> allGathered(const Type* mine, int count, MPI_Datatype type)
{
    const int ranks = Foam::TfdemRanks::count();
    std::vector<int> counts(ranks), offsets(ranks + 1, 0);
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 0; r < ranks; ++r)
    {
        offsets[r + 1] = offsets[r] + counts[r];
    }
    std::vector<Type> all(offsets.back());
    if (!all.empty())
    {
        MPI_Allgatherv
        (
            mine, count, type, all.data(), counts.data(), offsets.data(), type,
            MPI_COMM_WORLD
        );
    }
    return all;
}

} // End anonymous namespace


bool Foam::TfdemRanks::gasWhole_ = false;
bool Foam::TfdemRanks::startedMpi_ = false;


void Foam::TfdemRanks::start(int argc, char* argv[])
{
    for (int i = 1; i < argc; ++i)
    {
        if (std::strcmp(argv[i], "-parallel") == 0)
        {
            return;
        }
    }
    MPI_Init(&argc, &argv);
    startedMpi_ = true;
    gasWhole_ = count() > 1;
    if (rank() > 0)
    {
        messageStream::level = 0;
    }
}


void Foam::TfdemRanks::finish()
{
    if (startedMpi_)
    {
        MPI_Finalize();
        startedMpi_ = false;
    }
}


void Foam::TfdemRanks::checkTime(Time& runTime)
{
    if (!gasWhole_)
    {
        return;
    }
    const word writeControl
    (
        runTime.controlDict().getOrDefault<word>("writeControl", "timeStep")
    );
    const bool sameStepOnEveryRank =
        writeControl == "timeStep" || writeControl == "runTime"
     || writeControl == "adjustable" || writeControl == "adjustableRunTime";
    if (runTime.runTimeModifiable() || !sameStepOnEveryRank)
    {
        FatalErrorInFunction
            << "the gas is solved whole on each of " << count() << " ranks (mpirun without"
            << " -parallel), so every rank must read the same settings at the same step:"
            << " system/controlDict has runTimeModifiable " << runTime.runTimeModifiable()
            << " and writeControl " << writeControl << ". Fix: runTimeModifiable false;"
            << " writeControl timeStep or runTime (not clockTime or cpuTime). Or decompose"
            << " the mesh (decomposePar) and run with -parallel." << exit(FatalError);
    }
    if (!writesGas())
    {
        runTime.functionObjects().off();
    }
    Info<< "TFDEM ranks: the gas whole on each of " << count() << " ranks (rank 0 writes),"
        << " the particles split by LIGGGHTS" << nl << endl;
}


int Foam::TfdemRanks::rank()
{
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}


int Foam::TfdemRanks::count()
{
    int n = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &n);
    return n;
}


std::vector<int> Foam::TfdemRanks::gatherIds(const int* mine, std::size_t count)
{
    return allGathered(mine, int(count), MPI_INT);
}


std::vector<double> Foam::TfdemRanks::gatherDoubles(const double* mine, std::size_t count)
{
    return allGathered(mine, int(count), MPI_DOUBLE);
}


std::string Foam::TfdemRanks::gatherText(const std::string& mine)
{
    const std::vector<char> all = allGathered(mine.data(), int(mine.size()), MPI_CHAR);
    return std::string(all.begin(), all.end());
}
