/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Voronoi field, step 8 (VoronoiField.H): the order of the floes, along a
    Hilbert curve through their centroids (hilbert) or that of the seed
    points (seed).
\*---------------------------------------------------------------------------*/

#include "field/voronoiFieldDetail.H"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace iceDEM
{

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

} // anonymous namespace


void voronoiDetail::numberAlongHilbertCurve
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


} // namespace iceDEM
