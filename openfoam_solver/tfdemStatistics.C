#include "tfdemStatistics.H"
#include "tfdemRanks.H"
#include "IOmanip.H"

#include <mpi.h>

#include <cmath>
#include <limits>

#include "tfdem/particle_engine.h"
#include "tfdem/analysis.h"
#include "tfdem/distributed_coupling.h"

namespace
{

// Values per particle in the gathered VTK record: id, d, x (3), v (3), N_c, contact force
// (3), drag (3), fluid force (3).
constexpr int particleRecord = 18;

} // End anonymous namespace


Foam::TfdemStatistics::TfdemStatistics
(
    const fvMesh& mesh,
    const tfdem::OutputOptions& options,
    const std::vector<double>& particleDiameters,
    const tfdem::CartesianGrid& grid,
    const std::vector<int>& gridCellOfCell,
    const vector& g
)
:
    mesh_(mesh),
    options_(options),
    grid_(grid),
    gridCellOfCell_(gridCellOfCell),
    gravity_(mag(g)),
    sizeThreshold_
    (
        particleDiameters.size() == 2
      ? 0.5*(particleDiameters[0] + particleDiameters[1])
      : 0
    )
{
    for (direction a = 0; a < 3; ++a)
    {
        if (mag(g[a]) > mag(g[upAxis_]))
        {
            upAxis_ = a;
        }
    }
    if (options.statistics_interval <= 0)
    {
        return;
    }
    const Time& runTime = mesh.time();
    const scalar steps = options.statistics_interval/runTime.deltaTValue();
    sampleSteps_ = std::llround(steps);
    if (sampleSteps_ < 1 || std::abs(steps - sampleSteps_) > 1e-6*steps)
    {
        FatalErrorInFunction
            << "coupling.yaml: output.statistics_interval = " << options.statistics_interval
            << " s is not a whole number of gas steps of " << runTime.deltaTValue()
            << " s; use e.g. " << max(label(1), sampleSteps_)*runTime.deltaTValue()
            << exit(FatalError);
    }
    if (gravity_ <= 0)
    {
        FatalErrorInFunction
            << "coupling.yaml: output.statistics_interval needs gravity (constant/g):"
            << " the force fields are in units of the particles' weight" << exit(FatalError);
    }
    const std::pair<std::unique_ptr<volScalarField>*, std::pair<word, dimensionSet>> fields[] =
    {
        {&contactForceByWeight_, {"contactForceByWeight", dimless}},
        {&dragForceByWeight_, {"dragForceByWeight", dimless}},
        {&granularTemperature_, {"granularTemperature", dimVelocity*dimVelocity}}
    };
    for (const auto& field : fields)
    {
        field.first->reset
        (
            new volScalarField
            (
                IOobject(field.second.first, runTime.timeName(), mesh, IOobject::NO_READ, IOobject::AUTO_WRITE),
                mesh,
                dimensionedScalar(field.second.second, Zero),
                zeroGradientFvPatchScalarField::typeName
            )
        );
    }
    if (TfdemRanks::writesCase())
    {
        const fileName dir
        (
            runTime.globalPath()/"postProcessing"/"tfdemParticles"/runTime.timeName()
        );
        mkDir(dir);
        series_.reset(new OFstream(dir/"particles.dat"));
        *series_
            << "# t (s)  particles  mass (kg)  mean height (m)  bulk coordination number"
            << "  multicontact ratio"
            << (sizeThreshold_ > 0 ? "  segregation degree" : "") << nl;
    }
    Info<< "TFDEM statistics: every " << sampleSteps_ << " gas steps ("
        << options.statistics_interval << " s) to postProcessing/tfdemParticles and the"
        << " fields contactForceByWeight, dragForceByWeight, granularTemperature" << endl;
}


Foam::TfdemStatistics::~TfdemStatistics() = default;


bool Foam::TfdemStatistics::due(const Time& runTime) const
{
    return
        (sampleSteps_ > 0 && runTime.timeIndex() % sampleSteps_ == 0)
     || (options_.particles_vtk && runTime.writeTime());
}


