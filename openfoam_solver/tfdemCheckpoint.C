#include "tfdemCheckpoint.H"
#include "tfdemRanks.H"
#include "IOmanip.H"
#include "IFstream.H"
#include "OFstream.H"
#include "OSspecific.H"

#include <mpi.h>

#include <cmath>

#include "dem_instance.h"

const Foam::word Foam::TfdemCheckpoint::restartName("dem.restart");
const Foam::word Foam::TfdemCheckpoint::markerName("tfdem.checkpoint");


Foam::fileName Foam::TfdemCheckpoint::directory(const word& timeName) const
{
    return runTime_.globalPath()/timeName;
}


Foam::TfdemCheckpoint::TfdemCheckpoint(const Time& runTime)
:
    runTime_(runTime)
{
    const word start = runTime.timeName();
    const fileName dir = directory(start);
    if (isFile(dir/markerName))
    {
        IFstream in(dir/markerName);
        const dictionary marker(in);
        startTotals_.count = marker.get<label>("particles");
        startTotals_.mass = marker.get<scalar>("particleMass");
        startTotals_.removedCount = marker.get<label>("removedParticles");
        startTotals_.removedMass = marker.get<scalar>("removedMass");
        startDemStep_ = std::llround(marker.get<scalar>("demStep"));
        resuming_ = true;
        if (marker.get<bool>("demRestart"))
        {
            restartFile_ = dir/restartName;
        }
        if (!restartFile_.empty() && !isFile(restartFile_))
        {
            FatalErrorInFunction
                << dir/markerName << " names a checkpoint but " << restartFile_
                << " is missing; restart from an earlier time" << exit(FatalError);
        }
        Info<< "TFDEM checkpoint: resuming gas and particles from t = " << start
            << " s (" << (restartFile_.empty() ? "no particles" : restartFile_.c_str())
            << ")" << nl << endl;
        return;
    }
    if (isFile(dir/restartName) || isFile(dir/(restartName + ".tmp")))
    {
        FatalErrorInFunction
            << "the checkpoint at t = " << start << " s is incomplete (" << dir
            << " has no " << markerName << ": the run was stopped while writing it)."
            << " Delete " << dir << " (and processor*/" << start << ") and start from the"
            << " time before" << exit(FatalError);
    }
    const instantList times = runTime.times();
    const scalar first = times.size() > 1 ? times[1].value() : runTime.value();
    if (runTime.value() > first + 0.5*runTime.deltaTValue())
    {
        FatalErrorInFunction
            << "the gas starts at t = " << start << " s but " << dir << " has no TFDEM"
            << " checkpoint (" << markerName << "): the particles would start as the DEM"
            << " script makes them at t = 0. Start from a time tfdemFoam wrote (startFrom"
            << " latestTime) or from the first time, " << first << " s" << exit(FatalError);
    }
}


void Foam::TfdemCheckpoint::verify
(
    const tfdem::DemInstance& dem,
    const ParticleTotals& totals
) const
{
    if (!resuming())
    {
        return;
    }
    const scalar demTime = dem.step()*dem.time_step();
    if
    (
        !restartFile_.empty()
     && (
            dem.step() != startDemStep_
         || std::abs(demTime - runTime_.value()) > 0.5*dem.time_step()
        )
    )
    {
        FatalErrorInFunction
            << restartFile_ << ": the DEM resumes at step " << std::to_string(dem.step()).c_str() << " (t = "
            << demTime << " s) but the checkpoint was written at step "
            << std::to_string(startDemStep_).c_str()
            << ", t = " << runTime_.timeName() << " s" << exit(FatalError);
    }
    if
    (
        totals.count != startTotals_.count
     || std::abs(totals.mass - startTotals_.mass) > 1e-12*startTotals_.mass
    )
    {
        FatalErrorInFunction
            << restartFile_ << " holds " << totals.count << " particles of "
            << totals.mass << " kg; the checkpoint was written with "
            << startTotals_.count << " particles of " << startTotals_.mass << " kg"
            << exit(FatalError);
    }
}


void Foam::TfdemCheckpoint::write
(
    tfdem::DemInstance& dem,
    const ParticleTotals& totals
) const
{
    const fileName dir = directory(runTime_.timeName());
    if (TfdemRanks::writesCase())
    {
        mkDir(dir);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    const bool demRestart = dem.write_restart(dir/restartName);
    if (TfdemRanks::writesCase())
    {
        const fileName partial(dir/(markerName + ".tmp"));
        {
            OFstream out(partial);
            out << "// TFDEM checkpoint, written after the fields and " << restartName
                << ": a time without it is incomplete" << nl
                << setprecision(17)
                << "time             " << runTime_.value() << ';' << nl
                << "demRestart       " << Switch(demRestart) << ';' << nl
                << "demStep          " << std::to_string(dem.step()).c_str() << ';' << nl
                << "particles        " << totals.count << ';' << nl
                << "particleMass     " << totals.mass << ';' << nl
                << "removedParticles " << totals.removedCount << ';' << nl
                << "removedMass      " << totals.removedMass << ';' << nl;
        }
        if (!mv(partial, dir/markerName))
        {
            FatalErrorInFunction
                << "cannot rename " << partial << " to " << dir/markerName
                << exit(FatalError);
        }
    }
    MPI_Barrier(MPI_COMM_WORLD);
}
