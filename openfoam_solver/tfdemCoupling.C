#include "tfdemCoupling.H"
#include "IOmanip.H"

#include <mpi.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "dem_instance.h"
#include "tfdem/contact.h"

namespace
{

const Foam::word couplingFileName("coupling.yaml");

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

bool ownsMpi = false;

// Relative difference |a - b| / max(|a|, |b|).
double relativeDifference(double a, double b)
{
    const double scale = std::max(std::abs(a), std::abs(b));
    return scale > 0 ? std::abs(a - b)/scale : 0;
}

constexpr double geometryTolerance = 1e-9;

} // End anonymous namespace


bool Foam::TfdemCoupling::caseIsCoupled(const Time& runTime)
{
    return isFile(runTime.globalPath()/couplingFileName);
}


Foam::TfdemCoupling::TfdemCoupling
(
    const fvMesh& mesh,
    const volVectorField& pressureGradient,
    const volVectorField& gasVelocity,
    volScalarField& voidFraction,
    volScalarField& Ksl,
    volVectorField& Us,
    const dimensionedScalar& rho,
    const dimensionedScalar& nu,
    const fileName& forceRecordFile
)
:
    mesh_(mesh),
    pressureGradient_(pressureGradient),
    gasVelocity_(gasVelocity),
    voidFraction_(voidFraction),
    Ksl_(Ksl),
    Us_(Us),
    wallStart_(std::chrono::steady_clock::now())
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

    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised)
    {
        MPI_Init(nullptr, nullptr);
        ownsMpi = true;
    }
    MPI_Comm_dup(MPI_COMM_WORLD, &demComm_);

    checkGasProperties(rho, nu);
    createCore(setUpGrid());
    checkTwoDimensionalDepth();

    const fileName script(mesh.time().globalPath()/config_.dem_script);
    try
    {
        dem_.reset
        (
            new tfdem::DemInstance
            (
                demComm_,
                script,
                mesh.time().globalPath()/"log.liggghts"
            )
        );
    }
    catch (const std::runtime_error& e)
    {
        FatalErrorInFunction
            << configFile << ": dem.script: " << e.what() << exit(FatalError);
    }
    Info<< "TFDEM coupling: " << dem_->global_count() << " particles, DEM step "
        << dem_->time_step() << " s, " << config_.coupling_interval
        << " DEM steps per gas step" << nl << endl;
    checkTimeSteps(mesh.time());
    if (!forceRecordFile.empty())
    {
        const fileName path(forceRecordFile + "." + Foam::name(Pstream::myProcNo()));
        forceRecord_.open(path, std::ios::binary);
        if (!forceRecord_)
        {
            FatalErrorInFunction
                << "-recordForces: cannot write " << path << exit(FatalError);
        }
    }
    couple();
}


Foam::TfdemCoupling::~TfdemCoupling()
{
    dem_.reset();
    core_.reset();
    MPI_Comm_free(&demComm_);
    if (ownsMpi)
    {
        MPI_Finalize();
    }
}


void Foam::TfdemCoupling::checkGasProperties
(
    const dimensionedScalar& rho,
    const dimensionedScalar& nu
) const
{
    const double mu = rho.value()*nu.value();
    if
    (
        relativeDifference(rho.value(), config_.gas.density) > 1e-12
     || relativeDifference(mu, config_.gas.viscosity) > 1e-12
    )
    {
        FatalErrorInFunction
            << "gas properties disagree: constant/transportProperties gives rho = "
            << rho.value() << " kg/m^3, mu = rho nu = " << mu << " Pa s; "
            << config_.file.c_str() << " gives gas.density = " << config_.gas.density
            << ", gas.viscosity = " << config_.gas.viscosity
            << ". Make them equal." << exit(FatalError);
    }
}


