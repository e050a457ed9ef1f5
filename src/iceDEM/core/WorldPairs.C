/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "worldDetail.H"
#include "contact/NarrowPhase.H"
#include "contact/NeighbourList.H"
#include "prefetch.H"

#include <algorithm>

namespace iceDEM
{

using namespace worldDetail;

// The pair loop of a force evaluation: each neighbour pair's narrow phase
// and contact law, the contacts' and feature-pair lists' pools in pair order


int World::findPairContacts
(
    const ContactPair& p,
    Vec3& axis,
    FoundContact* found,
    FeaturePairList* features,
    double* separation
) const
{
    const Body& bi = bodies_[p.i];
    const BodyView A{&shapeOf(p.i), worldVertices(p.i), bi.rotation(), bi.x, bi.q};
    if (p.isWall())
    {
        const Wall& w = walls_[p.wall()];
        return findWallContacts(A, w.point, w.normal, found, maxContactsPerPair, separation);
    }
    Vec3 translated[maxShapeVertices];
    const BodyView B = viewOfJ(p, translated);
    NarrowPhaseSettings nps;
    nps.featureSkin = featureSkin_;
    return findContacts(A, B, nps, axis, found, maxContactsPerPair, features, separation);
}


BodyView World::viewOfJ(const ContactPair& p, Vec3* buffer) const
{
    const Body& bj = bodies_[p.j];
    if (p.image == Domain::noImage)
    {
        return BodyView{&shapeOf(p.j), worldVertices(p.j), bj.rotation(), bj.x, bj.q};
    }
    // A ghost: j's world vertices and centroid translated by the image
    const Vec3 s = domain_->shift(p.image);
    const Vec3* w = worldVertices(p.j);
    const int n = static_cast<int>(shapeOf(p.j).core().vertices().size());
    for (int k = 0; k < n; ++k) buffer[k] = w[k] + s;
    return BodyView{&shapeOf(p.j), buffer, bj.rotation(), bj.x + s, bj.q};
}


Vec3 World::centroidOfJ(const ContactPair& p) const
{
    const Vec3& x = bodies_[p.j].x;
    return p.image == Domain::noImage ? x : Vec3(x + domain_->shift(p.image));
}


RelativePose World::pairPose(const ContactPair& p) const
{
    const Body& bi = bodies_[p.i];
    return relativePose(bi.x, bi.q, centroidOfJ(p), bodies_[p.j].q);
}


bool World::certifiedApart(const ContactPair& p) const
{
    const NeighbourList& nl = *nlist_;
    if (nl.separated(p)) return true;
    // The certificate from the pair's own check costs a relative pose:
    // only where the first fails
    return !p.isWall() && p.checkSeparation > 0 && nl.separatedSinceCheck(p, pairPose(p));
}


World::PairMotion World::pairMotion(const ContactPair& p) const
{
    PairMotion pm;
    const Body& bi = bodies_[p.i];
    const Body* bj = p.isWall() ? nullptr : &bodies_[p.j];
    const int M = static_cast<int>(materials_.size());
    const int matJ = bj ? bj->material : walls_[p.wall()].material;
    pm.coeffs = &pairCoeffs_[bi.material*M + matJ];

    if (!bj || !bj->isFree()) pm.mEff = bi.mass;
    else if (!bi.isFree()) pm.mEff = bj->mass;
    else pm.mEff = bi.mass*bj->mass/(bi.mass + bj->mass);

    pm.bi = &bi;
    pm.bj = bj;
    pm.omegaI = &omegas_[p.i];
    pm.omegaJ = bj ? &omegas_[p.j] : nullptr;
    pm.xJ = bj ? centroidOfJ(p) : Vec3::Zero();
    return pm;
}


inline Vec3 World::relativeVelocity(const PairMotion& pm, const Vec3& x) const
{
    Vec3 vRel = -(pm.bi->v + pm.omegaI->cross(x - pm.bi->x));
    if (pm.bj) vRel += pm.bj->v + pm.omegaJ->cross(x - pm.xJ);
    return vRel;
}


void World::dampingMasses
(
    const PairMotion& pm,
    const FoundContact* found,
    int n,
    double* mEff
) const
{
    if (!settings_.contact.dampingPerPair)
    {
        for (int c = 0; c < n; ++c) mEff[c] = pm.mEff;
        return;
    }
    // The pair's damping is that of one contact of the terms' summed
    // stiffness S = sum |w| S_n, set by sqrt(m* S): with m*_t = m* S_n/S a
    // term's coefficient sqrt(m*_t S_n) is S_n sqrt(m*/S), and the terms'
    // (each times its |w|, as the law applies it) add up to sqrt(m* S).
    // The share S_n/S first, so that a lone term of weight 1 keeps m* to
    // the bit
    double S[maxContactsPerPair];
    double sum = 0;
    for (int c = 0; c < n; ++c)
    {
        S[c] = law_->normalStiffness(*pm.coeffs, found[c].g);
        sum += std::abs(found[c].g.weight)*S[c];
    }
    for (int c = 0; c < n; ++c)
    {
        mEff[c] = sum > 0 ? pm.mEff*(S[c]/sum) : pm.mEff;
    }
}


ContactResult World::contactForce
(
    const PairMotion& pm,
    double mEff,
    const ContactGeometry& g,
    Vec3& xi,
    double dtTangential
) const
{
    const Vec3 vRel = relativeVelocity(pm, g.point);
    return law_->evaluate(*pm.coeffs, g, mEff, vRel, xi, dtTangential);
}


void World::contactForces
(
    const PairMotion& pm,
    const double mEff[2],
    const ContactGeometry& g0,
    const ContactGeometry& g1,
    Vec3& xi0,
    Vec3& xi1,
    double dtTangential,
    ContactResult r[2]
) const
{
    const ContactGeometry* const g[2] = {&g0, &g1};
    const Vec3 vRel[2] = {relativeVelocity(pm, g0.point), relativeVelocity(pm, g1.point)};
    Vec3* const xi[2] = {&xi0, &xi1};
    law_->evaluateTwo(*pm.coeffs, g, mEff, vRel, xi, dtTangential, r);
}


void World::preparePairs()
{
    #ifdef _OPENMP
    const int maxThreads = omp_get_max_threads();
    #else
    const int maxThreads = 1;
    #endif
    if (int(scratch_.size()) < maxThreads) scratch_.resize(maxThreads);
    // All cleared here: the pools are sized from their sums, and a thread
    // that is not in the next team must leave nothing behind
    for (PairScratch& S : scratch_)
    {
        S.contacts.clear();
        S.lists.clear();
        S.entries.clear();
        S.listPairs.clear();
        S.segments.clear();
    }
    nlist_->hasContacts().resize(nlist_->pairs().size());
    chunkCounts_.resize(maxThreads);
    pairBalance_.resize(maxThreads);
    // The body sums of the last evaluation are done (no thread records
    // now): their chunks move here
    for (LoopBalance& b : sumBalance_)
    {
        b.resize(maxThreads);
        b.rebalance(maxThreads);
    }
}


void World::pairForces(double dtTangential)
{
    NeighbourList& nl = *nlist_;
    auto& pairs = nl.pairs();
    const int nPairs = static_cast<int>(pairs.size());

    // Orphaned work-sharing: called inside a parallel region (or by one
    // thread); scratch_ is sized by preparePairs
    {
        // The pools are written below by the runs of pairs each thread
        // searched
        const ThreadShare share(nPairs);
        const int thread = share.thread;
        PairScratch& S = scratch_[thread];

        FoundContact found[maxContactsPerPair];
        FeaturePairEntry listBuffer[FeaturePairList::capacity];
        // The pools as the last evaluation left them, read only in this loop
        const StoredContact* oldContacts = nl.contacts().data();
        const StoredFeatureList* oldLists = nl.featureLists().data();
        const FeaturePairEntry* oldEntries = nl.listEntries().data();

        // A pair's new feature-pair list into this thread's scratch, until
        // the pool pass appends it (the kept lists stay where they are)
        auto stageList = [&S]
        (
            int k,
            StoredFeatureList L,
            const FeaturePairEntry* from
        )
        {
            L.firstEntry = static_cast<int>(S.entries.size());
            S.listPairs.push_back(k);
            S.lists.push_back(L);
            S.entries.insert(S.entries.end(), from, from + L.count);
        };

        // Written only where it changes: most pairs' flags stay as they
        // were, and their cache lines shared
        unsigned char* hasContacts = nl.hasContacts().data();
        auto flagContacts = [hasContacts](int k, const ContactPair& p)
        {
            const unsigned char flag = p.nContacts > 0;
            if (hasContacts[k] != flag) hasContacts[k] = flag;
        };

        int searched = 0;
        int tooDeep = -1;
        SearchAhead ahead;
        auto searchPair = [&](int k)
        {
            ContactPair& p = pairs[k];
            // The data of the next pairs to be searched, asked for ahead
            ahead.advance
            (
                k,
                [&](int f) { return !nl.separated(pairs[f]); },
                [&](int f)
                {
                    const ContactPair& q = pairs[f];
                    prefetchPairShapes(q);
                    if (q.featureList >= 0)
                    {
                        prefetchRange(oldLists + q.featureList, sizeof(StoredFeatureList));
                    }
                },
                [&](int f)
                {
                    const ContactPair& q = pairs[f];
                    prefetchPair(q);
                    if (q.featureList >= 0)
                    {
                        const StoredFeatureList& L = oldLists[q.featureList];
                        prefetchRange(oldEntries + L.firstEntry, L.count*sizeof(FeaturePairEntry));
                    }
                    prefetchRange(oldContacts + q.firstContact, q.nContacts*sizeof(StoredContact));
                }
            );
            // A pair whose separation certificate still holds cannot touch:
            // no narrow phase (nor reads of its bodies' shapes and world
            // vertices); its feature-pair list is kept as the narrow phase
            // would keep it, after a separating axis. Most such pairs write
            // nothing: their cache lines stay shared between the threads
            if (certifiedApart(p))
            {
                if (p.nContacts > 0) clearPairForces(p);
                flagContacts(k, p);
                return;
            }
            ++searched;
            nl.spend(p);
            ensureBodyFrame(p.i);
            if (!p.isWall()) ensureBodyFrame(p.j);

            FeaturePairList list;
            list.buffer = listBuffer;
            if (p.featureList >= 0)
            {
                const StoredFeatureList& L = oldLists[p.featureList];
                list.count = L.count;
                list.entries = oldEntries + L.firstEntry;
                list.t = L.t;
                list.Q = L.Q;
                list.limit = L.limit;
                list.touched = p.nContacts > 0;
            }
            double separation = std::numeric_limits<double>::lowest();
            const int nFound = findPairContacts
            (
                p, p.axis, found, p.isWall() ? nullptr : &list, &separation
            );
            if (nFound == 0)
            {
                nl.certify
                (
                    p, separation,
                    p.isWall() ? RelativePose{Vec3::Zero(), Quat::Identity()} : pairPose(p)
                );
            }

            const StoredContact* previous = oldContacts + p.firstContact;
            const int nPrev = p.nContacts;
            clearPairForces(p);
            PairMotion pm{};
            double mEff[maxContactsPerPair];
            if (nFound > 0)
            {
                pm = pairMotion(p);
                dampingMasses(pm, found, nFound, mEff);
            }

            // Two contacts at a time through the contact law (its square
            // roots overlap), summed one by one in their order
            for (int c = 0; c < nFound; c += 2)
            {
                const int two = std::min(2, nFound - c);
                StoredContact sc[2];
                ContactResult r[2];
                for (int l = 0; l < two; ++l)
                {
                    const FoundContact& fc = found[c + l];
                    sc[l].featureI = fc.featureA;
                    sc[l].featureJ = fc.featureB;
                    sc[l].xi.setZero();
                    for (int m = 0; m < nPrev; ++m)
                    {
                        if
                        (
                            previous[m].featureI == fc.featureA
                         && previous[m].featureJ == fc.featureB
                        )
                        {
                            sc[l].xi = previous[m].xi;
                            break;
                        }
                    }
                }
                if (two == 2)
                {
                    contactForces(pm, mEff + c, found[c].g, found[c + 1].g, sc[0].xi, sc[1].xi, dtTangential, r);
                }
                else
                {
                    r[0] = contactForce(pm, mEff[c], found[c].g, sc[0].xi, dtTangential);
                }
                for (int l = 0; l < two; ++l)
                {
                    const FoundContact& fc = found[c + l];
                    storable(sc[l].xi, settings_.storeFloor);
                    S.contacts.push_back(sc[l]);
                    ++p.nContacts;

                    const Vec3& x = fc.g.point;
                    p.forceOnJ += r[l].forceOnJ;
                    p.torqueOnI += (x - pm.bi->x).cross(-r[l].forceOnJ) - r[l].coupleOnJ;
                    if (pm.bj) p.torqueOnJ += (x - pm.xJ).cross(r[l].forceOnJ) + r[l].coupleOnJ;
                    p.elasticEnergy += r[l].elasticEnergy;
                    p.deepest = std::max(p.deepest, fc.g.overlap);
                }
            }
            // Beyond the contact model's range (checkOverlapRange): the
            // first such pair of this thread's
            if
            (
                nFound > 0 && (tooDeep < 0 || k < tooDeep)
             && !(p.deepest < dilationSum(p))
            )
            {
                tooDeep = k;
            }

            // A list built by this search is staged; a held one stays in
            // the pool as it is; a dropped one is left there as garbage
            if (list.count >= 0 && list.entries == listBuffer)
            {
                StoredFeatureList L;
                L.t = list.t;
                L.Q = list.Q;
                L.limit = list.limit;
                L.count = list.count;
                stageList(k, L, list.entries);
            }
            else if (list.count < 0)
            {
                p.featureList = -1;
            }
            flagContacts(k, p);
        };

        // Contiguous chunks: a thread takes the pairs (sorted by i) of about
        // the bodies it moved in the step's first loop and sums in the last,
        // so their lines stay in its cache. Chunks of 64 handed out as
        // threads came free were 4-17 % slower on every field
        // (tests/benchmark/README.md, twenty-ninth round). The chunks'
        // boundaries even out the threads' times (LoopBalance), and a
        // thread done with its chunk takes blocks from the back of the
        // other's. Each block's contacts are a segment of this thread's
        // scratch (consecutive blocks of its own chunk one segment)
        std::vector<ContactSegment>& segments = S.segments;
        forEachClaimedBlock
        (
            pairBalance_, thread, share.nThreads, nPairs, pairBlock, &wallClock,
            [&](int begin, int end, bool)
            {
                const int from = static_cast<int>(S.contacts.size());
                ahead.start(begin, end);
                for (int k = begin; k < end; ++k) searchPair(k);
                const int count = static_cast<int>(S.contacts.size()) - from;
                if (!segments.empty() && segments.back().end == begin)
                {
                    segments.back().end = end;
                    segments.back().count += count;
                }
                else
                {
                    segments.push_back({begin, end, from, count, 0});
                }
            }
        );
        #pragma omp barrier

        // The contacts' pool in pair order (independent of the thread
        // count and of who searched which pair), written in parallel: each
        // thread copies its runs of pairs (segments), whose offsets in the
        // pool are the sums over the runs before them. The pair loop's
        // barrier made every count visible; one thread sizes the pool,
        // places the segments and appends the new feature-pair lists,
        // while the others post their counts
        #pragma omp master
        {
            std::size_t nContacts = 0;
            for (const PairScratch& T : scratch_) nContacts += T.contacts.size();
            nl.contacts().resize(nContacts);
            contactCount_ = static_cast<int>(nContacts);
            placeSegments();
            appendNewLists();
            pairBalance_.rebalance(share.nThreads);
        }

        PoolCounts& mine = chunkCounts_[thread];
        mine = PoolCounts();
        mine.searched = searched;
        mine.tooDeep = tooDeep;
        #pragma omp barrier

        if (thread == 0)
        {
            searchedPairs_ = 0;
            tooDeepPair_ = -1;
            for (int t = 0; t < share.nThreads; ++t)
            {
                const PoolCounts& c = chunkCounts_[t];
                searchedPairs_ += c.searched;
                if (c.tooDeep >= 0 && (tooDeepPair_ < 0 || c.tooDeep < tooDeepPair_))
                {
                    tooDeepPair_ = c.tooDeep;
                }
            }
        }

        // No barrier after this: what follows in the step (body sums) reads
        // the pairs' forces, not the pools. A segment of the scratch holds
        // the contacts of a run of pairs in pair order (a pair certified
        // apart has none): one copy each. A pair's header is written only
        // where it changes (a pair without contacts keeps its line shared
        // with the thread that reads it next). The pairs this thread
        // searched: the headers it has just written are in its cache
        for (const ContactSegment& g : segments)
        {
            std::copy
            (
                S.contacts.begin() + g.from,
                S.contacts.begin() + g.from + g.count,
                nl.contacts().data() + g.to
            );
            int offset = g.to;
            for (int k = g.begin; k < g.end; ++k)
            {
                ContactPair& p = pairs[k];
                if (p.firstContact != offset) p.firstContact = offset;
                offset += p.nContacts;
            }
        }
    }
}


void World::placeSegments()
{
    // The pool holds the contacts in pair order: the segments of all
    // threads in the order of their pairs, one after the other
    segmentOrder_.clear();
    for (int t = 0; t < int(scratch_.size()); ++t)
    {
        const std::vector<ContactSegment>& segments = scratch_[t].segments;
        for (int g = 0; g < int(segments.size()); ++g)
        {
            segmentOrder_.push_back({segments[g].begin, t, g});
        }
    }
    std::sort(segmentOrder_.begin(), segmentOrder_.end());
    int offset = 0;
    for (const auto& o : segmentOrder_)
    {
        ContactSegment& g = scratch_[o[1]].segments[o[2]];
        g.to = offset;
        offset += g.count;
    }
}


void World::appendNewLists()
{
    NeighbourList& nl = *nlist_;
    auto& pairs = nl.pairs();

    // The lists built in this evaluation, in pair order (so the pools'
    // layout does not depend on the number of threads either)
    newLists_.clear();
    for (int t = 0; t < int(scratch_.size()); ++t)
    {
        const std::vector<int>& listPairs = scratch_[t].listPairs;
        for (int l = 0; l < int(listPairs.size()); ++l)
        {
            newLists_.push_back({listPairs[l], t, l});
        }
    }
    std::sort(newLists_.begin(), newLists_.end());

    // Compacted, in pair order, once the garbage (replaced and dropped
    // lists, lists of pairs a build removed) outweighs what is kept
    if
    (
        nl.listEntries().size()
      > 2*listEntriesAtCompaction_ + FeaturePairList::capacity
    )
    {
        // The replaced lists are left out (the new ones follow)
        for (const auto& n : newLists_) pairs[n[0]].featureList = -1;
        nl.compactLists();
        listEntriesAtCompaction_ = nl.listEntries().size();
        ++listCompactions_;
    }

    for (const auto& n : newLists_)
    {
        const PairScratch& T = scratch_[n[1]];
        const StoredFeatureList& L = T.lists[n[2]];
        nl.appendList(pairs[n[0]], L, T.entries.data() + L.firstEntry);
    }
}


void World::computeForces(double dtTangential)
{
    resizeBodyFrames();
    ++evaluation_;
    preparePairs();
    const int nPairs = static_cast<int>(nlist_->pairs().size());
    parallelRegion(nPairs >= settings_.singleThreadBelow, [&] { pairForces(dtTangential); });
    // A start is an outer step's boundary; a body inserted in the middle
    // of an outer step takes the slow kick of the rest of it
    bodyForces(0, std::max(1, bodyForceInterval() - bodyForcePhase_));
}

} // namespace iceDEM
