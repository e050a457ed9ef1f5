/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Writers of createIceField (see iceFieldWriters.H).
\*---------------------------------------------------------------------------*/

#include "iceFieldWriters.H"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <system_error>

namespace iceDEM
{

namespace
{

//- Shortest decimal text that reads back as exactly the same double
struct exact
{
    double x;
};

std::ostream& operator<<(std::ostream& os, const exact& e)
{
    char buf[64];
    const std::to_chars_result res = std::to_chars(buf, buf + sizeof(buf), e.x);
    if (res.ec != std::errc())
    {
        const std::streamsize prec = os.precision
        (
            std::numeric_limits<double>::max_digits10
        );
        os  << e.x;
        os.precision(prec);
        return os;
    }
    return os.write(buf, res.ptr - buf);
}

} // anonymous namespace


bool writeIceFieldDict
(
    const std::string& fileName,
    const std::vector<Floe>& floes,
    const std::string& namePrefix,
    const std::string& material,
    const std::string& motion,
    const std::vector<std::string>& comment
)
{
    std::ofstream os(fileName);
    if (!os)
    {
        return false;
    }
    os  << "/*--------------------------------*- C++ -*----------------------------------*\\\n"
        << "  iceDEM: constant/iceField written by createIceField\n"
        << "\\*---------------------------------------------------------------------------*/\n"
        << "FoamFile\n{\n"
        << "    version     2.0;\n"
        << "    format      ascii;\n"
        << "    class       dictionary;\n"
        << "    location    \"constant\";\n"
        << "    object      iceField;\n"
        << "}\n"
        << "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n";
    for (const std::string& line : comment)
    {
        os  << "// " << line << '\n';
    }
    os  << "\nbodies\n{\n";

    for (std::size_t i = 0; i < floes.size(); ++i)
    {
        const Floe& f = floes[i];
        os  << "    " << namePrefix << i << "\n    {\n"
            << "        type        prism;\n"
            << "        outline     (";
        for (std::size_t k = 0; k < f.outline.size(); ++k)
        {
            os  << (k ? " (" : "(") << exact{f.outline[k].x()} << ' '
                << exact{f.outline[k].y()} << ')';
        }
        os  << ");\n"
            << "        zBottom     " << exact{f.zBottom} << ";\n"
            << "        thickness   " << exact{f.thickness} << ";\n"
            << "        radius      " << exact{f.radius} << ";\n"
            << "        material    " << material << ";\n"
            << "        motion      " << motion << ";\n"
            << "        velocity    (" << exact{f.velocity.x()} << ' '
            << exact{f.velocity.y()} << ' ' << exact{f.velocity.z()}
            << ");\n"
            << "    }\n";
    }
    os  << "}\n\n"
        << "// ************************************************************************* //\n";
    return bool(os);
}


bool writeIceFieldVtk
(
    const std::string& fileName,
    const std::vector<Floe>& floes
)
{
    std::ofstream os(fileName);
    if (!os)
    {
        return false;
    }
    os.precision(std::numeric_limits<double>::max_digits10);

    std::size_t nPoints = 0;
    std::size_t nPolys = 0;
    std::size_t nConn = 0;
    for (const Floe& f : floes)
    {
        const std::size_t m = f.outline.size();
        nPoints += 2*m;
        nPolys += m + 2;
        nConn += (2 + m) + 2*m + 5*m;
    }

    os  << "# vtk DataFile Version 3.0\n"
        << "iceDEM ice field (createIceField): true floe prisms\n"
        << "ASCII\nDATASET POLYDATA\n"
        << "POINTS " << nPoints << " double\n";
    for (const Floe& f : floes)
    {
        for (const double z : {f.zBottom, f.zBottom + f.thickness})
        {
            for (const Vec2& p : f.outline)
            {
                os  << p.x() << ' ' << p.y() << ' ' << z << '\n';
            }
        }
    }

    // Outward faces: bottom clockwise seen from above, top counter-clockwise
    os  << "POLYGONS " << nPolys << ' ' << nConn << '\n';
    std::size_t base = 0;
    for (const Floe& f : floes)
    {
        const std::size_t m = f.outline.size();
        os  << m;
        for (std::size_t k = m; k-- > 0;)
        {
            os  << ' ' << base + k;
        }
        os  << '\n' << m;
        for (std::size_t k = 0; k < m; ++k)
        {
            os  << ' ' << base + m + k;
        }
        os  << '\n';
        for (std::size_t k = 0; k < m; ++k)
        {
            const std::size_t k1 = (k + 1) % m;
            os  << "4 " << base + k << ' ' << base + k1 << ' '
                << base + m + k1 << ' ' << base + m + k << '\n';
        }
        base += 2*m;
    }

    os  << "CELL_DATA " << nPolys << '\n'
        << "SCALARS floe int 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < floes.size(); ++i)
    {
        for (std::size_t k = 0; k < floes[i].outline.size() + 2; ++k)
        {
            os  << i << '\n';
        }
    }
    os  << "SCALARS thickness double 1\nLOOKUP_TABLE default\n";
    for (const Floe& f : floes)
    {
        for (std::size_t k = 0; k < f.outline.size() + 2; ++k)
        {
            os  << f.thickness << '\n';
        }
    }
    os  << "SCALARS area double 1\nLOOKUP_TABLE default\n";
    for (const Floe& f : floes)
    {
        const double a = f.area();
        for (std::size_t k = 0; k < f.outline.size() + 2; ++k)
        {
            os  << a << '\n';
        }
    }
    return bool(os);
}


bool writeZonesVtk
(
    const std::string& fileName,
    const std::vector<ExclusionZone>& zones,
    double z,
    int circleSegments
)
{
    std::ofstream os(fileName);
    if (!os)
    {
        return false;
    }
    os.precision(std::numeric_limits<double>::max_digits10);

    const double twoPi = 2*std::acos(-1.0);
    std::vector<std::vector<Vec2>> loops;
    for (const ExclusionZone& zone : zones)
    {
        if (zone.type == ExclusionZone::Type::circle)
        {
            std::vector<Vec2> p(circleSegments);
            for (int k = 0; k < circleSegments; ++k)
            {
                const double t = twoPi*k/circleSegments;
                p[k] = zone.centre + zone.radius*Vec2(std::cos(t), std::sin(t));
            }
            loops.push_back(p);
        }
        else
        {
            loops.push_back(zone.points);
        }
    }

    std::size_t nPoints = 0;
    std::size_t nConn = 0;
    for (const auto& l : loops)
    {
        nPoints += l.size();
        nConn += l.size() + 2;
    }
    os  << "# vtk DataFile Version 3.0\n"
        << "iceDEM exclusion zones (createIceField)\n"
        << "ASCII\nDATASET POLYDATA\n"
        << "POINTS " << nPoints << " double\n";
    for (const auto& l : loops)
    {
        for (const Vec2& p : l)
        {
            os  << p.x() << ' ' << p.y() << ' ' << z << '\n';
        }
    }
    os  << "LINES " << loops.size() << ' ' << nConn << '\n';
    std::size_t base = 0;
    for (const auto& l : loops)
    {
        os  << l.size() + 1;
        for (std::size_t k = 0; k < l.size(); ++k)
        {
            os  << ' ' << base + k;
        }
        os  << ' ' << base << '\n';
        base += l.size();
    }
    os  << "CELL_DATA " << loops.size() << '\n'
        << "SCALARS zone int 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < loops.size(); ++i)
    {
        os  << i << '\n';
    }
    return bool(os);
}

} // namespace iceDEM
