/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "worldDetail.H"
#include "prefetch.H"

namespace iceDEM
{

using namespace worldDetail;

// The bodies' world frames (the core's vertices at the pose, the angular
// velocity): computed once per force evaluation, by the thread that first
// needs one; and the reads of a pair's shapes asked for ahead


void World::resizeBodyFrames()
{
    const int N = static_cast<int>(bodies_.size());
    if (int(vertexOffset_.size()) != N + 1)
    {
        vertexOffset_.assign(N + 1, 0);
        for (int i = 0; i < N; ++i)
        {
            vertexOffset_[i + 1] =
                vertexOffset_[i] + int(shapeOf(i).core().vertices().size());
        }
        worldVertices_.resize(vertexOffset_[N]);
        omegas_.resize(N);
        frameEvaluation_.reset(new std::atomic<long>[N]);
        for (int i = 0; i < N; ++i) frameEvaluation_[i].store(0);
    }
}


void World::updateBodyFrame(int i)
{
    const Body& b = bodies_[i];
    const Mat3 R = b.rotation();
    omegas_[i] = b.omega(R);
    const auto& V = shapeOf(i).core().vertices();
    Vec3* w = worldVertices_.data() + vertexOffset_[i];
    for (std::size_t k = 0; k < V.size(); ++k)
    {
        w[k] = R*V[k] + b.x;
    }
}


void World::ensureBodyFrame(int i)
{
    std::atomic<long>& stamp = frameEvaluation_[i];
    long seen = stamp.load(std::memory_order_acquire);
    if (seen == evaluation_) return;
    if
    (
        seen != frameBusy
     && stamp.compare_exchange_strong(seen, frameBusy, std::memory_order_acquire)
    )
    {
        updateBodyFrame(i);
        stamp.store(evaluation_, std::memory_order_release);
        return;
    }
    // Another thread is computing it (a frame takes some 50 ns)
    while (stamp.load(std::memory_order_acquire) != evaluation_) {}
}


void World::prefetchPairShapes(const ContactPair& p) const
{
    prefetchRange(&shapeOf(p.i), sizeof(DilatedShape));
    if (!p.isWall()) prefetchRange(&shapeOf(p.j), sizeof(DilatedShape));
}


void World::prefetchPair(const ContactPair& p) const
{
    // What the world frames and the separating-axis test read first: the
    // two shapes' vertices (found from their headers, asked for earlier by
    // prefetchPairShapes) and the world vertices (body j is anywhere in
    // memory)
    auto prefetchBody = [this](int i)
    {
        const auto& V = shapeOf(i).core().vertices();
        const std::size_t bytes = V.size()*sizeof(Vec3);
        prefetchRange(V.data(), bytes);
        prefetchRange(worldVertices(i), bytes);
    };
    prefetchBody(p.i);
    if (!p.isWall()) prefetchBody(p.j);
}


void World::updateWorldVertices()
{
    resizeBodyFrames();
    const int N = static_cast<int>(bodies_.size());
    parallelRegion(N >= settings_.singleThreadBelow, [&]
    {
        #pragma omp for schedule(static)
        for (int i = 0; i < N; ++i)
        {
            updateBodyFrame(i);
            frameEvaluation_[i].store(evaluation_);
        }
    });
}

} // namespace iceDEM
