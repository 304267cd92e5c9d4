#include "tfdemCoupling.H"

#include <mpi.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "dem_instance.h"
#include "tfdem/hard_sphere/engine.h"
#include "tfdem/distributed_coupling.h"
#include "tfdemFailure.H"
#include "tfdemOutlets.H"
#include "tfdemParticleAccounting.H"
#include "tfdemRanks.H"
#include "tfdemStartupChecks.H"
#include "tfdemStatistics.H"

namespace
{

const Foam::word couplingFileName("coupling.yaml");

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// The components of a vector field's internal values, 3 doubles per cell (Vector<scalar> is
// three contiguous scalars), for the core's flat arrays.
static_assert(sizeof(Foam::vector) == 3*sizeof(double), "vector must be 3 packed doubles");

const double* flatComponents(const Foam::volVectorField& field)
{
    return reinterpret_cast<const double*>(field.primitiveField().cdata());
}

} // End anonymous namespace


Foam::TfdemCoupling::TfdemCoupling
(
    TfdemCheckpoint& checkpoint,
    const fvMesh& mesh,
    const volVectorField& pressureGradient,
    const volVectorField& gasVelocity,
    volScalarField& voidFraction,
    volScalarField& exchangeCoefficient,
    volVectorField& solidVelocity,
    const dimensionedScalar& rho,
    const dimensionedScalar& nu,
    const uniformDimensionedVectorField& g,
    const fileName& forceRecordFile
)
:
    mesh_(mesh),
    pressureGradient_(pressureGradient),
    gasVelocity_(gasVelocity),
    voidFraction_(voidFraction),
    exchangeCoefficient_(exchangeCoefficient),
    solidVelocity_(solidVelocity),
    checkpoint_(checkpoint),
    report_(mesh.time()),
    forceRecord_(forceRecordFile)
{
    const fileName configFile(mesh.time().globalPath()/couplingFileName);
    try
    {
        config_ = tfdem::load_coupling_config(configFile);
    }
    catch (const tfdem::ConfigError& e)
    {
        FatalErrorInFunction
            << "errors in " << configFile << ":\n" << e.what() << exit(FatalError);
    }
    Info<< tfdem::describe(config_).c_str() << endl;

    MPI_Comm_dup(MPI_COMM_WORLD, &demComm_);

    tfdemChecks::gasProperties(config_, rho, nu);
    grid_ = discoverGrid(mesh);
    tfdemChecks::twoDimensionalDepth(config_, grid_.grid);
    try
    {
        core_.reset
        (
            new tfdem::DistributedCoupling
            (
                MPI_COMM_WORLD, grid_.grid, grid_.ownerOfGridCell, grid_.gridCellOfCell,
                std::vector<double>(grid_.gridCellOfCell.size(), grid_.grid.cell_volume()),
                config_.void_fraction, config_.transfer
            )
        );
    }
    catch (const std::invalid_argument& e)
    {
        FatalErrorInFunction
            << "errors in " << configFile << ":\n" << e.what() << exit(FatalError);
    }
    if (config_.void_fraction.diffusion_bandwidth > 0)
    {
        const double b = config_.void_fraction.diffusion_bandwidth;
        Info<< "TFDEM diffusion smoothing: the particle fields spread with bandwidth b = " << b
            << " m (standard deviation b/sqrt(2) = " << b/std::sqrt(2.0) << " m, "
            << b/grid_.grid.spacing[0] << " cells in x, " << b/grid_.grid.spacing[1]
            << " in y)" << endl;
    }
    const std::array<int, 3>& block = config_.void_fraction.particle_field_block;
    if (block != std::array<int, 3>{1, 1, 1})
    {
        Info<< "TFDEM particle field on blocks of " << block[0] << " x " << block[1] << " x "
            << block[2] << " gas cells (" << block[0]*grid_.grid.spacing[0] << " x "
            << block[1]*grid_.grid.spacing[1] << " x " << block[2]*grid_.grid.spacing[2]
            << " m), interpolated back to the gas cells" << endl;
    }
    startDem(g.value());
    tfdemChecks::particles(config_, *dem_);
    tfdemChecks::packing(*dem_, g.value(), !checkpoint_.resuming());
    if (const auto* soft = dynamic_cast<const tfdem::DemInstance*>(dem_.get()))
    {
        tfdemChecks::gravity(g, *soft);
        tfdemChecks::timeSteps(mesh.time(), config_, *soft, gasVelocity, g.value());
        tfdemChecks::scene(config_, grid_.grid, *soft, gasVelocity, g.value());
    }
    outlets_.reset
    (
        new TfdemOutlets
        (
            mesh, config_.outlets, configFile, *dem_, config_.particle_diameters.back()
        )
    );
    accounting_.reset
    (
        new TfdemParticleAccounting(*dem_, checkpoint_.startTotals(), mesh.time().value())
    );
    checkpoint_.verify(*dem_, accounting_->totals());
    statistics_.reset
    (
        new TfdemStatistics
        (
            mesh, config_.output, config_.particle_diameters, grid_.grid,
            grid_.gridCellOfCell, g.value()
        )
    );

    const tfdem::ParticleView view = particles();
    mapGasFraction(view);
    if (!checkpoint_.resuming())
    {
        computeForces(view);
    }
}


