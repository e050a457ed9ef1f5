/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "completeTime.H"
#include "markingTime.H"

#include "IFstream.H"
#include "OFstream.H"
#include "OSspecific.H"
#include "Pstream.H"
#include "IOobject.H"

#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <thread>

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

// * * * * * * * * * * * * * * * Static Data  * * * * * * * * * * * * * * * //

const char* const Foam::completeTime::markName = "iceDEMComplete";


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

//- Rename the finished temporary onto the file; remove the other
//  (compressed or not) variant of the file so that readers cannot pick a
//  stale one
bool renameIntoPlace
(
    const fileName& target,
    const fileName& tmp,
    IOstream::compressionType cmp
)
{
    const bool gz = (cmp == IOstream::COMPRESSED);
    const fileName src(gz ? fileName(tmp + ".gz") : tmp);
    const fileName dst(gz ? fileName(target + ".gz") : target);
    if (std::rename(src.c_str(), dst.c_str()) != 0)
    {
        WarningInFunction
            << "Could not rename " << src << " to " << dst << endl;
        return false;
    }
    const fileName other(gz ? target : fileName(target + ".gz"));
    std::remove(other.c_str());
    return true;
}


//- Flush a file's data, or a directory's entries, to the disk (fsync).
//  File systems that cannot sync a directory (EINVAL) have nothing to do;
//  another failure is warned about once per run: the time is still marked
//  (a kill cannot lose it, only a power failure)
void syncPath(const fileName& path, bool directory)
{
    const int fd = ::open
    (
        path.c_str(), O_RDONLY | O_CLOEXEC | (directory ? O_DIRECTORY : 0)
    );
    bool ok = fd >= 0;
    int err = ok ? 0 : errno;
    if (ok)
    {
        if (::fsync(fd) != 0)
        {
            err = errno;
            ok = (err == EINVAL || err == EROFS);
        }
        ::close(fd);
    }
    static bool warned = false;
    if (!ok && !warned)
    {
        warned = true;
        WarningInFunction
            << "Could not flush " << path << " to the disk ("
            << std::strerror(err) << "): a power failure could lose the"
            << " time being marked complete (a kill cannot)" << endl;
    }
}


