#include "tfdemCase.H"
#include "tfdemRanks.H"
#include "IFstream.H"
#include "OSspecific.H"

#include <mpi.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <vector>

#include "tfdem/suggest.h"

const Foam::word Foam::TfdemCase::lockName("tfdem.lock");

namespace
{

const Foam::word couplingFileName("coupling.yaml");

// The first character of `path` OpenFOAM strips from file names (fileName::valid), or 0
char strippedCharacter(const std::string& path)
{
    for (const char c : path)
    {
        if (c == '"' || c == '\'' || std::isspace(static_cast<unsigned char>(c)))
        {
            return c;
        }
    }
    return 0;
}

std::string describeCharacter(char c)
{
    if (c == ' ') return "a space";
    if (c == '"' || c == '\'') return std::string("a quote (") + c + ")";
    return "a blank (tab or newline)";
}

std::string hostName()
{
    char name[256] = "";
    gethostname(name, sizeof name - 1);
    return name;
}

// What the lock file says of the run holding it ("process P on H since T"), or ""
std::string lockHolder(const Foam::fileName& lock)
{
    std::ifstream in(lock);
    std::string line;
    std::getline(in, line);
    return line;
}

// A killed run's ranks can go on for a moment after mpirun is gone; a run started then waits
// for them this long before it refuses the case
constexpr int lockWaitSeconds = 10;

// Whether the exclusive lock on fd was taken within `seconds` (saying so while it waits)
bool lockedWithin(int fd, int seconds)
{
    for (int waited = 0; ::flock(fd, LOCK_EX | LOCK_NB) != 0; ++waited)
    {
        if (errno != EWOULDBLOCK || waited == seconds) return false;
        if (waited == 0)
        {
            Foam::Info<< "TFDEM: another run holds this case's lock; waiting up to " << seconds
                << " s for it to end" << Foam::endl;
        }
        ::sleep(1);
    }
    return true;
}

// A name in the case folder that looks like a misnamed coupling.yaml
bool nearCouplingName(const std::string& name)
{
    std::string lower(name);
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (lower == couplingFileName) return true;  // other capitals
    if (lower.compare(0, 9, "coupling.") == 0 && lower.find(".y") != std::string::npos) return true;
    return tfdem::edit_distance(lower, couplingFileName) <= 2;
}

// Whether a small top-level file of the case is a coupled DEM script
bool hasCouplingFix(const Foam::fileName& file)
{
    constexpr off_t largestScript = 1 << 20;
    if (Foam::fileSize(file) > largestScript) return false;
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str().find("tfdem/coupling") != std::string::npos;
}

} // End anonymous namespace


void Foam::TfdemCase::checkArguments(int argc, char* argv[])
{
    std::string casePath;
    for (int i = 1; i + 1 < argc; ++i)
    {
        if (std::strcmp(argv[i], "-case") == 0)
        {
            casePath = argv[i + 1];
        }
    }
    const bool given = !casePath.empty();
    if (!given)
    {
        // not Foam::cwd(): a fileName strips the very characters this check is about
        char here[4096];
        casePath = ::getcwd(here, sizeof here) ? here : "";
    }
    const char c = strippedCharacter(casePath);
    if (c)
    {
        FatalErrorInFunction
            << "the case path '" << casePath.c_str() << "' "
            << (given ? "(-case)" : "(the working directory)") << " holds "
            << describeCharacter(c).c_str() << ", which OpenFOAM strips from file names: it"
            << " would read and write another folder. Fix: rename the case folder, or the"
            << " folders above it, without blanks or quotes (e.g. my_bed for 'my bed')"
            << exit(FatalError);
    }
}


