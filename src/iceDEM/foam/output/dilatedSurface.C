/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "dilatedSurface.H"

#include <algorithm>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

using namespace iceDEM;

//- Append a polygon, oriented so that its normal points away from the
//  origin (the centroid, inside the convex shape)
void addOriented(SurfaceMesh& m, std::vector<int> loop)
{
    const int n = int(loop.size());
    Vec3 normal = Vec3::Zero();
    Vec3 centre = Vec3::Zero();
    for (int k = 0; k < n; ++k)
    {
        const Vec3& a = m.points[loop[k]];
        const Vec3& b = m.points[loop[(k + 1) % n]];
        normal += a.cross(b);
        centre += a;
    }
    if (normal.dot(centre) < 0)
    {
        std::reverse(loop.begin(), loop.end());
    }
    m.addPolygon(loop);
}


//- Unit direction between two unit normals: normalise((1-t) a + t b)
Vec3 arc(const Vec3& a, const Vec3& b, int i, int s)
{
    const double t = double(i)/s;
    return ((1 - t)*a + t*b).normalized();
}


void polyhedronSurface(SurfaceMesh& m, const PolyhedronView& P)
{
    const int base = int(m.points.size());
    m.points.insert(m.points.end(), P.vertices().begin(), P.vertices().end());
    for (int f = 0; f < int(P.faces().size()); ++f)
    {
        std::vector<int> loop(P.faces()[f].count);
        for (int k = 0; k < P.faces()[f].count; ++k)
        {
            loop[k] = base + P.faceVertex(f, k);
        }
        addOriented(m, loop);
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void iceDEM::SurfaceMesh::addPolygon(const std::vector<int>& loop)
{
    polygons.push_back(int(loop.size()));
    polygons.insert(polygons.end(), loop.begin(), loop.end());
    ++nPolygons;
}


iceDEM::SurfaceMesh iceDEM::dilatedSurface
(
    const DilatedShape& shape,
    SurfaceKind kind,
    int resolution
)
{
    SurfaceMesh m;

    if (kind == SurfaceKind::outer)
    {
        PolyhedronBuffer buffer;
        polyhedronSurface(m, shape.outer(buffer));
        return m;
    }
    if (kind == SurfaceKind::core)
    {
        polyhedronSurface(m, shape.core());
        return m;
    }

    const ConvexPolyhedron& P = shape.core();
    const double r = shape.radius();
    const int s = std::max(resolution, 1);
    const auto& faces = P.faces();
    const auto& verts = P.vertices();

    // Faces offset by r
    for (int f = 0; f < int(faces.size()); ++f)
    {
        const Vec3 shift = r*faces[f].normal;
        std::vector<int> loop(faces[f].count);
        for (int k = 0; k < faces[f].count; ++k)
        {
            loop[k] = int(m.points.size());
            m.points.push_back(verts[P.faceVertex(f, k)] + shift);
        }
        addOriented(m, loop);
    }

    // Edge cylinders
    for (int e = 0; e < int(P.edges().size()); ++e)
    {
        const Vec3& p0 = verts[P.edges()[e][0]];
        const Vec3& p1 = verts[P.edges()[e][1]];
        const Vec3& na = faces[P.edgeFaces()[e][0]].normal;
        const Vec3& nb = faces[P.edgeFaces()[e][1]].normal;

        const int base = int(m.points.size());
        for (int i = 0; i <= s; ++i)
        {
            const Vec3 d = r*arc(na, nb, i, s);
            m.points.push_back(p0 + d);
            m.points.push_back(p1 + d);
        }
        for (int i = 0; i < s; ++i)
        {
            addOriented
            (
                m,
                {base + 2*i, base + 2*i + 1, base + 2*i + 3, base + 2*i + 2}
            );
        }
    }

    // Vertex sphere patches: one fan triangle (c, na, nb) per edge at the
    // vertex, split on a barycentric grid; row 0 is the edge's arc
    for (int v = 0; v < int(verts.size()); ++v)
    {
        Vec3 c = Vec3::Zero();
        for (int k = P.vertexEdgeBegin(v); k < P.vertexEdgeEnd(v); ++k)
        {
            const int e = P.vertexEdges()[k];
            c += faces[P.edgeFaces()[e][0]].normal;
            c += faces[P.edgeFaces()[e][1]].normal;
        }
        c.normalize();

        for (int k = P.vertexEdgeBegin(v); k < P.vertexEdgeEnd(v); ++k)
        {
            const int e = P.vertexEdges()[k];
            const Vec3& na = faces[P.edgeFaces()[e][0]].normal;
            const Vec3& nb = faces[P.edgeFaces()[e][1]].normal;

            // Grid point (row k, column i), i = 0 .. s - row
            std::vector<int> row0, row1;
            auto makeRow = [&](int rowIndex, std::vector<int>& ids)
            {
                ids.clear();
                const double wc = double(rowIndex)/s;
                for (int i = 0; i <= s - rowIndex; ++i)
                {
                    const Vec3 dir =
                        rowIndex == 0
                      ? arc(na, nb, i, s)
                      : (
                            wc*c + (double(s - rowIndex - i)/s)*na
                          + (double(i)/s)*nb
                        ).normalized();
                    ids.push_back(int(m.points.size()));
                    m.points.push_back(verts[v] + r*dir);
                }
            };

            makeRow(0, row0);
            for (int rk = 0; rk < s; ++rk)
            {
                makeRow(rk + 1, row1);
                for (int i = 0; i < s - rk; ++i)
                {
                    addOriented(m, {row0[i], row0[i + 1], row1[i]});
                    if (i + 1 < s - rk)
                    {
                        addOriented(m, {row0[i + 1], row1[i + 1], row1[i]});
                    }
                }
                row0.swap(row1);
            }
        }
    }

    return m;
}


// ************************************************************************* //
