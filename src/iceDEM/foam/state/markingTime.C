/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "markingTime.H"
#include "completeTime.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::markingTime::markingTime
(
    const word& ctrlDictName,
    const argList& args
)
:
    Time(ctrlDictName, args),
    keep_(0),
    markPending_(false),
    writing_(false),
    runDepth_(0)
{
    // Time's constructor read the controlDict with its own readDict
    takePurgeWrite();
}


Foam::markingTime::markingTime
(
    const dictionary& dict,
    const fileName& rootPath,
    const fileName& caseName,
    const word& systemName,
    const word& constantName,
    const bool enableFunctionObjects,
    const bool enableLibs
)
:
    Time
    (
        dict, rootPath, caseName, systemName, constantName,
        enableFunctionObjects, enableLibs
    ),
    keep_(0),
    markPending_(false),
    writing_(false),
    runDepth_(0)
{
    takePurgeWrite();
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::markingTime::takePurgeWrite()
{
    keep_ = purgeWrite_;
    purgeWrite_ = 0;
}


void Foam::markingTime::markAndPurge()
{
    markPending_ = false;

    completeTime::testWriteDelay();
    completeTime::mark(*this);

    if (keep_ <= 0)
    {
        return;
    }
    // The same time written twice (a write at the end after one at a write
    // time) is one time, as in OpenFOAM's purge
    if (written_.empty() || written_.top() != timeName())
    {
        written_.push(timeName());
    }
    while (written_.size() > keep_)
    {
        // Unmarked first: a kill in the middle leaves it incomplete, not
        // marked with files missing
        const fileName dir
        (
            fileHandler().filePath(objectRegistry::path(written_.pop()))
        );
        completeTime::unmark(dir);
        fileHandler().rmDir(dir);
    }
}


// * * * * * * * * * * * * * Protected Member Functions  * * * * * * * * * * //

void Foam::markingTime::readDict()
{
    Time::readDict();
    takePurgeWrite();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void Foam::markingTime::setSolverWrites
(
    const std::function<void()>& writeOwn,
    const std::function<void()>& writeAfter
)
{
    writeOwn_ = writeOwn;
    writeAfter_ = writeAfter;
}


bool Foam::markingTime::writeObject
(
    IOstream::streamFormat fmt,
    IOstream::versionNumber ver,
    IOstream::compressionType cmp,
    const bool valid
) const
{
    if (writing_ || !writeTime())
    {
        return Time::writeObject(fmt, ver, cmp, valid);
    }

    writing_ = true;
    // Unmarked while any of its files is being (re)written
    completeTime::unmark(*this);
    if (writeOwn_)
    {
        writeOwn_();
    }
    const bool ok = Time::writeObject(fmt, ver, cmp, valid);
    if (writeAfter_)
    {
        writeAfter_();
    }
    // Marked once the function objects have written theirs too (in the
    // next run()); then an older time may go (purgeWrite). Not a time
    // whose write failed
    markPending_ = ok;
    if (!ok)
    {
        WarningInFunction
            << "Writing time " << timeName() << " failed: it is not marked"
            << " complete (a restart starts from the time before it)"
            << endl;
    }
    writing_ = false;
    return ok;
}


bool Foam::markingTime::run() const
{
    // A function object may call run() itself (runTimeControl does, after
    // its writeAndEnd): the mark waits for the outermost run(), after the
    // function objects' state is written
    ++runDepth_;
    const bool running = Time::run();
    --runDepth_;
    if (markPending_ && runDepth_ == 0)
    {
        // const as OpenFOAM's run(), which also changes the Time (it reads
        // modified objects); the mark writes files, not the Time's state
        const_cast<markingTime&>(*this).markAndPurge();
    }
    return running;
}


// ************************************************************************* //
