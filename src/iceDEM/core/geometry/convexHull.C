/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    ConvexPolyhedron::hull: the convex hull of a point set with CGAL, its
    coplanar triangles merged into polygonal faces. CGAL lives in this
    translation unit only.
\*---------------------------------------------------------------------------*/

// CGAL first, before any other header
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/Surface_mesh.h>

#include "ConvexPolyhedron.H"

#include <algorithm>
#include <cmath>
#include <map>

namespace iceDEM
{

namespace
{
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Point3 = Kernel::Point_3;
    using Mesh = CGAL::Surface_mesh<Point3>;
}


ConvexPolyhedron ConvexPolyhedron::hull(const std::vector<Vec3>& points)
{
    if (points.size() < 4)
    {
        throw Error("a convex hull needs at least 4 points", "points");
    }
    for (const Vec3& p : points)
    {
        if (!p.allFinite())
        {
            throw Error("a point is not finite", "points");
        }
    }

    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& p : points)
    {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double size = (hi - lo).norm();

    // Points closer than hullTolerance to an earlier one are that
    // one (a point listed twice with rounding): CGAL would keep both, and
    // the slivers between them have normals of rounding alone
    std::vector<Point3> pts;
    pts.reserve(points.size());
    {
        std::vector<std::size_t> byX(points.size());
        for (std::size_t k = 0; k < byX.size(); ++k) byX[k] = k;
        std::sort
        (
            byX.begin(), byX.end(),
            [&](std::size_t a, std::size_t b) { return points[a].x() < points[b].x(); }
        );
        const double merge = hullTolerance*size;
        std::vector<bool> merged(points.size(), false);
        for (std::size_t a = 0; a < byX.size(); ++a)
        {
            for
            (
                std::size_t b = a + 1;
                b < byX.size() && points[byX[b]].x() - points[byX[a]].x() < merge;
                ++b
            )
            {
                // The later of two close points goes (input order)
                const std::size_t i = std::min(byX[a], byX[b]);
                const std::size_t j = std::max(byX[a], byX[b]);
                if (!merged[i] && (points[i] - points[j]).norm() < merge)
                {
                    merged[j] = true;
                }
            }
        }
        for (std::size_t k = 0; k < points.size(); ++k)
        {
            if (!merged[k]) pts.emplace_back(points[k].x(), points[k].y(), points[k].z());
        }
    }
    if (pts.size() < 4)
    {
        throw Error("a convex hull needs at least 4 distinct points", "points");
    }

    // A solid hull needs three non-collinear points and a fourth off their plane
    bool solid = false;
    std::size_t i1 = 1;
    while (i1 < pts.size() && pts[i1] == pts[0]) ++i1;
    for (std::size_t k = i1 + 1; k < pts.size(); ++k)
    {
        if (CGAL::collinear(pts[0], pts[i1], pts[k]))
        {
            continue;
        }
        for (std::size_t m = 1; m < pts.size() && !solid; ++m)
        {
            solid = !CGAL::coplanar(pts[0], pts[i1], pts[k], pts[m]);
        }
        break;
    }
    if (!solid)
    {
        throw Error("the points are flat (collinear or coplanar): no solid hull", "points");
    }

    Mesh mesh;
    CGAL::convex_hull_3(pts.begin(), pts.end(), mesh);

    // Hull vertices, renumbered
    std::map<Mesh::Vertex_index, int> index;
    std::vector<Vec3> verts;
    for (Mesh::Vertex_index v : mesh.vertices())
    {
        const Point3& p = mesh.point(v);
        index[v] = static_cast<int>(verts.size());
        verts.emplace_back(p.x(), p.y(), p.z());
    }

    // Triangles with their planes
    struct Tri { std::array<int, 3> v; Vec3 n; };
    std::vector<Tri> tris;
    for (Mesh::Face_index f : mesh.faces())
    {
        Tri t;
        int k = 0;
        for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
        {
            if (k < 3) t.v[k] = index[v];
            ++k;
        }
        if (k != 3)
        {
            throw Error("unexpected non-triangular hull face", "points");
        }
        const Vec3 n = (verts[t.v[1]] - verts[t.v[0]]).cross(verts[t.v[2]] - verts[t.v[0]]);
        if (n.norm() <= 0)
        {
            continue;
        }
        t.n = n.normalized();
        tris.push_back(t);
    }

    // Group coplanar triangles into faces
    std::vector<int> group(tris.size(), -1);
    std::vector<std::vector<int>> faceLoops;
    for (std::size_t i = 0; i < tris.size(); ++i)
    {
        if (group[i] >= 0) continue;
        const int g = static_cast<int>(faceLoops.size());
        std::vector<int> members;
        for (std::size_t j = i; j < tris.size(); ++j)
        {
            // Heights of j's corners over i's plane, from a corner of i:
            // the same test wherever the body lies (its plane offsets, of
            // the size of its coordinates, would carry their rounding)
            const Vec3& origin = verts[tris[i].v[0]];
            double height = 0;
            for (int v : tris[j].v)
            {
                height = std::max(height, std::abs(tris[i].n.dot(verts[v] - origin)));
            }
            if
            (
                group[j] < 0
             && tris[j].n.dot(tris[i].n) > std::cos(hullTolerance)
             && height < hullTolerance*size
            )
            {
                group[j] = g;
                members.push_back(int(j));
            }
        }
        // The face polygon: its vertices ordered counter-clockwise about n
        const Vec3 n = tris[i].n;
        std::vector<int> vs;
        for (int m : members)
        {
            for (int v : tris[m].v) vs.push_back(v);
        }
        std::sort(vs.begin(), vs.end());
        vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
        Vec3 c = Vec3::Zero();
        for (int v : vs) c += verts[v];
        c /= double(vs.size());
        const Vec3 e1 = (verts[vs[0]] - c).normalized();
        const Vec3 e2 = n.cross(e1);
        std::sort
        (
            vs.begin(), vs.end(),
            [&](int a, int b)
            {
                const Vec3 pa = verts[a] - c, pb = verts[b] - c;
                return std::atan2(pa.dot(e2), pa.dot(e1))
                     < std::atan2(pb.dot(e2), pb.dot(e1));
            }
        );
        faceLoops.push_back(vs);
    }

    // A corner of a polyhedron belongs to three faces at least. A hull vertex
    // in two faces lies on the straight edge between them, one in a single
    // face inside it (CGAL keeps input points on an edge or a face): every
    // face drops it. A count, not a distance: the faces drop the same
    // vertices, so they stay closed whatever the lengths of the edges (an
    // offset core with a vertex of more than three faces has edges of
    // micrometres beside edges of metres, which a test of the area a
    // vertex turns dropped from one face but not from the next)
    std::vector<int> uses(verts.size(), 0);
    for (const auto& loop : faceLoops)
    {
        for (int v : loop) ++uses[v];
    }
    for (auto& loop : faceLoops)
    {
        loop.erase
        (
            std::remove_if(loop.begin(), loop.end(), [&](int v) { return uses[v] < 3; }),
            loop.end()
        );
    }

    // Canonical numbering, independent of CGAL's internal order (which may
    // vary from call to call): vertices still used, sorted by coordinates;
    // each loop starting at its smallest vertex; loops sorted. The same
    // points then give the same polyhedron bit for bit.
    std::vector<int> order;
    for (const auto& loop : faceLoops)
    {
        for (int v : loop) order.push_back(v);
    }
    std::sort(order.begin(), order.end());
    order.erase(std::unique(order.begin(), order.end()), order.end());
    std::sort
    (
        order.begin(), order.end(),
        [&](int a, int b)
        {
            const Vec3& p = verts[a];
            const Vec3& q = verts[b];
            return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
        }
    );
    std::fill(uses.begin(), uses.end(), -1);
    std::vector<Vec3> used;
    for (int v : order)
    {
        uses[v] = static_cast<int>(used.size());
        used.push_back(verts[v]);
    }
    for (auto& loop : faceLoops)
    {
        for (int& v : loop) v = uses[v];
        std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
    }
    std::sort(faceLoops.begin(), faceLoops.end());
    return ConvexPolyhedron(used, faceLoops);
}

} // namespace iceDEM
