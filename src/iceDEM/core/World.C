/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "worldDetail.H"
#include "contact/NarrowPhase.H"
#include "contact/NeighbourList.H"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

namespace iceDEM
{

using namespace worldDetail;

namespace
{
    //- Source of World::instance(): 1, 2, ... over the process
    std::atomic<long> worldsMade{0};
}

World::World(const WorldSettings& settings)
:
    settings_(settings),
    law_(ContactLaw::New(settings.contact)),
    instance_(++worldsMade)
{
    if (!(settings_.timeStep > 0))
    {
        throw Error("the DEM time step must be > 0", "deltaT");
    }
    if (!(settings_.contactCheckVelocity > 0))
    {
        throw Error("contactCheckVelocity must be > 0", "contactCheckVelocity");
    }
    if (!(settings_.contactStepsMin > 0) || settings_.contactStepsWarn < settings_.contactStepsMin)
    {
        throw Error("need 0 < contactStepsMin <= contactStepsWarn", "contactStepsMin");
    }
    if (settings_.bodyForceInterval < 1)
    {
        throw Error("bodyForceInterval must be an integer >= 1", "bodyForceInterval");
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
    // A shape added to a running world's hydrodynamics (inflow) keeps what
    // the ones before it keep (prepareModels)
    if (modelsReadOuter()) shapes_.back().keepOuter();
    return static_cast<int>(shapes_.size()) - 1;
}


void World::replaceShape(int index, const DilatedShape& s)
{
    if (index < 0 || index >= int(shapes_.size()))
    {
        throw Error("replaceShape: no shape " + std::to_string(index), "shape");
    }
    for (const Body& b : bodies_)
    {
        if (b.shape == index)
        {
            throw Error("replaceShape: shape " + std::to_string(index) + " is in use", "shape");
        }
    }
    if (int(s.core().vertices().size()) > maxShapeVertices)
    {
        throw Error("a shape has too many core vertices", "points");
    }
    shapes_[index] = s;
    if (modelsReadOuter()) shapes_[index].keepOuter();
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


void World::setDomain(const DomainSettings& s)
{
    if (initialised_)
    {
        throw Error("the domain can only be set before the run starts", "domain");
    }
    domain_ = std::make_unique<Domain>(s);
    if (!domain_->active()) domain_.reset();
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
    // kept, not derived each time (a quarter of a Kulluk run otherwise),
    // with a prism's caps
    if (modelsReadOuter())
    {
        for (DilatedShape& s : shapes_) s.keepOuter();
    }
}


bool World::modelsReadOuter() const
{
    for (const auto& m : forceModels_)
    {
        if (m->readsOuterPolyhedra()) return true;
    }
    return false;
}


double World::estimatedContactTime() const
{
    return estimatedContactTime(0, static_cast<int>(bodies_.size()));
}


double World::estimatedContactTime(int begin, int end) const
{
    double tc = std::numeric_limits<double>::max();
    const int M = static_cast<int>(materials_.size());
    for (int i = begin; i < end; ++i)
    {
        const Body& b = bodies_[i];
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

    // Periodic domain: free bodies into the periodic bounds (a no-op on a
    // restart, whose state was wrapped), then its checks
    wrapped_.clear();
    if (domain_)
    {
        for (Body& b : bodies_)
        {
            if (b.isFree()) domain_->wrap(b.x);
        }
        domain_->check(*this, skin, warnings_);
        wrapped_.assign(bodies_.size(), Domain::noImage);
    }

    vertexOffset_.clear();
    updateWorldVertices();
    nlist_ = std::make_unique<NeighbourList>(skin);
    listEntriesAtCompaction_ = 0;
    nlist_->build(*this);

    // Overlaps at start: intersecting cores are an error, but between two
    // bodies that were already in the run (a restart from a saved state,
    // or bodies removed or inserted during a run): a hard contact may
    // bring two cores together, and the restart continues the run as the
    // uninterrupted one does
    const int checkFrom =
        !restart ? 0
      : overlapCheckFrom_ >= 0 ? overlapCheckFrom_
      : static_cast<int>(bodies_.size());
    for (const ContactPair& p : nlist_->pairs())
    {
        if (p.isWall()) continue;
        if (p.i < checkFrom && p.j < checkFrom) continue;
        const BodyView A{&shapeOf(p.i), worldVertices(p.i), bodies_[p.i].rotation(), bodies_[p.i].x};
        Vec3 translated[maxShapeVertices];
        const BodyView B = viewOfJ(p, translated);
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
        const int N = static_cast<int>(bodies_.size());
        std::vector<int> pairOf(pendingRecords_.size());
        for (std::size_t r = 0; r < pendingRecords_.size(); ++r)
        {
            const ContactRecord& rec = pendingRecords_[r];
            // The first pair (i, j) in pair order, among body i's pairs (in
            // pair order too): a search of all pairs per record grew as the
            // square of the field (0.16 s of a 6,000-floe restart, most of
            // a minute at 100,000)
            auto it = pairs.end();
            if (rec.i >= 0 && rec.i < N)
            {
                for (int k = nlist_->bodyBegin(rec.i); k < nlist_->bodyEnd(rec.i); ++k)
                {
                    const ContactPair& p = pairs[nlist_->bodyPair(k)];
                    if (p.i == rec.i && p.j == rec.j)
                    {
                        it = pairs.begin() + nlist_->bodyPair(k);
                        break;
                    }
                }
            }
            // Periodic domain: a record names no image; the pair is the one
            // whose image of j is nearest to i (the only one in reach when
            // the domain passed its checks)
            if (domain_ && it != pairs.end() && !it->isWall())
            {
                double best = (centroidOfJ(*it) - bodies_[it->i].x).squaredNorm();
                for (auto jt = it + 1; jt != pairs.end() && jt->i == rec.i && jt->j == rec.j; ++jt)
                {
                    const double d = (centroidOfJ(*jt) - bodies_[jt->i].x).squaredNorm();
                    if (d < best)
                    {
                        best = d;
                        it = jt;
                    }
                }
            }
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
        // Contact geometry and counts for output, without touching the
        // springs; the bodies that were in the run keep their forces (the
        // next half kick's), bodies inserted during the run (from
        // overlapCheckFrom_) take theirs at their pose, as at a start: an
        // inserted floe moves as the same floe present from the start
        const std::size_t kept =
            overlapCheckFrom_ >= 0 ? std::size_t(overlapCheckFrom_) : bodies_.size();
        std::vector<Vec3> F(bodies_.size()), T(bodies_.size());
        for (std::size_t i = 0; i < bodies_.size(); ++i)
        {
            F[i] = bodies_[i].force;
            T[i] = bodies_[i].torque;
        }
        const NeighbourList saved = *nlist_;
        computeForces(0);
        *nlist_ = saved;
        for (std::size_t i = 0; i < std::min(kept, bodies_.size()); ++i)
        {
            bodies_[i].force = F[i];
            bodies_[i].torque = T[i];
        }
        if (restartInterval_ > 0) applyRestartSchedule();
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
            // A body may rest on a wall, but its core may not cross it
            // (beyond the contact model's range: checkOverlapRange)
            if (p.nContacts > 0 && p.isWall() && !(p.deepest < dilationSum(p)))
            {
                std::ostringstream msg;
                msg << "body " << bodies_[p.i].id << " lies across wall "
                    << walls_[p.wall()].name << " at the start (overlap " << p.deepest
                    << " m, dilation radius " << dilationSum(p) << " m): move the wall or the body";
                throw Error(msg.str(), "walls");
            }
        }
    }
    initialised_ = true;
}


void World::wallContactForces(std::vector<Vec3>& f) const
{
    f.assign(walls_.size(), Vec3::Zero());
    if (!nlist_) return;
    for (const ContactPair& p : nlist_->pairs())
    {
        if (p.isWall()) f[p.wall()] += p.forceOnJ;
    }
}


Vec3 World::modelForceOnFreeBodies() const
{
    Vec3 f = Vec3::Zero();
    // Multi-rate step: an inner step kicked with no model force
    const int interval = bodyForceInterval();
    if (interval > 1 && bodyForcePhase_ != 0) return f;
    for (std::size_t b = 0; b < modelForce_.size(); ++b)
    {
        if (bodies_[b].isFree()) f += modelForce_[b];
    }
    return interval > 1 ? Vec3(double(interval)*f) : f;
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
    n += newLists_.capacity()*sizeof(newLists_[0]);
    for (const PairScratch& S : scratch_)
    {
        n += S.contacts.capacity()*sizeof(StoredContact)
           + S.lists.capacity()*sizeof(StoredFeatureList)
           + S.entries.capacity()*sizeof(FeaturePairEntry)
           + S.listPairs.capacity()*sizeof(int);
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
        const PairMotion pm = pairMotion(p);
        double mEff[maxContactsPerPair];
        dampingMasses(pm, found, n, mEff);
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
            const ContactResult r = contactForce(pm, mEff[c], found[c].g, xi, 0);
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


int World::indexOfId(int id, int hint) const
{
    const int N = static_cast<int>(bodies_.size());
    const int start = std::min(hint, N - 1);
    for (int i = start; i >= 0; --i)
    {
        if (bodies_[i].id == id) return i;
    }
    for (int i = std::max(start + 1, 0); i < N; ++i)
    {
        if (bodies_[i].id == id) return i;
    }
    return -1;
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


double World::dilationSum(const ContactPair& p) const
{
    return
        shapes_[bodies_[p.i].shape].radius()
      + (p.isWall() ? 0 : shapes_[bodies_[p.j].shape].radius());
}


void World::checkOverlapRange() const
{
    if (tooDeepPair_ < 0) return;
    const ContactPair& p = nlist_->pairs()[tooDeepPair_];
    const double R = dilationSum(p);
    const double tc = estimatedContactTime();
    std::ostringstream msg;
    msg << "body " << bodies_[p.i].id << " and "
        << (p.isWall() ? "wall " + walls_[p.wall()].name : "body " + std::to_string(bodies_[p.j].id))
        << " overlap by " << p.deepest << " m, as much as their dilation radii's sum "
        << R << " m (a core inside the other: beyond the contact model). The DEM step "
        << settings_.timeStep << " s did not resolve this contact: an impact (estimated"
        << " contact time " << tc << " s at " << settings_.contactCheckVelocity
        << " m/s, shorter for faster impacts), or a light body held by loaded contacts whose"
        << " stiffness and damping the step does not resolve (an oscillation that changes"
        << " sign and grows at every step, which the check at the start does not see;"
        << " normalDamping perPair damps a pair of several contact terms as one contact):"
        << " reduce deltaT";
    throw Error(msg.str(), "deltaT");
}

} // namespace iceDEM
