/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    The domain sub-dictionary of constant/iceDEMProperties: periodic
    boundaries in x and/or y (core/domain/Domain), or inflow/outflow
    (core/domain/InflowOutflow, read in iceDEMCaseInflow.C). Its size checks against
    the floes and the structure run when the DEM starts (World::initialise)
    and stop with a FatalIOError on this entry.

        domain
        {
            type    periodic;       // none | periodic | inflowOutflow
            x       (0 1000);       // periodic in x over [xmin, xmax)
            y       (-200 200);     // and/or in y
        }
\*---------------------------------------------------------------------------*/

#include "iceDEMCase.H"
#include "dictionaryChecks.H"

#include "domain/Domain.H"

#include <cmath>

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::iceDEMCase::readDomain()
{
    if (!properties_.found("domain", keyType::LITERAL))
    {
        return;
    }
    if (!properties_.isDict("domain"))
    {
        FatalIOErrorInFunction(properties_)
            << "Entry 'domain' of constant/iceDEMProperties must be a"
            << " dictionary { type periodic; x (xmin xmax); y (ymin ymax); }"
            << " or { type inflowOutflow; ... } (doc/caseFiles.md)"
            << nl << exit(FatalIOError);
    }
    const dictionary& d = properties_.subDict("domain");
    const word type =
        selectName(d, "type", wordList{"none", "periodic", "inflowOutflow"});
    if (type == "inflowOutflow")
    {
        readInflowOutflow(d);
        return;
    }
    checkEntries
    (
        d, "constant/iceDEMProperties", {"domain", "domain(type periodic)"},
        "domain"
    );
    if (type == "none")
    {
        return;
    }

    ::iceDEM::DomainSettings s;
    const char* axes[2] = {"x", "y"};
    for (int k = 0; k < 2; ++k)
    {
        if (!d.found(axes[k], keyType::LITERAL)) continue;
        const List<scalar> bounds(d.get<List<scalar>>(axes[k]));
        if
        (
            bounds.size() != 2
         || !std::isfinite(bounds[0]) || !std::isfinite(bounds[1])
         || !(bounds[1] > bounds[0])
        )
        {
            FatalIOErrorInFunction(d)
                << "Entry '" << axes[k] << "' of 'domain' in"
                << " constant/iceDEMProperties must be (min max) with finite"
                << " min < max [m]; got " << bounds << nl
                << exit(FatalIOError);
        }
        s.periodic[k] = true;
        s.lo[k] = bounds[0];
        s.hi[k] = bounds[1];
    }
    if (!s.periodic[0] && !s.periodic[1])
    {
        FatalIOErrorInFunction(d)
            << "Entry 'domain' of constant/iceDEMProperties: type periodic"
            << " needs the periodic bounds 'x (xmin xmax);' and/or"
            << " 'y (ymin ymax);'" << nl
            << exit(FatalIOError);
    }

    coreCall(d, "domain", [&]{ world_->setDomain(s); });

    Info<< "iceDEM: periodic domain";
    for (int k = 0; k < 2; ++k)
    {
        if (s.periodic[k])
        {
            Info<< " " << axes[k] << " (" << s.lo[k] << " " << s.hi[k] << ")";
        }
    }
    Info<< nl;
}


// ************************************************************************* //
