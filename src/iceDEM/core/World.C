/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "contact/NarrowPhase.H"
#include "contact/NeighbourList.H"
#include "prefetch.H"

#include <algorithm>
#include <cmath>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace iceDEM
{

namespace
{

//- Loops shorter than this run on one thread: a parallel region (and its
//  barrier) costs more than it saves, and waits badly on a loaded machine
constexpr int minParallelLoop = 256;

//- Loops over bodies: a body's work is small, so a larger cut-off
constexpr int minParallelBodies = 1000;

//- The step's body and pair loops ask for the data of the body (pair)
//  this far ahead
constexpr int prefetchAhead = 2;

//- This thread's index and its static share [begin, end) of n items (all
//  of them outside a parallel region): every loop that splits n this way
//  gives a thread the same items
struct ThreadShare
{
    int thread = 0;
    int nThreads = 1;
    int begin = 0;
    int end = 0;

    explicit ThreadShare(int n)
    {
        #ifdef _OPENMP
        thread = omp_get_thread_num();
        nThreads = omp_get_num_threads();
        #endif
        begin = static_cast<int>(static_cast<long>(n)*thread/nThreads);
        end = static_cast<int>(static_cast<long>(n)*(thread + 1)/nThreads);
    }
};

//- A pair without contacts: no force, torque, energy or overlap
inline void clearPairForces(ContactPair& p)
{
    p.nContacts = 0;
    p.forceOnJ.setZero();
    p.torqueOnI.setZero();
    p.torqueOnJ.setZero();
    p.elasticEnergy = 0;
    p.deepest = 0;
}

//- Half a step of the velocities under the last forces (velocity Verlet)
inline void halfKick(Body& b, double dt)
{
    b.v += 0.5*dt/b.mass*b.force;
    b.L += 0.5*dt*b.torque;
}

//- Rotation of the free rigid body by the symplectic splitting about the
//  principal axes (x, y, z, y, x): each sub-rotation is exact, |L| is kept
//  exactly and the energy error stays bounded
void rotateFree(Quat& q, const Vec3& L, const Vec3& invI, double dt)
{
    Vec3 pi = q.toRotationMatrix().transpose()*L;
    auto sub = [&](int k, double h)
    {
        const double angle = h*pi[k]*invI[k];
        if (angle == 0) return;
        // One sine and cosine of the half angle serve the quaternion and,
        // by the double-angle formulas, the body components
        const double c = std::cos(0.5*angle);
        const double s = std::sin(0.5*angle);
        const double cosA = 1 - 2*s*s;
        const double sinA = 2*s*c;
        // The frame turns by +angle about axis k: the body components of L
        // in the plane (j, l) turn by -angle
        const int j = (k + 1) % 3;
        const int l = (k + 2) % 3;
        const double pj = pi[j];
        const double pl = pi[l];
        pi[j] = cosA*pj + sinA*pl;
        pi[l] = -sinA*pj + cosA*pl;
        Quat dq(c, 0, 0, 0);
        dq.vec()[k] = s;
        q = q*dq;
    };
    sub(0, 0.5*dt);
    sub(1, 0.5*dt);
    sub(2, dt);
    sub(1, 0.5*dt);
    sub(0, 0.5*dt);
    q.normalize();
}

} // anonymous namespace


struct World::PoolCounts
{
    int contacts = 0;
    int lists = 0;
    int entries = 0;
    //- Pairs this thread searched in the pair loop (diagnostics)
    int searched = 0;
    //- One cache line per thread (no false sharing)
    char pad[64 - 4*sizeof(int)];
};


struct World::PairScratch
{
    std::vector<StoredContact> contacts;
    std::vector<StoredFeatureList> lists;
    std::vector<std::uint32_t> entries;
};


World::World(const WorldSettings& settings)
:
    settings_(settings),
    law_(ContactLaw::New(settings.contact))
{
    if (!(settings_.timeStep > 0))
    {
        throw Error("the DEM time step must be > 0", "deltaT");
    }
    if (!(settings_.parallelEdgeSin > 0 && settings_.parallelEdgeSin < 1))
    {
        throw Error("parallelEdgeSin must be in (0, 1)", "parallelEdgeSin");
    }
    if (!(settings_.contactCheckVelocity > 0))
    {
        throw Error("contactCheckVelocity must be > 0", "contactCheckVelocity");
    }
    if (!(settings_.contactStepsMin > 0) || settings_.contactStepsWarn < settings_.contactStepsMin)
    {
        throw Error("need 0 < contactStepsMin <= contactStepsWarn", "contactStepsMin");
    }
}


World::~World() = default;


int World::addMaterial(const Material& m)
{
    checkMaterial(m);
    if (materialIndex(m.name) >= 0)
    {
        throw Error("material " + m.name + " defined twice", m.name);
    }
    const int M = static_cast<int>(materials_.size());
    std::vector<PairProperties> props((M + 1)*(M + 1));
    for (int a = 0; a < M; ++a)
    {
        for (int b = 0; b < M; ++b)
        {
            props[a*(M + 1) + b] = pairProps_[a*M + b];
        }
    }
    pairProps_.swap(props);
    materials_.push_back(m);
    return M;
}


int World::materialIndex(const std::string& name) const
{
    for (int k = 0; k < int(materials_.size()); ++k)
    {
        if (materials_[k].name == name) return k;
    }
    return -1;
}


void World::setPairProperties(int a, int b, const PairProperties& p)
{
    checkPairProperties(p);
    const int M = static_cast<int>(materials_.size());
    pairProps_[a*M + b] = p;
    pairProps_[b*M + a] = p;
}


int World::addShape(const DilatedShape& s)
{
    if (int(s.core().vertices().size()) > maxShapeVertices)
    {
        std::ostringstream msg;
        msg << "a shape has " << s.core().vertices().size()
            << " core vertices; at most " << maxShapeVertices << " are supported";
        throw Error(msg.str(), "points");
    }
    shapes_.push_back(s);
    return static_cast<int>(shapes_.size()) - 1;
}


int World::addBody
(
    int shape,
    int material,
    const Vec3& position,
    const Quat& orientation,
    const Vec3& velocity,
    const Vec3& omega,
    BodyMotion motion,
    int id
)
{
    if (shape < 0 || shape >= int(shapes_.size()))
    {
        throw Error("body refers to a shape that does not exist", "shape");
    }
    if (material < 0 || material >= int(materials_.size()))
    {
        throw Error("body refers to a material that does not exist", "material");
    }
    const DilatedShape& S = shapes_[shape];
    Body b;
    b.id = id >= 0 ? id : static_cast<int>(bodies_.size());
    b.shape = shape;
    b.material = material;
    b.motion = motion;
    const double rho = materials_[material].density;
    b.mass = rho*S.volume();
    b.invInertia = (rho*S.principalInertia()).cwiseInverse();
    const Quat Q = orientation.normalized();
    b.x = position + Q*S.centroidInput();
    b.q = (Q*S.principalToInput()).normalized();
    b.v = motion == BodyMotion::fixed ? Vec3::Zero() : velocity;
    b.setOmega(motion == BodyMotion::fixed ? Vec3::Zero() : omega);
    bodies_.push_back(b);
    initialised_ = false;
    return static_cast<int>(bodies_.size()) - 1;
}


void World::addWall(const Wall& w)
{
    if (w.material < 0 || w.material >= int(materials_.size()) || !(w.normal.norm() > 0))
    {
        throw Error("wall " + w.name + ": needs a material and a non-zero normal", w.name);
    }
    Wall wall(w);
    wall.normal.normalize();
    walls_.push_back(wall);
}


void World::addForceModel(const std::shared_ptr<BodyForceModel>& m)
{
    forceModels_.push_back(m);
    if (initialised_)
    {
        prepareModels();
    }
}


void World::prepareModels()
{
    // Only a world with models needs the sums (memory per floe, issue 7)
    const std::size_t n = forceModels_.empty() ? 0 : bodies_.size();
    modelForce_.assign(n, Vec3::Zero());
    modelTorque_.assign(n, Vec3::Zero());
    modelForce_.shrink_to_fit();
    modelTorque_.shrink_to_fit();
    // Buoyancy and drag clip every floe's outer polyhedron at every step:
    // kept, not derived each time (a quarter of a Kulluk run otherwise)
    for (const auto& m : forceModels_)
    {
        if (!m->readsOuterPolyhedra()) continue;
        for (DilatedShape& s : shapes_) s.keepOuter();
        break;
    }
}


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
    omegas_[i] = R*(b.invInertia.cwiseProduct(R.transpose()*b.L));
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


void World::prefetchPair(const ContactPair& p) const
{
    // What the world frames and the separating-axis test read first: the
    // two shapes' headers and vertices, and the world vertices (body j is
    // anywhere in memory)
    auto prefetchBody = [this](int i)
    {
        const auto& V = shapeOf(i).core().vertices();
        const std::size_t bytes = V.size()*sizeof(Vec3);
        prefetchRange(&shapeOf(i), sizeof(DilatedShape));
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
    #pragma omp parallel for schedule(static) if(N >= minParallelBodies)
    for (int i = 0; i < N; ++i)
    {
        updateBodyFrame(i);
        frameEvaluation_[i].store(evaluation_);
    }
}


double World::estimatedContactTime() const
{
    double tc = std::numeric_limits<double>::max();
    const int M = static_cast<int>(materials_.size());
    for (const Body& b : bodies_)
    {
        if (!b.isFree()) continue;
        double Estar = 0;
        for (int m = 0; m < M; ++m)
        {
            Estar = std::max
            (
                Estar,
                PairCoefficients::make(materials_[b.material], materials_[m], PairProperties()).Estar
            );
        }
        const double r = shapes_[b.shape].radius();
        tc = std::min
        (
            tc,
            ContactLaw::hertzContactTime(0.5*b.mass, r, Estar, settings_.contactCheckVelocity)
        );
    }
    return tc;
}


void World::initialise(bool restart)
{
    warnings_.clear();
    const int M = static_cast<int>(materials_.size());
    pairCoeffs_.resize(M*M);
    for (int a = 0; a < M; ++a)
    {
        for (int b = 0; b < M; ++b)
        {
            pairCoeffs_[a*M + b] =
                PairCoefficients::make(materials_[a], materials_[b], pairProps_[a*M + b]);
        }
    }

    // Default skin: the smallest dilation radius
    double skin = settings_.skin;
    if (!(skin > 0))
    {
        skin = std::numeric_limits<double>::max();
        for (const Body& b : bodies_) skin = std::min(skin, shapes_[b.shape].radius());
        if (bodies_.empty()) skin = 1;
    }
    // Default feature skin: half the smallest dilation radius
    featureSkin_ = settings_.featureSkin;
    if (featureSkin_ < 0)
    {
        featureSkin_ = bodies_.empty() ? 0 : std::numeric_limits<double>::max();
        for (const Body& b : bodies_) featureSkin_ = std::min(featureSkin_, 0.5*shapes_[b.shape].radius());
    }

    // Time step against the Hertz contact time
    if (!bodies_.empty())
    {
        const double tc = estimatedContactTime();
        const double steps = tc/settings_.timeStep;
        std::ostringstream msg;
        msg << "DEM time step " << settings_.timeStep << " s resolves the estimated"
            << " Hertz contact time " << tc << " s (impact at "
            << settings_.contactCheckVelocity << " m/s) with " << steps << " steps";
        if (steps < settings_.contactStepsMin)
        {
            throw Error(msg.str() + "; at least contactStepsMin = "
              + std::to_string(settings_.contactStepsMin) + " are needed: reduce deltaT", "deltaT");
        }
        if (steps < settings_.contactStepsWarn)
        {
            warnings_.push_back(msg.str() + " (fewer than contactStepsWarn)");
        }
    }

    prepareModels();

    vertexOffset_.clear();
    updateWorldVertices();
    nlist_ = std::make_unique<NeighbourList>(skin);
    nlist_->build(*this);

    // Overlaps at start: intersecting cores are always an error
    for (const ContactPair& p : nlist_->pairs())
    {
        if (p.isWall()) continue;
        const BodyView A{&shapeOf(p.i), worldVertices(p.i), bodies_[p.i].rotation(), bodies_[p.i].x};
        const BodyView B{&shapeOf(p.j), worldVertices(p.j), bodies_[p.j].rotation(), bodies_[p.j].x};
        if (coresIntersect(A, B))
        {
            std::ostringstream msg;
            msg << "bodies " << bodies_[p.i].id << " and " << bodies_[p.j].id
                << " overlap at the start (their cores intersect)";
            throw Error(msg.str(), "bodies");
        }
    }

    if (restart)
    {
        // Contact histories of the saved state into their pairs: counts,
        // then the pool in pair order (a pair's records in saved order)
        auto& pairs = nlist_->pairs();
        std::vector<int> pairOf(pendingRecords_.size());
        for (std::size_t r = 0; r < pendingRecords_.size(); ++r)
        {
            const ContactRecord& rec = pendingRecords_[r];
            auto it = std::find_if
            (
                pairs.begin(), pairs.end(),
                [&](const ContactPair& p) { return p.i == rec.i && p.j == rec.j; }
            );
            if (it == pairs.end() || it->nContacts >= maxContactsPerPair)
            {
                throw Error("a saved contact does not match the bodies' positions", "contacts");
            }
            ++it->nContacts;
            pairOf[r] = static_cast<int>(it - pairs.begin());
        }
        int first = 0;
        std::vector<int> fill(pairs.size());
        for (std::size_t k = 0; k < pairs.size(); ++k)
        {
            pairs[k].firstContact = first;
            fill[k] = first;
            first += pairs[k].nContacts;
        }
        auto& pool = nlist_->contacts();
        pool.assign(first, StoredContact());
        for (std::size_t r = 0; r < pendingRecords_.size(); ++r)
        {
            StoredContact& c = pool[fill[pairOf[r]]++];
            c.featureI = pendingRecords_[r].featureI;
            c.featureJ = pendingRecords_[r].featureJ;
            c.xi = pendingRecords_[r].xi;
        }
        pendingRecords_.clear();
        // Contact geometry and counts for output, without touching the springs
        std::vector<Vec3> F(bodies_.size()), T(bodies_.size());
        for (std::size_t i = 0; i < bodies_.size(); ++i)
        {
            F[i] = bodies_[i].force;
            T[i] = bodies_[i].torque;
        }
        const NeighbourList saved = *nlist_;
        computeForces(0);
        *nlist_ = saved;
        for (std::size_t i = 0; i < bodies_.size(); ++i)
        {
            bodies_[i].force = F[i];
            bodies_[i].torque = T[i];
        }
    }
    else
    {
        computeForces(0);
        for (const ContactPair& p : nlist_->pairs())
        {
            if (p.nContacts > 0 && !p.isWall())
            {
                std::ostringstream msg;
                msg << "bodies " << bodies_[p.i].id << " and " << bodies_[p.j].id
                    << " touch at the start (overlap " << p.deepest
                    << " m): move them apart";
                throw Error(msg.str(), "bodies");
            }
        }
    }
    initialised_ = true;
}


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
    const Body& bj = bodies_[p.j];
    const BodyView B{&shapeOf(p.j), worldVertices(p.j), bj.rotation(), bj.x, bj.q};
    NarrowPhaseSettings nps;
    nps.parallelEdgeSin = settings_.parallelEdgeSin;
    nps.featureSkin = featureSkin_;
    return findContacts(A, B, nps, axis, found, maxContactsPerPair, features, separation);
}


ContactResult World::contactForce
(
    const ContactPair& p,
    const ContactGeometry& g,
    Vec3& xi,
    double dtTangential
) const
{
    const Body& bi = bodies_[p.i];
    const Body* bj = p.isWall() ? nullptr : &bodies_[p.j];
    const int M = static_cast<int>(materials_.size());
    const int matJ = bj ? bj->material : walls_[p.wall()].material;
    const PairCoefficients& coeffs = pairCoeffs_[bi.material*M + matJ];

    double mEff;
    if (!bj || !bj->isFree()) mEff = bi.mass;
    else if (!bi.isFree()) mEff = bj->mass;
    else mEff = bi.mass*bj->mass/(bi.mass + bj->mass);

    const Vec3& x = g.point;
    Vec3 vRel = -(bi.v + omegas_[p.i].cross(x - bi.x));
    if (bj) vRel += bj->v + omegas_[p.j].cross(x - bj->x);

    return law_->evaluate(coeffs, g, mEff, vRel, xi, dtTangential);
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
    }
    staged_.resize(nlist_->pairs().size());
    chunkCounts_.resize(maxThreads);
}


