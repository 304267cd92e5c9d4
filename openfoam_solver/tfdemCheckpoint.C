#include "tfdemCheckpoint.H"
#include "tfdemCase.H"
#include "tfdemFailure.H"
#include "tfdemRanks.H"
#include "tfdemTime.H"
#include "OSspecific.H"

#include <mpi.h>
#include <zlib.h>

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "tfdem/particle_engine.h"

const Foam::word Foam::TfdemCheckpoint::restartName("dem.restart");
const Foam::word Foam::TfdemCheckpoint::markerName("tfdem.checkpoint");

namespace
{

// The gas fields the first step of a resumed run reads (createFields.H)
const char* const resumedFields[] =
    {"U", "p", "phi", "voidFractionPhi", "momentumPressureGradient"};

// How OpenFOAM ends every file it writes (IOobject::writeEndDivider)
const std::string closingDivider =
    "// *****************************************"
    "******************************** //\n";

std::string readText(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Why a field file OpenFOAM has just written is not whole ("" when it is)
std::string unfinished(const std::string& path)
{
    std::string tail;
    if (path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0)
    {
        gzFile in = gzopen(path.c_str(), "rb");
        if (!in) return "cannot be read back";
        std::string text;
        char buffer[1 << 16];
        int got;
        while ((got = gzread(in, buffer, sizeof buffer)) > 0) text.append(buffer, got);
        const bool failed = got < 0 || gzclose_r(in) != Z_OK;
        if (failed) return "is not a whole gzip stream (cut short?)";
        tail = text.substr(text.size() > closingDivider.size() ? text.size() - closingDivider.size() : 0);
    }
    else
    {
        std::ifstream in(path, std::ios::binary | std::ios::ate);
        if (!in) return std::string("cannot be read back: ") + std::strerror(errno);
        const std::streamoff size = in.tellg();
        if (size == 0) return "is empty";
        const std::streamoff n = std::min<std::streamoff>(size, closingDivider.size());
        tail.resize(n);
        in.seekg(size - n);
        in.read(&tail[0], n);
    }
    return tail == closingDivider ? "" : "lacks OpenFOAM's closing line (cut short)";
}

std::string synced(const std::string& path)
{
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0)
    {
        const std::string reason = std::strerror(errno);
        if (fd >= 0) ::close(fd);
        return path + " cannot be synced to disk: " + reason;
    }
    ::close(fd);
    return "";
}

// Every regular file under dir, recursively, as paths relative to dir
void listFiles(const Foam::fileName& dir, const std::string& prefix, std::vector<std::string>& out)
{
    for (const Foam::fileName& f : Foam::readDir(dir, Foam::fileName::FILE))
    {
        out.push_back(prefix + f);
    }
    for (const Foam::fileName& d : Foam::readDir(dir, Foam::fileName::DIRECTORY))
    {
        listFiles(dir/d, prefix + d + "/", out);
    }
}

std::string joined(const Foam::wordList& names)
{
    std::string text;
    for (const Foam::word& n : names)
    {
        text += (text.empty() ? "" : ", ") + n;
    }
    return text;
}

} // End anonymous namespace


Foam::fileName Foam::TfdemCheckpoint::directory(const word& timeName) const
{
    return runTime_.globalPath()/timeName;
}


Foam::wordList Foam::TfdemCheckpoint::markedTimes() const
{
    DynamicList<word> marked;
    for (const instant& t : TimePaths::findTimes(runTime_.globalPath(), runTime_.constant()))
    {
        if (isFile(directory(t.name())/markerName))
        {
            marked.append(t.name());
        }
    }
    return wordList(marked);
}


