#include "tfdemGrid.H"

#include <mpi.h>

#include "tfdem/cell_exchange.h"
#include "tfdemRanks.H"

#include <cmath>

namespace
{

constexpr double geometryTolerance = 1e-9;

double relativeDifference(double a, double b)
{
    const double scale = std::max(std::abs(a), std::abs(b));
    return scale > 0 ? std::abs(a - b)/scale : 0;
}

} // End anonymous namespace


Foam::TfdemGrid Foam::discoverGrid(const fvMesh& mesh)
{
    TfdemGrid out;
    tfdem::CartesianGrid& grid = out.grid;
    const boundBox domain(mesh.points(), true);
    const boundBox firstCell(mesh.points(), mesh.cellPoints()[0], false);
    vector spacing = firstCell.span();
    reduce(spacing, maxOp<vector>());
    for (direction a = 0; a < 3; ++a)
    {
        grid.origin[a] = domain.min()[a];
        grid.spacing[a] = spacing[a];
        grid.count[a] = std::lround(domain.span()[a]/grid.spacing[a]);
    }
    // Every grid cell must be exactly one mesh cell, on exactly one rank.
    const double cellVolume = grid.cell_volume();
    bool uniform = (returnReduce(mesh.nCells(), sumOp<label>()) == grid.cell_count());
    out.gridCellOfCell.assign(mesh.nCells(), -1);
    std::vector<int> meshCellsInGridCell(uniform ? grid.cell_count() : 0, 0);
    forAll(mesh.C(), celli)
    {
        const point& c = mesh.C()[celli];
        const double x[3] = {c.x(), c.y(), c.z()};
        const int g = uniform ? grid.locate(x) : -1;
        if (g < 0 || relativeDifference(mesh.V()[celli], cellVolume) > geometryTolerance)
        {
            uniform = false;
            break;
        }
        out.gridCellOfCell[celli] = g;
        ++meshCellsInGridCell[g];
    }
    reduce(uniform, andOp<bool>());
    // The ranks that share the mesh: all when decomposed, each alone when the gas is whole
    const MPI_Comm gasRanks = TfdemRanks::gasWhole() ? MPI_COMM_SELF : MPI_COMM_WORLD;
    if (uniform)
    {
        MPI_Allreduce
        (
            MPI_IN_PLACE, meshCellsInGridCell.data(), grid.cell_count(), MPI_INT,
            MPI_SUM, gasRanks
        );
        for (const int n : meshCellsInGridCell)
        {
            uniform = uniform && n == 1;
        }
    }
    if (!uniform)
    {
        FatalErrorInFunction
            << "the coupled solver needs a uniform Cartesian mesh (one blockMesh"
            << " block, no grading); this mesh has "
            << returnReduce(mesh.nCells(), sumOp<label>())
            << " cells in the box " << domain << exit(FatalError);
    }
    if (TfdemRanks::gasWhole())
    {
        out.ownerOfGridCell.assign(grid.cell_count(), tfdem::CellExchange::kEveryRank);
    }
    else
    {
        out.ownerOfGridCell.assign(grid.cell_count(), -1);
        for (const int g : out.gridCellOfCell)
        {
            out.ownerOfGridCell[g] = Pstream::myProcNo();
        }
        MPI_Allreduce
        (
            MPI_IN_PLACE, out.ownerOfGridCell.data(), grid.cell_count(), MPI_INT, MPI_MAX,
            MPI_COMM_WORLD
        );
    }
    Info<< "TFDEM coupling: Cartesian grid " << grid.count[0] << " x "
        << grid.count[1] << " x " << grid.count[2] << " cells of "
        << grid.spacing[0] << " x " << grid.spacing[1] << " x "
        << grid.spacing[2] << " m" << endl;
    return out;
}