void Foam::TfdemStatistics::writeSeriesRow
(
    scalar t,
    const tfdem::ParticleEngine& dem,
    const tfdem::ParticleView& p
)
{
    tfdem::analysis::ContactCounts counts =
        tfdem::analysis::contact_counts(coordination_.data(), coordination_.size());
    double sums[6] = {counts.particles, counts.contacts, counts.in_contact, counts.multi, 0, 0};
    for (std::size_t i = 0; i < p.count; ++i)
    {
        sums[4] += dem.masses()[i];
        sums[5] += p.position[3*i + upAxis_] - grid_.origin[upAxis_];
    }
    MPI_Allreduce(MPI_IN_PLACE, sums, 6, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    counts = {sums[0], sums[1], sums[2], sums[3]};
    tfdem::analysis::SegregationSums segregation;
    if (sizeThreshold_ > 0)
    {
        segregation = tfdem::analysis::segregation_sums
        (
            p, sizeThreshold_, upAxis_, grid_.origin[upAxis_]
        );
        MPI_Allreduce
        (
            MPI_IN_PLACE, segregation.data(), segregation.kComponents, MPI_DOUBLE,
            MPI_SUM, MPI_COMM_WORLD
        );
    }
    if (series_)
    {
        *series_
            << setprecision(10) << t << ' ' << label(sums[0]) << ' ' << setprecision(17)
            << sums[4] << ' ' << setprecision(10) << (sums[0] > 0 ? sums[5]/sums[0] : 0) << ' '
            << counts.bulk_coordination()
            << ' ' << counts.multicontact();
        if (sizeThreshold_ > 0)
        {
            // Undefined (nan, not 0 = mixed) once one size has left the bed
            const bool bothSizes =
                segregation.count_small > 0 && segregation.count_large > 0;
            *series_
                << ' '
                << (
                       bothSizes
                     ? tfdem::analysis::segregation_degree(segregation)
                     : std::numeric_limits<double>::quiet_NaN()
                   );
        }
        *series_ << endl;
    }
}


void Foam::TfdemStatistics::updateCellFields
(
    const tfdem::ParticleView& p,
    const tfdem::DistributedCoupling& core
)
{
    cellOfParticle_.resize(p.count);
    for (std::size_t i = 0; i < p.count; ++i)
    {
        cellOfParticle_[i] = grid_.locate(p.position + 3*i);
    }
    const std::size_t cells = grid_.cell_count();
    contactSums_.assign(3*cells, 0);
    dragSums_.assign(3*cells, 0);
    velocityMoments_.assign(tfdem::analysis::kVelocityMoments*cells, 0);
    tfdem::analysis::add_force_sums(p, cellOfParticle_.data(), contactForce_.data(), gravity_, contactSums_);
    tfdem::analysis::add_force_sums(p, cellOfParticle_.data(), core.particle_drag().data(), gravity_, dragSums_);
    tfdem::analysis::add_velocity_moments
    (
        tfdem::centroid_weights(cellOfParticle_.data(), p.count), p, velocityMoments_
    );
    for (std::vector<double>* sums : {&contactSums_, &dragSums_, &velocityMoments_})
    {
        MPI_Allreduce(MPI_IN_PLACE, sums->data(), int(sums->size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    }
    const tfdem::analysis::ForceMaps maps = tfdem::analysis::force_maps(contactSums_, dragSums_);
    const std::vector<double> theta = tfdem::analysis::granular_temperature(velocityMoments_);
    scalarField& contact = contactForceByWeight_->primitiveFieldRef();
    scalarField& drag = dragForceByWeight_->primitiveFieldRef();
    scalarField& temperature = granularTemperature_->primitiveFieldRef();
    forAll(contact, celli)
    {
        const int c = gridCellOfCell_[celli];
        contact[celli] = maps.contact[c];
        drag[celli] = maps.drag[c];
        temperature[celli] = theta[c];
    }
    for (auto* field : {&contactForceByWeight_, &dragForceByWeight_, &granularTemperature_})
    {
        (*field)->correctBoundaryConditions();
    }
}


namespace
{

//- Columns [first, first + width) of every rank's particle records, gathered on rank 0
//  (the section's values only, so rank 0 never holds every particle's whole record) and
//  written there one particle a line, in rank order.
void writeSection
(
    Foam::OFstream* out,
    const std::vector<double>& mine,
    int first,
    int width,
    bool integer,
    const std::vector<int>& particlesOfRank
)
{
    const std::size_t local = mine.size()/particleRecord;
    std::vector<double> part(width*local);
    for (std::size_t i = 0; i < local; ++i)
    {
        for (int k = 0; k < width; ++k)
        {
            part[width*i + k] = mine[particleRecord*i + first + k];
        }
    }
    std::vector<int> sizes(particlesOfRank.size()), offsets(particlesOfRank.size() + 1, 0);
    for (std::size_t r = 0; r < particlesOfRank.size(); ++r)
    {
        sizes[r] = width*particlesOfRank[r];
        offsets[r + 1] = offsets[r] + sizes[r];
    }
    std::vector<double> section(out ? offsets.back() : 0);
    MPI_Gatherv
    (
        part.data(), int(part.size()), MPI_DOUBLE, section.data(), sizes.data(), offsets.data(),
        MPI_DOUBLE, 0, MPI_COMM_WORLD
    );
    if (!out)
    {
        return;
    }
    for (std::size_t i = 0; i < section.size(); i += width)
    {
        for (int k = 0; k < width; ++k)
        {
            *out << (k ? " " : "");
            if (integer)
            {
                *out << Foam::label(section[i + k]);
            }
            else
            {
                *out << section[i + k];
            }
        }
        *out << Foam::nl;
    }
}


//- The particle file: every rank's records (`mine`), one VTK section at a time
void writeVtk
(
    const Foam::fileName& path,
    const std::vector<double>& mine,
    Foam::scalar t,
    bool writes
)
{
    using namespace Foam;
    int local = int(mine.size()/particleRecord);
    std::vector<int> particlesOfRank(TfdemRanks::count());
    MPI_Allgather(&local, 1, MPI_INT, particlesOfRank.data(), 1, MPI_INT, MPI_COMM_WORLD);
    label n = 0;
    for (int count : particlesOfRank)
    {
        n += count;
    }
    const fileName partial(path + ".tmp");
    std::unique_ptr<OFstream> file(writes ? new OFstream(partial) : nullptr);
    OFstream* out = file.get();
    const auto header = [&](const std::string& text)
    {
        if (out)
        {
            *out << text.c_str() << nl;
        }
    };
    if (out)
    {
        *out << "# vtk DataFile Version 3.0" << nl
            << "TFDEM particles at t = " << t << " s" << nl << "ASCII" << nl
            << "DATASET POLYDATA" << nl << "POINTS " << n << " double" << nl
            << setprecision(10);
    }
    writeSection(out, mine, 2, 3, false, particlesOfRank);
    if (out)
    {
        *out << "VERTICES " << n << ' ' << 2*n << nl;
        for (label i = 0; i < n; ++i)
        {
            *out << "1 " << i << nl;
        }
        *out << "POINT_DATA " << n << nl;
    }
    header("SCALARS id int 1\nLOOKUP_TABLE default");
    writeSection(out, mine, 0, 1, true, particlesOfRank);
    header("SCALARS diameter double 1\nLOOKUP_TABLE default");
    writeSection(out, mine, 1, 1, false, particlesOfRank);
    header("VECTORS velocity double");
    writeSection(out, mine, 5, 3, false, particlesOfRank);
    header("SCALARS coordination int 1\nLOOKUP_TABLE default");
    writeSection(out, mine, 8, 1, true, particlesOfRank);
    header("VECTORS contactForce double");
    writeSection(out, mine, 9, 3, false, particlesOfRank);
    header("VECTORS dragForce double");
    writeSection(out, mine, 12, 3, false, particlesOfRank);
    header("VECTORS fluidForce double");
    writeSection(out, mine, 15, 3, false, particlesOfRank);
    file.reset();
    if (writes)
    {
        mv(partial, path);
    }
}

} // End anonymous namespace


void Foam::TfdemStatistics::record
(
    const Time& runTime,
    const tfdem::ParticleEngine& dem,
    const tfdem::ParticleView& p,
    const tfdem::DistributedCoupling& core
)
{
    dem.contact_sample(contactForce_, coordination_);
    if (sampleSteps_ > 0)
    {
        updateCellFields(p, core);
        if (runTime.timeIndex() % sampleSteps_ == 0)
        {
            writeSeriesRow(runTime.value(), dem, p);
        }
    }
    if (!(options_.particles_vtk && runTime.writeTime()))
    {
        return;
    }
    std::vector<double> mine(particleRecord*p.count);
    for (std::size_t i = 0; i < p.count; ++i)
    {
        double* r = &mine[particleRecord*i];
        r[0] = dem.tags()[i];
        r[1] = p.diameter[i];
        r[8] = coordination_[i];
        for (int k = 0; k < 3; ++k)
        {
            r[2 + k] = p.position[3*i + k];
            r[5 + k] = p.velocity[3*i + k];
            r[9 + k] = contactForce_[3*i + k];
            r[12 + k] = core.particle_drag()[3*i + k];
            r[15 + k] = core.particle_force()[3*i + k];
        }
    }
    const fileName dir(runTime.globalPath()/"VTK");
    if (TfdemRanks::writesCase())
    {
        mkDir(dir);
    }
    writeVtk
    (
        dir/("particles_" + runTime.timeName() + ".vtk"), mine, runTime.value(),
        TfdemRanks::writesCase()
    );
}
