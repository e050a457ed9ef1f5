/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "postProcessingFile.H"

#include "OSspecific.H"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

//- Time (first column) of the last data row of a file; false when none.
//  Reads the tail only: the files can be large.
bool lastRowTime(const std::string& path, double& t)
{
    std::ifstream is(path, std::ios::binary);
    if (!is)
    {
        return false;
    }
    is.seekg(0, std::ios::end);
    const std::streamoff size = is.tellg();
    const std::streamoff tail = std::min<std::streamoff>(size, 1 << 16);
    is.seekg(size - tail);
    std::string text(static_cast<size_t>(tail), '\0');
    is.read(&text[0], tail);

    // The last complete line that is not a comment (a killed run may have
    // left the very last line half written)
    std::istringstream lines(text);
    std::string line;
    bool found = false;
    while (std::getline(lines, line))
    {
        if (lines.eof())
        {
            break;    // no newline after it: possibly cut
        }
        std::istringstream words(line);
        double v;
        if (!line.empty() && line[0] != '#' && (words >> v))
        {
            t = v;
            found = true;
        }
    }
    return found;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Functions  * * * * * * * * * * * * * * * //

void Foam::warnRowsBeyondStart
(
    const Time& runTime,
    const fileName& dir,
    const word& name
)
{
    const scalar t0 = runTime.startTime().value();
    const scalar tol = 1e-9*max(scalar(1), mag(t0));

    for (const fileName& sub : readDir(dir.path(), fileName::DIRECTORY))
    {
        scalar ts;
        if (!readScalar(sub, ts) || !(ts < t0 - tol))
        {
            continue;
        }
        const fileName file(dir.path()/sub/name);
        double last;
        if (isFile(file, false) && lastRowTime(file, last) && last > t0 + tol)
        {
            Warning
                << "iceDEM output: " << file << " has rows up to t = " << last
                << ", beyond the start time " << runTime.timeName(t0)
                << " of this run (an earlier run went on beyond it: stopped"
                << " after its last complete time, or restarted earlier)."
                << nl
                << "    They are left in place; the rows from "
                << runTime.timeName(t0) << " on are in " << dir/name
                << ": when joining the folders, take the rows of " << sub.c_str()
                << " up to " << runTime.timeName(t0) << " only." << endl;
        }
    }
}


Foam::fileName Foam::newOutputFile
(
    const Time& runTime,
    const fileName& dir,
    const word& name
)
{
    const fileName file(dir/name);
    if (isFile(file, false))
    {
        label n = 1;
        while (exists(file + "." + Foam::name(n), false, false))
        {
            ++n;
        }
        const fileName aside(file + "." + Foam::name(n));
        if (std::rename(file.c_str(), aside.c_str()) != 0)
        {
            FatalErrorInFunction
                << "Could not move " << file << " aside to " << aside
                << exit(FatalError);
        }
        Warning
            << "iceDEM output: " << file << " exists (a run started from "
            << runTime.timeName(runTime.startTime().value())
            << " before this one): moved to " << aside << endl;
    }
    warnRowsBeyondStart(runTime, dir, name);
    return file;
}


// ************************************************************************* //
