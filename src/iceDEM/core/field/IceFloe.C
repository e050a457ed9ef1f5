/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Floe outlines and the floe core prism (see IceFloe.H).
\*---------------------------------------------------------------------------*/

#include "field/IceFloe.H"
#include "field/fieldDetail.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace iceDEM
{

namespace
{

using fieldDetail::cross2;
using fieldDetail::str;

//- Diagonal of the bounding box
double outlineSize(const std::vector<Vec2>& p)
{
    if (p.empty())
    {
        return 0;
    }
    Vec2 lo = p[0];
    Vec2 hi = p[0];
    for (const Vec2& q : p)
    {
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    return (hi - lo).norm();
}

//- A line n . x = c with outward unit normal n
struct Line
{
    Vec2 n;
    double c;
};

//- Intersection of two lines; false when (nearly) parallel
bool intersect(const Line& a, const Line& b, Vec2& x)
{
    const double det = a.n.x()*b.n.y() - a.n.y()*b.n.x();
    if (!(std::abs(det) > 0))
    {
        return false;
    }
    x = Vec2
    (
        (a.c*b.n.y() - b.c*a.n.y())/det,
        (a.n.x()*b.c - b.n.x()*a.c)/det
    );
    return std::isfinite(x.x()) && std::isfinite(x.y());
}

//- Polygon vertex with the tag (line index) of the edge that starts there
struct TaggedVertex
{
    Vec2 p;
    int tag;
};

//- Keep the part of the polygon with n . x <= c (Sutherland-Hodgman for a
//  convex polygon); the new edge along the line gets the tag 'lineTag'
std::vector<TaggedVertex> clipTagged
(
    const std::vector<TaggedVertex>& poly,
    const Line& line,
    int lineTag
)
{
    std::vector<TaggedVertex> out;
    const std::size_t n = poly.size();
    out.reserve(n + 1);
    for (std::size_t k = 0; k < n; ++k)
    {
        const TaggedVertex& a = poly[k];
        const TaggedVertex& b = poly[(k + 1) % n];
        const double da = line.n.dot(a.p) - line.c;
        const double db = line.n.dot(b.p) - line.c;

        if (da <= 0)
        {
            if (db > 0)
            {
                // Leaving: a, then the exit point starts the edge on the line
                if (da < 0)
                {
                    out.push_back(a);
                    const Vec2 x = a.p + (b.p - a.p)*(da/(da - db));
                    out.push_back({x, lineTag});
                }
                else
                {
                    out.push_back({a.p, lineTag});
                }
            }
            else
            {
                out.push_back(a);
            }
        }
        else if (db < 0)
        {
            // Entering: the entry point starts the rest of edge k
            const Vec2 x = a.p + (b.p - a.p)*(da/(da - db));
            out.push_back({x, a.tag});
        }
    }
    return out;
}

} // anonymous namespace


double polygonSignedArea(const std::vector<Vec2>& p)
{
    const std::size_t n = p.size();
    if (n < 3)
    {
        return 0;
    }
    // Relative to the first vertex: no loss of precision far from the origin
    double a2 = 0;
    for (std::size_t i = 1; i + 1 < n; ++i)
    {
        a2 += cross2(p[i] - p[0], p[i + 1] - p[0]);
    }
    return 0.5*a2;
}


Vec2 polygonCentroid(const std::vector<Vec2>& p)
{
    const std::size_t n = p.size();
    if (n == 0)
    {
        return Vec2::Zero();
    }
    Vec2 s = Vec2::Zero();
    double a2 = 0;
    for (std::size_t i = 1; i + 1 < n; ++i)
    {
        const Vec2 u = p[i] - p[0];
        const Vec2 v = p[i + 1] - p[0];
        const double w = cross2(u, v);
        a2 += w;
        s += w*(u + v);
    }
    if (!(std::abs(a2) > 0))
    {
        Vec2 m = Vec2::Zero();
        for (const Vec2& q : p)
        {
            m += q;
        }
        return m/double(n);
    }
    return p[0] + s/(3.0*a2);
}


double convexPolygonWidth(const std::vector<Vec2>& p)
{
    const std::size_t n = p.size();
    if (n < 3)
    {
        return 0;
    }
    double width = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
    {
        const Vec2 e = p[(i + 1) % n] - p[i];
        const double len = e.norm();
        if (!(len > 0))
        {
            continue;
        }
        const Vec2 nrm(e.y()/len, -e.x()/len);
        double lo = 0;
        double hi = 0;
        for (const Vec2& q : p)
        {
            const double t = nrm.dot(q - p[i]);
            lo = std::min(lo, t);
            hi = std::max(hi, t);
        }
        width = std::min(width, hi - lo);
    }
    return std::isfinite(width) ? width : 0;
}


bool pointInPolygon(const Vec2& x, const std::vector<Vec2>& p)
{
    const std::size_t n = p.size();
    bool inside = false;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++)
    {
        const Vec2& a = p[j];
        const Vec2& b = p[i];

        // On the edge a-b
        if
        (
            cross2(b - a, x - a) == 0
         && (x - a).dot(x - b) <= 0
        )
        {
            return true;
        }

        // Crossing number along +x
        if ((a.y() > x.y()) != (b.y() > x.y()))
        {
            const double xc =
                a.x() + (x.y() - a.y())*(b.x() - a.x())/(b.y() - a.y());
            if (x.x() < xc)
            {
                inside = !inside;
            }
        }
    }
    return inside;
}


std::vector<Vec2> convexOutline
(
    const std::vector<Vec2>& outline,
    const std::string& entry,
    double tolerance
)
{
    for (const Vec2& q : outline)
    {
        if (!std::isfinite(q.x()) || !std::isfinite(q.y()))
        {
            throw Error("outline has a non-finite coordinate", entry);
        }
    }
    if (outline.size() < 3)
    {
        throw Error
        (
            "outline needs at least 3 vertices, got "
          + std::to_string(outline.size()),
            entry
        );
    }
    const double D = outlineSize(outline);
    const double eps = tolerance*D;
    if (!(D > 0))
    {
        throw Error("degenerate outline: all vertices coincide", entry);
    }

    // Drop repeated vertices (also the closing repeat of the first one)
    std::vector<Vec2> p;
    for (const Vec2& q : outline)
    {
        if (p.empty() || (q - p.back()).norm() > eps)
        {
            p.push_back(q);
        }
    }
    while (p.size() > 1 && (p.back() - p.front()).norm() <= eps)
    {
        p.pop_back();
    }

    const double area = polygonSignedArea(p);
    if (p.size() < 3 || !(std::abs(area) > eps*D))
    {
        throw Error
        (
            "degenerate outline: fewer than 3 distinct vertices or zero area",
            entry
        );
    }
    if (area < 0)
    {
        std::reverse(p.begin(), p.end());
    }

    // Drop straight vertices (on the segment between their neighbours); a
    // vertex on the line but outside the segment is a spike: not convex
    bool changed = true;
    while (changed && p.size() >= 3)
    {
        changed = false;
        const std::size_t n = p.size();
        for (std::size_t i = 0; i < n; ++i)
        {
            const Vec2& a = p[(i + n - 1) % n];
            const Vec2& b = p[(i + 1) % n];
            const Vec2 ab = b - a;
            const double dist = std::abs(cross2(ab, p[i] - a))/ab.norm();
            if (dist <= eps)
            {
                if ((p[i] - a).dot(b - p[i]) < 0)
                {
                    throw Error
                    (
                        "outline is not convex (it folds back on itself)",
                        entry
                    );
                }
                p.erase(p.begin() + i);
                changed = true;
                break;
            }
        }
    }
    if (p.size() < 3)
    {
        throw Error("degenerate outline: all vertices on one line", entry);
    }

    // Convex: every vertex on the left of (or on) every edge line
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i)
    {
        const Vec2 e = p[(i + 1) % n] - p[i];
        const double len = e.norm();
        for (std::size_t j = 0; j < n; ++j)
        {
            if (cross2(e, p[j] - p[i])/len < -eps)
            {
                std::ostringstream os;
                os  << "outline is not convex: vertex " << j
                    << " lies outside the line of edge " << i
                    << " (vertices counted after ordering counter-clockwise)";
                throw Error(os.str(), entry);
            }
        }
    }
    return p;
}