Foam::labelList Foam::TfdemCoupling::setUpGrid()
{
    const boundBox domain(mesh_.points(), true);
    const boundBox firstCell(mesh_.points(), mesh_.cellPoints()[0], false);
    vector spacing = firstCell.span();
    reduce(spacing, maxOp<vector>());
    for (direction a = 0; a < 3; ++a)
    {
        grid_.origin[a] = domain.min()[a];
        grid_.spacing[a] = spacing[a];
        grid_.count[a] = std::lround(domain.span()[a]/grid_.spacing[a]);
    }
    // Every grid cell must be exactly one mesh cell, on exactly one rank.
    const double cellVolume = grid_.cell_volume();
    bool uniform = (returnReduce(mesh_.nCells(), sumOp<label>()) == grid_.cell_count());
    labelList gridCellOfCell(mesh_.nCells(), -1);
    std::vector<int> meshCellsInGridCell(uniform ? grid_.cell_count() : 0, 0);
    forAll(mesh_.C(), celli)
    {
        const point& c = mesh_.C()[celli];
        const double x[3] = {c.x(), c.y(), c.z()};
        const int g = uniform ? grid_.locate(x) : -1;
        if (g < 0 || relativeDifference(mesh_.V()[celli], cellVolume) > geometryTolerance)
        {
            uniform = false;
            break;
        }
        gridCellOfCell[celli] = g;
        ++meshCellsInGridCell[g];
    }
    reduce(uniform, andOp<bool>());
    if (uniform)
    {
        MPI_Allreduce
        (
            MPI_IN_PLACE, meshCellsInGridCell.data(), grid_.cell_count(), MPI_INT,
            MPI_SUM, MPI_COMM_WORLD
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
            << returnReduce(mesh_.nCells(), sumOp<label>())
            << " cells in the box " << domain << exit(FatalError);
    }
    Info<< "TFDEM coupling: Cartesian grid " << grid_.count[0] << " x "
        << grid_.count[1] << " x " << grid_.count[2] << " cells of "
        << grid_.spacing[0] << " x " << grid_.spacing[1] << " x "
        << grid_.spacing[2] << " m" << endl;
    return gridCellOfCell;
}


void Foam::TfdemCoupling::createCore(const labelList& gridCellOfCell)
{
    std::vector<int> ownerOfGridCell(grid_.cell_count(), -1);
    for (const label g : gridCellOfCell)
    {
        ownerOfGridCell[g] = Pstream::myProcNo();
    }
    MPI_Allreduce
    (
        MPI_IN_PLACE, ownerOfGridCell.data(), grid_.cell_count(), MPI_INT, MPI_MAX,
        MPI_COMM_WORLD
    );
    const std::vector<int> ownedCells(gridCellOfCell.begin(), gridCellOfCell.end());
    core_.reset
    (
        new tfdem::DistributedCoupling
        (
            MPI_COMM_WORLD, grid_, std::move(ownerOfGridCell), ownedCells,
            std::vector<double>(ownedCells.size(), grid_.cell_volume()),
            config_.void_fraction, config_.transfer
        )
    );
}


void Foam::TfdemCoupling::checkTwoDimensionalDepth() const
{
    if (!config_.void_fraction.two_dimensional)
    {
        return;
    }
    const double depth = grid_.spacing[2];
    if
    (
        grid_.count[2] != 1
     || relativeDifference(depth, config_.particle_diameter) > geometryTolerance
    )
    {
        FatalErrorInFunction
            << config_.file.c_str() << ": coupling.void_fraction.two_dimensional"
            << " is true, so the mesh must be one cell deep with depth = "
            << "particles.diameter = " << config_.particle_diameter
            << " m (seed 000 2-D rule); the mesh has " << grid_.count[2]
            << " cell(s) of depth " << depth << " m" << exit(FatalError);
    }
}


void Foam::TfdemCoupling::checkContactTimeStep() const
{
    tfdem::DemInstance::LinearContact contact;
    if (!dem_->linear_contact(contact) || (contact.damping < 0 && contact.restitution < 0))
    {
        Info<< "TFDEM coupling: no linear k_n with gamman_abs or coefficientRestitution"
            << " in the DEM script: contact time not checked" << endl;
        return;
    }
    double lightest = std::numeric_limits<double>::max();
    for (std::size_t i = 0; i < dem_->local_count(); ++i)
    {
        lightest = std::min(lightest, dem_->masses()[i]);
    }
    reduce(lightest, minOp<scalar>());
    if (lightest == std::numeric_limits<double>::max())
    {
        return;
    }
    const double mEff = tfdem::contact::effective_mass(lightest, lightest);
    const double tc = contact.damping >= 0
      ? tfdem::contact::contact_time_from_damping(contact.stiffness, contact.damping, mEff)
      : tfdem::contact::contact_time(contact.stiffness, contact.restitution, mEff);
    const double dt = dem_->time_step();
    Info<< "TFDEM coupling: particle-particle contact time t_c = " << tc
        << " s (k_n = " << contact.stiffness << " N/m, lightest particles), "
        << tc/dt << " DEM steps per contact" << endl;
    if (dt > tc/10)
    {
        FatalErrorInFunction
            << mesh_.time().globalPath()/config_.dem_script << ": DEM timestep " << dt
            << " s is above t_c/10 = " << tc/10 << " s (seed 000 eq. 26 with k_n = "
            << contact.stiffness << " N/m and the lightest particles): contacts are not"
            << " resolved; use timestep <= t_c/50 = " << tc/50 << " s"
            << exit(FatalError);
    }
}


void Foam::TfdemCoupling::checkTimeSteps(const Time& runTime) const
{
    checkContactTimeStep();
    if (runTime.controlDict().lookupOrDefault<Switch>("adjustTimeStep", false))
    {
        FatalErrorInFunction
            << "system/controlDict: adjustTimeStep must be 'no' for a coupled"
            << " case: the gas step is coupling_interval DEM steps"
            << exit(FatalError);
    }
    const double demInterval = config_.coupling_interval*dem_->time_step();
    if (relativeDifference(runTime.deltaTValue(), demInterval) > 1e-9)
    {
        FatalErrorInFunction
            << "system/controlDict: deltaT = " << runTime.deltaTValue()
            << " s must equal dem.coupling_interval x DEM timestep = "
            << config_.coupling_interval << " x " << dem_->time_step() << " = "
            << demInterval << " s (" << config_.file.c_str()
            << "); the coupling interval must divide the gas step evenly"
            << exit(FatalError);
    }
}


void Foam::TfdemCoupling::evolve()
{
    const Clock::time_point start = Clock::now();
    dem_->run(config_.coupling_interval);
    demSeconds_ += secondsSince(start);
    couple();
}


namespace
{

// The components of a vector field's internal values, 3 doubles per cell (Vector<scalar> is
// three contiguous scalars), for the core's flat arrays.
static_assert(sizeof(Foam::vector) == 3*sizeof(double), "vector must be 3 packed doubles");

const double* flatComponents(const Foam::volVectorField& field)
{
    return reinterpret_cast<const double*>(field.primitiveField().cdata());
}

} // End anonymous namespace


void Foam::TfdemCoupling::couple()
{
    const Clock::time_point mapStart = Clock::now();
    const std::size_t n = dem_->local_count();
    diameter_.resize(n);
    density_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        diameter_[i] = 2*dem_->radii()[i];
        density_[i] = dem_->masses()[i]/tfdem::sphere_volume(diameter_[i]);
    }
    const tfdem::ParticleView particles
    {
        n, dem_->positions(), dem_->velocities(), diameter_.data(), density_.data()
    };
    try
    {
        core_->map(particles);
    }
    catch (const std::out_of_range& e)
    {
        FatalErrorInFunction
            << "at t = " << mesh_.time().value() << " s: " << e.what()
            << exit(FatalError);
    }
    const tfdem::CouplingTotals& totals = core_->totals();
    remoteRecords_ += core_->exchange().remote_records();
    flooredCellSteps_ += totals.floored_cells;
    ++couplingSteps_;
    if (totals.floored_cells)
    {
        Info<< "TFDEM coupling: void fraction floor "
            << config_.void_fraction.gas_fraction_floor << " used in "
            << totals.floored_cells << " cells (lowest value before it "
            << totals.lowest_unfloored << ")" << endl;
    }
    mapSeconds_ += secondsSince(mapStart);

    const Clock::time_point forceStart = Clock::now();
    // Gas velocity: U, which pEqn.H sets to the superficial face fluxes (they satisfy
    // continuity exactly) reconstructed in the cell and divided by eps, free of the odd-even
    // wiggles a cell-centred momentum solution has where eps and K jump (bed surfaces)
    core_->forces
    (
        particles, flatComponents(gasVelocity_),
        config_.pressure_gradient_force ? flatComponents(pressureGradient_) : nullptr
    );
    checkConservation();
    const std::vector<double>& force = core_->particle_force();
    std::copy(force.begin(), force.end(), dem_->fluid_force());
    writeCellFields();
    forceSeconds_ += secondsSince(forceStart);
    recordForces();
}