void Foam::TfdemCase::checkControlDict(const argList& args)
{
    const fileName file(args.rootPath()/args.globalCaseName()/"system"/"controlDict");
    IFstream in(file);
    if (!in.good())
    {
        return;  // OpenFOAM's own message names it
    }
    const dictionary control(in);
    const word writeControl(control.getOrDefault<word>("writeControl", "timeStep"));
    scalar interval = 1;
    const bool hasInterval =
        control.readIfPresent("writeInterval", interval)
     || control.readIfPresent("writeFrequency", interval);
    const bool steps = writeControl == "timeStep";
    if
    (
        !hasInterval || !std::isfinite(interval) || !(interval > 0)
     || (steps && (interval < 1 || interval != std::round(interval)))
    )
    {
        FatalIOErrorInFunction(control)
            << "writeInterval " << (hasInterval ? Foam::name(interval).c_str() : "missing")
            << " (writeControl " << writeControl << "): it must be "
            << (steps ? "a whole number of steps, at least 1" : "positive") << ". The gas"
            << " fields and the joint checkpoints are written every writeInterval ("
            << (steps ? "steps" : "seconds of simulated time") << "); to write only at the"
            << " end, set writeInterval to the run's length"
            << exit(FatalIOError);
    }
    scalar deltaT = 0;
    if (!control.readIfPresent("deltaT", deltaT) || !std::isfinite(deltaT) || !(deltaT > 0))
    {
        FatalIOErrorInFunction(control)
            << "deltaT must be a positive time step (s)" << exit(FatalIOError);
    }
    if (args.parRunControl().parRun() && control.getOrDefault<word>("startFrom", "") == "latestTime")
    {
        checkSplitTimes(args.rootPath()/args.globalCaseName());
    }
}


void Foam::TfdemCase::checkSplitTimes(const fileName& root)
{
    // Each processor folder's newest time (OpenFOAM's own message would say only that the
    // start times differ)
    word newest, newestAt, oldest, oldestAt;
    for (const fileName& name : readDir(root, fileName::DIRECTORY))
    {
        if (name.size() < 10 || name.compare(0, 9, "processor") != 0) continue;
        scalar latest = -1;
        word latestName;
        for (const fileName& t : readDir(root/name, fileName::DIRECTORY))
        {
            scalar value;
            if (readScalar(t, value) && value > latest)
            {
                latest = value;
                latestName = t;
            }
        }
        if (newest.empty() || latest > std::stod(newest)) newest = latestName, newestAt = name;
        if (oldest.empty() || latest < std::stod(oldest)) oldest = latestName, oldestAt = name;
    }
    if (!newest.empty() && newest != oldest)
    {
        FatalErrorInFunction
            << "the split gas's folders end at different times: " << newestAt << "/" << newest
            << " is the newest, " << oldestAt << " has nothing after " << oldest << " (its "
            << newest << " deleted, or never written by a run killed while writing). Fix: tfdem"
            << " resume " << root << " moves the unfinished time aside and resumes from the"
            << " newest checkpoint every folder holds; or restore " << oldestAt << "/" << newest
            << exit(FatalError);
    }
}


void Foam::TfdemCase::messagePrecision(unsigned digits)
{
    Sout.precision(digits);
    Serr.precision(digits);
    Pout.precision(digits);
    Perr.precision(digits);
    FatalError().precision(digits);
    FatalIOError.error::operator()().precision(digits);
}


Foam::fileName Foam::TfdemCase::absolute(const fileName& path)
{
    if (path.empty() || path.isAbsolute())
    {
        return path;
    }
    return cwd()/path;
}


std::string Foam::TfdemCase::freeSpace(const fileName& path)
{
    struct statvfs fs;
    if (statvfs(path.c_str(), &fs) != 0)
    {
        return "";
    }
    std::ostringstream text;
    text.precision(3);
    text << " (" << double(fs.f_bavail)*fs.f_frsize/1e6 << " MB free on its file system)";
    return text.str();
}


