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
#include <utility>

namespace iceDEM
{

namespace
{
    //- Relative tolerance of the planarity and convexity checks
    constexpr double geometryTolerance = 1e-9;
}


ConvexPolyhedron::ConvexPolyhedron()
:
    topology_(PolyhedronTopology::empty())
{}


ConvexPolyhedron::ConvexPolyhedron
(
    const std::vector<Vec3>& vertices,
    const std::vector<std::vector<int>>& faceLoops
)
{
    if (vertices.size() < 4 || faceLoops.size() < 4)
    {
        throw Error("a polyhedron needs at least 4 vertices and 4 faces", "points");
    }

    double size = 0;
    for (const Vec3& v : vertices)
    {
        size = std::max(size, (v - vertices[0]).norm());
    }
    if (!(size > 0) || !std::isfinite(size))
    {
        throw Error("degenerate polyhedron (all vertices coincide or not finite)", "points");
    }
    const double tol = geometryTolerance*size;

    std::vector<Plane> planes;
    planes.reserve(faceLoops.size());
    for (const auto& loop : faceLoops)
    {
        if (loop.size() < 3)
        {
            throw Error("a face has fewer than 3 vertices", "points");
        }

        // Newell's normal: robust for planar polygons
        Vec3 n = Vec3::Zero();
        Vec3 c = Vec3::Zero();
        for (std::size_t k = 0; k < loop.size(); ++k)
        {
            const int a = loop[k];
            const int b = loop[(k + 1) % loop.size()];
            if (a < 0 || b < 0 || a >= int(vertices.size()) || b >= int(vertices.size()))
            {
                throw Error("face refers to a vertex that does not exist", "points");
            }
            n += vertices[a].cross(vertices[b]);
            c += vertices[a];
        }
        c /= double(loop.size());
        const double nn = n.norm();
        if (nn < tol*tol)
        {
            throw Error("a face has zero area", "points");
        }
        Plane f;
        f.normal = n/nn;
        f.offset = f.normal.dot(c);
        for (int a : loop)
        {
            const double off = std::abs(f.normal.dot(vertices[a]) - f.offset);
            if (off > tol)
            {
                std::ostringstream msg;
                msg << "a face is not planar: its vertex (" << vertices[a].transpose()
                    << ") lies " << off << " from the plane of the face, more than "
                    << tol << " (" << geometryTolerance << " of the polyhedron's size);"
                    << " points meant to lie in one face must be coplanar to that";
                throw Error(msg.str(), "points");
            }
        }
        planes.push_back(f);
    }

    // Convex, with outward normals: every vertex on the inner side of every face
    for (const Plane& f : planes)
    {
        for (const Vec3& v : vertices)
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

    // Edges and adjacency: shared with every polyhedron of these loops
    topology_ = PolyhedronTopology::shared(int(vertices.size()), faceLoops);

    allocateGeometry();
    std::copy(vertices.begin(), vertices.end(), vertexData());
    std::copy(planes.begin(), planes.end(), planeData());
}


void ConvexPolyhedron::allocateGeometry()
{
    static_assert(sizeof(Vec3) % alignof(Plane) == 0, "planes after the vertices stay aligned");
    static_assert(alignof(Plane) <= alignof(std::max_align_t), "new[] aligns the block");

    const std::size_t nV = topology_->nVertices();
    const std::size_t nF = topology_->nFaces();
    geometry_.reset(new std::byte[geometryBytes()]);
    // Start the objects' lifetimes in the raw block, one by one (an array
    // placement-new may add a cookie); values set by the caller
    std::byte* p = geometry_.get();
    for (std::size_t v = 0; v < nV; ++v, p += sizeof(Vec3)) new (p) Vec3;
    for (std::size_t f = 0; f < nF; ++f, p += sizeof(Plane)) new (p) Plane;
}


ConvexPolyhedron::ConvexPolyhedron
(
    std::shared_ptr<const PolyhedronTopology> topology,
    const Vec3* vertices,
    const Plane* planes
)
:
    topology_(std::move(topology))
{
    allocateGeometry();
    std::copy(vertices, vertices + topology_->nVertices(), vertexData());
    std::copy(planes, planes + topology_->nFaces(), planeData());
}


ConvexPolyhedron::ConvexPolyhedron(const ConvexPolyhedron& P)
:
    topology_(P.topology_)
{
    if (P.geometry_)
    {
        allocateGeometry();
        std::copy(P.vertexData(), P.vertexData() + topology_->nVertices(), vertexData());
        std::copy(P.planeData(), P.planeData() + topology_->nFaces(), planeData());
    }
}


ConvexPolyhedron& ConvexPolyhedron::operator=(const ConvexPolyhedron& P)
{
    if (this != &P)
    {
        ConvexPolyhedron copy(P);
        *this = std::move(copy);
    }
    return *this;
}


ConvexPolyhedron::ConvexPolyhedron(ConvexPolyhedron&& P) noexcept
:
    topology_(std::move(P.topology_)),
    geometry_(std::move(P.geometry_))
{
    P.topology_ = PolyhedronTopology::empty();
}


ConvexPolyhedron& ConvexPolyhedron::operator=(ConvexPolyhedron&& P) noexcept
{
    if (this != &P)
    {
        topology_ = std::move(P.topology_);
        geometry_ = std::move(P.geometry_);
        P.topology_ = PolyhedronTopology::empty();
    }
    return *this;
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
    const auto V = vertices();
    const auto& faceVertices = topology_->faceVertices();
    double A = 0;
    for (const Face& f : faces())
    {
        Vec3 n = Vec3::Zero();
        for (int k = 0; k < f.count; ++k)
        {
            n += V[faceVertices[f.begin + k]]
                .cross(V[faceVertices[f.begin + (k + 1) % f.count]]);
        }
        A += 0.5*n.norm();
    }
    return A;
}


double ConvexPolyhedron::minWidth() const
{
    double w = std::numeric_limits<double>::max();
    for (const Face& f : faces())
    {
        double lo = std::numeric_limits<double>::max();
        for (const Vec3& v : vertices())
        {
            lo = std::min(lo, f.normal.dot(v));
        }
        w = std::min(w, f.offset - lo);
    }
    return w;
}


double ConvexPolyhedron::exteriorAngle(int e) const
{
    const Plane* planes = planeData();
    const auto& ef = edgeFaces()[e];
    const double c = planes[ef[0]].normal.dot(planes[ef[1]].normal);
    return std::acos(std::max(-1.0, std::min(1.0, c)));
}


Vec3 ConvexPolyhedron::edgeInwardInFace(int e, int side) const
{
    const Face f = faces()[edgeFaces()[e][side]];
    const auto V = vertices();
    const Vec3& a = V[edges()[e][0]];
    const Vec3& b = V[edges()[e][1]];
    const Vec3 t = (b - a).normalized();
    Vec3 w = f.normal.cross(t).normalized();

    Vec3 c = Vec3::Zero();
    for (int k = 0; k < f.count; ++k) c += V[faceVertices()[f.begin + k]];
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
    const auto V = vertices();
    for (const Vec3& v : V) size = std::max(size, (v - V[0]).norm());
    const double tol = geometryTolerance*(size + d);

    const Plane* planes = planeData();
    const int F = topology_->nFaces();
    std::vector<Vec3> points;
    for (int i = 0; i < F; ++i)
    {
        for (int j = i + 1; j < F; ++j)
        {
            for (int k = j + 1; k < F; ++k)
            {
                Mat3 A;
                A.row(0) = planes[i].normal.transpose();
                A.row(1) = planes[j].normal.transpose();
                A.row(2) = planes[k].normal.transpose();
                const double det = A.determinant();
                if (std::abs(det) < 1e-10)
                {
                    continue;
                }
                const Vec3 rhs
                (
                    planes[i].offset + d,
                    planes[j].offset + d,
                    planes[k].offset + d
                );
                const Vec3 x = A.partialPivLu().solve(rhs);
                bool inside = true;
                for (int m = 0; m < F; ++m)
                {
                    const Plane& f = planes[m];
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
    Vec3* V = P.vertexData();
    for (int v = 0; v < topology_->nVertices(); ++v)
    {
        V[v] = R*V[v] + t;
    }
    Plane* planes = P.planeData();
    for (int f = 0; f < topology_->nFaces(); ++f)
    {
        planes[f].normal = R*planes[f].normal;
        planes[f].offset = planes[f].normal.dot(V[faceVertex(f, 0)]);
    }
    return P;
}


std::size_t ConvexPolyhedron::heapBytes() const
{
    if (!geometry_) return 0;
    return geometryBytes();
}

} // namespace iceDEM
