/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "ConvexPolyhedron.H"
#include "MassProperties.H"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace iceDEM
{

namespace
{
    //- Relative tolerance of the planarity and convexity checks
    constexpr double geometryTolerance = 1e-9;
}


ConvexPolyhedron::ConvexPolyhedron
(
    const std::vector<Vec3>& vertices,
    const std::vector<std::vector<int>>& faceLoops
)
:
    vertices_(vertices)
{
    if (vertices_.size() < 4 || faceLoops.size() < 4)
    {
        throw Error("a polyhedron needs at least 4 vertices and 4 faces", "points");
    }

    double size = 0;
    for (const Vec3& v : vertices_)
    {
        size = std::max(size, (v - vertices_[0]).norm());
    }
    if (!(size > 0) || !std::isfinite(size))
    {
        throw Error("degenerate polyhedron (all vertices coincide or not finite)", "points");
    }
    const double tol = geometryTolerance*size;

    for (const auto& loop : faceLoops)
    {
        if (loop.size() < 3)
        {
            throw Error("a face has fewer than 3 vertices", "points");
        }
        Face f;
        f.begin = static_cast<int>(faceVertices_.size());
        f.count = static_cast<int>(loop.size());

        // Newell's normal: robust for planar polygons
        Vec3 n = Vec3::Zero();
        Vec3 c = Vec3::Zero();
        for (std::size_t k = 0; k < loop.size(); ++k)
        {
            const int a = loop[k];
            const int b = loop[(k + 1) % loop.size()];
            if (a < 0 || b < 0 || a >= int(vertices_.size()) || b >= int(vertices_.size()))
            {
                throw Error("face refers to a vertex that does not exist", "points");
            }
            n += vertices_[a].cross(vertices_[b]);
            c += vertices_[a];
            faceVertices_.push_back(a);
        }
        c /= double(loop.size());
        const double nn = n.norm();
        if (nn < tol*tol)
        {
            throw Error("a face has zero area", "points");
        }
        f.normal = n/nn;
        f.offset = f.normal.dot(c);
        for (int a : loop)
        {
            if (std::abs(f.normal.dot(vertices_[a]) - f.offset) > tol)
            {
                throw Error("a face is not planar", "points");
            }
        }
        faces_.push_back(f);
    }

    // Convex, with outward normals: every vertex on the inner side of every face
    for (const Face& f : faces_)
    {
        for (const Vec3& v : vertices_)
        {
            if (f.normal.dot(v) - f.offset > tol)
            {
                throw Error
                (
                    "the polyhedron is not convex (or a face is oriented inward)",
                    "points"
                );
            }
        }
    }

    buildTopology();
}


void ConvexPolyhedron::buildTopology()
{
    // Each directed edge a->b once; its reverse b->a in exactly one other face
    std::map<std::pair<int, int>, int> directed;
    for (int f = 0; f < int(faces_.size()); ++f)
    {
        for (int k = 0; k < faces_[f].count; ++k)
        {
            const int a = faceVertex(f, k);
            const int b = faceVertex(f, (k + 1) % faces_[f].count);
            if (!directed.emplace(std::make_pair(a, b), f).second)
            {
                throw Error("the surface is not a closed oriented polyhedron", "points");
            }
        }
    }

    edges_.clear();
    edgeFaces_.clear();
    for (const auto& d : directed)
    {
        const int a = d.first.first;
        const int b = d.first.second;
        const auto rev = directed.find(std::make_pair(b, a));
        if (rev == directed.end())
        {
            throw Error("the surface is not closed (an edge has one face)", "points");
        }
        if (a < b)
        {
            edges_.push_back({a, b});
            edgeFaces_.push_back({d.second, rev->second});
        }
    }

    std::vector<int> degree(vertices_.size(), 0);
    for (const auto& e : edges_)
    {
        ++degree[e[0]];
        ++degree[e[1]];
    }
    vertexEdgeStart_.assign(vertices_.size() + 1, 0);
    for (std::size_t v = 0; v < vertices_.size(); ++v)
    {
        if (degree[v] < 3)
        {
            throw Error("a vertex belongs to fewer than 3 edges (unused or degenerate vertex)", "points");
        }
        vertexEdgeStart_[v + 1] = vertexEdgeStart_[v] + degree[v];
    }
    vertexEdges_.assign(vertexEdgeStart_.back(), -1);
    std::vector<int> fill(vertexEdgeStart_.begin(), vertexEdgeStart_.end() - 1);
    for (int e = 0; e < int(edges_.size()); ++e)
    {
        vertexEdges_[fill[edges_[e][0]]++] = e;
        vertexEdges_[fill[edges_[e][1]]++] = e;
    }

    // Euler characteristic of a sphere
    if (int(vertices_.size()) - int(edges_.size()) + int(faces_.size()) != 2)
    {
        throw Error("the surface is not a closed polyhedron (V - E + F != 2)", "points");
    }
}


ConvexPolyhedron ConvexPolyhedron::box(const Vec3& h)
{
    if (!(h.minCoeff() > 0))
    {
        throw Error("box half extents must be positive", "halfExtents");
    }
    std::vector<Vec3> v;
    for (int k = 0; k < 8; ++k)
    {
        v.emplace_back
        (
            (k & 1 ? 1 : -1)*h.x(),
            (k & 2 ? 1 : -1)*h.y(),
            (k & 4 ? 1 : -1)*h.z()
        );
    }
    const std::vector<std::vector<int>> faces =
    {
        {0, 2, 3, 1},   // z-
        {4, 5, 7, 6},   // z+
        {0, 1, 5, 4},   // y-
        {2, 6, 7, 3},   // y+
        {0, 4, 6, 2},   // x-
        {1, 3, 7, 5}    // x+
    };
    return ConvexPolyhedron(v, faces);
}


ConvexPolyhedron ConvexPolyhedron::prism
(
    const std::vector<Vec2>& polygonIn,
    double zBottom,
    double height
)
{
    if (!(height > 0))
    {
        throw Error("prism height must be positive", "thickness");
    }
    if (polygonIn.size() < 3)
    {
        throw Error("a prism needs a polygon of at least 3 points", "outline");
    }
    std::vector<Vec2> poly(polygonIn);
    double area2 = 0;
    for (std::size_t k = 0; k < poly.size(); ++k)
    {
        const Vec2& a = poly[k];
        const Vec2& b = poly[(k + 1) % poly.size()];
        area2 += a.x()*b.y() - a.y()*b.x();
    }
    if (area2 < 0)
    {
        std::reverse(poly.begin(), poly.end());
    }

    const int n = static_cast<int>(poly.size());
    std::vector<Vec3> v;
    for (const Vec2& p : poly) v.emplace_back(p.x(), p.y(), zBottom);
    for (const Vec2& p : poly) v.emplace_back(p.x(), p.y(), zBottom + height);

    std::vector<std::vector<int>> faces;
    std::vector<int> bottom, top;
    for (int k = n - 1; k >= 0; --k) bottom.push_back(k);
    for (int k = 0; k < n; ++k) top.push_back(n + k);
    faces.push_back(bottom);
    faces.push_back(top);
    for (int k = 0; k < n; ++k)
    {
        const int k1 = (k + 1) % n;
        faces.push_back({k, k1, n + k1, n + k});
    }
    return ConvexPolyhedron(v, faces);
}


double ConvexPolyhedron::volume() const
{
    return polyhedronMassProperties(*this).volume;
}


double ConvexPolyhedron::area() const
{
    double A = 0;
    for (const Face& f : faces_)
    {
        Vec3 n = Vec3::Zero();
        for (int k = 0; k < f.count; ++k)
        {
            n += vertices_[faceVertices_[f.begin + k]]
                .cross(vertices_[faceVertices_[f.begin + (k + 1) % f.count]]);
        }
        A += 0.5*n.norm();
    }
    return A;
}


double ConvexPolyhedron::minWidth() const
{
    double w = std::numeric_limits<double>::max();
    for (const Face& f : faces_)
    {
        double lo = std::numeric_limits<double>::max();
        for (const Vec3& v : vertices_)
        {
            lo = std::min(lo, f.normal.dot(v));
        }
        w = std::min(w, f.offset - lo);
    }
    return w;
}


double ConvexPolyhedron::exteriorAngle(int e) const
{
    const double c = faces_[edgeFaces_[e][0]].normal.dot(faces_[edgeFaces_[e][1]].normal);
    return std::acos(std::max(-1.0, std::min(1.0, c)));
}


Vec3 ConvexPolyhedron::edgeInwardInFace(int e, int side) const
{
    const Face& f = faces_[edgeFaces_[e][side]];
    const Vec3& a = vertices_[edges_[e][0]];
    const Vec3& b = vertices_[edges_[e][1]];
    const Vec3 t = (b - a).normalized();
    Vec3 w = f.normal.cross(t).normalized();

    Vec3 c = Vec3::Zero();
    for (int k = 0; k < f.count; ++k) c += vertices_[faceVertices_[f.begin + k]];
    c /= double(f.count);
    if (w.dot(c - 0.5*(a + b)) < 0)
    {
        w = -w;
    }
    return w;
}


ConvexPolyhedron ConvexPolyhedron::offset(double d) const
{
    // Vertices of the offset polyhedron: intersections of three offset planes
    // that lie inside all of them. Faces have few planes, so brute force is
    // cheap and needs no dual hull.
    double size = 0;
    for (const Vec3& v : vertices_) size = std::max(size, (v - vertices_[0]).norm());
    const double tol = geometryTolerance*(size + d);

    const int F = static_cast<int>(faces_.size());
    std::vector<Vec3> points;
    for (int i = 0; i < F; ++i)
    {
        for (int j = i + 1; j < F; ++j)
        {
            for (int k = j + 1; k < F; ++k)
            {
                Mat3 A;
                A.row(0) = faces_[i].normal.transpose();
                A.row(1) = faces_[j].normal.transpose();
                A.row(2) = faces_[k].normal.transpose();
                const double det = A.determinant();
                if (std::abs(det) < 1e-10)
                {
                    continue;
                }
                const Vec3 rhs
                (
                    faces_[i].offset + d,
                    faces_[j].offset + d,
                    faces_[k].offset + d
                );
                const Vec3 x = A.partialPivLu().solve(rhs);
                bool inside = true;
                for (const Face& f : faces_)
                {
                    if (f.normal.dot(x) - f.offset - d > tol)
                    {
                        inside = false;
                        break;
                    }
                }
                if (inside)
                {
                    points.push_back(x);
                }
            }
        }
    }
    return hull(points);
}


ConvexPolyhedron ConvexPolyhedron::transformed(const Mat3& R, const Vec3& t) const
{
    ConvexPolyhedron P(*this);
    for (Vec3& v : P.vertices_)
    {
        v = R*v + t;
    }
    for (Face& f : P.faces_)
    {
        f.normal = R*f.normal;
        f.offset = f.normal.dot(P.vertices_[P.faceVertices_[f.begin]]);
    }
    return P;
}


std::size_t ConvexPolyhedron::heapBytes() const
{
    return vertices_.capacity()*sizeof(Vec3)
        + edges_.capacity()*sizeof(edges_[0])
        + edgeFaces_.capacity()*sizeof(edgeFaces_[0])
        + faceVertices_.capacity()*sizeof(int)
        + faces_.capacity()*sizeof(Face)
        + vertexEdgeStart_.capacity()*sizeof(int)
        + vertexEdges_.capacity()*sizeof(int);
}

} // namespace iceDEM
