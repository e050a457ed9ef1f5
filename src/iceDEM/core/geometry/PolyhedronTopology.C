/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "PolyhedronTopology.H"
#include "types.H"

#include <algorithm>
#include <iterator>
#include <map>
#include <mutex>

namespace iceDEM
{

namespace
{
    //- The registry behind PolyhedronTopology::shared(): content -> the
    //  topology, held weakly so that a topology no polyhedron uses any more
    //  is freed. Function-local statics: usable from other static objects.
    struct Registry
    {
        std::mutex mutex;
        std::map<std::vector<int>, std::weak_ptr<const PolyhedronTopology>> byContent;
        //- Size at which expired entries are swept next
        std::size_t sweepAt = 64;
    };

    Registry& registry()
    {
        static Registry r;
        return r;
    }

    //- The content that determines a topology: vertex count, face count,
    //  loop sizes, then the loops
    std::vector<int> contentKey(int nVertices, const std::vector<std::vector<int>>& loops)
    {
        std::vector<int> key{nVertices, static_cast<int>(loops.size())};
        for (const auto& loop : loops) key.push_back(static_cast<int>(loop.size()));
        for (const auto& loop : loops) key.insert(key.end(), loop.begin(), loop.end());
        return key;
    }
}


PolyhedronTopology::PolyhedronTopology
(
    int nVertices,
    const std::vector<std::vector<int>>& faceLoops
)
:
    nVertices_(nVertices)
{
    for (const auto& loop : faceLoops)
    {
        faces_.push_back
        (
            {static_cast<int>(faceVertices_.size()), static_cast<int>(loop.size())}
        );
        faceVertices_.insert(faceVertices_.end(), loop.begin(), loop.end());
    }

    // Each directed edge a->b once; its reverse b->a in exactly one other face
    std::map<std::pair<int, int>, int> directed;
    for (int f = 0; f < nFaces(); ++f)
    {
        const FaceLoop& F = faces_[f];
        for (int k = 0; k < F.count; ++k)
        {
            const int a = faceVertices_[F.begin + k];
            const int b = faceVertices_[F.begin + (k + 1) % F.count];
            if (!directed.emplace(std::make_pair(a, b), f).second)
            {
                throw Error("the surface is not a closed oriented polyhedron", "points");
            }
        }
    }

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

    std::vector<int> degree(nVertices_, 0);
    for (const auto& e : edges_)
    {
        ++degree[e[0]];
        ++degree[e[1]];
    }
    vertexEdgeStart_.assign(nVertices_ + 1, 0);
    for (int v = 0; v < nVertices_; ++v)
    {
        if (degree[v] < 3)
        {
            throw Error("a vertex belongs to fewer than 3 edges (unused or degenerate vertex)", "points");
        }
        vertexEdgeStart_[v + 1] = vertexEdgeStart_[v] + degree[v];
    }
    vertexEdges_.assign(vertexEdgeStart_.back(), -1);
    std::vector<int> fill(vertexEdgeStart_.begin(), vertexEdgeStart_.end() - 1);
    for (int e = 0; e < nEdges(); ++e)
    {
        vertexEdges_[fill[edges_[e][0]]++] = e;
        vertexEdges_[fill[edges_[e][1]]++] = e;
    }

    // Euler characteristic of a sphere
    if (nVertices_ - nEdges() + nFaces() != 2)
    {
        throw Error("the surface is not a closed polyhedron (V - E + F != 2)", "points");
    }

    // Edge of each face loop slot: the edge at its first vertex that ends
    // at the next one
    faceEdge_.assign(faceVertices_.size(), -1);
    for (const FaceLoop& F : faces_)
    {
        for (int k = 0; k < F.count; ++k)
        {
            const int a = faceVertices_[F.begin + k];
            const int b = faceVertices_[F.begin + (k + 1) % F.count];
            for (int m = vertexEdgeStart_[a]; m < vertexEdgeStart_[a + 1]; ++m)
            {
                const auto& e = edges_[vertexEdges_[m]];
                if ((e[0] == a ? e[1] : e[0]) == b)
                {
                    faceEdge_[F.begin + k] = vertexEdges_[m];
                }
            }
        }
    }

    // Exactly as large as needed: the object lives as long as its polyhedra
    faces_.shrink_to_fit();
    faceVertices_.shrink_to_fit();
    edges_.shrink_to_fit();
    edgeFaces_.shrink_to_fit();
}


std::shared_ptr<const PolyhedronTopology> PolyhedronTopology::shared
(
    int nVertices,
    const std::vector<std::vector<int>>& faceLoops
)
{
    std::vector<int> key = contentKey(nVertices, faceLoops);

    Registry& reg = registry();
    std::lock_guard<std::mutex> lock(reg.mutex);

    auto it = reg.byContent.find(key);
    if (it != reg.byContent.end())
    {
        if (auto existing = it->second.lock())
        {
            return existing;
        }
    }

    // Built under the lock: a throw leaves the registry unchanged
    std::shared_ptr<const PolyhedronTopology> topo
    (
        new PolyhedronTopology(nVertices, faceLoops)
    );

    if (it != reg.byContent.end())
    {
        it->second = topo;
    }
    else
    {
        if (reg.byContent.size() >= reg.sweepAt)
        {
            for (auto e = reg.byContent.begin(); e != reg.byContent.end();)
            {
                e = e->second.expired() ? reg.byContent.erase(e) : std::next(e);
            }
            reg.sweepAt = std::max<std::size_t>(64, 2*reg.byContent.size());
        }
        reg.byContent.emplace(std::move(key), topo);
    }
    return topo;
}


const std::shared_ptr<const PolyhedronTopology>& PolyhedronTopology::empty()
{
    static const std::shared_ptr<const PolyhedronTopology> none(new PolyhedronTopology());
    return none;
}


std::size_t PolyhedronTopology::heapBytes() const
{
    return faces_.capacity()*sizeof(FaceLoop)
        + faceVertices_.capacity()*sizeof(int)
        + edges_.capacity()*sizeof(edges_[0])
        + edgeFaces_.capacity()*sizeof(edgeFaces_[0])
        + vertexEdgeStart_.capacity()*sizeof(int)
        + vertexEdges_.capacity()*sizeof(int)
        + faceEdge_.capacity()*sizeof(int);
}


std::size_t PolyhedronTopology::sharedCount()
{
    Registry& reg = registry();
    std::lock_guard<std::mutex> lock(reg.mutex);
    std::size_t n = 0;
    for (const auto& e : reg.byContent)
    {
        if (!e.second.expired()) ++n;
    }
    return n;
}

} // namespace iceDEM
