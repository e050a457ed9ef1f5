/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Voronoi ice field generator (see VoronoiField.H). CGAL is included first,
    as in every CGAL translation unit of the core; it only provides the
    Delaunay neighbours of the seed points.
\*---------------------------------------------------------------------------*/

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "field/VoronoiField.H"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <utility>

namespace iceDEM
{

namespace
{

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using CgalPoint = Kernel::Point_2;

using Polygon = std::vector<Vec2>;

inline double cross2(const Vec2& a, const Vec2& b)
{
    return a.x()*b.y() - a.y()*b.x();
}

std::string str(double x)
{
    std::ostringstream os;
    os.precision(10);
    os << x;
    return os.str();
}

//- Part of the polygon with n . x <= c (Sutherland-Hodgman; exact area for
//  a simple, possibly non-convex polygon)
Polygon clipHalfPlane(const Polygon& poly, const Vec2& n, double c)
{
    Polygon out;
    const std::size_t m = poly.size();
    out.reserve(m + 2);
    for (std::size_t k = 0; k < m; ++k)
    {
        const Vec2& a = poly[k];
        const Vec2& b = poly[(k + 1) % m];
        const double da = n.dot(a) - c;
        const double db = n.dot(b) - c;
        if (da <= 0)
        {
            out.push_back(a);
            if (da < 0 && db > 0)
            {
                out.push_back(a + (b - a)*(da/(da - db)));
            }
        }
        else if (db < 0)
        {
            out.push_back(a + (b - a)*(da/(da - db)));
        }
    }
    return out;
}

Polygon rectangle(double xmin, double xmax, double ymin, double ymax)
{
    return {Vec2(xmin, ymin), Vec2(xmax, ymin), Vec2(xmax, ymax), Vec2(xmin, ymax)};
}

//- Sign of the orientation of (a, b, c)
inline int orient(const Vec2& a, const Vec2& b, const Vec2& c)
{
    const double d = cross2(b - a, c - a);
    return (d > 0) - (d < 0);
}

//- c on segment a-b, given a, b, c collinear
inline bool onSegment(const Vec2& a, const Vec2& b, const Vec2& c)
{
    return
        std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x())
     && std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

//- Segments a-b and c-d intersect or touch
bool segmentsIntersect
(
    const Vec2& a,
    const Vec2& b,
    const Vec2& c,
    const Vec2& d
)
{
    const int o1 = orient(a, b, c);
    const int o2 = orient(a, b, d);
    const int o3 = orient(c, d, a);
    const int o4 = orient(c, d, b);
    if (o1*o2 < 0 && o3*o4 < 0)
    {
        return true;
    }
    return
        (o1 == 0 && onSegment(a, b, c))
     || (o2 == 0 && onSegment(a, b, d))
     || (o3 == 0 && onSegment(c, d, a))
     || (o4 == 0 && onSegment(c, d, b));
}

//- Distance from point p to segment a-b
double segmentDistance(const Vec2& p, const Vec2& a, const Vec2& b)
{
    const Vec2 ab = b - a;
    const double L2 = ab.squaredNorm();
    double t = L2 > 0 ? (p - a).dot(ab)/L2 : 0;
    t = std::min(1.0, std::max(0.0, t));
    return (p - (a + t*ab)).norm();
}

//- Antiderivative of sqrt(R^2 - x^2)
double chordIntegral(double R, double x)
{
    x = std::min(R, std::max(-R, x));
    return 0.5*(x*std::sqrt(std::max(0.0, R*R - x*x)) + R*R*std::asin(x/R));
}

//- Area of the disc of radius R about the origin with x <= X and y <= Y
double discQuadrantArea(double R, double X, double Y)
{
    if (X <= -R || Y <= -R)
    {
        return 0;
    }
    X = std::min(X, R);

    // Chord at x: y in [-s, s], s = sqrt(R^2 - x^2), cut at y = Y
    //   |x| <= xY: length Y + s;  |x| > xY: 2s (Y >= 0) or 0 (Y < 0)
    const double xY = Y >= R ? 0 : std::sqrt(std::max(0.0, R*R - Y*Y));
    double area = 0;

    auto piece = [&](double a, double b, bool middle)
    {
        a = std::max(a, -R);
        b = std::min(b, X);
        if (b <= a)
        {
            return;
        }
        const double S = chordIntegral(R, b) - chordIntegral(R, a);
        if (middle)
        {
            area += Y*(b - a) + S;
        }
        else if (Y >= 0)
        {
            area += 2*S;
        }
    };

    if (Y >= R)
    {
        piece(-R, R, false);
    }
    else
    {
        piece(-R, -xY, false);
        piece(-xY, xY, true);
        piece(xY, R, false);
    }
    return area;
}

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

//- Free area of the region: region minus the zones inside it
double excludedArea(const VoronoiFieldSettings& s)
{
    double a = 0;
    for (const ExclusionZone& z : s.exclusionZones)
    {
        if (z.type == ExclusionZone::Type::circle)
        {
            a += circleRectangleArea
            (
                z.centre, z.radius, s.xmin, s.xmax, s.ymin, s.ymax
            );
        }
        else
        {
            a += polygonRectangleArea(z.points, s.xmin, s.xmax, s.ymin, s.ymax);
        }
    }
    return a;
}

//- Number of Voronoi cells
int cellCount(const VoronoiFieldSettings& s)
{
    if (s.nFloes > 0)
    {
        return s.nFloes;
    }
    const double A = (s.xmax - s.xmin)*(s.ymax - s.ymin);
    const double n = std::round(s.concentration*A/s.meanFloeArea);
    if (!(n >= 1))
    {
        throw Error
        (
            "region too small for one floe: concentration*area = "
          + str(s.concentration*A) + " m2 is less than half of meanFloeArea "
          + str(s.meanFloeArea) + " m2",
            "meanFloeArea"
        );
    }
    if (n > double(std::numeric_limits<int>::max()))
    {
        throw Error("meanFloeArea gives too many floes", "meanFloeArea");
    }
    return int(n);
}

//- One thickness draw
double drawThickness(const ThicknessSettings& t, FieldRandom& rng)
{
    using D = ThicknessSettings::Distribution;
    switch (t.distribution)
    {
        case D::constant:
            return t.value;
        case D::uniform:
            return rng.uniform(t.min, t.max);
        case D::normal:
        {
            for (int k = 0; k < t.maxDraws; ++k)
            {
                const double h = t.mean + t.standardDeviation*rng.normal();
                if (h >= t.min && h <= t.max)
                {
                    return h;
                }
            }
            throw Error
            (
                "normal thickness: no draw in [min, max] = [" + str(t.min)
              + ", " + str(t.max) + "] after maxDraws = "
              + std::to_string(t.maxDraws) + " draws; widen the bounds",
                "thickness"
            );
        }
    }
    return t.value;
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
    for (int it = 0; it < s.lloydIterations; ++it)
    {
        const std::vector<Polygon> cells =
            voronoiCells(seeds, tx0, tx1, ty0, ty1);
        for (int i = 0; i < nCells; ++i)
        {
            if (cells[i].size() >= 3)
            {
                seeds[i] = polygonCentroid(cells[i]);
            }
        }
    }

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


// * * * * * * * * * * * * * * * Building blocks * * * * * * * * * * * * * //

ThicknessSettings::Distribution thicknessDistributionFromName
(
    const std::string& name
)
{
    using D = ThicknessSettings::Distribution;
    if (name == "constant")
    {
        return D::constant;
    }
    if (name == "uniform")
    {
        return D::uniform;
    }
    if (name == "normal")
    {
        return D::normal;
    }
    throw Error
    (
        "unknown thickness distribution '" + name
      + "'; valid: 3(constant normal uniform)",
        "thickness"
    );
}


std::vector<std::vector<Vec2>> voronoiCells
(
    const std::vector<Vec2>& seeds,
    double xmin,
    double xmax,
    double ymin,
    double ymax
)
{
    const int n = int(seeds.size());
    std::vector<Polygon> cells(n);
    if (n == 0)
    {
        return cells;
    }

    std::vector<std::pair<CgalPoint, int>> points;
    points.reserve(n);
    for (int i = 0; i < n; ++i)
    {
        points.emplace_back(CgalPoint(seeds[i].x(), seeds[i].y()), i);
    }
    Delaunay dt;
    dt.insert(points.begin(), points.end());

    // Seeds that got a vertex (a repeated seed does not)
    std::vector<char> present(n, 0);
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    {
        present[v->info()] = 1;
    }

    // Delaunay neighbours, sorted: a fixed clipping order
    std::vector<std::vector<int>> nbr(n);
    if (dt.dimension() == 2)
    {
        for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e)
        {
            const auto f = e->first;
            const int i = e->second;
            const int a = f->vertex(Delaunay::cw(i))->info();
            const int b = f->vertex(Delaunay::ccw(i))->info();
            nbr[a].push_back(b);
            nbr[b].push_back(a);
        }
    }
    else
    {
        // Collinear seeds (or fewer than three): every other seed
        for (int i = 0; i < n; ++i)
        {
            for (int j = 0; j < n; ++j)
            {
                if (i != j && present[i] && present[j])
                {
                    nbr[i].push_back(j);
                }
            }
        }
    }

    const Polygon box = rectangle(xmin, xmax, ymin, ymax);
    for (int i = 0; i < n; ++i)
    {
        if (!present[i])
        {
            continue;
        }
        std::sort(nbr[i].begin(), nbr[i].end());
        nbr[i].erase(std::unique(nbr[i].begin(), nbr[i].end()), nbr[i].end());

        Polygon cell = box;
        const Vec2& p = seeds[i];
        for (const int j : nbr[i])
        {
            // Bisector half-plane (x - m) . (q - p) <= 0; the same line,
            // bit for bit, as seen from j
            const Vec2& q = seeds[j];
            const Vec2 nrm = q - p;
            const Vec2 m = 0.5*(p + q);
            cell = clipHalfPlane(cell, nrm, nrm.dot(m));
            if (cell.empty())
            {
                break;
            }
        }
        cells[i] = std::move(cell);
    }
    return cells;
}


double circleRectangleArea
(
    const Vec2& centre,
    double radius,
    double xmin,
    double xmax,
    double ymin,
    double ymax
)
{
    if (!(radius > 0) || !(xmax > xmin) || !(ymax > ymin))
    {
        return 0;
    }
    const double R = radius;
    const double x0 = xmin - centre.x();
    const double x1 = xmax - centre.x();
    const double y0 = ymin - centre.y();
    const double y1 = ymax - centre.y();
    const double a =
        discQuadrantArea(R, x1, y1) - discQuadrantArea(R, x0, y1)
      - discQuadrantArea(R, x1, y0) + discQuadrantArea(R, x0, y0);
    return std::max(0.0, a);
}


double polygonRectangleArea
(
    const std::vector<Vec2>& polygon,
    double xmin,
    double xmax,
    double ymin,
    double ymax
)
{
    Polygon p = polygon;
    p = clipHalfPlane(p, Vec2(-1, 0), -xmin);
    p = clipHalfPlane(p, Vec2(1, 0), xmax);
    p = clipHalfPlane(p, Vec2(0, -1), -ymin);
    p = clipHalfPlane(p, Vec2(0, 1), ymax);
    return std::abs(polygonSignedArea(p));
}


bool polygonsIntersect
(
    const std::vector<Vec2>& a,
    const std::vector<Vec2>& b
)
{
    if (a.empty() || b.empty())
    {
        return false;
    }
    const std::size_t na = a.size();
    const std::size_t nb = b.size();
    for (std::size_t i = 0; i < na; ++i)
    {
        for (std::size_t j = 0; j < nb; ++j)
        {
            if
            (
                segmentsIntersect
                (
                    a[i], a[(i + 1) % na], b[j], b[(j + 1) % nb]
                )
            )
            {
                return true;
            }
        }
    }
    return pointInPolygon(a[0], b) || pointInPolygon(b[0], a);
}


bool polygonIntersectsCircle
(
    const std::vector<Vec2>& polygon,
    const Vec2& centre,
    double radius
)
{
    const std::size_t n = polygon.size();
    if (n == 0)
    {
        return false;
    }
    if (pointInPolygon(centre, polygon))
    {
        return true;
    }
    for (std::size_t i = 0; i < n; ++i)
    {
        if
        (
            segmentDistance(centre, polygon[i], polygon[(i + 1) % n])
         <= radius
        )
        {
            return true;
        }
    }
    return false;
}


bool zoneIntersects
(
    const ExclusionZone& zone,
    const std::vector<Vec2>& polygon
)
{
    if (zone.type == ExclusionZone::Type::circle)
    {
        return polygonIntersectsCircle(polygon, zone.centre, zone.radius);
    }
    return polygonsIntersect(zone.points, polygon);
}


void checkVoronoiFieldSettings(const VoronoiFieldSettings& s)
{
    auto finite = [](double x) { return std::isfinite(x); };

    if
    (
        !finite(s.xmin) || !finite(s.xmax) || !finite(s.ymin)
     || !finite(s.ymax) || !(s.xmax > s.xmin) || !(s.ymax > s.ymin)
    )
    {
        throw Error
        (
            "region must have max > min in x and y (finite), got ["
          + str(s.xmin) + ", " + str(s.xmax) + "] x [" + str(s.ymin) + ", "
          + str(s.ymax) + "]",
            "region"
        );
    }
    if (!(s.concentration > 0 && s.concentration <= 1))
    {
        throw Error
        (
            "concentration must be in (0, 1], got " + str(s.concentration),
            "concentration"
        );
    }
    if (!(s.radius > 0) || !finite(s.radius))
    {
        throw Error("radius must be > 0, got " + str(s.radius), "radius");
    }
    if (s.nFloes <= 0 && !(s.meanFloeArea > 0 && finite(s.meanFloeArea)))
    {
        throw Error
        (
            "give nFloes > 0 or meanFloeArea > 0 (got meanFloeArea "
          + str(s.meanFloeArea) + ")",
            "meanFloeArea"
        );
    }
    if (s.lloydIterations < 0)
    {
        throw Error("lloydIterations must be >= 0", "lloydIterations");
    }
    if (!(s.minCoreEdgeRatio >= 0) || !finite(s.minCoreEdgeRatio))
    {
        throw Error("minCoreEdgeRatio must be >= 0", "minCoreEdgeRatio");
    }
    if (!(s.minCoreWidthRatio >= 0) || !finite(s.minCoreWidthRatio))
    {
        throw Error("minCoreWidthRatio must be >= 0", "minCoreWidthRatio");
    }
    if (s.maxCorrections < 0)
    {
        throw Error("maxCorrections must be >= 0", "maxCorrections");
    }
    if (!(s.concentrationTolerance > 0))
    {
        throw Error
        (
            "concentrationTolerance must be > 0", "concentrationTolerance"
        );
    }
    if (!(s.concentrationResolution > 0 && s.concentrationResolution < 1))
    {
        throw Error
        (
            "concentrationResolution must be in (0, 1)",
            "concentrationResolution"
        );
    }
    if (!(s.tolerance > 0 && s.tolerance < 1))
    {
        throw Error("tolerance must be in (0, 1)", "tolerance");
    }
    if (!(s.iceDensity > 0) || !finite(s.iceDensity))
    {
        throw Error
        (
            "iceDensity must be > 0, got " + str(s.iceDensity), "iceDensity"
        );
    }
    if (!(s.waterDensity > 0) || !finite(s.waterDensity))
    {
        throw Error
        (
            "waterDensity must be > 0, got " + str(s.waterDensity),
            "waterDensity"
        );
    }
    if (!(s.iceDensity < s.waterDensity))
    {
        throw Error
        (
            "iceDensity " + str(s.iceDensity)
          + " must be less than waterDensity " + str(s.waterDensity)
          + " for the floes to float",
            "iceDensity"
        );
    }
    if (!finite(s.waterLevel))
    {
        throw Error("waterLevel must be finite", "waterLevel");
    }
    if (!finite(s.velocity.x()) || !finite(s.velocity.y()) || !finite(s.velocity.z()))
    {
        throw Error("velocity must be finite", "velocity");
    }

    // Thickness
    {
        using D = ThicknessSettings::Distribution;
        const ThicknessSettings& t = s.thickness;
        const double h2r = 2*s.radius;
        const std::string tooThin =
            " must be larger than twice the dilation radius (2r = "
          + str(h2r) + ")";
        if (t.distribution == D::constant)
        {
            if (!(t.value > h2r) || !finite(t.value))
            {
                throw Error("thickness " + str(t.value) + tooThin, "thickness");
            }
        }
        else
        {
            if (!(t.min > h2r) || !finite(t.min))
            {
                throw Error
                (
                    "thickness min " + str(t.min) + tooThin, "thickness"
                );
            }
            if (!(t.max > t.min) || !finite(t.max))
            {
                throw Error
                (
                    "thickness max " + str(t.max) + " must be > min "
                  + str(t.min),
                    "thickness"
                );
            }
            if (t.distribution == D::normal)
            {
                if (!(t.standardDeviation > 0) || !finite(t.standardDeviation))
                {
                    throw Error
                    (
                        "thickness standardDeviation must be > 0",
                        "thickness"
                    );
                }
                if (!(t.mean >= t.min && t.mean <= t.max))
                {
                    throw Error
                    (
                        "thickness mean " + str(t.mean) + " must lie in [min, max]",
                        "thickness"
                    );
                }
                if (t.maxDraws < 1)
                {
                    throw Error("thickness maxDraws must be >= 1", "thickness");
                }
            }
        }
    }

    // Size: the tessellation rectangle and a mean cell must hold a core
    {
        const double l = s.xmax - s.xmin;
        const double w = s.ymax - s.ymin;
        const double sc = std::sqrt(s.concentration);
        const double minCell =
            2*s.radius
          + std::max(s.minCoreEdgeRatio, s.minCoreWidthRatio)*s.radius;
        if (!(std::min(l, w)*sc > minCell))
        {
            throw Error
            (
                "region too small for one floe: the tessellated rectangle "
                "(sides times sqrt(concentration)) is not wider than "
                "2r + max(minCoreEdgeRatio, minCoreWidthRatio) r = "
              + str(minCell) + " m",
                "region"
            );
        }
        const int n = cellCount(s);
        const double meanCell = s.concentration*l*w/n;
        if (!(std::sqrt(meanCell) > minCell))
        {
            throw Error
            (
                "floes too small for the dilation radius: mean floe area "
              + str(meanCell) + " m2 is not larger than (2r + max("
                "minCoreEdgeRatio, minCoreWidthRatio) r)^2 = "
              + str(minCell*minCell) + " m2",
                s.nFloes > 0 ? "nFloes" : "meanFloeArea"
            );
        }
    }

    // Exclusion zones: valid, not overlapping, not covering the region
    const std::size_t nz = s.exclusionZones.size();
    for (std::size_t i = 0; i < nz; ++i)
    {
        const ExclusionZone& z = s.exclusionZones[i];
        const std::string zn = "exclusion zone '" + z.name + "': ";
        if (z.type == ExclusionZone::Type::circle)
        {
            if
            (
                !(z.radius > 0) || !finite(z.radius)
             || !finite(z.centre.x()) || !finite(z.centre.y())
            )
            {
                throw Error(zn + "circle radius must be > 0", "exclusionZones");
            }
        }
        else
        {
            const std::size_t np = z.points.size();
            if (np < 3 || !(std::abs(polygonSignedArea(z.points)) > 0))
            {
                throw Error
                (
                    zn + "polygon needs at least 3 points and a non-zero area",
                    "exclusionZones"
                );
            }
            for (std::size_t a = 0; a < np; ++a)
            {
                for (std::size_t b = a + 1; b < np; ++b)
                {
                    // Adjacent edges share a vertex: skip them
                    if (b == a + 1 || (a == 0 && b == np - 1))
                    {
                        continue;
                    }
                    if
                    (
                        segmentsIntersect
                        (
                            z.points[a], z.points[(a + 1) % np],
                            z.points[b], z.points[(b + 1) % np]
                        )
                    )
                    {
                        throw Error
                        (
                            zn + "polygon intersects itself", "exclusionZones"
                        );
                    }
                }
            }
        }
    }
    for (std::size_t i = 0; i < nz; ++i)
    {
        for (std::size_t j = i + 1; j < nz; ++j)
        {
            const ExclusionZone& a = s.exclusionZones[i];
            const ExclusionZone& b = s.exclusionZones[j];
            bool overlap = false;
            using T = ExclusionZone::Type;
            if (a.type == T::circle && b.type == T::circle)
            {
                overlap = (a.centre - b.centre).norm() <= a.radius + b.radius;
            }
            else if (a.type == T::circle)
            {
                overlap = polygonIntersectsCircle(b.points, a.centre, a.radius);
            }
            else if (b.type == T::circle)
            {
                overlap = polygonIntersectsCircle(a.points, b.centre, b.radius);
            }
            else
            {
                overlap = polygonsIntersect(a.points, b.points);
            }
            if (overlap)
            {
                throw Error
                (
                    "exclusion zones '" + a.name + "' and '" + b.name
                  + "' overlap or touch; merge them into one polygon",
                    "exclusionZones"
                );
            }
        }
    }
    const double A = (s.xmax - s.xmin)*(s.ymax - s.ymin);
    const double freeArea = A - excludedArea(s);
    if (!(freeArea > s.tolerance*A))
    {
        throw Error
        (
            "exclusion zones cover the region: no free area is left",
            "exclusionZones"
        );
    }
}


// * * * * * * * * * * * * * * * * Generator * * * * * * * * * * * * * * * //

FloeNumbering floeNumberingFromName(const std::string& name)
{
    if (name == "hilbert") return FloeNumbering::hilbert;
    if (name == "seed") return FloeNumbering::seed;
    throw Error
    (
        "unknown floeNumbering '" + name + "'; valid: 2(hilbert seed)",
        "floeNumbering"
    );
}


const char* floeNumberingName(FloeNumbering n)
{
    return n == FloeNumbering::hilbert ? "hilbert" : "seed";
}


namespace
{

//- Position of grid cell (x, y) along the Hilbert curve through a
//  2^bits x 2^bits grid: the quadrant at each level, finest last, with the
//  sub-square turned so the curve stays continuous
std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y, int bits)
{
    std::uint64_t d = 0;
    for (std::uint32_t half = 1u << (bits - 1); half > 0; half >>= 1)
    {
        const std::uint32_t rx = (x & half) ? 1 : 0;
        const std::uint32_t ry = (y & half) ? 1 : 0;
        d += std::uint64_t(half)*half*((3*rx) ^ ry);
        // Turn the quadrant into the curve's base orientation
        if (ry == 0)
        {
            if (rx == 1)
            {
                x = half - 1 - (x & (half - 1));
                y = half - 1 - (y & (half - 1));
            }
            std::swap(x, y);
        }
    }
    return d;
}


//- Step 8: floes renumbered along the Hilbert curve of their centroids
void numberAlongHilbertCurve
(
    std::vector<Floe>& floes,
    const VoronoiFieldSettings& s
)
{
    constexpr int bits = 16;
    const double cells = double((1u << bits) - 1);
    auto gridIndex = [cells](double v, double lo, double hi)
    {
        const double t = std::min(1.0, std::max(0.0, (v - lo)/(hi - lo)));
        return static_cast<std::uint32_t>(t*cells);
    };

    std::vector<std::pair<std::uint64_t, int>> key(floes.size());
    for (std::size_t i = 0; i < floes.size(); ++i)
    {
        const Vec2 g = floes[i].centroid();
        key[i] =
        {
            hilbertIndex
            (
                gridIndex(g.x(), s.xmin, s.xmax),
                gridIndex(g.y(), s.ymin, s.ymax),
                bits
            ),
            static_cast<int>(i)
        };
    }
    // Pairs compare by index, then by the old number: a total order
    std::sort(key.begin(), key.end());

    std::vector<Floe> ordered;
    ordered.reserve(floes.size());
    for (const auto& k : key)
    {
        ordered.push_back(std::move(floes[k.second]));
    }
    floes.swap(ordered);
}

} // anonymous namespace


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
        // DEM refuses the touching floes. A correction that would reach 1
        // goes half-way to 1 instead: every field keeps its gaps (of about
        // (1 - c_t)/2 of a floe's distance from its neighbour).
        double next = roundTo(ct*c/rep.concentration, s.concentrationResolution);
        if (next >= 1)
        {
            next = 0.5*(ct + 1);
        }
        if (next == ct || next >= 1)
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
