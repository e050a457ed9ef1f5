/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Voronoi field, steps 2-3 (VoronoiField.H): the Voronoi cells of the seed
    points clipped to the tessellation rectangle, and the Lloyd relaxation.
    CGAL is included first, as in every CGAL translation unit of the core;
    it only provides the Delaunay neighbours of the seed points (exact
    predicates), the cells are clipped here in a fixed order.
\*---------------------------------------------------------------------------*/

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "field/voronoiFieldDetail.H"

#include <algorithm>
#include <utility>

namespace iceDEM
{

using namespace voronoiDetail;

namespace
{

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using CgalPoint = Kernel::Point_2;

Polygon rectangle(double xmin, double xmax, double ymin, double ymax)
{
    return {Vec2(xmin, ymin), Vec2(xmax, ymin), Vec2(xmax, ymax), Vec2(xmin, ymax)};
}

} // anonymous namespace


Polygon voronoiDetail::clipHalfPlane
(
    const Polygon& poly,
    const Vec2& n,
    double c
)
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


void voronoiDetail::lloydRelaxation
(
    std::vector<Vec2>& seeds,
    int iterations,
    double xmin,
    double xmax,
    double ymin,
    double ymax
)
{
    for (int it = 0; it < iterations; ++it)
    {
        const std::vector<Polygon> cells =
            voronoiCells(seeds, xmin, xmax, ymin, ymax);
        for (std::size_t i = 0; i < seeds.size(); ++i)
        {
            if (cells[i].size() >= 3)
            {
                seeds[i] = polygonCentroid(cells[i]);
            }
        }
    }
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


} // namespace iceDEM
