/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "structureSelection.H"

// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * //

void Foam::iceDEMStatistics::selectionNotEmpty
(
    const dictionary& dict,
    const word& object,
    const char* key,
    bool given,
    label size,
    const char* all
)
{
    if (given && size == 0)
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' of function object " << object
            << " in system/controlDict is an empty list: it would select"
            << " nothing. Give names (or regular expressions), or omit"
            << " the entry to select " << all << nl
            << exit(FatalIOError);
    }
}


std::vector<Foam::label> Foam::iceDEMStatistics::selectStructure
(
    const iceDEMCase& c,
    bool given,
    const wordRes& selection,
    const dictionary& dict,
    const word& object,
    wordList& unused
)
{
    const ::iceDEM::World& w = c.world();
    const label nBodies = label(w.bodies().size());
    std::vector<label> bodies;
    unused.clear();
    for (label i = 0; i < nBodies; ++i)
    {
        const word n = c.name(i);
        const bool isFree = w.bodies()[i].isFree();
        if (given ? selection.match(n) : !isFree)
        {
            if (isFree)
            {
                FatalIOErrorInFunction(dict)
                    << "Entry 'structure' of function object " << object
                    << " in system/controlDict selects body " << n
                    << ", which is free: the structure must be fixed or"
                    << " prescribed bodies" << nl << exit(FatalIOError);
            }
            bodies.push_back(i);
        }
        else if (!isFree)
        {
            unused.append(n);
        }
    }
    if (given)
    {
        for (const wordRe& r : selection)
        {
            bool any = false;
            for (label i = 0; i < nBodies; ++i) { any = any || r.match(c.name(i)); }
            if (!any)
            {
                FatalIOErrorInFunction(dict)
                    << "Entry 'structure' of function object " << object
                    << " in system/controlDict: '" << r << "' matches no"
                    << " body. Bodies that are not free: " << unused << nl
                    << exit(FatalIOError);
            }
        }
    }
    return bodies;
}


// ************************************************************************* //
