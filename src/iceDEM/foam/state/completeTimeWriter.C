/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "completeTimeWriter.H"

#include "Pstream.H"

// * * * * * * * * * * * * * * * Local Data  * * * * * * * * * * * * * * * * //

namespace
{

//- Set by the handler, read at the end of every step
volatile std::sig_atomic_t terminateFlag = 0;

extern "C" void onTerminate(int)
{
    // Async-signal-safe: a flag only
    terminateFlag = 1;
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::markingTime& Foam::completeTimeWriter::markingTimeOf(Time& runTime)
{
    markingTime* t = dynamic_cast<markingTime*>(&runTime);
    if (!t)
    {
        FatalErrorInFunction
            << "The solver's Time is not completeTime::createTime's: its"
            << " written times could not be marked complete"
            << exit(FatalError);
    }
    return *t;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::completeTimeWriter::completeTimeWriter
(
    Time& runTime,
    const std::function<void()>& writeOwn,
    const std::function<void()>& writeAfter
)
:
    runTime_(markingTimeOf(runTime))
{
    runTime_.setSolverWrites(writeOwn, writeAfter);
    struct sigaction act;
    act.sa_handler = onTerminate;
    sigemptyset(&act.sa_mask);
    act.sa_flags = SA_RESTART;    // no EINTR in the middle of a write
    if (sigaction(SIGTERM, &act, &previous_) != 0)
    {
        FatalErrorInFunction
            << "Could not install the SIGTERM handler" << exit(FatalError);
    }
    Info<< "iceDEM: SIGTERM writes a complete time at the end of the step"
        << " and stops (exit code 0)" << endl;   // flushed: scripts wait for it
}


// * * * * * * * * * * * * * * * * Destructor  * * * * * * * * * * * * * * //

Foam::completeTimeWriter::~completeTimeWriter()
{
    sigaction(SIGTERM, &previous_, nullptr);
    // Their captures live no longer than the solver's loop
    runTime_.setSolverWrites(nullptr, nullptr);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

bool Foam::completeTimeWriter::terminateRequested()
{
    return terminateFlag != 0;
}


bool Foam::completeTimeWriter::write()
{
    bool stop = terminateRequested();
    if (Pstream::parRun())
    {
        reduce(stop, orOp<bool>());
    }

    if (!stop && !runTime_.writeTime())
    {
        return false;
    }

    if (stop)
    {
        Info<< "iceDEM: SIGTERM: writing time " << runTime_.timeName()
            << " and stopping" << nl;
        // Write time now and the last step: run() returns false after it
        runTime_.stopAt(Time::saWriteNow);
        runTime_.setEndTime(runTime_.value());
        runTime_.writeNow();
    }
    else
    {
        runTime_.write();
    }
    // (markingTime::writeObject: the solver's own files with OpenFOAM's,
    // the mark in the next runTime.run())
    return true;
}


// ************************************************************************* //
