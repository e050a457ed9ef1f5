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

    //- Blocks of consecutive bodies (pairs) in which build searches the grid
    //  (carries the pairs over) as tasks: the threads of a team waiting for
    //  the build take them (a serial build was 4 % of the 90 % pack's step
    //  on two threads, the other thread waiting); several per thread, so
    //  that a thread held up does not hold up the build
    constexpr int buildBlocks = 32;

    //- Order of pairs: by i, then bodies before walls, then by image
    inline long long pairKey(int i, int j, int image, int nBodies)
    {
        const long long jj = j >= 0 ? j : nBodies + (-1 - j);
        return (static_cast<long long>(i)*(nBodies + 1000000LL) + jj)*9 + image;
    }
}


void NeighbourList::build(const World& world)
{
    const std::vector<Body>& bodies = world.bodies();
    const int N = static_cast<int>(bodies.size());
    const Domain* domain = world.domain();
    const bool periodic = domain && domain->active();
    ++builds_;

    candidates_.clear();
    extras_.clear();

    radius_.resize(N);
    for (int i = 0; i < N; ++i)
    {
        radius_[i] = world.shapeOf(i).boundingRadius();
    }
    const std::vector<double>& R = radius_;

    auto movable = [&](int i, int j)
    {
        return bodies[i].isFree() || bodies[j].isFree();
    };
    //- Body i and body j at y (j itself or an image of it) are candidates
    auto close = [&](int i, int j, const Vec3& y)
    {
        const double reach = R[i] + R[j] + skin_;
        return (bodies[i].x - y).squaredNorm() < reach*reach;
    };
    //- The order of the pairs (pairKey)
    auto key = [N](const Candidate& c) { return pairKey(c.i, c.j, c.image, N); };
    auto before = [&key](const Candidate& a, const Candidate& b) { return key(a) < key(b); };
    //- The pair of i with image 'image' of j, stored with the smaller
    //  index first (the image then applies to the other), among extras:
    //  the pairs that do not come in the grid's order (below)
    auto addPair = [](std::vector<Candidate>& extras, int i, int j, int image)
    {
        if (i < j) extras.push_back({i, j, image});
        else extras.push_back({j, i, Domain::inverse(image)});
    };

    if (N > 1)
    {
        // Small and large bodies
        std::vector<double> sorted(R);
        std::nth_element(sorted.begin(), sorted.begin() + N/2, sorted.end());
        const double rMedian = sorted[N/2];
        const double largeLimit = largeBodyFactor*rMedian;

        std::vector<int> small, large;
        double rMax = 0;
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
            }
        }

        // Grid items: the small bodies, then their ghosts near a periodic
        // side (within the reach of a pair of small bodies)
        items_.clear();
        for (int i : small) items_.push_back(Ghost{i, Domain::noImage, bodies[i].x});
        const int nReal = static_cast<int>(items_.size());
        if (periodic) domain->ghosts(bodies, small, 2*rMax + skin_, items_);
        const int nItems = static_cast<int>(items_.size());

        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max());
        Vec3 hi = -lo;
        for (const Ghost& g : items_)
        {
            lo = lo.cwiseMin(g.x);
            hi = hi.cwiseMax(g.x);
        }

        if (nReal > 0)
        {
            // Cells as wide as the reach of a pair of median bodies; each
            // real body searches the cells within its own reach of the
            // largest small body, R_i + rMax + skin (cells as wide as the
            // largest reach held about 15 floes each in a pack of Voronoi
            // floes, whose largest radius is three times their smallest:
            // a body tested some 130 items for its 6 neighbours)
            double h = 2*rMedian + skin_;
            const Vec3 extent = hi - lo;
            auto cellsFor = [&](double hh)
            {
                return (std::floor(extent.x()/hh) + 1)
                      *(std::floor(extent.y()/hh) + 1)
                      *(std::floor(extent.z()/hh) + 1);
            };
            const double maxCells = maxCellsPerBody*nItems + 64;
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

            // Counting sort of the items by cell (stable: by item)
            cellOf_.assign(nItems, -1);
            cellStart_.assign(nCells + 1, 0);
            for (int k = 0; k < nItems; ++k)
            {
                int cx, cy, cz;
                cellOf_[k] = cellIndex(items_[k].x, cx, cy, cz);
                ++cellStart_[cellOf_[k] + 1];
            }
            for (int c = 0; c < nCells; ++c)
            {
                cellStart_[c + 1] += cellStart_[c];
            }
            // The items themselves in cell order: the search below reads
            // them one after the other
            cellItems_.resize(nItems);
            std::vector<int> fill(cellStart_.begin(), cellStart_.end() - 1);
            for (int k = 0; k < nItems; ++k)
            {
                cellItems_[fill[cellOf_[k]]++] = items_[k];
            }

            // The cells [first, last] along each axis that hold every item
            // within 'reach' of x (widened by a relative 1e-9 against the
            // rounding of the bounds; clamped to the grid)
            const int n[3] = {nx, ny, nz};
            auto cellRange = [&](const Vec3& x, double reach, int first[3], int last[3])
            {
                const double wide = reach*(1 + 1e-9);
                for (int d = 0; d < 3; ++d)
                {
                    const double a = std::floor((x[d] - wide - lo[d])/h);
                    const double b = std::floor((x[d] + wide - lo[d])/h);
                    first[d] = int(std::max(0.0, std::min(double(n[d] - 1), a)));
                    last[d] = int(std::max(0.0, std::min(double(n[d] - 1), b)));
                }
            };

            // Real bodies against the items within their reach. The real
            // items come in the order of their bodies, so the candidates
            // come by i; each body's are sorted by (j, image) as they
            // come, and a pair found from its larger index (through an
            // image) joins the block's extras
            const auto searchBlock = [&](SearchBlock& block, int rBegin, int rEnd)
            {
                std::vector<Candidate>& found = block.candidates;
                found.clear();
                block.extras.clear();
                for (int r = rBegin; r < rEnd; ++r)
                {
                    const int i = items_[r].body;
                    const std::size_t segment = found.size();
                    int first[3], last[3];
                    cellRange(bodies[i].x, R[i] + rMax + skin_, first, last);
                    for (int z = first[2]; z <= last[2]; ++z)
                    for (int y = first[1]; y <= last[1]; ++y)
                    for (int x = first[0]; x <= last[0]; ++x)
                    {
                        const int c = (z*ny + y)*nx + x;
                        for (int k = cellStart_[c]; k < cellStart_[c + 1]; ++k)
                        {
                            // The distance first: it reads the item and the
                            // radii, movable reads body j (a cache miss for
                            // most items, which are not close)
                            const Ghost& g = cellItems_[k];
                            const int j = g.body;
                            if (g.image == Domain::noImage)
                            {
                                if (j > i && close(i, j, g.x) && movable(i, j))
                                {
                                    found.push_back({i, j, Domain::noImage});
                                }
                            }
                            else if (j != i && close(i, j, g.x) && movable(i, j))
                            {
                                if (i < j) found.push_back({i, j, g.image});
                                else addPair(block.extras, i, j, g.image);
                            }
                        }
                    }
                    std::sort(found.begin() + segment, found.end(), before);
                }
            };
            // In blocks searched as tasks (by the team that waits for this
            // build, if any), joined in the bodies' order: the same lists
            // whoever searched a block
            const int nBlocks = std::min(nReal, buildBlocks);
            if (int(blocks_.size()) < nBlocks) blocks_.resize(nBlocks);
            #pragma omp taskloop grainsize(1) default(shared)
            for (int b = 0; b < nBlocks; ++b)
            {
                int rBegin, rEnd;
                equalShare(nReal, b, nBlocks, rBegin, rEnd);
                searchBlock(blocks_[b], rBegin, rEnd);
            }
            for (int b = 0; b < nBlocks; ++b)
            {
                const SearchBlock& block = blocks_[b];
                candidates_.insert(candidates_.end(), block.candidates.begin(), block.candidates.end());
                extras_.insert(extras_.end(), block.extras.begin(), block.extras.end());
            }
        }

        // Large bodies against everything (and every image of it)
        for (int L : large)
        {
            for (int j = 0; j < N; ++j)
            {
                if (j == L) continue;
                const bool isLarge = R[j] > largeLimit;
                if (isLarge && j < L) continue;    // large pair once
                if (!movable(L, j)) continue;
                if (close(L, j, bodies[j].x))
                {
                    addPair(extras_, L, j, Domain::noImage);
                }
                if (!periodic) continue;
                for (int image = 0; image < 9; ++image)
                {
                    if (image == Domain::noImage) continue;
                    // By the image's code: along a direction that is not
                    // periodic the shift is zero, and the image would be
                    // the body itself (its contacts counted again)
                    if
                    (
                        (Domain::imageX(image) != 0 && !domain->periodic(0))
                     || (Domain::imageY(image) != 0 && !domain->periodic(1))
                    )
                    {
                        continue;
                    }
                    const Vec3 s = domain->shift(image);
                    if (close(L, j, bodies[j].x + s)) addPair(extras_, L, j, image);
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
                extras_.push_back({i, -1 - w, Domain::noImage});
            }
        }
    }

    // The grid's candidates (sorted) and the extras (sorted here: the
    // pairs through images found from their larger index, those of the
    // large bodies and of the walls) merged, then each pair once (a pair
    // through an image is found from both of its bodies)
    if (!extras_.empty())
    {
        std::sort(extras_.begin(), extras_.end(), before);
        merged_.resize(candidates_.size() + extras_.size());
        std::merge
        (
            candidates_.begin(), candidates_.end(),
            extras_.begin(), extras_.end(),
            merged_.begin(), before
        );
        candidates_.swap(merged_);
    }
    candidates_.erase
    (
        std::unique
        (
            candidates_.begin(), candidates_.end(),
            [&key](const Candidate& a, const Candidate& b) { return key(a) == key(b); }
        ),
        candidates_.end()
    );

    // Pairs of bodies wrapped since the last build (periodic domain): the
    // image of j relative to i changes by the wraps (the image then moves
    // with i: a feature-pair list's relative pose is unchanged)
    const std::vector<int>& wraps = world.wraps();
    std::vector<std::pair<long long, int>> oldOrder;
    bool wrapped = false;
    if (periodic && int(wraps.size()) == N && coversBodies(N))
    {
        for (int w : wraps) wrapped = wrapped || w != Domain::noImage;
    }
    if (wrapped)
    {
        oldOrder.reserve(pairs_.size());
        for (int k = 0; k < int(pairs_.size()); ++k)
        {
            ContactPair& p = pairs_[k];
            const int wi = wraps[p.i];
            const int wj = p.isWall() ? Domain::noImage : wraps[p.j];
            if (wi == Domain::noImage && wj == Domain::noImage)
            {
                oldOrder.emplace_back(pairKey(p.i, p.j, p.image, N), k);
                continue;
            }
            int image = p.image;
            if (!p.isWall())
            {
                image = Domain::afterWraps(p.image, wi, wj);
            }
            if (image < 0) continue;    // out of reach: its history ends
            p.image = image;
            oldOrder.emplace_back(pairKey(p.i, p.j, p.image, N), k);
        }
        std::sort(oldOrder.begin(), oldOrder.end());
    }

    // New pairs, carrying over the contacts of pairs that persist. Their
    // separation certificates move to the new reference poses: less the
    // motion since the last build (track() ran for every body this step
    // when the list covered the bodies; otherwise they start anew)
    const bool carryCertificates = coversBodies(N);
    const std::size_t nOld = wrapped ? oldOrder.size() : pairs_.size();
    auto oldPair = [&](std::size_t k) -> const ContactPair&
    {
        return wrapped ? pairs_[oldOrder[k].second] : pairs_[k];
    };
    auto oldKey = [&](std::size_t k)
    {
        if (wrapped) return oldOrder[k].first;
        return pairKey(pairs_[k].i, pairs_[k].j, pairs_[k].image, N);
    };
    // In blocks of consecutive pairs, as tasks like the search; each block
    // finds its first old pair by bisection (both lists are sorted by key)
    const int nNew = static_cast<int>(candidates_.size());
    std::vector<ContactPair>& next = sparePairs_;
    next.resize(nNew);
    const auto carryBlock = [&](int kBegin, int kEnd)
    {
        if (kBegin == kEnd) return;
        std::size_t lo = 0, hi = nOld;
        const long long firstKey = key(candidates_[kBegin]);
        while (lo < hi)
        {
            const std::size_t mid = lo + (hi - lo)/2;
            if (oldKey(mid) < firstKey) lo = mid + 1;
            else hi = mid;
        }
        std::size_t old = lo;
        for (int k = kBegin; k < kEnd; ++k)
        {
            ContactPair& p = next[k];
            const long long pk = key(candidates_[k]);
            while (old < nOld && oldKey(old) < pk)
            {
                ++old;
            }
            if (old < nOld && oldKey(old) == pk)
            {
                p = oldPair(old);
                p.clearance = carryCertificates
                    ? p.clearance - motion(p)
                    : std::numeric_limits<double>::lowest();
            }
            else
            {
                p = ContactPair{};
                p.i = candidates_[k].i;
                p.j = candidates_[k].j;
                p.image = candidates_[k].image;
            }
        }
    };
    const int nCarry = std::min(nNew, buildBlocks);
    #pragma omp taskloop grainsize(1) default(shared)
    for (int b = 0; b < nCarry; ++b)
    {
        int kBegin, kEnd;
        equalShare(nNew, b, nCarry, kBegin, kEnd);
        carryBlock(kBegin, kEnd);
    }
    pairs_.swap(next);
    hasContacts_.clear();

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
        poseAtBuild_[i] = BuildPose{bodies[i].q, bodies[i].x};
    }
    motion_.assign(N, 0);

    // A new drifting frame: the free bodies' mean velocity (summed in body
    // order: the same whatever the threads)
    Vec3 sum = Vec3::Zero();
    int nFree = 0;
    for (const Body& b : bodies)
    {
        if (!b.isFree()) continue;
        sum += b.v;
        ++nFree;
    }
    driftVelocity_ = nFree > 0 ? Vec3(sum/nFree) : Vec3::Zero();
    drift_.setZero();
    driftLength_ = 0;
}