bool Foam::TfdemCase::coupled(const Time& runTime)
{
    const fileName dir(runTime.globalPath());
    if (isFile(dir/couplingFileName))
    {
        return true;
    }
    std::vector<std::string> found;
    if (isDir(dir/couplingFileName))
    {
        found.push_back(couplingFileName + " is a folder, not a file");
    }
    for (const fileName& name : readDir(dir, fileName::FILE))
    {
        if (nearCouplingName(name))
        {
            found.push_back("'" + name + "' (a misnamed " + couplingFileName + "?)");
        }
        else if (hasCouplingFix(dir/name))
        {
            found.push_back("the DEM script '" + name + "' (it has a tfdem/coupling fix)");
        }
    }
    if (isFile(dir/runTime.timeName()/"voidFraction"))
    {
        found.push_back(runTime.timeName() + "/voidFraction (the gas fraction of particles)");
    }
    if (found.empty())
    {
        Info<< "TFDEM: no " << couplingFileName << " in " << dir
            << ": running the gas only (void fraction 1, no particles, no LIGGGHTS)\n" << endl;
        return false;
    }
    std::string list;
    for (const std::string& f : found)
    {
        list += "\n    " + f;
    }
    FatalErrorInFunction
        << "no " << couplingFileName << " in " << dir << ", but the case is set up for"
        << " particles:" << list.c_str() << "\nWithout " << couplingFileName << " the gas would"
        << " run alone, as if the bed were empty. Fix: restore " << couplingFileName
        << " (the coupling settings; docs/src/reference/coupling-yaml.md), or, for a gas-only run, remove the"
        << " particle files named above" << exit(FatalError);
    return false;
}


Foam::TfdemCase::TfdemCase(const Time& runTime)
{
    const fileName dir(runTime.globalPath());
    const fileName lock(dir/lockName);
    std::string problem;
    if (TfdemRanks::rank() == 0)
    {
        lock_ = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
        if (lock_ < 0)
        {
            problem =
                "cannot create " + lock + ": " + std::strerror(errno) + ". The case folder "
              + dir + " must be writable: a run writes its fields, checkpoints and logs there."
                " Fix: make it writable, or copy the case to a writable place";
        }
        else if (!lockedWithin(lock_, lockWaitSeconds))
        {
            const std::string holder = lockHolder(lock);
            problem =
                "another tfdemFoam is running in " + dir + " ("
              + (holder.empty() ? std::string("its lock is ") + lock : holder)
              + "; waited " + std::to_string(lockWaitSeconds) + " s for it to end): two runs"
                " in one case would write the same checkpoints and logs. Wait for it to end,"
                " or stop it first";
        }
        else
        {
            std::ostringstream who;
            const std::time_t now = std::time(nullptr);
            char date[64];
            std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
            who << "process " << ::getpid() << " on " << hostName() << " since " << date
                << " (" << TfdemRanks::count() << " rank(s))\n";
            const std::string text = who.str();
            const bool recorded =
                ::ftruncate(lock_, 0) == 0
             && ::pwrite(lock_, text.data(), text.size(), 0) == ssize_t(text.size());
            // shared from now on: a new run's exclusive lock fails while any rank holds it
            ::flock(lock_, LOCK_SH);
            if (!recorded)
            {
                problem =
                    "cannot write " + lock + ": " + std::strerror(errno) + freeSpace(dir);
            }
        }
    }
    int length = int(problem.size());
    MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
    problem.resize(length);
    MPI_Bcast(&problem[0], length, MPI_CHAR, 0, MPI_COMM_WORLD);
    if (problem.empty() && TfdemRanks::rank() != 0)
    {
        lock_ = ::open(lock.c_str(), O_RDONLY);
        if (lock_ >= 0) ::flock(lock_, LOCK_SH | LOCK_NB);
    }
    if (!problem.empty())
    {
        FatalErrorInFunction << problem.c_str() << exit(FatalError);
    }
    if (!chDir(dir))
    {
        FatalErrorInFunction
            << "cannot make the case " << dir << " the working directory" << exit(FatalError);
    }
}


void Foam::TfdemCase::written(const Time& runTime, bool ok, const std::string& consequence)
{
    int failed = ok ? 0 : 1;
    MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (failed)
    {
        FatalErrorInFunction
            << "writing the gas fields of t = " << runTime.timeName() << " s to "
            << runTime.path()/runTime.timeName() << " failed"
            << freeSpace(runTime.path()).c_str() << " (a full disk, or a folder that cannot be"
            << " written?). " << consequence.c_str() << exit(FatalError);
    }
}
