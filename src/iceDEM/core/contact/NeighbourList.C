/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "NeighbourList.H"

#include <algorithm>
#include <cmath>

namespace iceDEM
{

namespace
{
    //- Bodies with a bounding radius above this multiple of the median are
    //  "large" (a structure among floes) and are tested against all bodies
    //  instead of sizing the grid cells
    constexpr double largeBodyFactor = 3.0;

    //- At most this many grid cells per body (a sparse field enlarges cells)
    constexpr double maxCellsPerBody = 8.0;

    //- Order of pairs: by i, then bodies before walls
    inline long long pairKey(int i, int j, int nBodies)
    {
        const long long jj = j >= 0 ? j : nBodies + (-1 - j);
        return static_cast<long long>(i)*(nBodies + 1000000LL) + jj;
    }
}


void NeighbourList::build(const World& world)
{
    const std::vector<Body>& bodies = world.bodies();
    const int N = static_cast<int>(bodies.size());
    ++builds_;

    candidates_.clear();

    std::vector<double> R(N);
    for (int i = 0; i < N; ++i)
    {
        R[i] = world.shapeOf(i).boundingRadius();
    }

    auto close = [&](int i, int j)
    {
        const double reach = R[i] + R[j] + skin_;
        return (bodies[i].x - bodies[j].x).squaredNorm() < reach*reach;
    };
    auto movable = [&](int i, int j)
    {
        return bodies[i].isFree() || bodies[j].isFree();
    };

    if (N > 1)
    {
        // Small and large bodies
        std::vector<double> sorted(R);
        std::nth_element(sorted.begin(), sorted.begin() + N/2, sorted.end());
        const double largeLimit = largeBodyFactor*sorted[N/2];

        std::vector<int> small, large;
        double rMax = 0;
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max());
        Vec3 hi = -lo;
        for (int i = 0; i < N; ++i)
        {
            if (R[i] > largeLimit)
            {
                large.push_back(i);
            }
            else
            {
                small.push_back(i);
                rMax = std::max(rMax, R[i]);
                lo = lo.cwiseMin(bodies[i].x);
                hi = hi.cwiseMax(bodies[i].x);
            }
        }

        if (!small.empty())
        {
            // Cells at least one interaction range wide: neighbours are in
            // the 27 surrounding cells
            double h = 2*rMax + skin_;
            const Vec3 extent = hi - lo;
            auto cellsFor = [&](double hh)
            {
                return (std::floor(extent.x()/hh) + 1)
                      *(std::floor(extent.y()/hh) + 1)
                      *(std::floor(extent.z()/hh) + 1);
            };
            const double maxCells = maxCellsPerBody*small.size() + 64;
            while (cellsFor(h) > maxCells)
            {
                h *= 1.5;
            }
            const int nx = int(std::floor(extent.x()/h)) + 1;
            const int ny = int(std::floor(extent.y()/h)) + 1;
            const int nz = int(std::floor(extent.z()/h)) + 1;
            const int nCells = nx*ny*nz;

            auto cellIndex = [&](const Vec3& x, int& cx, int& cy, int& cz)
            {
                cx = std::min(nx - 1, int((x.x() - lo.x())/h));
                cy = std::min(ny - 1, int((x.y() - lo.y())/h));
                cz = std::min(nz - 1, int((x.z() - lo.z())/h));
                return (cz*ny + cy)*nx + cx;
            };

            // Counting sort of the small bodies by cell (stable: by index)
            cellOf_.assign(N, -1);
            cellStart_.assign(nCells + 1, 0);
            for (int i : small)
            {
                int cx, cy, cz;
                cellOf_[i] = cellIndex(bodies[i].x, cx, cy, cz);
                ++cellStart_[cellOf_[i] + 1];
            }
            for (int c = 0; c < nCells; ++c)
            {
                cellStart_[c + 1] += cellStart_[c];
            }
            cellBodies_.assign(small.size(), -1);
            std::vector<int> fill(cellStart_.begin(), cellStart_.end() - 1);
            for (int i : small)
            {
                cellBodies_[fill[cellOf_[i]]++] = i;
            }

            for (int i : small)
            {
                int cx, cy, cz;
                cellIndex(bodies[i].x, cx, cy, cz);
                for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                {
                    const int x = cx + dx, y = cy + dy, z = cz + dz;
                    if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz)
                    {
                        continue;
                    }
                    const int c = (z*ny + y)*nx + x;
                    for (int k = cellStart_[c]; k < cellStart_[c + 1]; ++k)
                    {
                        const int j = cellBodies_[k];
                        if (j > i && movable(i, j) && close(i, j))
                        {
                            candidates_.emplace_back(i, j);
                        }
                    }
                }
            }
        }

