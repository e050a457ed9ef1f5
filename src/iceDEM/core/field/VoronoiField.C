/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Voronoi ice field generator (method in VoronoiField.H): one pass of
    steps 1-7 (seeds, cells, short edges, spreading, exclusion, thickness,
    the report's statistics), the concentration correction around it, and
    the report's summary. The steps' pieces are in the other VoronoiField
    files (list in voronoiFieldDetail.H).
\*---------------------------------------------------------------------------*/

#include "field/voronoiFieldDetail.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <utility>

namespace iceDEM
{

using namespace voronoiDetail;

namespace
{

//- Round x to a multiple of res (res > 0)
double roundTo(double x, double res)
{
    return std::round(x/res)*res;
}

//- tan(turn/2) at vertex j of a convex counter-clockwise polygon
//  = cot(interior angle/2): how far the shrunk corner moves along each edge
//  per unit shrink distance
double cornerCut(const Polygon& p, std::size_t j)
{
    const std::size_t n = p.size();
    const Vec2 uIn = (p[j] - p[(j + n - 1) % n]).normalized();
    const Vec2 uOut = (p[(j + 1) % n] - p[j]).normalized();
    const double den = 1 + uIn.dot(uOut);
    if (!(den > 0))
    {
        return std::numeric_limits<double>::infinity();
    }
    return cross2(uIn, uOut)/den;
}

//- Collapse edges whose core edge (polygon shrunk by r) would be shorter
//  than minCore to their midpoint; returns the number collapsed
int collapseShortEdges(Polygon& p, double r, double minCore)
{
    int count = 0;
    while (p.size() >= 3)
    {
        const std::size_t n = p.size();
        std::vector<double> cut(n);
        for (std::size_t j = 0; j < n; ++j)
        {
            cut[j] = cornerCut(p, j);
        }
        std::size_t kMin = 0;
        double coreMin = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < n; ++k)
        {
            const double L = (p[(k + 1) % n] - p[k]).norm();
            const double core = L - r*(cut[k] + cut[(k + 1) % n]);
            if (core < coreMin)
            {
                coreMin = core;
                kMin = k;
            }
        }
        if (coreMin >= minCore)
        {
            break;
        }
        const std::size_t k1 = (kMin + 1) % n;
        const Vec2 mid = 0.5*(p[kMin] + p[k1]);
        p[kMin] = mid;
        p.erase(p.begin() + k1);
        ++count;
    }
    return count;
}

//- One pass of the generator (steps 1-7) with tessellation concentration ct
std::vector<Floe> generateOnce
(
    const VoronoiFieldSettings& s,
    int nCells,
    double ct,
    double freeArea,
    VoronoiFieldReport& rep
)
{
    const double l = s.xmax - s.xmin;
    const double w = s.ymax - s.ymin;
    const Vec2 C(0.5*(s.xmin + s.xmax), 0.5*(s.ymin + s.ymax));
    const double sc = std::sqrt(ct);
    const double tx0 = C.x() - 0.5*l*sc;
    const double tx1 = C.x() + 0.5*l*sc;
    const double ty0 = C.y() - 0.5*w*sc;
    const double ty1 = C.y() + 0.5*w*sc;

    FieldRandom rng(s.seed);

    // 1. Seeds
    std::vector<Vec2> seeds(nCells);
    for (Vec2& p : seeds)
    {
        const double u = rng.uniform01();
        const double v = rng.uniform01();
        p = Vec2(tx0 + (tx1 - tx0)*u, ty0 + (ty1 - ty0)*v);
    }

    // 2. Lloyd relaxation
    lloydRelaxation(seeds, s.lloydIterations, tx0, tx1, ty0, ty1);

    // 3. Cells
    std::vector<Polygon> cells = voronoiCells(seeds, tx0, tx1, ty0, ty1);

    // 7. (drawn here, for every cell in order: the thickness of a cell does
    //    not depend on which cells are removed)
    std::vector<double> thickness(nCells);
    for (double& h : thickness)
    {
        h = drawThickness(s.thickness, rng);
    }

    rep = VoronoiFieldReport();
    rep.nCells = nCells;
    rep.tessellationConcentration = ct;
    rep.targetConcentration = s.concentration;
    rep.regionArea = l*w;
    rep.freeArea = freeArea;
    rep.excludedArea = l*w - freeArea;

    const double inv = 1/sc;
    std::vector<Floe> floes;
    floes.reserve(nCells);

    for (int i = 0; i < nCells; ++i)
    {
        // 4. Clean outline, short edges collapsed, core check
        Polygon p;
        try
        {
            p = convexOutline(cells[i], "outline", s.tolerance);
            rep.nCollapsedEdges += collapseShortEdges
            (
                p, s.radius, s.minCoreEdgeRatio*s.radius
            );
            p = convexOutline(p, "outline", s.tolerance);
            const Polygon core =
                shrinkConvexPolygon(p, s.radius, s.tolerance);
            if (!(convexPolygonWidth(core) >= s.minCoreWidthRatio*s.radius))
            {
                throw Error("core too thin", "radius");
            }
        }
        catch (const Error&)
        {
            ++rep.nTooSmall;
            continue;
        }

        // 5. Move the centroid out by 1/sqrt(c_t) about the centre
        const Vec2 g = polygonCentroid(p);
        const Vec2 shift = (C + (g - C)*inv) - g;
        for (Vec2& q : p)
        {
            q += shift;
        }

        // 6. Exclusion zones
        bool excluded = false;
        for (const ExclusionZone& z : s.exclusionZones)
        {
            if (zoneIntersects(z, p))
            {
                excluded = true;
                break;
            }
        }
        if (excluded)
        {
            ++rep.nExcluded;
            continue;
        }

        Floe f;
        f.outline = std::move(p);
        f.thickness = thickness[i];
        f.radius = s.radius;
        f.zBottom =
            s.waterLevel - (s.iceDensity/s.waterDensity)*thickness[i];
        f.velocity = s.velocity;
        floes.push_back(std::move(f));
    }

    // Statistics
    rep.nFloes = int(floes.size());
    if (!floes.empty())
    {
        double sum = 0;
        double sum2 = 0;
        double hSum = 0;
        rep.minArea = std::numeric_limits<double>::max();
        rep.maxArea = 0;
        rep.minThickness = std::numeric_limits<double>::max();
        rep.maxThickness = 0;
        for (const Floe& f : floes)
        {
            const double a = f.area();
            sum += a;
            rep.minArea = std::min(rep.minArea, a);
            rep.maxArea = std::max(rep.maxArea, a);
            hSum += f.thickness;
            rep.minThickness = std::min(rep.minThickness, f.thickness);
            rep.maxThickness = std::max(rep.maxThickness, f.thickness);
            const std::size_t ne = f.outline.size();
            if (rep.edgeHistogram.size() <= ne)
            {
                rep.edgeHistogram.resize(ne + 1, 0);
            }
            ++rep.edgeHistogram[ne];
        }
        const double n = double(floes.size());
        rep.meanArea = sum/n;
        for (const Floe& f : floes)
        {
            const double d = f.area() - rep.meanArea;
            sum2 += d*d;
        }
        rep.sdArea = std::sqrt(sum2/n);
        rep.floeArea = sum;
        rep.meanThickness = hSum/n;
    }
    rep.concentration = rep.floeArea/freeArea;
    return floes;
}

} // anonymous namespace


// * * * * * * * * * * * * * * * * Generator * * * * * * * * * * * * * * * //

std::vector<Floe> generateVoronoiField
(
    const VoronoiFieldSettings& s,
    VoronoiFieldReport& report
)
{
    checkVoronoiFieldSettings(s);

    const int nCells = cellCount(s);
    const double A = (s.xmax - s.xmin)*(s.ymax - s.ymin);
    const double freeArea = A - excludedArea(s);
    const double c = s.concentration;

    std::vector<Floe> best;
    VoronoiFieldReport bestReport;
    double bestErr = std::numeric_limits<double>::infinity();

    const double cMax = maxFieldConcentration(s.tolerance);
    double ct = c;
    for (int iter = 0; ; ++iter)
    {
        VoronoiFieldReport rep;
        std::vector<Floe> floes = generateOnce(s, nCells, ct, freeArea, rep);
        rep.corrections = iter;

        const double err = std::abs(rep.concentration - c);
        if (err < bestErr)
        {
            bestErr = err;
            best = std::move(floes);
            bestReport = rep;
        }
        if
        (
            !s.correctConcentration
         || err <= s.concentrationTolerance*c
         || iter >= s.maxCorrections
         || rep.nFloes == 0
        )
        {
            break;
        }
        // c_t stays below 1: at 1 the cells tile the tessellation rectangle
        // and step 5 moves nothing, so neighbours share their edges and the
        // DEM refuses the touching floes. A correction that would pass
        // cMax (gaps above the tolerance) goes half-way to it instead:
        // every field keeps its gaps (of about (1 - c_t)/2 of a floe's
        // distance from its neighbour).
        double next = roundTo(ct*c/rep.concentration, s.concentrationResolution);
        if (next > cMax)
        {
            next = 0.5*(ct + cMax);
        }
        if (next == ct || next > cMax)
        {
            break;
        }
        ct = next;
    }

    if (best.empty())
    {
        if (bestReport.nExcluded > 0)
        {
            throw Error
            (
                "every floe touches an exclusion zone: no floe is left",
                "exclusionZones"
            );
        }
        throw Error
        (
            "every floe is too small for the dilation radius " + str(s.radius),
            "radius"
        );
    }

    if (s.floeNumbering == FloeNumbering::hilbert)
    {
        numberAlongHilbertCurve(best, s);
    }

    report = bestReport;
    return best;
}


void VoronoiFieldReport::print(std::ostream& os) const
{
    const std::ios::fmtflags flags = os.flags();
    const std::streamsize prec = os.precision();
    os.precision(6);

    os  << "Voronoi ice field\n"
        << "    region area           " << regionArea << " m2\n"
        << "    excluded area         " << excludedArea << " m2\n"
        << "    free area             " << freeArea << " m2\n"
        << "    Voronoi cells         " << nCells
        << " (tessellation concentration " << tessellationConcentration
        << " after " << corrections << " corrections)\n"
        << "    floes                 " << nFloes << "\n"
        << "    removed               " << nExcluded
        << " in exclusion zones, " << nTooSmall
        << " too small for the radius\n"
        << "    collapsed short edges " << nCollapsedEdges << "\n"
        << "    concentration         target " << targetConcentration
        << " achieved " << concentration << " (floe area / free area)\n"
        << "    floe area [m2]        total " << floeArea
        << " mean " << meanArea << " sd " << sdArea
        << " min " << minArea << " max " << maxArea << "\n"
        << "    thickness [m]         mean " << meanThickness
        << " min " << minThickness << " max " << maxThickness << "\n"
        << "    edges per floe       ";
    for (std::size_t k = 0; k < edgeHistogram.size(); ++k)
    {
        if (edgeHistogram[k] > 0)
        {
            os  << ' ' << k << ':' << edgeHistogram[k];
        }
    }
    os  << "\n";

    os.flags(flags);
    os.precision(prec);
}


} // namespace iceDEM
