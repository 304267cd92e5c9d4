#include "tfdemCoupling.H"

#include <mpi.h>

#include <cmath>
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
    return isFile(runTime.path()/couplingFileName);
}


Foam::TfdemCoupling::TfdemCoupling
(
    const fvMesh& mesh,
    const volScalarField& p,
    const surfaceScalarField& superficialFlux,
    volScalarField& voidFraction,
    volScalarField& Ksl,
    volVectorField& Us,
    const dimensionedScalar& rho,
    const dimensionedScalar& nu
)
:
    mesh_(mesh),
    p_(p),
    superficialFlux_(superficialFlux),
    voidFraction_(voidFraction),
    Ksl_(Ksl),
    Us_(Us),
    wallStart_(std::chrono::steady_clock::now())
{
    const fileName configFile(mesh.time().path()/couplingFileName);
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

    if (Pstream::parRun())
    {
        FatalErrorInFunction
            << "the coupled solver runs serially in this version; run tfdemFoam"
            << " without -parallel for cases with " << couplingFileName
            << exit(FatalError);
    }
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised)
    {
        MPI_Init(nullptr, nullptr);
        ownsMpi = true;
    }

    checkGasProperties(rho, nu);
    setUpGrid();
    checkTwoDimensionalDepth();

    const fileName script(mesh.time().path()/config_.dem_script);
    try
    {
        dem_.reset
        (
            new tfdem::DemInstance
            (
                MPI_COMM_WORLD,
                script,
                mesh.time().path()/"log.liggghts"
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
    couple();
}


Foam::TfdemCoupling::~TfdemCoupling()
{
    dem_.reset();
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


void Foam::TfdemCoupling::setUpGrid()
{
    const boundBox domain(mesh_.points(), true);
    const boundBox firstCell(mesh_.points(), mesh_.cellPoints()[0], false);
    for (direction a = 0; a < 3; ++a)
    {
        grid_.origin[a] = domain.min()[a];
        grid_.spacing[a] = firstCell.span()[a];
        grid_.count[a] = std::lround(domain.span()[a]/grid_.spacing[a]);
    }
    cellOfGridCell_.assign(grid_.cell_count(), -1);
    const double cellVolume = grid_.cell_volume();
    bool uniform = (grid_.cell_count() == mesh_.nCells());
    forAll(mesh_.C(), celli)
    {
        const point& c = mesh_.C()[celli];
        const double x[3] = {c.x(), c.y(), c.z()};
        const int g = uniform ? grid_.locate(x) : -1;
        if
        (
            g < 0 || cellOfGridCell_[g] >= 0
         || relativeDifference(mesh_.V()[celli], cellVolume) > geometryTolerance
        )
        {
            uniform = false;
            break;
        }
        cellOfGridCell_[g] = celli;
    }
    if (!uniform)
    {
        FatalErrorInFunction
            << "the coupled solver needs a uniform Cartesian mesh (one blockMesh"
            << " block, no grading); this mesh has " << mesh_.nCells()
            << " cells in the box " << domain << exit(FatalError);
    }
    cellVolume_.assign(grid_.cell_count(), cellVolume);
    Info<< "TFDEM coupling: Cartesian grid " << grid_.count[0] << " x "
        << grid_.count[1] << " x " << grid_.count[2] << " cells of "
        << grid_.spacing[0] << " x " << grid_.spacing[1] << " x "
        << grid_.spacing[2] << " m" << endl;
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
            << mesh_.time().path()/config_.dem_script << ": DEM timestep " << dt
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


void Foam::TfdemCoupling::gatherCellFields()
{
    // Interstitial gas velocity seen by particles: the superficial face fluxes, which satisfy
    // continuity exactly, reconstructed in the cell and divided by the cell's eps. Unlike the
    // momentum solution U, it has no odd-even wiggles where eps and K jump (bed surfaces).
    const volVectorField gasVelocity(fvc::reconstruct(superficialFlux_)/voidFraction_);
    const volVectorField gradP(fvc::grad(p_));
    const std::size_t n = cellOfGridCell_.size();
    cellVelocity_.resize(3*n);
    cellPressureGradient_.resize(3*n);
    for (std::size_t g = 0; g < n; ++g)
    {
        const label celli = cellOfGridCell_[g];
        for (direction a = 0; a < 3; ++a)
        {
            cellVelocity_[3*g + a] = gasVelocity[celli][a];
            cellPressureGradient_[3*g + a] = gradP[celli][a];
        }
    }
}


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
        tfdem::compute_weights(grid_, particles, config_.void_fraction, weights_);
    }
    catch (const std::out_of_range& e)
    {
        FatalErrorInFunction
            << "at t = " << mesh_.time().value() << " s: " << e.what()
            << exit(FatalError);
    }
    tfdem::map_gas_fraction
    (
        weights_, particles, cellVolume_,
        config_.void_fraction.gas_fraction_floor, gasFraction_
    );
    flooredCellSteps_ += gasFraction_.floored_cells;
    ++couplingSteps_;
    if (gasFraction_.floored_cells)
    {
        Info<< "TFDEM coupling: void fraction floor "
            << config_.void_fraction.gas_fraction_floor << " used in "
            << gasFraction_.floored_cells << " cells (lowest value before it "
            << gasFraction_.lowest_unfloored << ")" << endl;
    }

    mapSeconds_ += secondsSince(mapStart);

    const Clock::time_point forceStart = Clock::now();
    gatherCellFields();
    const std::vector<double> uAt =
        tfdem::average_to_particles(weights_, cellVelocity_.data(), 3);
    const std::vector<double> epsAt =
        tfdem::average_to_particles(weights_, gasFraction_.gas_fraction.data(), 1);
    const std::vector<double> gradPAt = config_.pressure_gradient_force
      ? tfdem::average_to_particles(weights_, cellPressureGradient_.data(), 3)
      : std::vector<double>();

    const tfdem::CellGas cells
    {
        cellVolume_.size(), cellVelocity_.data(),
        gasFraction_.gas_fraction.data(), cellVolume_.data()
    };
    const tfdem::GasAtParticles atParticles
    {
        uAt.data(), epsAt.data(),
        gradPAt.empty() ? nullptr : gradPAt.data(),
        nullptr
    };
    tfdem::transfer(weights_, particles, cells, atParticles, config_.transfer, transfer_);

    checkConservation(particles);
    double* force = dem_->fluid_force();
    std::copy(transfer_.particle_force.begin(), transfer_.particle_force.end(), force);
    writeCellFields();
    forceSeconds_ += secondsSince(forceStart);
}


void Foam::TfdemCoupling::writeCellFields()
{
    scalarField& eps = voidFraction_.primitiveFieldRef();
    scalarField& K = Ksl_.primitiveFieldRef();
    vectorField& Us = Us_.primitiveFieldRef();
    for (std::size_t g = 0; g < cellOfGridCell_.size(); ++g)
    {
        const label celli = cellOfGridCell_[g];
        eps[celli] = gasFraction_.gas_fraction[g];
        K[celli] = transfer_.cell_coefficient[g];
        Us[celli] = vector
        (
            transfer_.cell_solid_velocity[3*g],
            transfer_.cell_solid_velocity[3*g + 1],
            transfer_.cell_solid_velocity[3*g + 2]
        );
    }
    voidFraction_.correctBoundaryConditions();
    Ksl_.correctBoundaryConditions();
    Us_.correctBoundaryConditions();
}


void Foam::TfdemCoupling::checkConservation(const tfdem::ParticleView& particles)
{
    if (gasFraction_.floored_cells == 0)
    {
        double particleVolume = 0, mappedVolume = 0;
        for (std::size_t i = 0; i < particles.count; ++i)
        {
            particleVolume += tfdem::sphere_volume(particles.diameter[i]);
        }
        for (std::size_t g = 0; g < cellVolume_.size(); ++g)
        {
            mappedVolume += (1 - gasFraction_.gas_fraction[g])*cellVolume_[g];
        }
        if (particleVolume > 0)
        {
            ++volumeCheckedSteps_;
            maxVolumeMismatch_ = std::max
            (
                maxVolumeMismatch_,
                std::abs(mappedVolume - particleVolume)/particleVolume
            );
        }
    }
    const auto& m = transfer_.momentum_imbalance;
    if (transfer_.drag_magnitude_sum > 0)
    {
        maxMomentumImbalance_ = std::max
        (
            maxMomentumImbalance_,
            std::sqrt(m[0]*m[0] + m[1]*m[1] + m[2]*m[2])/transfer_.drag_magnitude_sum
        );
    }
}


void Foam::TfdemCoupling::report() const
{
    const auto& m = transfer_.momentum_imbalance;
    Info<< "TFDEM coupling: " << couplingSteps_ << " coupling steps; void"
        << " fraction floor used in " << flooredCellSteps_ << " cell-steps;"
        << " last momentum imbalance (particle drag - gas sink) ("
        << m[0] << " " << m[1] << " " << m[2] << ") N of total |drag| "
        << transfer_.drag_magnitude_sum << " N" << nl
        << "TFDEM conservation: max |sum (1-eps) V_cell - sum V_p| / sum V_p = "
        << maxVolumeMismatch_ << " over " << volumeCheckedSteps_
        << " steps without floor; max |momentum imbalance|"
        << " / sum |drag| = " << maxMomentumImbalance_ << " ("
        << tfdem::transfer_method_names()[int(config_.transfer.method)].c_str()
        << ")" << endl;
    const double total = demSeconds_ + mapSeconds_ + forceSeconds_ + gasSeconds_;
    if (total > 0)
    {
        Info<< "TFDEM timing: DEM " << demSeconds_ << " s, locate+map " << mapSeconds_
            << " s, forces " << forceSeconds_ << " s, gas " << gasSeconds_
            << " s; (DEM + coupling + gas) / DEM = "
            << (demSeconds_ > 0 ? total/demSeconds_ : 0) << endl;
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