        // Large bodies against everything
        for (int L : large)
        {
            for (int j = 0; j < N; ++j)
            {
                if (j == L) continue;
                const bool isLarge = R[j] > largeLimit;
                if (isLarge && j < L) continue;    // large pair once
                if (movable(L, j) && close(L, j))
                {
                    candidates_.emplace_back(std::min(L, j), std::max(L, j));
                }
            }
        }
    }

    // Walls
    const auto& walls = world.walls();
    for (int i = 0; i < N; ++i)
    {
        if (!bodies[i].isFree()) continue;
        for (int w = 0; w < int(walls.size()); ++w)
        {
            const double d = walls[w].normal.dot(bodies[i].x - walls[w].point);
            if (d < R[i] + skin_)
            {
                candidates_.emplace_back(i, -1 - w);
            }
        }
    }

    std::sort
    (
        candidates_.begin(), candidates_.end(),
        [N](const std::pair<int, int>& a, const std::pair<int, int>& b)
        {
            return pairKey(a.first, a.second, N) < pairKey(b.first, b.second, N);
        }
    );
    candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());

    // New pairs, carrying over the contacts of pairs that persist. Their
    // separation certificates move to the new reference poses: less the
    // motion since the last build (track() ran for every body this step
    // when the list covered the bodies; otherwise they start anew)
    const bool carryCertificates = coversBodies(N);
    std::vector<ContactPair> next(candidates_.size());
    std::size_t old = 0;
    for (std::size_t k = 0; k < candidates_.size(); ++k)
    {
        ContactPair& p = next[k];
        p.i = candidates_[k].first;
        p.j = candidates_[k].second;
        const long long key = pairKey(p.i, p.j, N);
        while (old < pairs_.size() && pairKey(pairs_[old].i, pairs_[old].j, N) < key)
        {
            ++old;
        }
        if (old < pairs_.size() && pairKey(pairs_[old].i, pairs_[old].j, N) == key)
        {
            p = pairs_[old];
            p.clearance = carryCertificates
                ? p.clearance - motion(p)
                : std::numeric_limits<double>::lowest();
        }
    }
    pairs_.swap(next);

    // Per-body pair lists
    bodyStart_.assign(N + 1, 0);
    for (const ContactPair& p : pairs_)
    {
        ++bodyStart_[p.i + 1];
        if (!p.isWall()) ++bodyStart_[p.j + 1];
    }
    for (int b = 0; b < N; ++b)
    {
        bodyStart_[b + 1] += bodyStart_[b];
    }
    bodyPairs_.assign(bodyStart_[N], -1);
    std::vector<int> fill(bodyStart_.begin(), bodyStart_.end() - 1);
    for (int k = 0; k < int(pairs_.size()); ++k)
    {
        bodyPairs_[fill[pairs_[k].i]++] = k;
        if (!pairs_[k].isWall()) bodyPairs_[fill[pairs_[k].j]++] = k;
    }

    poseAtBuild_.resize(N);
    for (int i = 0; i < N; ++i)
    {
        poseAtBuild_[i] = BuildPose{bodies[i].q, bodies[i].x, R[i]};
    }
    motion_.assign(N, 0);
}


std::size_t NeighbourList::bytes() const
{
    return pairs_.capacity()*sizeof(ContactPair)
        + contacts_.capacity()*sizeof(StoredContact)
        + lists_.capacity()*sizeof(StoredFeatureList)
        + listEntries_.capacity()*sizeof(std::uint32_t)
        + (bodyStart_.capacity() + bodyPairs_.capacity())*sizeof(int);
}

} // namespace iceDEM
