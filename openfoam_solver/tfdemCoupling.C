#include "tfdemCoupling.H"

#include <mpi.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tfdem/distributed_coupling.h"
#include "tfdem/engine_registry.h"
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

// The fastest inflow: the largest |U| on the patches where U is fixed and gas flows in (an
// outlet's velocity, fixed by its condition on a resumed run, is no inflow)
Foam::scalar largestInflowSpeed(const Foam::volVectorField& U)
{
    Foam::scalar fastest = 0;
    forAll(U.boundaryField(), patchi)
    {
        // The case's own patches only: every rank holds them in the same order (a split
        // run's processor patches differ by rank, and the sums below are collective)
        const Foam::fvPatchVectorField& Ub = U.boundaryField()[patchi];
        if (Ub.coupled() || !Ub.fixesValue())
        {
            continue;
        }
        const Foam::scalar inflow = -Foam::gSum(Ub & U.mesh().Sf().boundaryField()[patchi]);
        if (inflow > 0)
        {
            fastest = Foam::max(fastest, Foam::gMax(Foam::mag(Ub)));
        }
    }
    return fastest;
}

// The speed of a free fall over the domain's extent along gravity: an impact any bed sees.
Foam::scalar fallSpeed(const Foam::volVectorField& U, const Foam::vector& g)
{
    const Foam::boundBox domain(U.mesh().points(), true);
    return Foam::mag(g) > 0 ? std::sqrt(2*Foam::mag(g)*Foam::mag(domain.span() & (g/Foam::mag(g)))) : 0;
}

} // End anonymous namespace


Foam::TfdemCoupling::TfdemCoupling
(
    TfdemCheckpoint& checkpoint,
    const fvMesh& mesh,
    const volVectorField& pressureGradient,
    const volVectorField& gasVelocity,
    volScalarField& voidFraction,
    surfaceScalarField& voidFractionFaces,
    surfaceScalarField& voidFractionFlux,
    const surfaceScalarField& flux,
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
    voidFractionFaces_(voidFractionFaces),
    voidFractionFlux_(voidFractionFlux),
    flux_(flux),
    exchangeCoefficient_(exchangeCoefficient),
    solidVelocity_(solidVelocity),
    checkpoint_(checkpoint),
    report_(mesh.time()),
    forceRecord_(forceRecordFile)
{
    const fileName configFile(mesh.time().globalPath()/couplingFileName);
    loadConfig(configFile);
    MPI_Comm_dup(MPI_COMM_WORLD, &demComm_);
    tfdemChecks::gasProperties(config_, rho, nu);
    grid_ = discoverGrid(mesh);
    tfdemChecks::twoDimensionalDepth(config_, grid_.grid);
    startCore(configFile);
    startDem(g.value());
    tfdemChecks::particles(config_, *dem_);
    tfdemChecks::packing(*dem_, g.value(), !checkpoint_.resuming());
    checkEngine(gasVelocity, g.value());
    startBookkeeping(configFile, g.value());

    const tfdem::ParticleView view = particles();
    mapGasFraction(view);
    if (!checkpoint_.resuming())
    {
        computeForces(view);
    }
}


void Foam::TfdemCoupling::loadConfig(const fileName& configFile)
{
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
}


void Foam::TfdemCoupling::startCore(const fileName& configFile)
{
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
            << " in y; the mapping into cells spreads h^2/12 of its variance, the diffusion"
            << " the rest)" << endl;
    }
    const std::array<int, 3>& block = config_.void_fraction.particle_field_block;
    if (block != std::array<int, 3>{1, 1, 1})
    {
        Info<< "TFDEM particle field on blocks of " << block[0] << " x " << block[1] << " x "
            << block[2] << " gas cells (" << block[0]*grid_.grid.spacing[0] << " x "
            << block[1]*grid_.grid.spacing[1] << " x " << block[2]*grid_.grid.spacing[2]
            << " m), interpolated back to the gas cells" << endl;
    }
}


void Foam::TfdemCoupling::startBookkeeping(const fileName& configFile, const vector& g)
{
    outlets_.reset
    (
        new TfdemOutlets
        (
            mesh_, config_.outlets, configFile, *dem_, config_.particle_diameters.back()
        )
    );
    accounting_.reset
    (
        new TfdemParticleAccounting(*dem_, checkpoint_.startTotals(), mesh_.time().value())
    );
    checkpoint_.verify(*dem_, accounting_->totals());
    statistics_.reset
    (
        new TfdemStatistics
        (
            mesh_, config_.output, config_.particle_diameters, grid_.grid,
            grid_.gridCellOfCell, g
        )
    );
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
    return mesh_.time().globalPath()/("log." + config_.engine);
}


