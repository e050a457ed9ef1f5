/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "worldDetail.H"
#include "contact/NarrowPhase.H"
#include "contact/NeighbourList.H"
#include "domain/InflowOutflow.H"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace iceDEM
{

using namespace worldDetail;

void World::stepBy(double dt)
{
    if (!initialised_)
    {
        initialise();
    }
    if (firstInserted_ >= 0)
    {
        joinInserted();
    }
    resizeBodyFrames();
    ++evaluation_;
    preparePairs();
    const int N = static_cast<int>(bodies_.size());

    // Without body-force models the whole step is one parallel region;
    // models prepare serially (flow sampling), between two regions
    const bool oneRegion = forceModels_.empty();
    const bool listCoversBodies = nlist_->coversBodies(bodies_.size());
    bool rebuild = !listCoversBodies;
    const bool periodic = domain_ != nullptr;

    // One team for the first half step, the world frames, the neighbour
    // list and the contacts (fewer fork-joins and barriers: on a loaded
    // machine each waits for the slowest thread)
    #pragma omp parallel if(N >= minParallelBodies)
    {
        // First half kick, drift, rotation; then the neighbour list's
        // check (some body moved more than skin/2) and the body's motion
        // bound (the world frames follow in the pair loop, where needed)
        #pragma omp for schedule(static) reduction(||: rebuild)
        for (int i = 0; i < N; ++i)
        {
            Body& b = bodies_[i];
            if (b.isFree())
            {
                halfKick(b, dt);
                b.x += dt*b.v;
                rotateFree(b.q, b.L, b.invInertia, dt);
            }
            if (listCoversBodies && nlist_->track(i, b.x, b.q))
            {
                rebuild = true;
            }
            // Migration: a free body leaving through a periodic side
            // re-enters at the other (after track: its motion bound is
            // that of the unwrapped path); the list is rebuilt
            if (periodic && b.isFree())
            {
                const int w = domain_->wrap(b.x);
                if (w != Domain::noImage)
                {
                    wrapped_[i] = w;
                    rebuild = true;
                }
            }
        }

        if (rebuild)
        {
            #pragma omp single
            {
                nlist_->build(*this);
                if (periodic) std::fill(wrapped_.begin(), wrapped_.end(), int(Domain::noImage));
                preparePairs();
            }
        }

        pairForces(dt);

        if (oneRegion) sumBodyForces(dt);
    }

    // Body-force models: their serial preparation, then the body sums and
    // the second half kick
    if (!oneRegion) bodyForces(dt);
    time_ += dt;
    ++step_;

    // Bodies leave and enter between steps
    if (inflowOutflow_) inflowOutflow_->update(*this);
}


void World::step()
{
    stepBy(settings_.timeStep);
}


void World::advanceTo(double t)
{
    const double dt = settings_.timeStep;
    // Steps shorter than this fraction of dt are merged into the last one
    constexpr double mergeFraction = 1e-6;
    while (t - time_ > mergeFraction*dt)
    {
        const double remaining = t - time_;
        if (remaining < (1 + mergeFraction)*dt)
        {
            // The last step: a full one when only round-off separates them,
            // so the trajectory does not depend on how t was summed (a
            // restart reads t from a directory name)
            stepBy(remaining > (1 - mergeFraction)*dt ? dt : remaining);
            time_ = t;
        }
        else
        {
            stepBy(dt);
        }
    }
}


void World::setPrescribedState
(
    int i,
    const Vec3& x,
    const Quat& q,
    const Vec3& v,
    const Vec3& omega
)
{
    Body& b = bodies_.at(i);
    if (b.motion != BodyMotion::prescribed)
    {
        throw Error("setPrescribedState on a body whose motion is not prescribed");
    }
    b.x = x;
    b.q = q.normalized();
    b.v = v;
    b.setOmega(omega);
}

} // namespace iceDEM