bool NeighbourList::applyWraps(const std::vector<int>& wraps, const Domain& domain)
{
    const int N = static_cast<int>(poseAtBuild_.size());
    if (int(wraps.size()) != N || int(bodyStart_.size()) != N + 1) return false;

    auto newImage = [&wraps](const ContactPair& p)
    {
        return Domain::afterWraps(p.image, wraps[p.i], wraps[p.j]);
    };

    // Checked first, so that a refusal leaves the list as it was
    for (int i = 0; i < N; ++i)
    {
        if (wraps[i] == Domain::noImage) continue;
        for (int k = bodyStart_[i]; k < bodyStart_[i + 1]; ++k)
        {
            const ContactPair& p = pairs_[bodyPairs_[k]];
            if (!p.isWall() && newImage(p) < 0) return false;
        }
    }
    for (int i = 0; i < N; ++i)
    {
        const int w = wraps[i];
        if (w == Domain::noImage) continue;
        for (int k = bodyStart_[i]; k < bodyStart_[i + 1]; ++k)
        {
            ContactPair& p = pairs_[bodyPairs_[k]];
            if (p.isWall()) continue;
            // Once per pair: from its first body that wrapped
            const int first = wraps[p.i] != Domain::noImage ? p.i : p.j;
            if (first == i) p.image = newImage(p);
        }
        poseAtBuild_[i].x += domain.shift(w);
    }
    return true;
}