Foam::word Foam::TfdemCheckpoint::newestGoodBefore(const word& before) const
{
    const double limit = std::stod(before);
    const wordList marked = markedTimes();
    for (label i = marked.size() - 1; i >= 0; --i)
    {
        if (std::stod(marked[i]) >= limit) continue;
        try
        {
            const tfdem::CheckpointManifest m = tfdem::parse_manifest
            (
                readText(directory(marked[i])/markerName), marked[i]/markerName
            );
            if
            (
                !m.legacy()
             && tfdem::manifest_problems(m, std::stod(marked[i]), marked[i] + "/" + restartName).empty()
             && tfdem::changed_files(m, runTime_.globalPath()).empty()
            )
            {
                return marked[i];
            }
        }
        catch (const std::invalid_argument&)
        {}
    }
    return word();
}


std::string Foam::TfdemCheckpoint::lastGoodText() const
{
    return lastGood_.empty()
      ? std::string("the run had written no checkpoint yet.")
      : "the last good checkpoint is t = " + lastGood_ + " s (to resume from it, delete any"
        " time folder after it and set startFrom latestTime).";
}


std::string Foam::TfdemCheckpoint::fallback(const word& timeName) const
{
    const word good = newestGoodBefore(timeName);
    if (good.empty())
    {
        return "No earlier checkpoint of this case verifies: start afresh (delete the time"
               " folders after the first)";
    }
    return "The newest earlier checkpoint that verifies is t = " + good + " s: move " + timeName
         + " (and any later time folder) aside, then resume (startFrom latestTime)";
}


