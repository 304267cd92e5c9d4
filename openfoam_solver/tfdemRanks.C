#include "tfdemRanks.H"

#include <mpi.h>

#include <cstring>
#include <vector>

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


std::string Foam::TfdemRanks::gatherText(const std::string& mine)
{
    const int ranks = count();
    int length = int(mine.size());
    std::vector<int> lengths(ranks), offsets(ranks + 1, 0);
    MPI_Allgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 0; r < ranks; ++r)
    {
        offsets[r + 1] = offsets[r] + lengths[r];
    }
    std::string all(offsets[ranks], ' ');
    MPI_Allgatherv
    (
        mine.data(), length, MPI_CHAR, &all[0], lengths.data(), offsets.data(), MPI_CHAR,
        MPI_COMM_WORLD
    );
    return all;
}