//- Every file and directory under dir (depth first), then dir itself
void syncTree(const fileName& dir)
{
    if (DIR* d = ::opendir(dir.c_str()))
    {
        while (const dirent* e = ::readdir(d))
        {
            const std::string name(e->d_name);
            if (name == "." || name == "..") continue;
            const fileName entry(dir/name);
            struct stat st;
            if (::lstat(entry.c_str(), &st) != 0) continue;
            if (S_ISDIR(st.st_mode)) syncTree(entry);
            else if (S_ISREG(st.st_mode)) syncPath(entry, false);
        }
        ::closedir(d);
    }
    syncPath(dir, true);
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Functions  * * * * * * * * * * * * * * * //

void Foam::completeTime::testWriteDelay()
{
    // Test-only hook (tests/cases/iceDEMRestartKill): a pause inside every
    // write so that a kill lands in one with certainty. Off by default.
    static const double delay = []
    {
        const char* s = std::getenv("ICEDEM_TEST_WRITE_DELAY");
        const double d = s ? std::atof(s) : 0;
        if (d > 0)
        {
            Info<< "iceDEM: ICEDEM_TEST_WRITE_DELAY = " << d
                << " s (test only: every write pauses)" << endl;
        }
        return d > 0 && std::isfinite(d) ? d : 0.0;
    }();

    if (delay > 0)
    {
        std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    }
}


bool Foam::completeTime::atomicWrite
(
    const regIOobject& io,
    IOstream::streamFormat fmt,
    IOstream::versionNumber ver,
    IOstream::compressionType cmp,
    const unsigned precision
)
{
    mkDir(io.path());
    const fileName target(io.objectPath());
    const fileName tmp(target + ".writing");

    bool ok = false;
    {
        OFstream os(tmp, fmt, ver, cmp);
        if (!os.good())
        {
            WarningInFunction
                << "Could not open " << tmp << " for writing" << endl;
            return false;
        }
        if (precision > 0) os.precision(precision);
        ok = io.writeHeader(os) && io.writeData(os);
        IOobject::writeEndDivider(os);
        ok = ok && os.good();
    }

    testWriteDelay();

    return ok && renameIntoPlace(target, tmp, cmp);
}


void Foam::completeTime::mark(const Time& runTime)
{
    const fileName dir(runTime.timePath()/"uniform");
    mkDir(dir);
    // On the disk before the mark: after a power failure a marked time
    // holds what was written, not what the page cache had not stored yet
    syncTree(runTime.timePath());
    const fileName target(dir/markName);
    const fileName tmp(target + ".writing");
    {
        OFstream os(tmp);
        IOobject io
        (
            markName, runTime.timeName(), "uniform", runTime,
            IOobject::NO_READ, IOobject::NO_WRITE, false
        );
        io.writeHeader(os, "dictionary");
        os  << "// Written last: every file of this time directory is"
            << " complete (iceDEM restart)" << nl;
        os.writeEntry("time", runTime.timeName());
        IOobject::writeEndDivider(os);
        if (!os.good())
        {
            FatalErrorInFunction
                << "Could not write " << tmp << exit(FatalError);
        }
    }
    syncPath(tmp, false);
    renameIntoPlace(target, tmp, IOstream::UNCOMPRESSED);
    // The mark, and the time directory's entry in the case (or processor)
    // directory, on the disk before purgeWrite may remove an older time
    syncPath(dir, true);
    syncPath(runTime.timePath().path(), true);
}


void Foam::completeTime::unmark(const Time& runTime)
{
    unmark(runTime.timePath());
}


void Foam::completeTime::unmark(const fileName& timeDir)
{
    const fileName dir(timeDir/"uniform");
    const fileName target(dir/markName);
    // Gone from the disk before any file of the time is written again
    if (std::remove(target.c_str()) == 0)
    {
        syncPath(dir, true);
    }
}


Foam::completeTime::status Foam::completeTime::statusOf
(
    const fileName& timeDir
)
{
    if (isFile(timeDir/"uniform"/markName, false))
    {
        return status::complete;
    }
    if
    (
        !isDir(timeDir/"uniform")
     && (
            readDir(timeDir, fileName::FILE).size()
          + readDir(timeDir, fileName::DIRECTORY).size()
        ) > 0
    )
    {
        return status::initial;
    }
    return status::incomplete;
}


namespace Foam
{
namespace completeTime
{
    //- createTime at the value of the directory's name (OpenFOAM's)
    static autoPtr<Time> createTimeFromComplete(const argList& args);
}
}


namespace
{

// OpenFOAM starts from the value of the time directory's name (1 for "1"),
// not from the value in its uniform/time, which the run that wrote it had
// summed step by step (1.0000000000000004): the restarted run's times would
// then differ from the uninterrupted run's by rounding, and with them
// whatever depends on the time (a wind table: 2e-13 m apart after 1 s). The
// summed value is taken back when it names the same time.
void restoreSummedTime(Foam::Time& runTime)
{
    using namespace Foam;
    const fileName file(runTime.timePath()/"uniform"/"time");
    if (!isFile(file, false))
    {
        return;     // initial conditions, or a case start without a directory
    }
    IFstream is(file);
    if (!is.good())
    {
        return;
    }
    const dictionary d(is);
    scalar summed = 0;
    if
    (
        d.readIfPresent("value", summed)
     && std::isfinite(summed)
     && summed != runTime.value()
     && Time::timeName(runTime.timeToUserTime(summed)) == runTime.timeName()
    )
    {
        runTime.setTime(summed, runTime.timeIndex());
    }
}

} // anonymous namespace


Foam::autoPtr<Foam::Time> Foam::completeTime::createTime
(
    const argList& args
)
{
    autoPtr<Time> runTime(createTimeFromComplete(args));
    restoreSummedTime(*runTime);
    return runTime;
}


Foam::autoPtr<Foam::Time> Foam::completeTime::createTimeFromComplete
(
    const argList& args
)
{
    Info<< "Create time\n" << endl;

    const fileName dictPath
    (
        args.rootPath()/args.globalCaseName()/"system"/Time::controlDictName
    );

    // The Time as the controlDict sets it up, with OpenFOAM's start time
    const auto asControlDictSays = [&args]()
    {
        return autoPtr<Time>(new markingTime(Time::controlDictName, args));
    };

    // What the controlDict asks for; anything unusual: OpenFOAM's own Time
    // (and its own messages)
    dictionary ctrl;
    {
        IFstream is(dictPath);
        if (!is.good())
        {
            return asControlDictSays();
        }
        ctrl.read(is);
        ctrl.remove("FoamFile");
    }
    const word startFrom(ctrl.getOrDefault<word>("startFrom", "latestTime"));
    scalar requested = 0;
    if
    (
        !(startFrom == "latestTime" || startFrom == "firstTime")
     && !(startFrom == "startTime" && ctrl.readIfPresent("startTime", requested))
    )
    {
        return asControlDictSays();
    }

    // The time directories of this (processor) case and their status
    wordList names;
    labelList ok;
    for (const instant& t : TimePaths::findTimes(args.path(), "constant"))
    {
        if (t.name() == "constant")
        {
            continue;
        }
        names.append(t.name());
        ok.append(statusOf(args.path()/t.name()) != status::incomplete);
    }

    // Every rank sees every rank's list
    List<wordList> allNames(Pstream::nProcs());
    List<labelList> allOk(Pstream::nProcs());
    allNames[Pstream::myProcNo()] = names;
    allOk[Pstream::myProcNo()] = ok;
    Pstream::gatherList(allNames);
    Pstream::gatherList(allOk);
    Pstream::scatterList(allNames);
    Pstream::scatterList(allOk);

    // Per time name: its value, and the ranks on which it is complete
    struct info { scalar value; label nOk; label nSeen; };
    std::map<std::string, info> times;
    forAll(allNames, proci)
    {
        forAll(allNames[proci], k)
        {
            const word& n = allNames[proci][k];
            info& i = times[n];
            i.value = readScalar(n);
            i.nSeen += 1;
            i.nOk += allOk[proci][k];
        }
    }
    const label nProcs = Pstream::nProcs();
    auto completeOnAll = [&](const info& i) { return i.nOk == nProcs; };

    // The controlDict's choice, in the messages
    const std::string selectorText
    (
        startFrom == "startTime" ? "startTime" : "startFrom " + startFrom
    );
    const char* const selector = selectorText.c_str();

    // The time OpenFOAM would start from (firstTime: the earliest; an
    // incomplete one falls back to the case's start below, as nothing
    // complete comes before it)
    const info* wanted = nullptr;
    word wantedName;
    for (const auto& t : times)
    {
        const bool match =
            startFrom == "latestTime"
          ? (!wanted || t.second.value > wanted->value)
          : startFrom == "firstTime"
          ? (!wanted || t.second.value < wanted->value)
          : mag(t.second.value - requested)
            <= 1e-12*max(scalar(1), mag(requested));
        if (match)
        {
            wanted = &t.second;
            wantedName = t.first;
        }
    }
    if (!wanted || completeOnAll(*wanted))
    {
        // Nothing to start from (OpenFOAM says so) or a complete time
        return asControlDictSays();
    }

    // The last complete time at or before it
    const info* from = nullptr;
    word fromName;
    scalar fromValue = 0;
    for (const auto& t : times)
    {
        if
        (
            completeOnAll(t.second) && t.second.value < wanted->value
         && (!from || t.second.value > from->value)
        )
        {
            from = &t.second;
            fromName = t.first;
            fromValue = t.second.value;
        }
    }

    // None: a case whose initial state is not a time directory (iceDEMFoam
    // reads constant/iceField) starts over from the controlDict's startTime,
    // as its first run did, if no directory of that time exists
    bool fromCaseStart = false;
    if (!from)
    {
        scalar caseStart = 0;
        ctrl.readIfPresent("startTime", caseStart);
        bool startHasDir = false;
        for (const auto& t : times)
        {
            startHasDir = startHasDir
             || mag(t.second.value - caseStart)
                <= 1e-12*max(scalar(1), mag(caseStart));
        }
        if (!startHasDir && caseStart < wanted->value)
        {
            fromCaseStart = true;
            fromValue = caseStart;
            fromName = Time::timeName(caseStart);
        }
    }

    // The incomplete times skipped (those after the start time)
    wordList skipped;
    for (const auto& t : times)
    {
        if
        (
            (!(from || fromCaseStart) || t.second.value > fromValue)
         && t.second.value <= wanted->value
        )
        {
            skipped.append(word(t.first));
        }
    }
    auto where = [&](const word& n)
    {
        const info& i = times[n];
        std::string s;
        if (nProcs > 1)
        {
            s = " (complete on " + Foam::name(i.nOk) + " of "
              + Foam::name(nProcs) + " processor directories)";
        }
        return word(s, false);
    };

    if (!from && !fromCaseStart)
    {
        FatalErrorInFunction
            << "The start time " << wantedName << " ("
            << selector
            << " in " << dictPath << ") is incomplete" << where(wantedName)
            << ": it has no uniform/" << markName
            << " (the run was stopped while writing it) and there is no"
            << " complete time before it to start from." << nl
            << "    Incomplete time directories: " << skipped << nl
            << exit(FatalError);
    }

    forAll(skipped, k)
    {
        Warning
            << "iceDEM restart: time directory " << skipped[k]
            << " is incomplete" << where(skipped[k]) << ": no uniform/"
            << markName << " (the run was stopped while writing it)." << nl
            << "    It is left in place; the run overwrites its files if it"
            << " reaches that time." << endl;
    }
    Warning
        << "iceDEM restart: starting from " << fromName
        << (
               fromCaseStart
             ? ", the case's startTime (no complete time was written), before "
             : ", the last complete time before "
           )
        << wantedName << " ("
        << selector
        << " in " << dictPath << ")" << nl << endl;

    // OpenFOAM's Time from the controlDict read above with the start time
    // replaced (in memory only: the user's file is not touched)
    ctrl.set("startFrom", word("startTime"));
    ctrl.set("startTime", fromValue);

    const bool functionObjects =
        argList::validOptions.found("withFunctionObjects")
      ? args.found("withFunctionObjects")
      : argList::validOptions.found("noFunctionObjects")
      ? !args.found("noFunctionObjects")
      : false;

    return autoPtr<Time>
    (
        new markingTime
        (
            ctrl,
            args.rootPath(),
            args.caseName(),
            "system",
            "constant",
            functionObjects,
            !args.found("no-libs")
        )
    );
}


// ************************************************************************* //
