#include "tfdemOutlets.H"
#include "tfdemRanks.H"
#include "IOmanip.H"

#include <mpi.h>

#include "tfdem/particle_engine.h"
#include "tfdem/suggest.h"

Foam::TfdemOutlets::TfdemOutlets
(
    const fvMesh& mesh,
    const std::vector<std::string>& names,
    const fileName& config,
    tfdem::ParticleEngine& dem,
    double reach
)
{
    const tfdem::ParticleEngine::Box box = dem.box();
    const boundBox domain(mesh.points(), true);
    std::vector<std::string> patchNames;
    for (const polyPatch& p : mesh.boundaryMesh())
    {
        if (!p.coupled())
        {
            patchNames.push_back(p.name());
        }
    }
    for (const std::string& name : names)
    {
        const label patchi = mesh.boundaryMesh().findPatchID(name);
        if (patchi < 0)
        {
            FatalErrorInFunction
                << config << ": dem.outlets: no patch '" << name.c_str() << "'"
                << tfdem::did_you_mean(name, patchNames).c_str() << "; patches: "
                << tfdem::quoted_list(patchNames).c_str() << exit(FatalError);
        }
        const polyPatch& patch = mesh.boundaryMesh()[patchi];
        vector normal = gSum(patch.faceAreas());
        vector lower(GREAT, GREAT, GREAT), upper(-GREAT, -GREAT, -GREAT);
        for (const point& p : patch.localPoints())
        {
            lower = min(lower, p);
            upper = max(upper, p);
        }
        reduce(lower, minOp<vector>());
        reduce(upper, maxOp<vector>());
        Outlet o;
        o.name = name;
        for (int a = 1; a < 3; ++a)
        {
            if (mag(normal[a]) > mag(normal[o.axis])) o.axis = a;
        }
        o.side = normal[o.axis] > 0 ? 1 : -1;
        o.position = o.side > 0 ? domain.max()[o.axis] : domain.min()[o.axis];
        o.lower = lower;
        o.upper = upper;
        if (mag(normal) == 0 || mag(upper[o.axis] - lower[o.axis]) > 1e-9*domain.mag())
        {
            FatalErrorInFunction
                << config << ": dem.outlets: patch '" << name.c_str() << "' is not flat on a face of"
                << " the domain; particles can leave through such patches only"
                << exit(FatalError);
        }
        const int side = o.side > 0 ? 1 : 0;
        dem.open_outlet(o.axis, side);
        const double face = o.side > 0 ? box.upper[o.axis] : box.lower[o.axis];
        if (box.drops[o.axis][side] && (face - o.position)*o.side < reach)
        {
            FatalErrorInFunction
                << config << ": dem.outlets: patch '" << name.c_str() << "' lies at "
                << "xyz"[o.axis] << " = " << o.position << " m, but the DEM's box ends at "
                << face << " m there and drops the particles that cross it (LIGGGHTS boundary"
                << " f): they would be lost before the coupler counts them as leaving. Fix:"
                << " make the DEM's box reach at least one particle diameter (" << reach
                << " m) beyond the outlet, or that side of it shrink-wrapped (boundary m)"
                << exit(FatalError);
        }
        outlets_.push_back(o);
        Info<< "TFDEM outlets: particles leave through '" << name.c_str() << "' ("
            << "xyz"[o.axis] << (o.side > 0 ? " >= " : " <= ") << o.position << " m)" << endl;
    }
    if (!outlets_.empty() && TfdemRanks::writesCase())
    {
        const Time& runTime = mesh.time();
        const fileName dir(runTime.globalPath()/"postProcessing"/"tfdemOutlets"/runTime.timeName());
        mkDir(dir);
        file_.reset(new OFstream(dir/"outlets.dat"));
        *file_
            << "# t (s)  outlet  particles that left since the last write  their mass (kg)" << nl;
    }
}


int Foam::TfdemOutlets::leftThrough(const tfdem::ParticleEngine& dem, std::size_t i) const
{
    const double* x = dem.positions() + 3*i;
    for (std::size_t k = 0; k < outlets_.size(); ++k)
    {
        const Outlet& o = outlets_[k];
        if ((x[o.axis] - o.position)*o.side < 0)
        {
            continue;
        }
        bool across = true;
        for (int a = 0; a < 3; ++a)
        {
            across = across && (a == o.axis || (x[a] >= o.lower[a] && x[a] <= o.upper[a]));
        }
        if (across)
        {
            return int(k);
        }
    }
    return -1;
}


Foam::TfdemOutlets::Removed Foam::TfdemOutlets::remove(tfdem::ParticleEngine& dem)
{
    Removed removed;
    if (outlets_.empty())
    {
        return removed;
    }
    // Per outlet: number and mass leaving on this rank; then every rank's leaving IDs
    std::vector<double> tally(2*outlets_.size(), 0);
    std::vector<int> mine;
    for (std::size_t i = 0; i < dem.local_count(); ++i)
    {
        const int k = leftThrough(dem, i);
        if (k < 0) continue;
        mine.push_back(dem.tags()[i]);
        tally[2*k] += 1;
        tally[2*k + 1] += dem.masses()[i];
    }
    MPI_Allreduce(MPI_IN_PLACE, tally.data(), int(tally.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    removed.tags = TfdemRanks::gatherIds(mine.data(), mine.size());
    if (removed.tags.empty())
    {
        return removed;
    }
    dem.remove_particles(removed.tags);
    for (std::size_t k = 0; k < outlets_.size(); ++k)
    {
        outlets_[k].countSinceWrite += label(tally[2*k]);
        outlets_[k].massSinceWrite += tally[2*k + 1];
        removed.mass += tally[2*k + 1];
    }
    return removed;
}


void Foam::TfdemOutlets::write(const Time& runTime)
{
    for (Outlet& o : outlets_)
    {
        if (file_)
        {
            *file_
                << setprecision(10) << runTime.value() << ' ' << o.name << ' '
                << o.countSinceWrite << ' ' << setprecision(17) << o.massSinceWrite << endl;
        }
        o.countSinceWrite = 0;
        o.massSinceWrite = 0;
    }
}
