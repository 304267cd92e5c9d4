#include "tfdemRanks.H"

#include "tfdem/gas_layout.h"

#include <mpi.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include <dirent.h>
#include <unistd.h>

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


//- processor0, processor1, ... in the case folder (-case, else the working folder)
int decomposedCount(int argc, char* argv[])
{
    std::string root = ".";
    for (int i = 1; i + 1 < argc; ++i)
    {
        if (std::strcmp(argv[i], "-case") == 0) root = argv[i + 1];
    }
    DIR* dir = opendir(root.c_str());
    if (!dir) return 0;
    int count = 0;
    while (const dirent* e = readdir(dir))
    {
        const std::string name = e->d_name;
        count += name.size() > 9 && name.compare(0, 9, "processor") == 0
              && name.find_first_not_of("0123456789", 9) == std::string::npos;
    }
    closedir(dir);
    return count;
}

//- The launcher's rank count and this rank before MPI starts (Open MPI's, MPICH's), or 0
int launcherEnv(const char* openMpi, const char* mpich)
{
    const char* v = std::getenv(openMpi);
    if (!v) v = std::getenv(mpich);
    return v ? std::atoi(v) : 0;
}

//- With -parallel, OpenFOAM stops on a decomposition for another rank count with "number of
//  processor directories = 2 is not equal to the number of processors = 3" and no fix; say it
//  first, with the fixes (a checkpoint resumes on the new count after re-decomposing)
void checkDecomposition(int argc, char* argv[])
{
    const int ranks = launcherEnv("OMPI_COMM_WORLD_SIZE", "PMI_SIZE");
    const int decomposed = decomposedCount(argc, argv);
    if (ranks == 0 || decomposed == 0 || decomposed == ranks) return;
    if (launcherEnv("OMPI_COMM_WORLD_RANK", "PMI_RANK") == 0)
    {
        std::cerr
            << "\n--> TFDEM FATAL ERROR: the gas is decomposed for " << decomposed
            << " ranks (processor0 ... processor" << decomposed - 1 << ") but this run has "
            << ranks << " (mpirun -np " << ranks << " tfdemFoam -parallel). Fix: run on "
            << decomposed << " ranks; or split it for " << ranks << ": reconstructPar"
            << " -latestTime, numberOfSubdomains " << ranks << " in system/decomposeParDict,"
            << " decomposePar -force -latestTime (a checkpoint resumes on the new count); or"
            << " leave out -parallel to solve the gas whole on each rank (after reconstructPar)"
            << std::endl;
    }
    else
    {
        ::sleep(2);  // rank 0's message first: mpirun aborts the job at the first rank to exit
    }
    std::exit(1);
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
            checkDecomposition(argc, argv);
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


void Foam::TfdemRanks::checkTime(TfdemTime& runTime)
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
        runTime.quiet();
    }
    Info<< "TFDEM ranks: the gas whole on each of " << count() << " ranks (rank 0 writes),"
        << " the particles split by LIGGGHTS" << nl << endl;
}


void Foam::TfdemRanks::adviseLayout(label cells)
{
    if (count() < 2)
    {
        return;
    }
    const tfdem::gas_layout::Layout running =
        gasWhole_ ? tfdem::gas_layout::Layout::whole : tfdem::gas_layout::Layout::split;
    Info<< "TFDEM parallel: "
        << tfdem::gas_layout::advice(double(cells), count(), running).c_str() << nl << endl;
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
