/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Voronoi field, exclusion zones (VoronoiField.H, step 6 and the
    concentration over the free area): the exact area of a zone inside the
    region, whether a floe touches a zone, and the zones' checks (valid,
    not overlapping one another, not covering the region).
\*---------------------------------------------------------------------------*/

#include "field/voronoiFieldDetail.H"

#include <algorithm>
#include <cmath>

namespace iceDEM
{

using namespace voronoiDetail;

namespace
{

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

} // anonymous namespace


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


//- Area of the zones inside the region (the free area is the rest)
double voronoiDetail::excludedArea(const VoronoiFieldSettings& s)
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


void voronoiDetail::checkExclusionZones(const VoronoiFieldSettings& s)
{
    auto finite = [](double x) { return std::isfinite(x); };

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


} // namespace iceDEM