void Foam::TfdemCoupling::startDem(const vector& g)
{
    // Files by their names in coupling.yaml: the case is the working directory (TfdemCase)
    const tfdem::DemResume resume = checkpoint_.demResume();
    if (checkpoint_.resuming() && !resume.engine.empty() && resume.engine != config_.engine)
    {
        FatalErrorInFunction
            << "the checkpoint at t = " << mesh_.time().timeName() << " s was written by the "
            << resume.engine.c_str() << " engine (its marker's engine entry) but "
            << config_.file.c_str() << " has dem.engine: " << config_.engine.c_str() << ". Fix:"
            << " resume it with dem.engine: " << resume.engine.c_str() << ", or start afresh"
            << " with " << config_.engine.c_str() << " (delete the time folders after the first)"
            << exit(FatalError);
    }
    tfdem::EngineStart start;
    start.communicator = MPI_Comm_c2f(demComm_);
    start.config = &config_;
    start.resume = checkpoint_.resuming() ? &resume : nullptr;
    for (direction a = 0; a < 3; ++a)
    {
        start.gravity[a] = g[a];
    }
    start.gas_step = mesh_.time().deltaTValue();
    start.log_file = demLog();
    try
    {
        dem_ = tfdem::find_engine(config_.engine)->start(start);
    }
    catch (const std::exception& e)
    {
        FatalErrorInFunction << config_.file.c_str() << ": " << e.what() << exit(FatalError);
    }
}


void Foam::TfdemCoupling::checkEngine(const volVectorField& U, const vector& g) const
{
    tfdem::CaseAtStart context;
    context.config = &config_;
    for (direction a = 0; a < 3; ++a)
    {
        context.gravity[a] = g[a];
        context.cell_size[a] = grid_.grid.spacing[a];
    }
    context.gas_step = mesh_.time().deltaTValue();
    context.adjustable_gas_step =
        mesh_.time().controlDict().lookupOrDefault<Switch>("adjustTimeStep", false);
    context.fastest_inflow = largestInflowSpeed(U);
    context.fall_speed = fallSpeed(U, g);
    context.resuming = checkpoint_.resuming();
    const tfdem::StartReport report = dem_->check_start(context);
    for (const std::string& line : report.lines)
    {
        Info<< line.c_str() << endl;
    }
    for (const std::string& warning : report.warnings)
    {
        Info<< "TFDEM warning: " << warning.c_str() << endl;
    }
    if (!report.refusal.empty())
    {
        FatalErrorInFunction << report.refusal.c_str() << exit(FatalError);
    }
    Info<< endl;
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
    accounting_->check(*dem_, runTime.value(), removed.tags, removed.mass);
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
    voidFractionFaces_ = fvc::interpolate(voidFraction_);
    voidFractionFlux_ = voidFractionFaces_*flux_;
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


void Foam::TfdemCoupling::gasSolved(double seconds)
{
    report_.addSeconds(TfdemRunReport::Part::gas, seconds);
    const vector gasReceived =
        gSum(mesh_.V().field()*exchangeCoefficient_.primitiveField()*(gasVelocity_.primitiveField() - solidVelocity_.primitiveField()));
    report_.momentumExchange
    (
        mesh_.time().deltaTValue(), gasReceived, particleDrag_, particleDragMagnitude_
    );
}


void Foam::TfdemCoupling::write()
{
    checkpoint_.checkDiskSpace();
    const bool gasWritten = !TfdemRanks::writesGas() || mesh_.time().write();
    const Clock::time_point start = Clock::now();
    outlets_->write(mesh_.time());
    checkpoint_.write(*dem_, accounting_->totals(), gasWritten);
    report_.addSeconds(TfdemRunReport::Part::checkpoint, secondsSince(start));
}


void Foam::TfdemCoupling::report() const
{
    const std::string engineReport = dem_->end_report();
    if (!engineReport.empty())
    {
        Info<< engineReport.c_str() << endl;
    }
    report_.report
    (
        core_->totals(),
        tfdem::transfer_method_names()[int(config_.transfer.method)],
        config_.void_fraction.void_fraction_floor
    );
    forceRecord_.report(*dem_);
}