void Foam::TfdemCoupling::recordForces()
{
    if (!forceRecord_.is_open())
    {
        return;
    }
    // Per step: particle count (uint64), their atom IDs (int), their forces (3 doubles each)
    const Clock::time_point start = Clock::now();
    const std::uint64_t n = dem_->local_count();
    forceRecord_.write(reinterpret_cast<const char*>(&n), sizeof(n));
    forceRecord_.write(reinterpret_cast<const char*>(dem_->tags()), n*sizeof(int));
    forceRecord_.write
    (
        reinterpret_cast<const char*>(core_->particle_force().data()), 3*n*sizeof(double)
    );
    recordSeconds_ += secondsSince(start);
}


void Foam::TfdemCoupling::writeCellFields()
{
    scalarField& eps = voidFraction_.primitiveFieldRef();
    scalarField& K = Ksl_.primitiveFieldRef();
    vectorField& Us = Us_.primitiveFieldRef();
    const std::vector<double>& coreEps = core_->gas_fraction();
    const std::vector<double>& coreK = core_->coefficient();
    const std::vector<double>& coreUs = core_->solid_velocity();
    forAll(eps, celli)
    {
        eps[celli] = coreEps[celli];
        K[celli] = coreK[celli];
        Us[celli] = vector(coreUs[3*celli], coreUs[3*celli + 1], coreUs[3*celli + 2]);
    }
    voidFraction_.correctBoundaryConditions();
    Ksl_.correctBoundaryConditions();
    Us_.correctBoundaryConditions();
}