Foam::TfdemCheckpoint::TfdemCheckpoint(TfdemTime& runTime)
:
    runTime_(runTime),
    layout_(Pstream::parRun() ? "split" : TfdemRanks::gasWhole() ? "whole" : "serial"),
    kept_(runTime.keepWrites())
{
    if (runTime.writeFormat() == IOstream::ASCII && IOstream::defaultPrecision() < 17)
    {
        Info<< "TFDEM warning: system/controlDict writePrecision "
            << IOstream::defaultPrecision() << " (ascii): a run resumed from these"
            << " checkpoints continues close to, not bit for bit as, a straight run; set"
            << " writePrecision 17 (or writeFormat binary) for bit-for-bit restarts" << endl;
    }
    const word start = runTime.timeName();
    const fileName dir = directory(start);
    const wordList marked = markedTimes();
    if (isFile(dir/markerName))
    {
        readStart(marked);
        return;
    }
    if (isFile(dir/restartName) || isFile(dir/(restartName + ".tmp")))
    {
        FatalErrorInFunction
            << "the checkpoint at t = " << start << " s is incomplete (" << dir
            << " has no " << markerName << ": the run was stopped while writing it)."
            << " Fix: tfdem resume <case> moves it aside (into incomplete/) and sets the case"
            << " to resume from the newest checkpoint; or delete " << dir << " (and processor*/"
            << start << ") and start from the time before" << exit(FatalError);
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
    if (!marked.empty())
    {
        const word newest = marked.last();
        tfdem::CheckpointManifest m;
        try
        {
            m = tfdem::parse_manifest(readText(directory(newest)/markerName), newest/markerName);
        }
        catch (const std::invalid_argument&)
        {}
        const std::string how =
            layout_ == "split" && m.layout != "split"
          ? "to resume it split over ranks, decompose that time first (decomposePar -time "
            + newest + "), then run with startFrom latestTime"
          : layout_ != "split" && m.layout == "split"
          ? "its gas fields are in processor*/" + newest + ": run it split again (mpirun -np "
            + std::to_string(m.ranks) + " tfdemFoam -parallel) or reconstructPar -time "
            + newest + " first, with startFrom latestTime"
          : "to resume it, set startFrom latestTime";
        FatalErrorInFunction
            << "this run starts afresh at t = " << start << " s but the case holds TFDEM"
            << " checkpoints up to t = " << newest << " s (" << joined(marked).c_str()
            << (m.layout.empty() ? "" : "; the newest written by a " + m.layout + " run on "
                + std::to_string(m.ranks) + " rank(s)").c_str()
            << "): writing over them would leave one run's gas beside another's particles."
            << " Fix: " << how.c_str() << "; to start afresh, delete those time folders"
            << " first (foamListTimes -rm)" << exit(FatalError);
    }
    lastGood_ = word();
}


void Foam::TfdemCheckpoint::readMarker(const word& start)
{
    const fileName marker = directory(start)/markerName;
    try
    {
        start_ = tfdem::parse_manifest(readText(marker), marker);
    }
    catch (const std::invalid_argument& e)
    {
        FatalErrorInFunction
            << "the checkpoint marker cannot be read: " << e.what() << ". "
            << fallback(start).c_str() << exit(FatalError);
    }
    std::string wrong;
    if (TfdemRanks::rank() == 0)
    {
        for
        (
            const std::string& p
          : tfdem::manifest_problems(start_, runTime_.value(), start + "/" + restartName)
        )
        {
            wrong += "\n    " + p;
        }
    }
    stopIfAny
    (
        wrong,
        "the checkpoint marker " + marker + " holds entries that cannot be so (edited or"
        " damaged)",
        "Resuming from it would run from a state it does not describe. " + fallback(start)
    );
}


bool Foam::TfdemCheckpoint::redecomposed() const
{
    // A checkpoint written split over M ranks and resumed split over N != M: reconstructPar
    // and decomposePar replaced its processor*/ files by fields made from them, which its
    // hashes do not cover (a serial or whole run reads fields made from them beside them)
    return
        layout_ == "split" && start_.layout == "split"
     && start_.ranks != TfdemRanks::count();
}


bool Foam::TfdemCheckpoint::verifiable(const std::string& path) const
{
    return !redecomposed() || path.compare(0, 9, "processor") != 0;
}


void Foam::TfdemCheckpoint::checkFilesUnchanged(const word& start) const
{
    const fileName marker = directory(start)/markerName;
    std::string problems;
    if (TfdemRanks::rank() == 0)
    {
        for (const std::string& c : tfdem::changed_files(start_, runTime_.globalPath()))
        {
            if (verifiable(c))
            {
                problems += "\n    " + c;
            }
        }
    }
    stopIfAny
    (
        problems,
        "the checkpoint at t = " + start + " s is not as it was written (" + marker
      + " lists each file with its size and hash)",
        "Resuming from it would run from damaged data. " + fallback(start)
    );
    if (start_.legacy())
    {
        Info<< "TFDEM warning: " << marker << " was written before checkpoints listed their"
            << " files: its files cannot be verified" << endl;
    }
}


void Foam::TfdemCheckpoint::checkResumedFields(const word& start) const
{
    // The gas fields this run reads: its own layout's, listed by the marker or made from it
    std::string missing;
    std::string derived;
    for (const char* name : resumedFields)
    {
        const fileName file = runTime_.path()/start/name;
        if (!isFile(file))
        {
            missing += std::string(missing.empty() ? "" : ", ") + name;
            continue;
        }
        bool listed = false;
        for (const auto& f : start_.files)
        {
            listed = listed || runTime_.globalPath()/f.path == file;
        }
        if ((!listed || redecomposed()) && !start_.legacy()) derived = file;
    }
    const std::string missingAll = TfdemRanks::gatherText(missing);
    if (!missingAll.empty())
    {
        const std::string how =
            layout_ == "split" && start_.layout != "split"
          ? "it was written by a " + start_.layout + " run: decompose it for this run first"
            " (decomposePar -time " + start + ")"
          : layout_ != "split" && start_.layout == "split"
          ? "it was written split over " + std::to_string(start_.ranks) + " ranks (its fields"
            " are in processor*/" + start + "): run split again (mpirun -np "
          + std::to_string(start_.ranks) + " tfdemFoam -parallel) or reconstructPar -time "
          + start + " first"
          : "a resumed run needs each of them to continue bit for bit; " + fallback(start);
        FatalErrorInFunction
            << "the gas fields to resume from are missing in " << runTime_.path()/start
            << ": " << missing.c_str() << ". " << how.c_str() << exit(FatalError);
    }
    if (!derived.empty())
    {
        Info<< "TFDEM checkpoint: the gas fields of t = " << start << " s are read from "
            << runTime_.path()/start << ", made from the " << start_.layout.c_str()
            << " checkpoint's on " << start_.ranks << " rank(s) (not covered by its hashes)"
            << endl;
    }
}


void Foam::TfdemCheckpoint::refuseLaterCheckpoints(const word& start, const wordList& marked) const
{
    DynamicList<word> later;
    for (const word& t : marked)
    {
        if (std::stod(t) > runTime_.value() + 0.5*runTime_.deltaTValue()) later.append(t);
    }
    if (!later.empty())
    {
        FatalErrorInFunction
            << "this run resumes from t = " << start << " s but the case holds later"
            << " checkpoints (" << joined(later).c_str() << " s) that it would overwrite."
            << " Fix: move those time folders aside (or delete them) to go on from "
            << start << " s, or resume from the newest (startFrom latestTime)"
            << exit(FatalError);
    }
}


void Foam::TfdemCheckpoint::readStart(const wordList& marked)
{
    const word start = runTime_.timeName();
    readMarker(start);
    checkFilesUnchanged(start);
    checkResumedFields(start);
    refuseLaterCheckpoints(start, marked);
    if (start_.write_format == "ascii" && start_.write_precision < 17)
    {
        Info<< "TFDEM warning: the checkpoint's fields were written at writePrecision "
            << start_.write_precision << ": this run continues close to, not bit for bit"
            << " as, a straight run" << endl;
    }
    resuming_ = true;
    lastGood_ = start;
    tfdemFailure::checkpointWritten(start);
    label verified = 0;
    for (const auto& f : start_.files)
    {
        lastBytes_ += f.digest.size;
        verified += verifiable(f.path);
    }
    Info<< "TFDEM checkpoint: resuming gas and particles from t = " << start << " s ("
        << (start_.dem_restart ? (directory(start)/restartName).c_str() : "no particles")
        << ", " << verified << (verified == 1 ? " file" : " files") << " verified)" << nl << endl;
}


tfdem::DemResume Foam::TfdemCheckpoint::demResume() const
{
    tfdem::DemResume r;
    r.step = start_.dem_step;
    r.engine = start_.engine;
    r.time = start_.time;
    if (start_.dem_restart)
    {
        r.restart_file = fileName(runTime_.timeName()/restartName);  // relative to the case
    }
    r.outputs = start_.outputs;
    return r;
}


Foam::ParticleTotals Foam::TfdemCheckpoint::startTotals() const
{
    ParticleTotals t;
    t.count = label(start_.particles);
    t.mass = start_.particle_mass;
    t.removedCount = label(start_.removed_particles);
    t.removedMass = start_.removed_mass;
    return t;
}


void Foam::TfdemCheckpoint::verify
(
    const tfdem::ParticleEngine& dem,
    const ParticleTotals& totals
) const
{
    if (!resuming())
    {
        return;
    }
    const scalar demTime = dem.time();
    if
    (
        dem.step() != start_.dem_step
     || std::abs(demTime - runTime_.value()) > 1e-6*runTime_.deltaTValue()
    )
    {
        FatalErrorInFunction
            << directory(runTime_.timeName())/restartName << ": " << dem.name().c_str()
            << " resumes at step " << std::to_string(dem.step()).c_str() << " (t = " << demTime
            << " s) but the checkpoint was written at step "
            << std::to_string(start_.dem_step).c_str() << ", t = " << runTime_.timeName()
            << " s: the marker or the restart file was changed. "
            << fallback(runTime_.timeName()).c_str() << exit(FatalError);
    }
    if
    (
        totals.count != start_.particles
     || std::abs(totals.mass - start_.particle_mass) > 1e-12*start_.particle_mass
    )
    {
        FatalErrorInFunction
            << directory(runTime_.timeName())/restartName << " holds " << totals.count
            << " particles of " << totals.mass << " kg; the checkpoint was written with "
            << label(start_.particles) << " particles of " << start_.particle_mass << " kg:"
            << " the marker or the restart file was changed. "
            << fallback(runTime_.timeName()).c_str() << exit(FatalError);
    }
}


void Foam::TfdemCheckpoint::stopIfAny
(
    const std::string& problems,
    const std::string& what,
    const std::string& fix
) const
{
    const std::string all = TfdemRanks::gatherText(problems);
    if (!all.empty())
    {
        FatalErrorInFunction
            << what.c_str() << ":" << all.c_str() << "\n" << fix.c_str() << exit(FatalError);
    }
}


void Foam::TfdemCheckpoint::checkDiskSpace() const
{
    std::string problem;
    struct statvfs fs;
    if
    (
        TfdemRanks::rank() == 0 && lastBytes_ > 0
     && statvfs(runTime_.globalPath().c_str(), &fs) == 0
    )
    {
        const double free = double(fs.f_bavail)*fs.f_frsize;
        const double needed = 1.25*lastBytes_;  // the same files again, with room to spare
        if (free < needed)
        {
            std::ostringstream text;
            text.precision(3);
            text << "\n    " << free/1e6 << " MB free, the last checkpoint took "
                 << lastBytes_/1e6 << " MB";
            problem = text.str();
        }
    }
    stopIfAny
    (
        problem,
        "the disk holding " + runTime_.globalPath() + " cannot take the checkpoint of t = "
      + runTime_.timeName() + " s",
        "Nothing of it was written; " + lastGoodText() + " Free disk space, then resume"
    );
}


std::vector<std::string> Foam::TfdemCheckpoint::gasFiles
(
    const word& timeName,
    std::string& problems
) const
{
    std::vector<std::string> files;
    if (!TfdemRanks::writesGas())
    {
        return files;
    }
    const fileName root = runTime_.path()/timeName;
    std::vector<std::string> names;
    listFiles(root, "", names);
    const std::string prefix =
        runTime_.path() == runTime_.globalPath()
      ? std::string(timeName) + "/"
      : std::string(runTime_.caseName().name()) + "/" + timeName + "/";
    for (const std::string& n : names)
    {
        if (n.compare(0, restartName.size(), restartName) == 0) continue;
        if (n.compare(0, markerName.size(), markerName) == 0) continue;
        const std::string why = unfinished(root/n);
        if (!why.empty())
        {
            problems += "\n    " + prefix + n + " " + why;
        }
        files.push_back(prefix + n);
    }
    return files;
}


bool Foam::TfdemCheckpoint::writeDemRestart
(
    tfdem::ParticleEngine& dem,
    const fileName& dir,
    const std::string& stopped
) const
{
    if (TfdemRanks::writesCase())
    {
        mkDir(dir);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    try
    {
        return dem.write_restart(dir/restartName);
    }
    catch (const std::exception& e)
    {
        FatalErrorInFunction << e.what() << ". " << stopped.c_str() << exit(FatalError);
    }
    return false;
}


std::string Foam::TfdemCheckpoint::fileDigests
(
    const std::vector<std::string>& listed,
    std::string& problems
) const
{
    std::ostringstream mine;
    for (const std::string& path : listed)
    {
        const fileName file = runTime_.globalPath()/path;
        std::string why = synced(file);
        if (why.empty())
        {
            try
            {
                const tfdem::FileDigest d = tfdem::digest_file(file);
                mine << path << '\t' << d.size << '\t' << tfdem::hex(d.hash) << '\n';
            }
            catch (const std::runtime_error& e)
            {
                why = e.what();
            }
        }
        if (!why.empty()) problems += "\n    " + why;
    }
    return mine.str();
}


tfdem::CheckpointManifest Foam::TfdemCheckpoint::manifest
(
    tfdem::ParticleEngine& dem,
    const ParticleTotals& totals,
    bool demRestart,
    const std::string& digests
) const
{
    tfdem::CheckpointManifest m;
    m.time = runTime_.value();
    m.dem_restart = demRestart;
    m.dem_step = dem.step();
    m.engine = dem.key();
    m.particles = totals.count;
    m.particle_mass = totals.mass;
    m.removed_particles = totals.removedCount;
    m.removed_mass = totals.removedMass;
    m.layout = layout_;
    m.ranks = TfdemRanks::count();
    m.write_format = runTime_.writeFormat() == IOstream::ASCII ? "ascii" : "binary";
    m.write_precision = int(IOstream::defaultPrecision());
    std::istringstream lines(digests);
    std::string path, hash;
    unsigned long long size;
    while (lines >> path >> size >> hash)
    {
        m.files.push_back({path, {size, tfdem::from_hex(hash)}});
    }
    m.outputs = dem.output_sizes();
    return m;
}


std::string Foam::TfdemCheckpoint::writeMarker
(
    const tfdem::CheckpointManifest& m,
    const fileName& dir
) const
{
    std::string problems;
    const fileName partial(dir/(markerName + ".tmp"));
    {
        std::ofstream out(partial);
        out << tfdem::format_manifest(m);
        out.close();
        if (!out) problems = "\n    " + partial + ": " + std::strerror(errno);
    }
    if (problems.empty()) problems = synced(partial);
    if (problems.empty() && std::rename(partial.c_str(), (dir/markerName).c_str()) != 0)
    {
        problems = "cannot rename " + partial + ": " + std::strerror(errno);
    }
    if (problems.empty()) problems = synced(dir);
    if (!problems.empty() && problems[0] != '\n') problems = "\n    " + problems;
    return problems;
}


void Foam::TfdemCheckpoint::write
(
    tfdem::ParticleEngine& dem,
    const ParticleTotals& totals,
    bool gasWritten
)
{
    const word t = runTime_.timeName();
    const fileName dir = directory(t);
    const std::string stopped =
        "The run stops before this checkpoint is marked complete; " + lastGoodText();
    TfdemCase::written(runTime_, gasWritten, stopped);

    std::string problems;
    const std::vector<std::string> gas = gasFiles(t, problems);
    stopIfAny
    (
        problems,
        "the gas fields of t = " + t + " s were not written whole"
      + TfdemCase::freeSpace(runTime_.globalPath()),
        "A full disk, or a folder that cannot be written, cuts files short. " + stopped
    );
    const bool demRestart = writeDemRestart(dem, dir, stopped);

    // Each rank's files with their digests, synced to disk
    std::vector<std::string> listed(gas);
    if (TfdemRanks::writesCase() && demRestart)
    {
        listed.push_back(t + "/" + restartName);
    }
    const std::string mine = fileDigests(listed, problems);
    stopIfAny(problems, "the checkpoint of t = " + t + " s could not be verified", stopped);
    const tfdem::CheckpointManifest m =
        manifest(dem, totals, demRestart, TfdemRanks::gatherText(mine));
    if (TfdemRanks::writesCase())
    {
        problems = writeMarker(m, dir);
        lastBytes_ = 0;
        for (const auto& f : m.files)
        {
            lastBytes_ += f.digest.size;
        }
    }
    stopIfAny
    (
        problems,
        "the marker of the checkpoint of t = " + t + " s could not be written"
      + TfdemCase::freeSpace(runTime_.globalPath()),
        stopped
    );
    lastGood_ = t;
    tfdemFailure::checkpointWritten(t);
    written_.push_back(t);
    purge();
}


void Foam::TfdemCheckpoint::purge()
{
    while (kept_ > 0 && written_.size() > kept_)
    {
        const word oldest = written_.front();
        written_.erase(written_.begin());
        if (TfdemRanks::writesCase())
        {
            rmDir(directory(oldest));
        }
        if (runTime_.path() != runTime_.globalPath())
        {
            rmDir(runTime_.path()/oldest);
        }
    }
}