void World::pairForces(double dtTangential)
{
    NeighbourList& nl = *nlist_;
    auto& pairs = nl.pairs();
    const int nPairs = static_cast<int>(pairs.size());

    // Orphaned work-sharing: called inside a parallel region (or by one
    // thread); staged_ and scratch_ are sized by preparePairs
    {
        // The pools are written below by static chunks of pairs
        const ThreadShare share(nPairs);
        const int thread = share.thread;
        PairScratch& S = scratch_[thread];

        FoundContact found[maxContactsPerPair];
        std::uint32_t listBuffer[FeaturePairList::capacity];
        // The pools of the last evaluation, read only in this loop
        const StoredContact* oldContacts = nl.contacts().data();
        const StoredFeatureList* oldLists = nl.featureLists().data();
        const std::uint32_t* oldEntries = nl.listEntries().data();

        // A pair's new feature-pair list into this thread's scratch; until
        // the pool pass, the pair's featureList is its index there
        auto stageList = [&S]
        (
            ContactPair& p,
            StoredFeatureList L,
            const std::uint32_t* from
        )
        {
            p.featureList = static_cast<int>(S.lists.size());
            L.firstEntry = static_cast<int>(S.entries.size());
            S.lists.push_back(L);
            S.entries.insert(S.entries.end(), from, from + L.count);
        };

        int searched = 0;
        #pragma omp for schedule(dynamic, 64)
        for (int k = 0; k < nPairs; ++k)
        {
            ContactPair& p = pairs[k];
            if (k + prefetchAhead < nPairs && !nl.separated(pairs[k + prefetchAhead]))
            {
                prefetchPair(pairs[k + prefetchAhead]);
            }
            // A pair whose separation certificate still holds cannot touch:
            // no narrow phase (nor reads of its bodies' shapes and world
            // vertices); its feature-pair list is kept as the narrow phase
            // would keep it, after a separating axis. Most such pairs write
            // nothing: their cache lines stay shared between the threads
            if (nl.separated(p))
            {
                if (p.nContacts > 0) clearPairForces(p);
                if (p.featureList >= 0)
                {
                    staged_[k] = {thread, 0};
                    const StoredFeatureList& L = oldLists[p.featureList];
                    stageList(p, L, oldEntries + L.firstEntry);
                }
                continue;
            }
            staged_[k] = {thread, static_cast<int>(S.contacts.size())};
            ++searched;
            ensureBodyFrame(p.i);
            if (!p.isWall()) ensureBodyFrame(p.j);

            FeaturePairList list;
            list.buffer = listBuffer;
            if (p.featureList >= 0)
            {
                const StoredFeatureList& L = oldLists[p.featureList];
                list.count = L.count;
                list.entries = oldEntries + L.firstEntry;
                list.xA = L.xA;
                list.xB = L.xB;
                list.qA = L.qA;
                list.qB = L.qB;
                list.touched = p.nContacts > 0;
            }
            double separation = std::numeric_limits<double>::lowest();
            const int nFound = findPairContacts
            (
                p, p.axis, found, p.isWall() ? nullptr : &list, &separation
            );
            if (nFound == 0) nl.certify(p, separation);

            const StoredContact* previous = oldContacts + p.firstContact;
            const int nPrev = p.nContacts;
            clearPairForces(p);

            for (int c = 0; c < nFound; ++c)
            {
                const FoundContact& fc = found[c];
                StoredContact sc;
                sc.featureI = fc.featureA;
                sc.featureJ = fc.featureB;
                sc.xi.setZero();
                for (int m = 0; m < nPrev; ++m)
                {
                    if (previous[m].featureI == fc.featureA && previous[m].featureJ == fc.featureB)
                    {
                        sc.xi = previous[m].xi;
                        break;
                    }
                }
                const ContactResult r = contactForce(p, fc.g, sc.xi, dtTangential);
                S.contacts.push_back(sc);
                ++p.nContacts;

                const Vec3& x = fc.g.point;
                p.forceOnJ += r.forceOnJ;
                p.torqueOnI += (x - bodies_[p.i].x).cross(-r.forceOnJ) - r.coupleOnJ;
                if (!p.isWall()) p.torqueOnJ += (x - bodies_[p.j].x).cross(r.forceOnJ) + r.coupleOnJ;
                p.elasticEnergy += r.elasticEnergy;
                p.deepest = std::max(p.deepest, fc.g.overlap);
            }

            if (list.count >= 0)
            {
                StoredFeatureList L;
                L.xA = list.xA;
                L.xB = list.xB;
                L.qA = list.qA;
                L.qB = list.qB;
                L.count = list.count;
                stageList(p, L, list.entries);
            }
            else if (p.featureList >= 0)
            {
                p.featureList = -1;
            }
        }

        // The new pools in pair order (independent of the thread count),
        // written in parallel: each thread takes a static chunk of the
        // pairs, whose offsets in the pools are the sums over the chunks
        // before it. The pair loop's barrier made every count visible; the
        // pools' sizes are the scratch totals, so one thread sizes them
        // while the others count their chunks
        #pragma omp master
        {
            std::size_t nContacts = 0, nLists = 0, nEntries = 0;
            for (const PairScratch& T : scratch_)
            {
                nContacts += T.contacts.size();
                nLists += T.lists.size();
                nEntries += T.entries.size();
            }
            nl.contacts().resize(nContacts);
            nl.featureLists().resize(nLists);
            nl.listEntries().resize(nEntries);
            contactCount_ = static_cast<int>(nContacts);
        }

        PoolCounts& mine = chunkCounts_[thread];
        mine = PoolCounts();
        mine.searched = searched;
        for (int k = share.begin; k < share.end; ++k)
        {
            const ContactPair& p = pairs[k];
            mine.contacts += p.nContacts;
            if (p.featureList < 0) continue;
            ++mine.lists;
            mine.entries += scratch_[staged_[k][0]].lists[p.featureList].count;
        }
        #pragma omp barrier

        if (thread == 0)
        {
            searchedPairs_ = 0;
            for (int t = 0; t < share.nThreads; ++t) searchedPairs_ += chunkCounts_[t].searched;
        }

        PoolCounts offset;
        for (int t = 0; t < thread; ++t)
        {
            offset.contacts += chunkCounts_[t].contacts;
            offset.lists += chunkCounts_[t].lists;
            offset.entries += chunkCounts_[t].entries;
        }

        // No barrier after this: what follows in the step (body sums) reads
        // the pairs' forces, not the pools. A pair's header is written only
        // where it changes (a pair without contacts or list keeps its line
        // shared with the thread that reads it next)
        for (int k = share.begin; k < share.end; ++k)
        {
            ContactPair& p = pairs[k];
            if (p.firstContact != offset.contacts) p.firstContact = offset.contacts;
            if (p.nContacts > 0)
            {
                const StoredContact* from =
                    scratch_[staged_[k][0]].contacts.data() + staged_[k][1];
                std::copy(from, from + p.nContacts, nl.contacts().data() + p.firstContact);
                offset.contacts += p.nContacts;
            }

            if (p.featureList < 0) continue;
            const PairScratch& T = scratch_[staged_[k][0]];
            const int l = p.featureList;
            p.featureList = offset.lists++;
            StoredFeatureList& L = nl.featureLists()[p.featureList];
            L = T.lists[l];
            const std::uint32_t* fromEntry = T.entries.data() + L.firstEntry;
            std::copy(fromEntry, fromEntry + L.count, nl.listEntries().data() + offset.entries);
            L.firstEntry = offset.entries;
            offset.entries += L.count;
        }
    }
}