void Foam::TfdemCoupling::checkConservation()
{
    const tfdem::CouplingTotals& totals = core_->totals();
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
}


void Foam::TfdemCoupling::report() const
{
    reportConservation();
    reportPositions();
    reportTiming();
}


void Foam::TfdemCoupling::reportConservation() const
{
    const tfdem::CouplingTotals& totals = core_->totals();
    const auto& m = totals.momentum_imbalance;
    Info<< "TFDEM coupling: " << couplingSteps_ << " coupling steps; void"
        << " fraction floor used in " << flooredCellSteps_ << " cell-steps;"
        << " last momentum imbalance (particle drag - gas sink) ("
        << m[0] << " " << m[1] << " " << m[2] << ") N of total |drag| "
        << totals.drag_magnitude_sum << " N" << nl
        << "TFDEM conservation: max |sum (1-eps) V_cell - sum V_p| / sum V_p = "
        << maxVolumeMismatch_ << " over " << volumeCheckedSteps_
        << " steps without floor; max |momentum imbalance|"
        << " / sum |drag| = " << maxMomentumImbalance_ << " ("
        << tfdem::transfer_method_names()[int(config_.transfer.method)].c_str()
        << ")" << endl;
    if (Pstream::parRun())
    {
        Info<< "TFDEM parallel: " << returnReduce(remoteRecords_, sumOp<scalar>())
            << " cell records received from particles on other ranks over "
            << couplingSteps_ << " coupling steps" << endl;
    }
}


void Foam::TfdemCoupling::reportPositions() const
{
    // Equal in a DEM-only replay of the recorded forces when the particles went through the
    // same steps and contacts
    double positionSum[3] = {0, 0, 0};
    for (std::size_t i = 0; i < 3*dem_->local_count(); ++i)
    {
        positionSum[i % 3] += dem_->positions()[i];
    }
    MPI_Allreduce(MPI_IN_PLACE, positionSum, 3, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    Info<< "TFDEM positions: sum of x, y, z over particles = "
        << setprecision(17) << positionSum[0] << " " << positionSum[1] << " "
        << positionSum[2] << setprecision(IOstream::defaultPrecision()) << endl;
    if (forceRecord_.is_open())
    {
        Info<< "TFDEM record: forces written in "
            << returnReduce(recordSeconds_, maxOp<scalar>()) << " s (not in the split below)"
            << endl;
    }
}


void Foam::TfdemCoupling::reportTiming() const
{
    // Split of rank 0's coupled loop, the rank Info prints on (the parts run one after the
    // other, so a rank's sum is the loop's wall time; time a rank spends waiting for others
    // falls in the part it waits in)
    const double split[4] = {demSeconds_, mapSeconds_, forceSeconds_, gasSeconds_};
    const double total = split[0] + split[1] + split[2] + split[3];
    if (total > 0)
    {
        Info<< "TFDEM timing: DEM " << split[0] << " s, locate+map " << split[1]
            << " s, forces " << split[2] << " s, gas " << split[3]
            << " s; (DEM + coupling + gas) / DEM = " << (split[0] > 0 ? total/split[0] : 0)
            << " on " << Pstream::nProcs() << " rank(s)" << endl;
    }
}


void Foam::TfdemCoupling::progress()
{
    const Time& runTime = mesh_.time();
    const scalar t = runTime.value();
    const scalar end = runTime.endTime().value();
    if (t + 0.5*runTime.deltaTValue() < nextProgressTime_ && t + 0.5*runTime.deltaTValue() < end)
    {
        return;
    }
    nextProgressTime_ = t + 0.01*(end - runTime.startTime().value());
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart_).count();
    const scalar done = (t - runTime.startTime().value())/(end - runTime.startTime().value());
    Info<< "TFDEM progress: t = " << t << " s of " << end << " s, wall "
        << label(wall) << " s, ETA " << label(done > 0 ? wall*(1 - done)/done : 0)
        << " s" << endl;
}
