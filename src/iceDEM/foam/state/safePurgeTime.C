/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "safePurgeTime.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::safePurgeTime::safePurgeTime
(
    const word& ctrlDictName,
    const argList& args
)
:
    Time(ctrlDictName, args),
    keep_(0)
{
    // Time's constructor read the controlDict with its own readDict
    takePurgeWrite();
}


Foam::safePurgeTime::safePurgeTime
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
    keep_(0)
{
    takePurgeWrite();
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::safePurgeTime::takePurgeWrite()
{
    keep_ = purgeWrite_;
    purgeWrite_ = 0;
}


// * * * * * * * * * * * * * Protected Member Functions  * * * * * * * * * * //

void Foam::safePurgeTime::readDict()
{
    Time::readDict();
    takePurgeWrite();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void Foam::safePurgeTime::purgeMarked()
{
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
        fileHandler().rmDir
        (
            fileHandler().filePath(objectRegistry::path(written_.pop()))
        );
    }
}


// * * * * * * * * * * * * * * * * Functions  * * * * * * * * * * * * * * * //

void Foam::purgeMarked(Time& runTime)
{
    if (safePurgeTime* t = dynamic_cast<safePurgeTime*>(&runTime))
    {
        t->purgeMarked();
    }
}


// ************************************************************************* //