void NeighbourList::appendList
(
    ContactPair& p,
    StoredFeatureList L,
    const FeaturePairEntry* entries
)
{
    L.firstEntry = static_cast<int>(listEntries_.size());
    listEntries_.insert(listEntries_.end(), entries, entries + L.count);
    p.featureList = static_cast<int>(lists_.size());
    lists_.push_back(L);
}


void NeighbourList::compactLists()
{
    // The pools become the spares, read while the kept lists are appended
    // to the emptied spares of the last compaction
    lists_.swap(spareLists_);
    listEntries_.swap(spareEntries_);
    lists_.clear();
    listEntries_.clear();
    lists_.reserve(spareLists_.size());
    listEntries_.reserve(spareEntries_.size());
    for (ContactPair& p : pairs_)
    {
        if (p.featureList < 0) continue;
        const StoredFeatureList& L = spareLists_[p.featureList];
        appendList(p, L, spareEntries_.data() + L.firstEntry);
    }
}


std::size_t NeighbourList::bytes() const
{
    return (pairs_.capacity() + sparePairs_.capacity())*sizeof(ContactPair)
        + contacts_.capacity()*sizeof(StoredContact)
        + lists_.capacity()*sizeof(StoredFeatureList)
        + listEntries_.capacity()*sizeof(FeaturePairEntry)
        + spareLists_.capacity()*sizeof(StoredFeatureList)
        + spareEntries_.capacity()*sizeof(FeaturePairEntry)
        + (bodyStart_.capacity() + bodyPairs_.capacity())*sizeof(int);
}

} // namespace iceDEM