void World::sumBodyForces(double dtKick)
{
    const int N = static_cast<int>(bodies_.size());

    // Orphaned: called inside a parallel region (or by one thread). Each
    // thread takes a static chunk of bodies and does all of a body's work,
    // so the chunk needs no barrier: contact sums in the body's fixed pair
    // order, body-force models, totals and the second half kick
    const ThreadShare share(N);
    const int begin = share.begin;
    const int end = share.end;

    for (int b = begin; b < end; ++b)
    {
        const ContactLoad c = contactLoad(b);
        bodies_[b].force = c.force;
        bodies_[b].torque = c.torque;
    }

    const bool models = !forceModels_.empty();
    if (models)
    {
        for (int b = begin; b < end; ++b)
        {
            modelForce_[b].setZero();
            modelTorque_[b].setZero();
        }
        for (const auto& m : forceModels_)
        {
            m->addForces(*this, begin, end, modelForce_.data(), modelTorque_.data());
        }
    }

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
    }
}


void World::bodyForces(double dtKick)
{
    const int N = static_cast<int>(bodies_.size());

    // Serial preparation of the body-force models (e.g. flow sampling,
    // which may use a parallel region of its own and MPI)
    for (const auto& m : forceModels_)
    {
        m->prepare(*this);
    }

    #pragma omp parallel if(N >= minParallelBodies)
    {
        sumBodyForces(dtKick);
    }
}