Foam::TfdemCoupling::~TfdemCoupling()
{
    statistics_.reset();
    dem_.reset();
    core_.reset();
    MPI_Comm_free(&demComm_);
}


Foam::fileName Foam::TfdemCoupling::demLog() const
{
    return mesh_.time().globalPath()/"log.liggghts";
}


void Foam::TfdemCoupling::startDem(const vector& g)
{
    // Files by their names in coupling.yaml: the case is the working directory (TfdemCase)
    const tfdem::DemResume resume = checkpoint_.demResume();
    const tfdem::DemResume* resumed = checkpoint_.resuming() ? &resume : nullptr;
    const std::string engine =
        config_.engine == tfdem::Engine::HardSphere ? "hard_sphere" : "liggghts";
    if (resumed && !resume.engine.empty() && resume.engine != engine)
    {
        FatalErrorInFunction
            << "the checkpoint at t = " << mesh_.time().timeName() << " s was written by the "
            << resume.engine.c_str() << " engine (its marker's engine entry) but "
            << config_.file.c_str() << " has dem.engine: " << engine.c_str() << ". Fix: resume"
            << " it with dem.engine: " << resume.engine.c_str() << ", or start afresh with "
            << engine.c_str() << " (delete the time folders after the first)"
            << exit(FatalError);
    }
    if (config_.engine == tfdem::Engine::HardSphere)
    {
        if (TfdemRanks::count() > 1)
        {
            FatalErrorInFunction
                << config_.file.c_str() << ": dem.engine: hard_sphere runs on one rank (its"
                << " event-driven collisions are processed one after another), not on "
                << TfdemRanks::count() << ": run tfdemFoam without mpirun, or use dem.engine:"
                << " liggghts" << exit(FatalError);
        }
        const double gravity[3] = {g.x(), g.y(), g.z()};
        try
        {
            dem_.reset
            (
                new tfdem::hard_sphere::HardSphereEngine
                (
                    config_.hard_sphere, config_.dem_particles, gravity, resumed
                )
            );
        }
        catch (const std::exception& e)
        {
            FatalErrorInFunction << config_.file.c_str() << ": " << e.what() << exit(FatalError);
        }
        Info<< "TFDEM coupling: " << dem_->global_count() << " particles in "
            << dem_->name().c_str() << " (" << config_.dem_particles.c_str() << "), one flow step"
            << " per gas step of " << mesh_.time().deltaTValue() << " s, gravity " << g
            << " m/s^2 (constant/g)" << endl;
        const auto& hard = static_cast<const tfdem::hard_sphere::HardSphereEngine&>(*dem_);
        if (hard.overlaps().pairs + hard.overlaps().walls > 0)
        {
            Info<< "TFDEM hard spheres: " << label(hard.overlaps().pairs) << " overlapping pairs"
                << " and " << label(hard.overlaps().walls) << " spheres into a wall in "
                << config_.dem_particles.c_str() << " (deepest "
                << 100*hard.overlaps().deepest << " % of a diameter) taken as touching where"
                << " they are" << endl;
        }
        Info<< endl;
        return;
    }
    try
    {
        dem_.reset
        (
            new tfdem::DemInstance(demComm_, config_.dem_script, demLog(), resumed)
        );
    }
    catch (const std::exception& e)
    {
        FatalErrorInFunction
            << config_.file.c_str() << ": dem.script: " << e.what() << exit(FatalError);
    }
    for (const std::string& name : dem_->unresumable_outputs())
    {
        if (checkpoint_.resuming())
        {
            Info<< "TFDEM warning: " << name.c_str() << ": an output named by a pattern or a"
                << " variable is not cut back to the checkpoint (files written after it by"
                << " the stopped run stay until written again)" << endl;
        }
    }
    Info<< "TFDEM coupling: " << dem_->global_count() << " particles, DEM step "
        << static_cast<const tfdem::DemInstance&>(*dem_).time_step() << " s, "
        << tfdemChecks::couplingInterval
           (
               config_, mesh_.time().deltaTValue(),
               static_cast<const tfdem::DemInstance&>(*dem_).time_step()
           )
        << " DEM steps per gas step" << nl << endl;
    demBalance();
}