std::vector<Vec2> shrinkConvexPolygon
(
    const std::vector<Vec2>& outline,
    double d,
    double tolerance
)
{
    if (!(d >= 0) || !std::isfinite(d))
    {
        throw Error
        (
            "shrink distance must be >= 0, got " + str(d), "radius"
        );
    }
    const std::vector<Vec2> p = convexOutline(outline, "outline", tolerance);
    if (d == 0)
    {
        return p;
    }
    const std::size_t n = p.size();
    const double D = outlineSize(p);
    const double eps = tolerance*D;

    // Local frame about the vertex mean (precision far from the origin)
    Vec2 o = Vec2::Zero();
    for (const Vec2& q : p)
    {
        o += q;
    }
    o /= double(n);

    // Moved edge lines n_i . x = n_i . p_i - d
    std::vector<Line> lines(n);
    std::vector<TaggedVertex> poly(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        const Vec2 a = p[i] - o;
        const Vec2 b = p[(i + 1) % n] - o;
        const Vec2 u = (b - a).normalized();
        lines[i].n = Vec2(u.y(), -u.x());
        lines[i].c = lines[i].n.dot(a) - d;
        poly[i] = {a, int(i)};
    }

    // Intersection of the moved half-planes, each edge tagged by its line
    for (std::size_t i = 0; i < n && !poly.empty(); ++i)
    {
        poly = clipTagged(poly, lines[i], int(i));
    }

    const std::string tooSmall =
        "outline too small for the dilation radius " + str(d)
      + ": nothing is left of it after shrinking by the radius";

    // Drop (nearly) zero-length edges of the clipped polygon
    {
        std::vector<TaggedVertex> q;
        for (const TaggedVertex& v : poly)
        {
            if (q.empty() || (v.p - q.back().p).norm() > eps)
            {
                q.push_back(v);
            }
            else
            {
                // The edge leaving this point lies on v's line
                q.back().tag = v.tag;
            }
        }
        while (q.size() > 1 && (q.back().p - q.front().p).norm() <= eps)
        {
            q.pop_back();
        }
        poly.swap(q);
    }
    if (poly.size() < 3)
    {
        throw Error(tooSmall, "outline");
    }

    // Thinnest width of what is left
    {
        double minWidth = D;
        const std::size_t m = poly.size();
        for (std::size_t k = 0; k < m; ++k)
        {
            const Line& L = lines[poly[k].tag];
            double w = 0;
            for (const TaggedVertex& v : poly)
            {
                w = std::max(w, L.c - L.n.dot(v.p));
            }
            minWidth = std::min(minWidth, w);
        }
        if (!(minWidth > eps))
        {
            throw Error(tooSmall, "outline");
        }
    }

    // Edge lines in order, consecutive repeats merged
    std::vector<int> tags;
    for (const TaggedVertex& v : poly)
    {
        if (tags.empty() || tags.back() != v.tag)
        {
            tags.push_back(v.tag);
        }
    }
    while (tags.size() > 1 && tags.back() == tags.front())
    {
        tags.pop_back();
    }

    // Vertices as exact intersections of neighbouring moved lines; edges
    // that come out shorter than the tolerance are dropped
    std::vector<Vec2> core;
    bool changed = true;
    while (changed)
    {
        changed = false;
        const std::size_t m = tags.size();
        if (m < 3)
        {
            throw Error(tooSmall, "outline");
        }
        core.assign(m, Vec2::Zero());
        for (std::size_t k = 0; k < m; ++k)
        {
            if (!intersect(lines[tags[(k + m - 1) % m]], lines[tags[k]], core[k]))
            {
                throw Error(tooSmall, "outline");
            }
        }
        for (std::size_t k = 0; k < m; ++k)
        {
            if ((core[(k + 1) % m] - core[k]).norm() <= eps)
            {
                tags.erase(tags.begin() + k);
                changed = true;
                break;
            }
        }
    }

    for (Vec2& v : core)
    {
        v += o;
    }
    return core;
}


