#include "tfdemStartupChecks.H"
#include "emptyFvPatchFields.H"

#include <mpi.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "tfdemRanks.H"
#include "tfdem/packing_check.h"
#include "tfdem/particle_engine.h"
#include "tfdem/particles.h"

namespace
{

constexpr double geometryTolerance = 1e-9;
constexpr double propertyTolerance = 1e-9;

double relativeDifference(double a, double b)
{
    const double scale = std::max(std::abs(a), std::abs(b));
    return scale > 0 ? std::abs(a - b)/scale : 0;
}

// Smallest and largest of `values` over all ranks (inf, -inf when there are none).
void globalRange(const std::vector<double>& values, double& lowest, double& highest)
{
    lowest = std::numeric_limits<double>::infinity();
    highest = -lowest;
    for (const double v : values)
    {
        lowest = std::min(lowest, v);
        highest = std::max(highest, v);
    }
    MPI_Allreduce(MPI_IN_PLACE, &lowest, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &highest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
}

// particles.diameter as written in coupling.yaml's style: "d" or "[d1, d2]".
std::string diameterList(const tfdem::CouplingConfig& config)
{
    std::ostringstream list;
    const auto& d = config.particle_diameters;
    if (d.size() != 1) list << "[";
    for (std::size_t k = 0; k < d.size(); ++k) list << (k ? ", " : "") << d[k];
    if (d.size() != 1) list << "]";
    return list.str();
}

} // End anonymous namespace


void Foam::tfdemChecks::gasProperties
(
    const tfdem::CouplingConfig& config,
    const dimensionedScalar& rho,
    const dimensionedScalar& nu
)
{
    const double mu = rho.value()*nu.value();
    if
    (
        relativeDifference(rho.value(), config.gas.density) > 1e-12
     || relativeDifference(mu, config.gas.viscosity) > 1e-12
    )
    {
        FatalErrorInFunction
            << "gas properties disagree: constant/transportProperties gives rho = "
            << rho.value() << " kg/m^3, mu = rho nu = " << mu << " Pa s; "
            << config.file.c_str() << " gives gas.density = " << config.gas.density
            << ", gas.viscosity = " << config.gas.viscosity
            << ". Make them equal." << exit(FatalError);
    }
}


void Foam::tfdemChecks::twoDimensionalDepth
(
    const tfdem::CouplingConfig& config,
    const tfdem::CartesianGrid& grid
)
{
    if (!config.void_fraction.two_dimensional)
    {
        return;
    }
    const double depth = grid.spacing[2];
    if (config.particle_diameters.size() != 1)
    {
        FatalErrorInFunction
            << config.file.c_str() << ": coupling.void_fraction.two_dimensional"
            << " is true (one particle layer, seed 000 2-D rule), which needs one"
            << " particle size; particles.diameter lists "
            << label(config.particle_diameters.size()) << ". For a mixture use a"
            << " pseudo-2-D bed several diameters deep with two_dimensional: false"
            << exit(FatalError);
    }
    if
    (
        grid.count[2] != 1
     || relativeDifference(depth, config.particle_diameters[0]) > geometryTolerance
    )
    {
        FatalErrorInFunction
            << config.file.c_str() << ": coupling.void_fraction.two_dimensional"
            << " is true, so the mesh must be one cell deep with depth = "
            << "particles.diameter = " << config.particle_diameters[0]
            << " m (seed 000 2-D rule); the mesh has " << grid.count[2]
            << " cell(s) of depth " << depth << " m" << exit(FatalError);
    }
}


void Foam::tfdemChecks::particles
(
    const tfdem::CouplingConfig& config,
    const tfdem::ParticleEngine& dem
)
{
    const std::size_t n = dem.local_count();
    std::vector<double> diameter(n), density(n), sizeMismatch(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        diameter[i] = 2*dem.radii()[i];
        density[i] =
            diameter[i] > 0 ? dem.masses()[i]/tfdem::sphere_volume(diameter[i]) : 0;
        sizeMismatch[i] = std::numeric_limits<double>::infinity();
        for (const double listed : config.particle_diameters)
        {
            sizeMismatch[i] =
                std::min(sizeMismatch[i], relativeDifference(diameter[i], listed));
        }
    }
    double leastMismatch, worstMismatch;
    globalRange(sizeMismatch, leastMismatch, worstMismatch);
    double dMin, dMax, rhoMin, rhoMax;
    globalRange(diameter, dMin, dMax);
    globalRange(density, rhoMin, rhoMax);
    if (dMin > dMax)
    {
        return;  // no particles
    }
    if (!(dMin > 0))
    {
        FatalErrorInFunction
            << dem.name().c_str() << ": a particle has diameter " << dMin
            << " m; every DEM particle needs a positive diameter" << exit(FatalError);
    }
    if
    (
        worstMismatch > propertyTolerance
     || relativeDifference(rhoMin, config.particle_density) > propertyTolerance
     || relativeDifference(rhoMax, config.particle_density) > propertyTolerance
    )
    {
        FatalErrorInFunction
            << "particles disagree: the DEM (" << dem.name().c_str()
            << ", its particles) has diameters " << dMin << " to " << dMax
            << " m and densities " << rhoMin << " to " << rhoMax << " kg/m^3; "
            << config.file.c_str() << " gives particles.diameter = "
            << diameterList(config).c_str() << " m, particles.density = "
            << config.particle_density << " kg/m^3. Make them equal."
            << exit(FatalError);
    }
}




void Foam::tfdemChecks::packing
(
    const tfdem::ParticleEngine& dem,
    const vector& g,
    bool freshStart
)
{
    const std::size_t n = dem.local_count();
    std::vector<double> diameter(n), own(n), mass(dem.masses(), dem.masses() + n);
    std::vector<int> tags(dem.tags(), dem.tags() + n), types(dem.types(), dem.types() + n);
    for (std::size_t i = 0; i < n; ++i)
    {
        diameter[i] = 2*dem.radii()[i];
    }
    const std::vector<double> x = TfdemRanks::gatherDoubles(dem.positions(), 3*n);
    const std::vector<double> v = TfdemRanks::gatherDoubles(dem.velocities(), 3*n);
    const std::vector<double> d = TfdemRanks::gatherDoubles(diameter.data(), n);
    const std::vector<double> m = TfdemRanks::gatherDoubles(mass.data(), n);
    const std::vector<int> id = TfdemRanks::gatherIds(tags.data(), n);
    const std::vector<int> type = TfdemRanks::gatherIds(types.data(), n);
    tfdem::ParticleView all;
    all.count = d.size();
    all.position = x.data();
    all.velocity = v.data();
    all.diameter = d.data();
    const tfdem::PackingCheck check = tfdem::check_packing(all);

    constexpr std::size_t named = 10;
    std::ostringstream bad;
    bad.precision(8);
    for (std::size_t k = 0; k < std::min(named, check.not_finite.size()); ++k)
    {
        const std::size_t i = check.not_finite[k];
        bad << "\n    id " << id[i] << ": position (" << x[3*i] << ' ' << x[3*i + 1] << ' '
            << x[3*i + 2] << ") m, velocity (" << v[3*i] << ' ' << v[3*i + 1] << ' '
            << v[3*i + 2] << ") m/s, diameter " << d[i] << " m";
    }
    for (std::size_t k = 0; k < std::min(named, check.coincident.size()); ++k)
    {
        const auto [i, j] = check.coincident[k];
        bad << "\n    ids " << id[i] << " and " << id[j] << " both at (" << x[3*i] << ' '
            << x[3*i + 1] << ' ' << x[3*i + 2] << ") m";
    }
    if (!check.not_finite.empty() || !check.coincident.empty())
    {
        FatalErrorInFunction
            << "the DEM's particles cannot start: " << label(check.not_finite.size())
            << " with a position, velocity or diameter that is not a finite number, "
            << label(check.coincident.size()) << " pair(s) with their centres at one point"
            << " (LIGGGHTS would divide by their distance and stop on a floating-point"
            << " exception):" << bad.str().c_str() << "\nFix the DEM's data file or the"
            << " commands that place the particles (a packing written twice into one file?)"
            << exit(FatalError);
    }
    if (!freshStart || check.overlaps.empty())
    {
        return;
    }
    double energy = 0, lift = 0, smallest = GREAT;
    bool known = true;
    const tfdem::PackingCheck::Overlap* deepest = &check.overlaps.front();
    std::size_t deep = 0;
    for (const auto& o : check.overlaps)
    {
        const double relative = o.depth/std::min(d[o.a], d[o.b]);
        if (relative > deepest->depth/std::min(d[deepest->a], d[deepest->b])) deepest = &o;
        if (relative > 0.01) ++deep;
        const double e = dem.overlap_energy(type[o.a], type[o.b], 0.5*d[o.a], 0.5*d[o.b], o.depth);
        known = known && e >= 0;
        energy += e;
    }
    for (std::size_t i = 0; i < d.size(); ++i)
    {
        lift += m[i]*mag(g);
        smallest = std::min(smallest, d[i]);
    }
    lift *= smallest;
    const double relative = deepest->depth/std::min(d[deepest->a], d[deepest->b]);
    Info<< "TFDEM packing: " << label(check.overlaps.size()) << " overlapping pairs, "
        << label(deep) << " deeper than 1 % of d; deepest " << 100*relative << " % of d (ids "
        << id[deepest->a] << " and " << id[deepest->b] << ")";
    if (known && lift > 0)
    {
        Info<< "; their elastic energy " << energy << " J is " << energy/lift << " x the"
            << " energy that lifts the whole bed by one diameter";
    }
    Info<< endl;
    const std::string kept = dem.kept_overlaps_warning(relative);
    if (!kept.empty())
    {
        Info<< "TFDEM warning: " << kept.c_str() << endl;
    }
    if (known && lift > 0 && energy > lift)
    {
        Info<< "TFDEM warning: the initial packing stores more elastic energy in its overlaps"
            << " than lifting the whole bed by a particle diameter takes (" << energy/lift
            << " x): the bed will be thrown apart as it starts, not fluidized. A packing"
            << " squeezed into too small a box, or made with stiffer contacts than this run's?"
            << " Pack it with this run's contacts (tfdem.packing, tutorials/poured_packing)"
            << endl;
    }
}


void Foam::tfdemChecks::inletVoidFraction
(
    const volVectorField& U,
    const volScalarField& voidFraction,
    bool voidFractionRead
)
{
    const fvMesh& mesh = U.mesh();
    forAll(U.boundaryField(), patchi)
    {
        const fvPatchVectorField& Ub = U.boundaryField()[patchi];
        if (!Ub.fixesValue() || isA<emptyFvPatchVectorField>(Ub))
        {
            continue;
        }
        const scalar inflow = -gSum(Ub & mesh.Sf().boundaryField()[patchi]);
        if (inflow <= 0)
        {
            continue;
        }
        const word& name = mesh.boundary()[patchi].name();
        if (!voidFractionRead)
        {
            FatalErrorInFunction
                << "gas flows in through patch '" << name << "' (fixed U) but the case has no "
                << U.time().timeName()/"voidFraction" << ": the inlet velocity would count"
                << " as interstitial (times the gas fraction of the cells behind it). Add "
                << "0/voidFraction with " << name << " { type fixedValue; value uniform 1; }"
                << " for a superficial inlet velocity (or zeroGradient for an interstitial"
                << " one); see docs/src/theory/gas.md, Inflow" << exit(FatalError);
        }
        const fvPatchScalarField& eb = voidFraction.boundaryField()[patchi];
        const bool superficial = eb.fixesValue() && gMin(eb) == 1 && gMax(eb) == 1;
        Info<< "TFDEM coupling: inlet '" << name << "': U is "
            << (superficial ? "superficial (voidFraction fixedValue 1)"
                            : "interstitial (voidFraction not fixed at 1)")
            << ", inflow " << inflow << " m^3/s" << endl;
    }
}
