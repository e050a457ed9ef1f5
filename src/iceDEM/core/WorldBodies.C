/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

// World: bodies removed before the run, and removed or inserted during it
// (inflow/outflow); a change during the run restarts the contact state
// from the kept bodies' contact records

#include "World.H"
#include "contact/NarrowPhase.H"
#include "contact/NeighbourList.H"

#include <sstream>

namespace iceDEM
{

void World::removeBodies(const std::vector<bool>& remove)
{
    if (initialised_)
    {
        throw Error("bodies can only be removed before the run starts");
    }
    std::vector<Body> kept;
    for (std::size_t i = 0; i < bodies_.size(); ++i)
    {
        if (i >= remove.size() || !remove[i]) kept.push_back(bodies_[i]);
    }
    bodies_.swap(kept);
}


void World::restartWith(const std::vector<ContactRecord>& records, int newFrom)
{
    const long step = step_;
    const double time = time_;
    pendingRecords_ = records;
    overlapCheckFrom_ = newFrom;
    try
    {
        initialise(true);
    }
    catch (...)
    {
        overlapCheckFrom_ = -1;
        throw;
    }
    overlapCheckFrom_ = -1;
    step_ = step;
    time_ = time;
}


void World::removeBodiesInRun(const std::vector<bool>& remove)
{
    if (!initialised_)
    {
        throw Error("removeBodiesInRun before the run started: use removeBodies");
    }
    if (firstInserted_ >= 0) joinInserted();
    const int N = static_cast<int>(bodies_.size());
    std::vector<int> newIndex(N, -1);
    int n = 0;
    for (int i = 0; i < N; ++i)
    {
        if (!(i < int(remove.size()) && remove[i])) newIndex[i] = n++;
    }
    if (n == N) return;

    // The removed bodies' contact forces leave their neighbours' sums
    for (const ContactPair& p : nlist_->pairs())
    {
        if (p.isWall() || p.nContacts == 0) continue;
        const bool goneI = newIndex[p.i] < 0;
        const bool goneJ = newIndex[p.j] < 0;
        if (goneI == goneJ) continue;
        if (goneJ)
        {
            bodies_[p.i].force += p.forceOnJ;
            bodies_[p.i].torque -= p.torqueOnI;
        }
        else
        {
            bodies_[p.j].force -= p.forceOnJ;
            bodies_[p.j].torque -= p.torqueOnJ;
        }
    }

    std::vector<ContactRecord> records;
    for (ContactRecord r : contactRecords())
    {
        if (newIndex[r.i] < 0 || (r.j >= 0 && newIndex[r.j] < 0)) continue;
        r.i = newIndex[r.i];
        if (r.j >= 0) r.j = newIndex[r.j];
        records.push_back(r);
    }

    std::vector<Body> kept;
    kept.reserve(n);
    for (int i = 0; i < N; ++i)
    {
        if (newIndex[i] >= 0) kept.push_back(bodies_[i]);
    }
    bodies_.swap(kept);

    // The kept bodies' model forces of the step just taken stay readable
    // (modelForceOnFreeBodies: the drive of a force balance), as their
    // total forces do
    std::vector<Vec3> mf, mt;
    if (modelForce_.size() == std::size_t(N))
    {
        mf.reserve(n);
        mt.reserve(n);
        for (int i = 0; i < N; ++i)
        {
            if (newIndex[i] < 0) continue;
            mf.push_back(modelForce_[i]);
            mt.push_back(modelTorque_[i]);
        }
    }
    restartWith(records, n);    // no new body: no overlap check
    if (!mf.empty() && modelForce_.size() == mf.size())
    {
        modelForce_.swap(mf);
        modelTorque_.swap(mt);
    }
}


int World::insertBodyInRun
(
    int shape,
    int material,
    const Vec3& position,
    const Quat& orientation,
    const Vec3& velocity,
    const Vec3& omega,
    int id
)
{
    if (!initialised_)
    {
        throw Error("insertBodyInRun before the run started: use addBody");
    }
    const int first = static_cast<int>(bodies_.size());
    const int i = addBody(shape, material, position, orientation, velocity, omega, BodyMotion::free, id);
    initialised_ = true;        // still running: the body joins at the next step
    bodies_[i].force.setZero();
    bodies_[i].torque.setZero();
    if (firstInserted_ < 0) firstInserted_ = first;
    return i;
}


void World::joinInserted()
{
    const int first = firstInserted_;
    firstInserted_ = -1;
    restartWith(contactRecords(), first);
    // An inserted body must not touch anything: overlaps of cores are
    // refused by initialise, touching dilated surfaces here
    FoundContact found[maxContactsPerPair];
    for (const ContactPair& p : nlist_->pairs())
    {
        if (p.i < first && (p.isWall() || p.j < first)) continue;
        ensureBodyFrame(p.i);
        if (!p.isWall()) ensureBodyFrame(p.j);
        Vec3 axis = p.axis;
        if (findPairContacts(p, axis, found) > 0)
        {
            std::ostringstream msg;
            const int inserted = p.isWall() || p.i >= first ? p.i : p.j;
            const int other = inserted == p.i ? p.j : p.i;
            msg << "inserted body " << bodies_[inserted].id << " touches ";
            if (p.isWall()) msg << "wall " << walls_[p.wall()].name;
            else msg << "body " << bodies_[other].id;
            throw Error(msg.str(), "bodies");
        }
    }
    checkInsertedBodyForceLimits(first);
}

} // namespace iceDEM