bool thickEnough(double thickness, double radius, double tolerance)
{
    // Above 4r by the relative tolerance: the core's height h - 2r, once
    // its ends are placed at zBottom + r and zBottom + h - r, is rounded
    return
        std::isfinite(thickness)
     && thickness > DilatedShape::minOuterWidthInRadii*radius*(1 + tolerance);
}


std::string thinFloeText(double radius)
{
    return
        " must be more than four times the dilation radius (4r = "
      + str(DilatedShape::minOuterWidthInRadii*radius) + "): the core, h - 2r thick, must be"
        " at least 2r thick, as a dilated element's radius is at most half"
        " its core's thinnest width";
}


ConvexPolyhedron floeCore
(
    const std::vector<Vec2>& outline,
    double zBottom,
    double thickness,
    double radius,
    double tolerance
)
{
    if (!(radius > 0) || !std::isfinite(radius))
    {
        throw Error
        (
            "dilation radius must be > 0, got " + str(radius), "radius"
        );
    }
    if (!thickEnough(thickness, radius, tolerance))
    {
        throw Error
        (
            "floe thickness " + str(thickness) + thinFloeText(radius),
            "thickness"
        );
    }
    if (!std::isfinite(zBottom))
    {
        throw Error("zBottom is not a finite number", "zBottom");
    }

    const std::vector<Vec2> core =
        shrinkConvexPolygon(outline, radius, tolerance);

    return ConvexPolyhedron::prism
    (
        core,
        zBottom + radius,
        thickness - 2*radius
    );
}


double Floe::area() const
{
    return std::abs(polygonSignedArea(outline));
}


Vec2 Floe::centroid() const
{
    return polygonCentroid(outline);
}


ConvexPolyhedron Floe::core() const
{
    return floeCore(outline, zBottom, thickness, radius);
}


} // namespace iceDEM