void World::computeForces(double dtTangential)
{
    resizeBodyFrames();
    ++evaluation_;
    preparePairs();
    const int nPairs = static_cast<int>(nlist_->pairs().size());
    #pragma omp parallel if(nPairs >= minParallelLoop)
    {
        pairForces(dtTangential);
    }
    bodyForces(0);
}


void World::stepBy(double dt)
{
    if (!initialised_)
    {
        initialise();
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
        }

        if (rebuild)
        {
            #pragma omp single
            {
                nlist_->build(*this);
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


ContactLoad World::contactLoad(int b) const
{
    ContactLoad c;
    if (!nlist_) return c;
    const auto& pairs = nlist_->pairs();
    for (int k = nlist_->bodyBegin(b); k < nlist_->bodyEnd(b); ++k)
    {
        const ContactPair& p = pairs[nlist_->bodyPair(k)];
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
    }
    return c;
}


int World::contactPairCount() const
{
    int n = 0;
    if (nlist_)
    {
        for (const ContactPair& p : nlist_->pairs()) n += p.nContacts > 0;
    }
    return n;
}


std::size_t World::contactStateBytes() const
{
    std::size_t n = nlist_ ? nlist_->bytes() : 0;
    n += staged_.capacity()*sizeof(staged_[0]);
    for (const PairScratch& S : scratch_)
    {
        n += S.contacts.capacity()*sizeof(StoredContact)
           + S.lists.capacity()*sizeof(StoredFeatureList)
           + S.entries.capacity()*sizeof(std::uint32_t);
    }
    return n;
}


long World::neighbourListBuilds() const
{
    return nlist_ ? nlist_->builds() : 0;
}


const NeighbourList& World::neighbourList() const
{
    if (!nlist_) throw Error("neighbourList() before initialise");
    return *nlist_;
}


Energies World::energies() const
{
    Energies e;
    for (const Body& b : bodies_)
    {
        if (!b.isFree()) continue;
        e.kinetic += b.kineticEnergy();
        e.gravitational -= b.mass*settings_.gravity.dot(b.x);
    }
    // Summed in pair order (independent of the thread count)
    if (nlist_)
    {
        for (const ContactPair& p : nlist_->pairs()) e.elastic += p.elasticEnergy;
    }
    return e;
}


std::vector<ContactRecord> World::contactRecords() const
{
    std::vector<ContactRecord> records;
    if (!nlist_) return pendingRecords_;
    for (const ContactPair& p : nlist_->pairs())
    {
        const StoredContact* sc = nlist_->contactsOf(p);
        for (int c = 0; c < p.nContacts; ++c)
        {
            records.push_back({p.i, p.j, sc[c].featureI, sc[c].featureJ, sc[c].xi});
        }
    }
    return records;
}


void World::setContactRecords(const std::vector<ContactRecord>& records)
{
    pendingRecords_ = records;
}


std::vector<World::ContactInfo> World::contacts() const
{
    // Recomputed from the stored state (the contact geometry is that of the
    // last force evaluation; the force uses the present velocities)
    std::vector<ContactInfo> list;
    if (!nlist_) return list;
    FoundContact found[maxContactsPerPair];
    for (const ContactPair& p : nlist_->pairs())
    {
        if (p.nContacts == 0) continue;
        Vec3 axis = p.axis;
        const int n = findPairContacts(p, axis, found);
        for (int c = 0; c < n; ++c)
        {
            Vec3 xi = Vec3::Zero();
            const StoredContact* sc = nlist_->contactsOf(p);
            for (int m = 0; m < p.nContacts; ++m)
            {
                if (sc[m].featureI == found[c].featureA && sc[m].featureJ == found[c].featureB)
                {
                    xi = sc[m].xi;
                }
            }
            const ContactResult r = contactForce(p, found[c].g, xi, 0);
            list.push_back
            (
                {p.i, p.j, found[c].g.type, found[c].g.point, found[c].g.normal, r.forceOnJ, found[c].g.overlap}
            );
        }
    }
    return list;
}


int World::bodyContactCount(int b) const
{
    int n = 0;
    if (nlist_)
    {
        for (int k = nlist_->bodyBegin(b); k < nlist_->bodyEnd(b); ++k)
        {
            n += nlist_->pairs()[nlist_->bodyPair(k)].nContacts;
        }
    }
    return n;
}


void World::checkFinite() const
{
    for (const Body& b : bodies_)
    {
        if
        (
            !b.x.allFinite() || !b.v.allFinite() || !b.L.allFinite()
         || !b.q.coeffs().allFinite() || !b.force.allFinite()
        )
        {
            std::ostringstream msg;
            msg << "body " << b.id << " has a non-finite state at time " << time_
                << " (x = " << b.x.transpose() << ", v = " << b.v.transpose()
                << "): the time step is probably too large";
            throw Error(msg.str());
        }
    }
}

} // namespace iceDEM