void Foam::TfdemCoupling::demBalance() const
{
    if (TfdemRanks::count() < 2)
    {
        return;
    }
    const std::array<int, 3> grid =
        static_cast<const tfdem::DemInstance&>(*dem_).processor_grid();
    double most = dem_->local_count(), least = most, total = most;
    MPI_Allreduce(MPI_IN_PLACE, &most, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &least, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    const double mean = total/TfdemRanks::count();
    Info<< "TFDEM parallel: LIGGGHTS' processor grid " << grid[0] << " x " << grid[1] << " x "
        << grid[2] << " (even cuts of the box): particles per rank " << least << " to " << most
        << ", mean " << mean;
    if (mean > 0 && most > kDemImbalance*mean)
    {
        Info<< ". TFDEM advice: the fullest rank holds " << most/mean << " times the mean and"
            << " the others wait for it every DEM step (its cuts leave ranks in the freeboard)."
            << " Fix: cut only across the bed (processors * 1 1; * 1 * for a 3-D bed)";
    }
    Info<< nl << endl;
}


tfdem::ParticleView Foam::TfdemCoupling::particles()
{
    const std::size_t n = dem_->local_count();
    diameter_.resize(n);
    density_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        diameter_[i] = 2*dem_->radii()[i];
        density_[i] = dem_->masses()[i]/tfdem::sphere_volume(diameter_[i]);
    }
    return {n, dem_->positions(), dem_->velocities(), diameter_.data(), density_.data()};
}


void Foam::TfdemCoupling::evolve()
{
    const Time& runTime = mesh_.time();
    Clock::time_point start = Clock::now();
    const bool recordContacts = statistics_->due(runTime);
    tfdemFailure::enter(tfdemFailure::Phase::dem, runTime.value());
    try
    {
        dem_->advance(runTime.deltaTValue(), recordContacts);
    }
    catch (const std::exception& e)
    {
        FatalErrorInFunction
            << "at t = " << runTime.value() << " s, " << dem_->name().c_str() << ": " << e.what()
            << exit(FatalError);
    }
    tfdemFailure::enter(tfdemFailure::Phase::coupling, runTime.value());
    const TfdemOutlets::Removed removed = outlets_->remove(*dem_);
    accounting_->check(*dem_, runTime.value(), removed.tags, removed.mass, demLog() + ".screen");
    report_.addSeconds(TfdemRunReport::Part::dem, secondsSince(start));

    const tfdem::ParticleView view = particles();
    mapGasFraction(view);
    computeForces(view);

    if (recordContacts)
    {
        start = Clock::now();
        statistics_->record(runTime, *dem_, view, *core_);
        report_.addSeconds(TfdemRunReport::Part::statistics, secondsSince(start));
    }
}


void Foam::TfdemCoupling::mapGasFraction(const tfdem::ParticleView& view)
{
    const Clock::time_point start = Clock::now();
    try
    {
        core_->map(view);
    }
    catch (const std::exception& e)
    {
        FatalErrorInFunction
            << "at t = " << mesh_.time().value() << " s: " << e.what() << exit(FatalError);
    }
    if (core_->totals().lowest_unfloored <= 0)
    {
        stopOnEmptyGas(view);
    }
    scalarField& eps = voidFraction_.primitiveFieldRef();
    const std::vector<double>& coreEps = core_->void_fraction();
    forAll(eps, celli)
    {
        eps[celli] = coreEps[celli];
    }
    voidFraction_.correctBoundaryConditions();
    report_.addSeconds(TfdemRunReport::Part::map, secondsSince(start));
}


void Foam::TfdemCoupling::computeForces(const tfdem::ParticleView& view)
{
    const Clock::time_point start = Clock::now();
    // Gas velocity: U, which pEqn.H sets to the superficial face fluxes (they satisfy
    // continuity exactly) reconstructed in the cell and divided by eps, free of the odd-even
    // wiggles a cell-centred momentum solution has where eps and K jump (bed surfaces)
    try
    {
        core_->forces
        (
            view, flatComponents(gasVelocity_),
            config_.pressure_gradient_force ? flatComponents(pressureGradient_) : nullptr
        );
    }
    catch (const std::exception& e)
    {
        FatalErrorInFunction
            << "at t = " << mesh_.time().value() << " s: " << e.what() << exit(FatalError);
    }
    report_.couplingStep(core_->totals(), core_->exchange().remote_records());
    report_.communication
    (
        core_->exchange().bytes_sent(), core_->exchange().messages_sent(),
        dem_->ghost_count(), dem_->local_count()
    );
    const std::vector<double>& drag = core_->particle_drag();
    double sums[4] = {0, 0, 0, 0};
    for (std::size_t i = 0; i < view.count; ++i)
    {
        const double* f = &drag[3*i];
        for (int a = 0; a < 3; ++a) sums[a] += f[a];
        sums[3] += std::sqrt(f[0]*f[0] + f[1]*f[1] + f[2]*f[2]);
    }
    MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    particleDrag_ = vector(sums[0], sums[1], sums[2]);
    particleDragMagnitude_ = sums[3];
    const std::vector<double>& force = core_->particle_force();
    dem_->set_fluid_force(force);

    scalarField& K = exchangeCoefficient_.primitiveFieldRef();
    vectorField& Us = solidVelocity_.primitiveFieldRef();
    const std::vector<double>& coreK = core_->exchange_coefficient();
    const std::vector<double>& coreUs = core_->solid_velocity();
    forAll(K, celli)
    {
        K[celli] = coreK[celli];
        Us[celli] = vector(coreUs[3*celli], coreUs[3*celli + 1], coreUs[3*celli + 2]);
    }
    exchangeCoefficient_.correctBoundaryConditions();
    solidVelocity_.correctBoundaryConditions();
    report_.addSeconds(TfdemRunReport::Part::forces, secondsSince(start));
    forceRecord_.write(*dem_, force);
}


