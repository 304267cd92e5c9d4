#include "tfdemRunReport.H"
#include "tfdemRanks.H"

#include <mpi.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "tfdem/distributed_coupling.h"
#include "tfdem/scene_check.h"

Foam::TfdemRunReport::TfdemRunReport(const Time& runTime)
:
    runTime_(runTime),
    wallStart_(std::chrono::steady_clock::now())
{}


void Foam::TfdemRunReport::communication
(
    double bytesSent,
    double messagesSent,
    std::size_t ghosts,
    std::size_t owned
)
{
    bytesSent_ = bytesSent;
    messagesSent_ = messagesSent;
    ghostSum_ += double(ghosts);
    ownedSum_ += double(owned);
    ghostMost_ = std::max(ghostMost_, double(ghosts));
    ++communicationSteps_;
}


void Foam::TfdemRunReport::communicationSummary() const
{
    if (TfdemRanks::count() < 2 || communicationSteps_ == 0)
    {
        return;
    }
    const double steps = communicationSteps_;
    double most[4] = {bytesSent_/steps, messagesSent_/steps, ghostSum_/steps, ghostMost_};
    double all[3] = {bytesSent_/steps, ghostSum_/steps, ownedSum_/steps};
    MPI_Allreduce(MPI_IN_PLACE, most, 4, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, all, 3, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    const double ranks = TfdemRanks::count();
    Info<< "TFDEM communication: per coupling step the cell exchange sent " << most[0]
        << " bytes in " << most[1] << " messages from the busiest rank (" << all[0]
        << " bytes from all " << TfdemRanks::count() << "); LIGGGHTS' ghost particles "
        << all[1]/ranks << " per rank on average (" << all[1]/max(all[2], 1.0)
        << " of the particles), " << most[3] << " on the fullest rank at most: its neighbour"
        << " exchange sends each ghost's position, velocity and spin (9 doubles, 72 bytes)"
        << " every DEM step" << endl;
}


void Foam::TfdemRunReport::couplingStep
(
    const tfdem::CouplingTotals& totals,
    double remoteRecords
)
{
    ++couplingSteps_;
    remoteRecords_ += remoteRecords;
    flooredCellSteps_ += totals.floored_cells;
    if (totals.floored_cells && totals.particle_volume > 0)
    {
        const double floored = totals.floored_solid_volume/totals.particle_volume;
        const double removed = totals.removed_solid_volume/totals.particle_volume;
        ++flooredSteps_;
        flooredShareSum_ += floored;
        largestFlooredShare_ = std::max(largestFlooredShare_, floored);
        largestRemovedShare_ = std::max(largestRemovedShare_, removed);
        lowestUnfloored_ = std::min(lowestUnfloored_, totals.lowest_unfloored);
        std::ostringstream s;
        s.precision(3);
        s   << "TFDEM coupling: void fraction floor used in " << totals.floored_cells
            << " cells (lowest value before it " << totals.lowest_unfloored << "): they hold "
            << 100*floored << " % of the particles' volume, whose drag sees the floor's eps; "
            << 100*removed << " % is left out of the gas's map";
        Info<< s.str().c_str() << endl;
    }
    if (totals.floored_cells == 0 && totals.particle_volume > 0)
    {
        ++volumeCheckedSteps_;
        maxVolumeMismatch_ = std::max
        (
            maxVolumeMismatch_,
            std::abs(totals.mapped_volume - totals.particle_volume)/totals.particle_volume
        );
    }
    const auto& m = totals.momentum_imbalance;
    if (totals.drag_magnitude_sum > 0)
    {
        maxMomentumImbalance_ = std::max
        (
            maxMomentumImbalance_,
            std::sqrt(m[0]*m[0] + m[1]*m[1] + m[2]*m[2])/totals.drag_magnitude_sum
        );
    }
    const auto& f = totals.pressure_force_imbalance;
    if (totals.pressure_force_magnitude_sum > 0)
    {
        maxPressureForceImbalance_ = std::max
        (
            maxPressureForceImbalance_,
            std::sqrt(f[0]*f[0] + f[1]*f[1] + f[2]*f[2])
           /totals.pressure_force_magnitude_sum
        );
    }
}


void Foam::TfdemRunReport::progress()
{
    const scalar t = runTime_.value();
    const scalar start = runTime_.startTime().value();
    const scalar end = runTime_.endTime().value();
    const scalar halfStep = 0.5*runTime_.deltaTValue();
    if (t + halfStep < nextProgressTime_ && t + halfStep < end)
    {
        return;
    }
    nextProgressTime_ = t + 0.01*(end - start);
    const double wall = std::chrono::duration<double>
    (
        std::chrono::steady_clock::now() - wallStart_
    ).count();
    const scalar done = (t - start)/(end - start);
    Info<< "TFDEM progress: t = " << t << " s of " << end << " s, wall "
        << label(wall) << " s, ETA " << label(done > 0 ? wall*(1 - done)/done : 0)
        << " s" << endl;
}


void Foam::TfdemRunReport::momentumExchange
(
    scalar dt,
    const vector& gasReceived,
    const vector& particleDrag,
    scalar particleDragMagnitude
)
{
    gasImpulse_ += dt*gasReceived;
    particleImpulse_ += dt*particleDrag;
    dragImpulseMagnitude_ += dt*particleDragMagnitude;
    largestStepExchangeDifference_ =
        max(largestStepExchangeDifference_, dt*mag(gasReceived - particleDrag));
    ++exchangeSteps_;
}


void Foam::TfdemRunReport::courant(scalar courantNumber)
{
    largestCourant_ = max(largestCourant_, courantNumber);
    if (!runTime_.writeTime())
    {
        return;
    }
    Info<< "TFDEM gas Courant number: largest " << largestCourant_ << " since the last write"
        << endl;
    const std::string problem =
        tfdem::gas_step_problem(largestCourant_, runTime_.deltaTValue());
    if (!problem.empty())
    {
        Info<< "TFDEM warning: " << problem.c_str() << endl;
    }
    largestCourant_ = 0;
}


void Foam::TfdemRunReport::floorSummary(scalar floor) const
{
    if (flooredSteps_ == 0)
    {
        return;
    }
    const double steps = std::max(couplingSteps_, label(1));
    const double meanShare = flooredShareSum_/steps;
    std::ostringstream s;
    s.precision(3);
    s   << "TFDEM void fraction floor " << floor << ": used in " << flooredSteps_ << " of "
        << couplingSteps_ << " coupling steps (" << 100*flooredSteps_/steps << " %), lowest eps"
        << " before it " << lowestUnfloored_ << ". The particles in floored cells were "
        << 100*meanShare << " % of the particles' volume over the run (at most "
        << 100*largestFlooredShare_ << " % in one step): their drag saw eps = " << floor
        << " instead of a lower one, and the map left out at most " << 100*largestRemovedShare_
        << " % of the particles' volume in one step. ";
    if (meanShare < negligibleFlooredShare)
    {
        s   << "Below " << 100*negligibleFlooredShare << " % of the bed over the run this changes"
            << " the bed's drag far less than the drag law's own uncertainty: it does not matter"
            << " for bed averages.";
    }
    else
    {
        s   << "Above " << 100*negligibleFlooredShare << " % of the bed over the run it may"
            << " change the bed's drag and expansion: use cells several particle diameters wide,"
            << " or coupling.void_fraction.method porous_cube or divided.";
    }
    Info<< s.str().c_str() << endl;
}


namespace
{

//- This process's peak resident set (VmHWM of /proc/self/status), MB; 0 where there is none
double peakResidentMegabytes()
{
    std::ifstream status("/proc/self/status");
    std::string key;
    double kilobytes = 0;
    while (status >> key)
    {
        if (key == "VmHWM:")
        {
            status >> kilobytes;
            break;
        }
        status.ignore(1024, '\n');
    }
    return kilobytes/1024.0;
}

}  // namespace


void Foam::TfdemRunReport::memory() const
{
    struct { double megabytes; int rank; } mine{peakResidentMegabytes(), TfdemRanks::rank()}, most, least;
    double total = mine.megabytes;
    MPI_Allreduce(&mine, &most, 1, MPI_DOUBLE_INT, MPI_MAXLOC, MPI_COMM_WORLD);
    MPI_Allreduce(&mine, &least, 1, MPI_DOUBLE_INT, MPI_MINLOC, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    Info<< "TFDEM memory: peak resident set " << most.megabytes << " MB on the largest of "
        << TfdemRanks::count() << " rank(s) (rank " << most.rank << "), " << least.megabytes
        << " MB on the smallest (rank " << least.rank << "), " << total << " MB over all (gas,"
        << " DEM and coupling of each rank's process)" << endl;
}


void Foam::TfdemRunReport::report
(
    const tfdem::CouplingTotals& last,
    const word& transferMethod,
    scalar voidFractionFloor
) const
{
    floorSummary(voidFractionFloor);
    const auto& m = last.momentum_imbalance;
    Info<< "TFDEM coupling: " << couplingSteps_ << " coupling steps; void"
        << " fraction floor used in " << flooredCellSteps_ << " cell-steps;"
        << " last momentum imbalance (particle drag - gas sink) ("
        << m[0] << " " << m[1] << " " << m[2] << ") N of total |drag| "
        << last.drag_magnitude_sum << " N" << nl
        << "TFDEM conservation: max |sum (1-eps) V_cell - sum V_p| / sum V_p = "
        << maxVolumeMismatch_ << " over " << volumeCheckedSteps_
        << " steps without floor; max |momentum imbalance|"
        << " / sum |drag| = " << maxMomentumImbalance_ << " (" << transferMethod << ")"
        << "; max |pressure force imbalance| / sum V_p |grad p| = "
        << maxPressureForceImbalance_ << endl;
    if (dragImpulseMagnitude_ > 0)
    {
        Info<< "TFDEM momentum exchange: drag impulse the gas received " << gasImpulse_
            << " N s, the particles " << particleImpulse_ << " N s over the run; |difference|"
            << " / sum |drag impulse| = "
            << mag(gasImpulse_ - particleImpulse_)/dragImpulseMagnitude_
            << " over " << exchangeSteps_ << " coupling steps; the largest of one step is "
            << largestStepExchangeDifference_*exchangeSteps_/dragImpulseMagnitude_
            << " of a step's mean |drag impulse| (the particles feel the gas velocity of the"
            << " step before)" << endl;
    }
    if (TfdemRanks::gasWhole())
    {
        Info<< "TFDEM parallel: the gas whole on each of " << TfdemRanks::count()
            << " ranks; the cells' particle sums added on rank 0 and broadcast in each of "
            << couplingSteps_ << " coupling steps" << endl;
    }
    else if (TfdemRanks::count() > 1)
    {
        double received = remoteRecords_;
        MPI_Allreduce(MPI_IN_PLACE, &received, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
        Info<< "TFDEM parallel: " << received
            << " cell records received from particles on other ranks over "
            << couplingSteps_ << " coupling steps" << endl;
    }
    const double* s = seconds_;
    const double total = s[0] + s[1] + s[2] + s[3] + s[4] + s[5];
    if (total > 0)
    {
        Info<< "TFDEM timing: DEM " << s[0] << " s, locate+map " << s[1]
            << " s, forces " << s[2] << " s, gas " << s[3] << " s, statistics " << s[4]
            << " s, checkpoints " << s[5] << " s; (DEM + coupling + gas) / DEM = "
            << (s[0] > 0 ? (s[0] + s[1] + s[2] + s[3])/s[0] : 0) << " on "
            << TfdemRanks::count() << " rank(s)" << endl;
    }
    communicationSummary();
    memory();
}
