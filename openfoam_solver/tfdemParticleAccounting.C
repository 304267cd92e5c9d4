#include "tfdemParticleAccounting.H"
#include "tfdemRanks.H"

#include <mpi.h>

#include <algorithm>
#include <sstream>

#include "tfdem/particle_engine.h"

namespace
{

// Lost particles named in the message, over all ranks.
constexpr int namedLostParticles = 10;

} // End anonymous namespace


Foam::TfdemParticleAccounting::TfdemParticleAccounting
(
    const tfdem::ParticleEngine& dem,
    const ParticleTotals& start,
    scalar t
)
{
    totals_ = count(dem);
    totals_.removedCount = start.removedCount;
    totals_.removedMass = start.removedMass;
    remember(dem, t);
}


Foam::ParticleTotals Foam::TfdemParticleAccounting::count
(
    const tfdem::ParticleEngine& dem
) const
{
    double local[2] = {double(dem.local_count()), 0};
    for (std::size_t i = 0; i < dem.local_count(); ++i)
    {
        local[1] += dem.masses()[i];
    }
    MPI_Allreduce(MPI_IN_PLACE, local, 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    ParticleTotals t;
    t.count = label(local[0]);
    t.mass = local[1];
    return t;
}


void Foam::TfdemParticleAccounting::remember(const tfdem::ParticleEngine& dem, scalar t)
{
    const std::size_t n = dem.local_count();
    lastTags_.assign(dem.tags(), dem.tags() + n);
    lastPositions_.assign(dem.positions(), dem.positions() + 3*n);
    lastVelocities_.assign(dem.velocities(), dem.velocities() + 3*n);
    lastTime_ = t;
}


void Foam::TfdemParticleAccounting::check
(
    const tfdem::ParticleEngine& dem,
    scalar t,
    const std::vector<int>& removedTags,
    scalar removedMass
)
{
    const ParticleTotals now = count(dem);
    totals_.removedCount += label(removedTags.size());
    totals_.removedMass += removedMass;
    totals_.count -= label(removedTags.size());
    totals_.mass -= removedMass;
    if (now.count >= totals_.count)
    {
        totals_.count = now.count;
        totals_.mass = now.mass;
        remember(dem, t);
        return;
    }
    label lostHere = 0;
    const std::string named =
        TfdemRanks::gatherText(describeLost(dem, removedTags, lostHere));
    FatalErrorInFunction
        << totals_.count - now.count << " of " << totals_.count
        << " particles were lost in the DEM between t = " << lastTime_ << " and "
        << t << " s (" << totals_.mass - now.mass << " kg), not through an outlet."
        << nl << "Lost particles (at most " << namedLostParticles << " per rank), at their"
        << " last position before:" << nl << named.c_str()
        << dem.lost_particles_hint().c_str() << exit(FatalError);
}


std::string Foam::TfdemParticleAccounting::describeLost
(
    const tfdem::ParticleEngine& dem,
    const std::vector<int>& removedTags,
    label& lost
) const
{
    // Every current ID, over all ranks (only on this error path)
    std::vector<int> present = TfdemRanks::gatherIds(dem.tags(), dem.local_count());
    present.insert(present.end(), removedTags.begin(), removedTags.end());
    std::sort(present.begin(), present.end());
    std::ostringstream out;
    lost = 0;
    for (std::size_t i = 0; i < lastTags_.size(); ++i)
    {
        if (std::binary_search(present.begin(), present.end(), lastTags_[i]))
        {
            continue;
        }
        if (++lost <= namedLostParticles)
        {
            const double* x = &lastPositions_[3*i];
            const double* v = &lastVelocities_[3*i];
            out << "  [rank " << TfdemRanks::rank() << "] id " << lastTags_[i] << " at ("
                << x[0] << ' ' << x[1] << ' ' << x[2] << ") m, v = (" << v[0] << ' '
                << v[1] << ' ' << v[2] << ") m/s\n";
        }
    }
    if (lost > namedLostParticles)
    {
        out << "  [rank " << TfdemRanks::rank() << "] and " << lost - namedLostParticles
            << " more\n";
    }
    return out.str();
}