void Foam::TfdemCoupling::stopOnEmptyGas(const tfdem::ParticleView& view) const
{
    const tfdem::CouplingTotals& totals = core_->totals();
    const tfdem::CartesianGrid& grid = grid_.grid;
    const int cell = totals.lowest_cell;
    const int i = cell % grid.count[0];
    const int j = (cell/grid.count[0]) % grid.count[1];
    const int k = cell/(grid.count[0]*grid.count[1]);
    std::ostringstream mine;
    for (const std::size_t p : core_->particles_in_cell(cell))
    {
        const double* x = view.position + 3*p;
        mine << "    id " << dem_->tags()[p] << " at (" << x[0] << ' ' << x[1] << ' '
             << x[2] << ") m, d = " << view.diameter[p] << " m\n";
    }
    const std::string listed = TfdemRanks::gatherText(mine.str());
    FatalErrorInFunction
        << "at t = " << mesh_.time().value() << " s the particles mapped into grid cell "
        << cell << " (i j k = " << i << ' ' << j << ' ' << k << ", centre ("
        << grid.centre(0, i) << ' ' << grid.centre(1, j) << ' ' << grid.centre(2, k)
        << ") m, volume " << grid.cell_volume() << " m^3) fill it: gas fraction "
        << totals.lowest_unfloored << " before any floor (coupling.void_fraction."
        << "method " << tfdem::void_fraction_method_names()[int(config_.void_fraction.method)].c_str()
        << "). Particles with a share in it:\n" << listed.c_str()
        << "A gas fraction <= 0 has no drag law and no gas. Fix: cells several particle"
        << " diameters wide, or a mapping that spreads each particle over the cells it"
        << " overlaps (coupling.void_fraction.method: divided or porous_cube), or, for cells"
        << " smaller than a particle, the diffusion smoothing (coupling.void_fraction."
        << "diffusion_bandwidth: 3-4 particle diameters in metres, with transfer:"
        << " per_particle_conservative)."
        << exit(FatalError);
}


void Foam::TfdemCoupling::gasSolved()
{
    const vector gasReceived =
        gSum(mesh_.V().field()*exchangeCoefficient_.primitiveField()*(gasVelocity_.primitiveField() - solidVelocity_.primitiveField()));
    report_.momentumExchange
    (
        mesh_.time().deltaTValue(), gasReceived, particleDrag_, particleDragMagnitude_
    );
}


void Foam::TfdemCoupling::write(bool gasWritten)
{
    const Clock::time_point start = Clock::now();
    outlets_->write(mesh_.time());
    checkpoint_.write(*dem_, accounting_->totals(), gasWritten);
    report_.addSeconds(TfdemRunReport::Part::checkpoint, secondsSince(start));
}


void Foam::TfdemCoupling::report() const
{
    if (const auto* hard = dynamic_cast<const tfdem::hard_sphere::HardSphereEngine*>(dem_.get()))
    {
        const tfdem::hard_sphere::FlightCounts& c = hard->totals();
        Info<< "TFDEM hard spheres: " << label(c.pair) << " pair and " << label(c.wall)
            << " wall collisions (" << label(c.elastic) << " made elastic by the TC model), "
            << label(c.predictions) << " event predictions, " << label(c.list_builds)
            << " builds of all neighbour lists and " << label(c.lists_renewed)
            << " of one particle's over " << std::to_string(hard->step()).c_str()
            << " flow steps" << endl;
    }
    report_.report
    (
        core_->totals(),
        tfdem::transfer_method_names()[int(config_.transfer.method)],
        config_.void_fraction.void_fraction_floor
    );
    forceRecord_.report(*dem_);
}
