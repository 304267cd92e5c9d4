#include "tfdemStartupChecks.H"
#include "emptyFvPatchFields.H"

#include <mpi.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "dem_instance.h"
#include "tfdemRanks.H"
#include "tfdem/contact.h"
#include "tfdem/packing_check.h"
#include "tfdem/particles.h"
#include "tfdem/scene_check.h"

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
            << config.dem_script.c_str() << ": a particle has diameter " << dMin
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
            << "particles disagree: the DEM (" << config.dem_script.c_str()
            << " and its data file) has diameters " << dMin << " to " << dMax
            << " m and densities " << rhoMin << " to " << rhoMax << " kg/m^3; "
            << config.file.c_str() << " gives particles.diameter = "
            << diameterList(config).c_str() << " m, particles.density = "
            << config.particle_density << " kg/m^3. Make them equal."
            << exit(FatalError);
    }
}


namespace
{

// The deepest overlap, as a fraction of d, hard spheres start from without a warning
constexpr double hardOverlapTolerated = 0.01;

// Elastic energy (J) of an overlap `depth` between atom types a and b of radii ra, rb: linear
// (1/2) k_n delta^2, Hertz (8/15) E* sqrt(R*) delta^(5/2) (the integral of the contact forces);
// negative when the script gives neither model
double overlapEnergy
(
    const tfdem::DemInstance& dem,
    int a,
    int b,
    double ra,
    double rb,
    double depth
)
{
    tfdem::DemInstance::LinearContact linear;
    if (dem.linear_contact(a, b, linear))
    {
        return 0.5*linear.stiffness*depth*depth;
    }
    tfdem::DemInstance::HertzContact hertz;
    if (dem.hertz_contact(a, b, hertz))
    {
        const double modulus = tfdem::contact::effective_modulus
        (
            hertz.young_a, hertz.poisson_a, hertz.young_b, hertz.poisson_b
        );
        return 8.0/15.0*modulus*std::sqrt(ra*rb/(ra + rb))*std::pow(depth, 2.5);
    }
    return -1;
}

} // End anonymous namespace


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
    const auto* soft = dynamic_cast<const tfdem::DemInstance*>(&dem);
    double energy = 0, lift = 0, smallest = GREAT;
    bool known = soft != nullptr;
    const tfdem::PackingCheck::Overlap* deepest = &check.overlaps.front();
    std::size_t deep = 0;
    for (const auto& o : check.overlaps)
    {
        const double relative = o.depth/std::min(d[o.a], d[o.b]);
        if (relative > deepest->depth/std::min(d[deepest->a], d[deepest->b])) deepest = &o;
        if (relative > 0.01) ++deep;
        const double e =
            soft
          ? overlapEnergy(*soft, type[o.a], type[o.b], 0.5*d[o.a], 0.5*d[o.b], o.depth)
          : -1;
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
    if (!soft && relative > hardOverlapTolerated)
    {
        Info<< "TFDEM warning: the initial packing's pairs overlap up to " << 100*relative
            << " % of d (a soft-sphere packing?): hard spheres do not push them apart, they"
            << " stay so until the pairs part (and count in the gas fraction). Pack the bed"
            << " with stiffer contacts, or let it settle in the hard-sphere engine first"
            << endl;
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


void Foam::tfdemChecks::gravity
(
    const uniformDimensionedVectorField& g,
    const tfdem::DemInstance& dem
)
{
    double demGravity[3];
    if (!dem.gravity(demGravity))
    {
        Info<< "TFDEM warning: the DEM script has no fix gravity: the particles feel no"
            << " weight (the gas has constant/g = " << g.value() << " m/s^2)" << endl;
        return;
    }
    const vector gDem(demGravity[0], demGravity[1], demGravity[2]);
    if (mag(gDem - g.value()) > 1e-9*max(mag(g.value()), SMALL))
    {
        FatalErrorInFunction
            << "gravity disagrees: constant/g is " << g.value()
            << " m/s^2, the DEM script's fix gravity gives " << gDem
            << " m/s^2. Make them equal." << exit(FatalError);
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
                << " one); see the README, Inflow" << exit(FatalError);
        }
        const fvPatchScalarField& eb = voidFraction.boundaryField()[patchi];
        const bool superficial = eb.fixesValue() && gMin(eb) == 1 && gMax(eb) == 1;
        Info<< "TFDEM coupling: inlet '" << name << "': U is "
            << (superficial ? "superficial (voidFraction fixedValue 1)"
                            : "interstitial (voidFraction not fixed at 1)")
            << ", inflow " << inflow << " m^3/s" << endl;
    }
}


namespace
{

// Smallest value of a per-particle property (mass, radius) of each atom type (index type - 1;
// infinity: a type without particles, e.g. a wall material), over all ranks.
std::vector<double> smallestOfType(const tfdem::DemInstance& dem, const double* values)
{
    std::vector<double> smallest(dem.type_count(), std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < dem.local_count(); ++i)
    {
        double& m = smallest[dem.types()[i] - 1];
        m = std::min(m, values[i]);
    }
    MPI_Allreduce
    (
        MPI_IN_PLACE, smallest.data(), int(smallest.size()), MPI_DOUBLE, MPI_MIN,
        MPI_COMM_WORLD
    );
    return smallest;
}

// The fastest inflow: the largest |U| on the patches where U is fixed.
double largestInflowSpeed(const volVectorField& U)
{
    scalar fastest = 0;
    forAll(U.boundaryField(), patchi)
    {
        if (U.boundaryField()[patchi].fixesValue())
        {
            fastest = max(fastest, gMax(mag(U.boundaryField()[patchi])));
        }
    }
    return fastest;
}

// The speed of a free fall over the domain's extent along gravity: an impact any bed sees.
double fallSpeed(const volVectorField& U, const vector& g)
{
    const boundBox domain(U.mesh().points(), true);
    return mag(g) > 0 ? std::sqrt(2*mag(g)*mag(domain.span() & (g/mag(g)))) : 0;
}

// The fastest a particle may hit another or a wall: the fastest inflow, or the free fall.
double largestImpactSpeed(const volVectorField& U, const vector& g)
{
    return max(largestInflowSpeed(U), fallSpeed(U, g));
}

// Past this overlap at the free fall's impact, as a fraction of the smaller diameter, soft
// contacts let particles pass halfway through one another
constexpr double largestSoundImpactOverlap = 0.5;

// Reduced value (1/a + 1/b)^-1 of a contact's two sides (effective mass, effective radius);
// a type without particles is a wall (infinite mass and radius).
double reduced(double a, double b)
{
    if (std::isinf(a)) return b;
    if (std::isinf(b)) return a;
    return tfdem::contact::effective_mass(a, b);
}

// Contact time of atom types a and b between their lightest, smallest particles and what
// it is (for the messages), and the deepest overlap of an elastic impact at each of
// `speeds`; negative when the script gives no contact model we know.
double contactTime
(
    const tfdem::DemInstance& dem,
    int a,
    int b,
    double mEff,
    double rEff,
    double impactSpeed,
    std::string& model,
    double& restitution,
    const std::vector<double>& speeds,
    std::vector<double>& overlaps
)
{
    overlaps.assign(speeds.size(), 0);
    std::ostringstream what;
    restitution = tfdem::kUnknownRestitution;
    tfdem::DemInstance::LinearContact linear;
    if
    (
        dem.linear_contact(a, b, linear)
     && (linear.damping >= 0 || linear.restitution >= 0)
    )
    {
        what << "linear, k_n = " << linear.stiffness << " N/m, "
             << (linear.damping >= 0 ? "eta_n = " : "e_n = ")
             << (linear.damping >= 0 ? linear.damping : linear.restitution)
             << (linear.damping >= 0 ? " N s/m" : "") << ", m_eff = " << mEff << " kg";
        model = what.str();
        restitution = linear.damping >= 0
          ? tfdem::contact::restitution_from_damping(linear.stiffness, linear.damping, mEff)
          : linear.restitution;
        for (std::size_t k = 0; k < speeds.size(); ++k)
        {
            overlaps[k] = tfdem::contact::linear_impact_overlap(linear.stiffness, mEff, speeds[k]);
        }
        return linear.damping >= 0
          ? tfdem::contact::contact_time_from_damping(linear.stiffness, linear.damping, mEff)
          : tfdem::contact::contact_time(linear.stiffness, linear.restitution, mEff);
    }
    tfdem::DemInstance::HertzContact hertz;
    if (dem.hertz_contact(a, b, hertz))
    {
        const double modulus = tfdem::contact::effective_modulus
        (
            hertz.young_a, hertz.poisson_a, hertz.young_b, hertz.poisson_b
        );
        what << "Hertz, E* = " << modulus << " Pa, R* = " << rEff << " m, m_eff = " << mEff
             << " kg, elastic at impact speed " << impactSpeed << " m/s";
        model = what.str();
        for (std::size_t k = 0; k < speeds.size(); ++k)
        {
            overlaps[k] = tfdem::contact::hertz_impact_overlap(modulus, rEff, mEff, speeds[k]);
        }
        return tfdem::contact::hertz_contact_time(modulus, rEff, mEff, impactSpeed);
    }
    return -1;
}

void contactTimeSteps
(
    const fileName& script,
    const tfdem::DemInstance& dem,
    double impactSpeed,
    double fall
)
{
    if (!dem.integrates())
    {
        Info<< "TFDEM coupling: the DEM script integrates no particle motion (no fix nve*):"
            << " a frozen bed, contact time not checked" << endl;
        return;
    }
    const std::vector<double> lightest = smallestOfType(dem, dem.masses());
    const std::vector<double> smallest = smallestOfType(dem, dem.radii());
    const double dt = dem.time_step();
    bool checked = false;
    for (int a = 1; a <= dem.type_count(); ++a)
    {
        for (int b = a; b <= dem.type_count(); ++b)
        {
            const double mEff = reduced(lightest[a - 1], lightest[b - 1]);
            if (std::isinf(mEff))
            {
                continue;
            }
            std::string model;
            double restitution;
            std::vector<double> overlap;
            const double rEff = reduced(smallest[a - 1], smallest[b - 1]);
            const double tc = contactTime
            (
                dem, a, b, mEff, rEff, impactSpeed, model, restitution, {impactSpeed, fall},
                overlap
            );
            if (tc < 0)
            {
                continue;
            }
            checked = true;
            const double d = 2*std::min(smallest[a - 1], smallest[b - 1]);
            Info<< "TFDEM coupling: contact of atom types " << a << " and " << b << " ("
                << model.c_str() << "): t_c = " << tc << " s (lightest particles), " << tc/dt
                << " DEM steps per contact; deepest overlap " << 100*overlap[1]/d << " % of d at"
                << " a free fall's impact (" << fall << " m/s), " << 100*overlap[0]/d << " % at "
                << impactSpeed << " m/s" << endl;
            if (overlap[1] > largestSoundImpactOverlap*d)
            {
                Info<< "TFDEM warning: contact of atom types " << a << " and " << b << ": a"
                    << " particle falling " << fall << " m/s onto another sinks "
                    << 100*overlap[1]/d << " % of its diameter into it (more than "
                    << 100*largestSoundImpactOverlap << " %): the contacts are too soft for"
                    << " the bed; stiffen k_n (or E)" << endl;
            }
            const std::string problem = tfdem::dem_step_problem(tc, dt, restitution);
            if (!problem.empty())
            {
                FatalErrorInFunction
                    << script << ": contact of atom types " << a << " and " << b
                    << " (" << model.c_str() << "): " << problem.c_str() << exit(FatalError);
            }
            const std::string advice = tfdem::dem_step_advice(tc, dt, restitution);
            if (!advice.empty())
            {
                Info<< "TFDEM coupling: advice: contact of atom types " << a << " and " << b
                    << ": " << advice.c_str() << endl;
            }
        }
    }
    if (!checked)
    {
        Info<< "TFDEM coupling: the DEM script gives neither a linear contact (k_n with"
            << " gamman_abs or coefficientRestitution) nor a Hertz one (youngsModulus):"
            << " contact time not checked" << endl;
    }
}

} // End anonymous namespace


void Foam::tfdemChecks::scene
(
    const tfdem::CouplingConfig& config,
    const tfdem::CartesianGrid& grid,
    const tfdem::DemInstance& dem,
    const volVectorField& U,
    const vector& g
)
{
    tfdem::DemInstance::LinearContact contact;
    const scalar inflow = largestInflowSpeed(U);
    if
    (
        !dem.linear_contact(1, 1, contact) || contact.damping < 0 || inflow <= 0
     || config.particle_diameters.empty()
    )
    {
        Info<< "TFDEM scene: not checked (it needs a linear contact with absolute damping"
            << " and an inflow)" << endl;
        return;
    }
    tfdem::Scene s;
    s.particle_diameter = config.particle_diameters.front();  // smallest: shortest contact
    s.particle_density = config.particle_density;
    s.gas = config.gas;
    s.gravity = mag(g);
    s.gas_velocity = inflow;
    s.cell_size = std::min(grid.spacing[0], grid.spacing[1]);
    s.normal_stiffness = contact.stiffness;
    s.normal_damping = contact.damping;
    s.dem_time_step = dem.time_step();
    s.coupling_interval = tfdemChecks::couplingInterval(config, U.mesh().time().deltaTValue(), dem.time_step());
    s.drag_law = config.transfer.law;
    try
    {
        std::istringstream report(tfdem::format_report(tfdem::check_scene(s)));
        for (std::string line; std::getline(report, line);)
        {
            Info<< "TFDEM scene: " << line.c_str() << endl;
        }
    }
    catch (const std::exception& e)
    {
        Info<< "TFDEM scene: not checked (" << e.what() << ")" << endl;
    }
}


void Foam::tfdemChecks::timeSteps
(
    const Time& runTime,
    const tfdem::CouplingConfig& config,
    const tfdem::DemInstance& dem,
    const volVectorField& U,
    const vector& g
)
{
    contactTimeSteps
    (
        runTime.globalPath()/config.dem_script, dem, largestImpactSpeed(U, g), fallSpeed(U, g)
    );
    if (runTime.controlDict().lookupOrDefault<Switch>("adjustTimeStep", false))
    {
        FatalErrorInFunction
            << "system/controlDict: adjustTimeStep must be 'no' for a coupled"
            << " case: the gas step is coupling_interval DEM steps"
            << exit(FatalError);
    }
    // Given or derived, the gas step must be that many DEM steps
    const double deltaT = runTime.deltaTValue(), dt = dem.time_step();
    const long interval = couplingInterval(config, deltaT, dt);
    if (interval >= 1 && relativeDifference(deltaT, interval*dt) <= 1e-9)
    {
        return;
    }
    if (config.coupling_interval == 0)
    {
        const long below = std::max(1L, static_cast<long>(std::floor(deltaT/dt)));
        FatalErrorInFunction
            << "system/controlDict: deltaT = " << deltaT << " s is not a whole number of DEM"
            << " steps of " << dt << " s (the DEM script's timestep; " << deltaT/dt
            << " of them): use deltaT = " << below << " x " << dt << " = " << below*dt
            << " s, or a DEM timestep of deltaT / " << below << " = " << deltaT/below << " s"
            << exit(FatalError);
    }
    FatalErrorInFunction
        << "system/controlDict: deltaT = " << deltaT
        << " s must equal dem.coupling_interval x DEM timestep = "
        << config.coupling_interval << " x " << dt << " = " << interval*dt << " s ("
        << config.file.c_str() << "); the coupling interval must divide the gas step evenly"
        << exit(FatalError);
}


long Foam::tfdemChecks::couplingInterval
(
    const tfdem::CouplingConfig& config,
    double gasStep,
    double demStep
)
{
    return config.coupling_interval > 0 ? config.coupling_interval : std::llround(gasStep/demStep);
}
