/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "worldDetail.H"
#include "contact/NeighbourList.H"

#include <algorithm>

namespace iceDEM
{

using namespace worldDetail;

// A body's sums: its contacts' loads in its fixed pair order, the
// body-force models and gravity, the second half kick


void World::sumBodyForces(double dtKick, int slowScale)
{
    const int N = static_cast<int>(bodies_.size());

    // Orphaned: called inside a parallel region (or by one thread). Each
    // thread takes a chunk of bodies and does all of a body's work, so the
    // chunk needs no barrier: contact sums in the body's fixed pair order,
    // body-force models, totals and the second half kick. The chunks are
    // evened out by their times (LoopBalance; the steps with body-force
    // models and those without apart), from the next evaluation on, and a
    // thread done with its chunk takes blocks of the other's
    const bool models = !forceModels_.empty() && slowScale > 0;
    const ThreadShare share(N);
    forEachClaimedBlock
    (
        sumBalance_[models ? 1 : 0], share.thread, share.nThreads, N,
        bodyBlock, &wallClock,
        [&](int begin, int end, bool)
        {
            sumBodyChunk(begin, end, dtKick, slowScale, models);
        }
    );
}


void World::sumBodyChunk
(
    int begin,
    int end,
    double dtKick,
    int slowScale,
    bool models
)
{
    for (int b = begin; b < end; ++b)
    {
        const ContactLoad c = contactLoad(b);
        bodies_[b].force = c.force;
        bodies_[b].torque = c.torque;
    }

    if (models)
    {
        for (int b = begin; b < end; ++b)
        {
            modelForce_[b].setZero();
            modelTorque_[b].setZero();
        }
        // Body by body, then model by model: the hydrodynamic models of a
        // floe share its transformed and clipped polyhedron
        // (hydro/WaterFrame.H); a body's sum is in model order, as before
        for (int b = begin; b < end; ++b)
        {
            for (const auto& m : forceModels_)
            {
                m->addForces(*this, b, b + 1, modelForce_.data(), modelTorque_.data());
            }
        }
    }

    if (bodyForceInterval() == 1)
    {
        for (int b = begin; b < end; ++b)
        {
            Body& body = bodies_[b];
            if (models)
            {
                body.force += modelForce_[b];
                body.torque += modelTorque_[b];
            }
            if (body.isFree())
            {
                body.force += body.mass*settings_.gravity;
                // Second half kick of a step (velocity Verlet)
                if (dtKick > 0) halfKick(body, dtKick);
            }
            storable(body, settings_.storeFloor);
        }
        return;
    }

    // Multi-rate step (WorldStep.C): a free body's slow force (models and
    // gravity) enters its kick force slowScale times where it is
    // evaluated, not at all in an inner step; a fixed or prescribed body
    // is never kicked and keeps the load it takes
    for (int b = begin; b < end; ++b)
    {
        Body& body = bodies_[b];
        if (slowScale > 0)
        {
            Vec3 f = modelForce_[b];
            Vec3 t = modelTorque_[b];
            if (body.isFree())
            {
                f += body.mass*settings_.gravity;
                f *= double(slowScale);
                t *= double(slowScale);
            }
            body.force += f;
            body.torque += t;
        }
        // Second half kick of a step (velocity Verlet)
        if (body.isFree() && dtKick > 0) halfKick(body, dtKick);
        storable(body, settings_.storeFloor);
    }
}


void World::bodyForces(double dtKick, int slowScale)
{
    const int N = static_cast<int>(bodies_.size());

    // Serial preparation of the body-force models (e.g. flow sampling,
    // which may use a parallel region of its own and MPI)
    for (const auto& m : forceModels_)
    {
        m->prepare(*this);
    }

    parallelRegion(N >= settings_.singleThreadBelow, [&] { sumBodyForces(dtKick, slowScale); });
}


ContactLoad World::contactLoad(int b) const
{
    ContactLoad c;
    if (!nlist_) return c;
    const auto& pairs = nlist_->pairs();
    auto add = [&c, b](const ContactPair& p)
    {
        if (p.i == b)
        {
            c.force -= p.forceOnJ;
            c.torque += p.torqueOnI;
        }
        else
        {
            c.force += p.forceOnJ;
            c.torque += p.torqueOnJ;
        }
    };
    const int begin = nlist_->bodyBegin(b), end = nlist_->bodyEnd(b);
    // Only the pairs with contacts carry a force: where the pair loop's
    // flags are those of these pairs, the others are not read (most of a
    // drifting field's; the same sums in the same order). The flagged ones
    // are picked without a branch, a block of them at a time (in a pack a
    // body's pairs that touch and those that do not come in no order a
    // branch predictor learns), then summed
    const std::vector<unsigned char>& flags = nlist_->hasContacts();
    if (flags.size() != pairs.size())
    {
        for (int k = begin; k < end; ++k) add(pairs[nlist_->bodyPair(k)]);
        return c;
    }
    constexpr int block = 32;
    int touching[block];
    for (int first = begin; first < end; first += block)
    {
        const int last = std::min(end, first + block);
        int n = 0;
        for (int k = first; k < last; ++k)
        {
            const int pk = nlist_->bodyPair(k);
            touching[n] = pk;
            n += flags[pk] != 0;
        }
        for (int t = 0; t < n; ++t) add(pairs[touching[t]]);
    }
    return c;
}

} // namespace iceDEM
