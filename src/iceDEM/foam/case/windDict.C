/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "windDict.H"

#include "Tuple2.H"
#include "List.H"

#include <cmath>
#include <utility>
#include <vector>

::iceDEM::WindHistory Foam::iceDEMChecks::readWindHistory
(
    const dictionary& dict
)
{
    const word type = selectName(dict, "type", wordList({"uniform", "table"}));

    auto finite = [](const vector& v)
    {
        return
            std::isfinite(v.x()) && std::isfinite(v.y())
         && std::isfinite(v.z());
    };

    if (type == "uniform")
    {
        if (dict.found("table", keyType::LITERAL))
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'table' is for type table; type uniform takes"
                << " 'velocity'" << nl << exit(FatalIOError);
        }
        const vector U = dict.get<vector>("velocity");
        if (!finite(U))
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'velocity' is " << U << ": every component must"
                << " be a finite number [m/s]" << nl << exit(FatalIOError);
        }
        return ::iceDEM::WindHistory(toVec3(U));
    }

    if (dict.found("velocity", keyType::LITERAL))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'velocity' is for type uniform; type table takes"
            << " 'table' ((time (Ux Uy Uz)) ...)" << nl << exit(FatalIOError);
    }
    const List<Tuple2<scalar, vector>> rows =
        dict.get<List<Tuple2<scalar, vector>>>("table");
    if (rows.empty())
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'table' is empty: give at least one row"
            << " (time (Ux Uy Uz))" << nl << exit(FatalIOError);
    }
    std::vector<std::pair<double, ::iceDEM::Vec3>> table;
    table.reserve(rows.size());
    forAll(rows, k)
    {
        const scalar t = rows[k].first();
        const vector& U = rows[k].second();
        if (!std::isfinite(t) || !finite(U))
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'table', row " << k << " (" << t << " " << U
                << "): time and velocity must be finite numbers"
                << nl << exit(FatalIOError);
        }
        if (k > 0 && !(t > rows[k - 1].first()))
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'table', row " << k << ": the times must increase"
                << " strictly (" << rows[k - 1].first() << " then " << t
                << ")" << nl << exit(FatalIOError);
        }
        table.emplace_back(t, toVec3(U));
    }
    return coreCall
    (
        dict, "wind",
        [&]{ return ::iceDEM::WindHistory(std::move(table)); }
    );
}
