/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "iceDEMCase.H"
#include "iceDEMState.H"
#include "dictionaryChecks.H"

#include "uniformDimensionedFields.H"
#include "HashSet.H"
#include "FixedList.H"

#include <algorithm>
#include <cmath>
#include <limits>

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(iceDEMCase, 0);
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

::iceDEM::WorldSettings Foam::iceDEMCase::readSettings() const
{
    const dictionary& d = properties_;

    ::iceDEM::WorldSettings s;

    s.timeStep = positive(d, "deltaT");
    s.gravity = toVec3(g_);

    if (d.found("neighbourSkin", keyType::LITERAL))
    {
        s.skin = positive(d, "neighbourSkin");
    }
    else
    {
        s.skin = -1;    // the core takes the smallest dilation radius
    }

    // Narrow phase's feature-pair lists; 0: none
    if (d.found("featureSkin", keyType::LITERAL))
    {
        s.featureSkin = nonNegative(d, "featureSkin", 0);
    }
    else
    {
        s.featureSkin = -1;     // the core takes half the smallest radius
    }

    wordList contactModels;
    for (const std::string& n : ::iceDEM::ContactLaw::names())
    {
        contactModels.append(word(n));
    }
    s.contact.model = selectName(d, "contactModel", contactModels, "hertz");
    s.contact.tangentialModel =
        selectName(d, "tangentialModel", wordList({"mindlin", "ratio"}), "mindlin");
    s.contact.tangentialStiffnessRatio =
        positive(d, "tangentialStiffnessRatio", 2.0/3.0);
    s.contact.maxEdgeRadiusRatio =
        inRange(d, "maxEdgeRadiusRatio", 1, 1e6, 10);

    s.parallelEdgeSin = inRange(d, "parallelEdgeSin", 0, 0.5, iceDEM::WorldSettings().parallelEdgeSin);
    s.mergeSharePower = inRange(d, "mergeSharePower", 1, 16, iceDEM::WorldSettings().mergeSharePower);
    s.contactCheckVelocity = positive(d, "contactCheckVelocity", 1);
    s.contactStepsWarn = positive(d, "contactStepsWarn", 10);
    s.contactStepsMin = nonNegative(d, "contactStepsMin", 3);

    if (s.contactStepsMin > s.contactStepsWarn)
    {
        FatalIOErrorInFunction(d)
            << "Entry 'contactStepsMin' (" << s.contactStepsMin
            << ") is larger than 'contactStepsWarn' ("
            << s.contactStepsWarn << "): it must not be" << nl
            << exit(FatalIOError);
    }

    return s;
}


void Foam::iceDEMCase::readMaterials()
{
    if (!properties_.isDict("materials"))
    {
        FatalIOErrorInFunction(properties_)
            << "Missing sub-dictionary 'materials', e.g." << nl
            << "    materials { ice { density 900; youngsModulus 1e9;"
            << " poissonsRatio 0.33; } }" << nl
            << exit(FatalIOError);
    }
    const dictionary& mats = properties_.subDict("materials");

    for (const entry& e : mats)
    {
        const word& name = e.keyword();
        if (name.empty() || name[0] == '_')
        {
            continue;
        }
        if (!e.isDict())
        {
            FatalIOErrorInFunction(mats)
                << "Entry '" << name << "' of 'materials' must be a"
                << " dictionary { density ..; youngsModulus ..;"
                << " poissonsRatio ..; }" << nl
                << exit(FatalIOError);
        }
        const dictionary& d = e.dict();
        checkEntries
        (
            d, "constant/iceDEMProperties", {"materials/*"},
            "material " + name
        );

        ::iceDEM::Material m;
        m.name = name;
        m.density = positive(d, "density");
        m.youngsModulus = positive(d, "youngsModulus");
        m.poissonsRatio = inRange(d, "poissonsRatio", -0.99, 0.5);

        coreCall
        (
            d, "material " + name,
            [&]{ ::iceDEM::checkMaterial(m); }
        );

        const label index =
            coreCall(d, "material " + name, [&]{ return world_->addMaterial(m); });
        materialIndex_.insert(name, index);
    }

    if (materialIndex_.empty())
    {
        FatalIOErrorInFunction(mats)
            << "No material in 'materials'" << nl
            << exit(FatalIOError);
    }
}


Foam::label Foam::iceDEMCase::materialOf(const dictionary& dict) const
{
    const word name = dict.get<word>("material");
    const auto iter = materialIndex_.cfind(name);
    if (!iter.found())
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'material': unknown material '" << name << "'" << nl
            << "    Materials of " << "constant/iceDEMProperties" << ": "
            << flatOutput(materialIndex_.sortedToc()) << nl
            << exit(FatalIOError);
    }
    return iter.val();
}


void Foam::iceDEMCase::readInteractions()
{
    if (!properties_.isDict("interactions"))
    {
        FatalIOErrorInFunction(properties_)
            << "Missing sub-dictionary 'interactions' (friction and"
            << " restitution of every pair of materials in contact), e.g."
            << nl
            << "    interactions { iceIce { materials (ice ice);"
            << " friction 0.2; restitution 0.3; } }" << nl
            << exit(FatalIOError);
    }
    const dictionary& inter = properties_.subDict("interactions");

    // Pairs (min, max) of material indices with an entry
    HashSet<labelPair, labelPair::Hash<>> defined;

    for (const entry& e : inter)
    {
        const word& name = e.keyword();
        if (name.empty() || name[0] == '_')
        {
            continue;
        }
        if (!e.isDict())
        {
            FatalIOErrorInFunction(inter)
                << "Entry '" << name << "' of 'interactions' must be a"
                << " dictionary { materials (a b); friction ..;"
                << " restitution ..; }" << nl
                << exit(FatalIOError);
        }
        const dictionary& d = e.dict();
        checkEntries
        (
            d, "constant/iceDEMProperties", {"interactions/*"},
            "interaction " + name
        );

        const FixedList<word, 2> names(d.get<FixedList<word, 2>>("materials"));
        label ab[2];
        for (label k = 0; k < 2; ++k)
        {
            const auto iter = materialIndex_.cfind(names[k]);
            if (!iter.found())
            {
                FatalIOErrorInFunction(d)
                    << "Entry 'materials': unknown material '" << names[k]
                    << "'" << nl
                    << "    Materials: "
                    << flatOutput(materialIndex_.sortedToc()) << nl
                    << exit(FatalIOError);
            }
            ab[k] = iter.val();
        }

        ::iceDEM::PairProperties p;
        p.friction = nonNegative(d, "friction", 0);
        p.restitution = d.getOrDefault<scalar>("restitution", 1);
        if (!(p.restitution > 0 && p.restitution <= 1))
        {
            FatalIOErrorInFunction(d)
                << "Entry 'restitution' is " << p.restitution
                << ": it must lie in (0, 1]" << nl
                << exit(FatalIOError);
        }
        coreCall
        (
            d, "interaction " + name,
            [&]{ ::iceDEM::checkPairProperties(p); }
        );

        const labelPair key(min(ab[0], ab[1]), max(ab[0], ab[1]));
        if (!defined.insert(key))
        {
            FatalIOErrorInFunction(d)
                << "Entry 'materials': the pair (" << names[0] << ' '
                << names[1] << ") has more than one entry in 'interactions'"
                << nl << exit(FatalIOError);
        }

        coreCall
        (
            d, "interaction " + name,
            [&]{ world_->setPairProperties(ab[0], ab[1], p); }
        );
    }

    // Which pairs can meet: bodies with bodies (same material only when
    // two bodies have it), bodies with walls
    const label nMat = materialIndex_.size();
    labelList bodyCount(nMat, 0);
    labelList wallCount(nMat, 0);
    for (const ::iceDEM::Body& b : world_->bodies())
    {
        ++bodyCount[b.material];
    }
    for (const ::iceDEM::Wall& w : world_->walls())
    {
        ++wallCount[w.material];
    }
    // The structure of a coupled solver (added later) meets the bodies like
    // a wall does
    if (properties_.isDict("structure"))
    {
        const dictionary& sd = properties_.subDict("structure");
        if (sd.found("material", keyType::LITERAL))
        {
            ++wallCount[materialOf(sd)];
        }
    }
    wordList matNames(nMat);
    forAllConstIters(materialIndex_, iter)
    {
        matNames[iter.val()] = iter.key();
    }

    for (label a = 0; a < nMat; ++a)
    {
        for (label b = a; b < nMat; ++b)
        {
            const bool meet =
                (a == b ? bodyCount[a] >= 2 : bodyCount[a] && bodyCount[b])
             || (bodyCount[a] && wallCount[b])
             || (bodyCount[b] && wallCount[a]);

            if (meet && !defined.found(labelPair(a, b)))
            {
                FatalIOErrorInFunction(inter)
                    << "No entry in 'interactions' for the material pair ("
                    << matNames[a] << ' ' << matNames[b] << "): every pair"
                    << " of materials whose bodies or walls can touch needs"
                    << " one, e.g." << nl
                    << "    " << matNames[a] << '_' << matNames[b]
                    << " { materials (" << matNames[a] << ' ' << matNames[b]
                    << "); friction 0.2; restitution 0.3; }" << nl
                    << exit(FatalIOError);
            }
        }
    }
}


void Foam::iceDEMCase::readWalls()
{
    if (!properties_.found("walls", keyType::LITERAL))
    {
        return;
    }
    const dictionary& walls = properties_.subDict("walls");

    for (const entry& e : walls)
    {
        const word& name = e.keyword();
        if (name.empty() || name[0] == '_')
        {
            continue;
        }
        if (!e.isDict())
        {
            FatalIOErrorInFunction(walls)
                << "Entry '" << name << "' of 'walls' must be a dictionary"
                << " { point (x y z); normal (nx ny nz); material m; }" << nl
                << exit(FatalIOError);
        }
        const dictionary& d = e.dict();
        checkEntries
        (
            d, "constant/iceDEMProperties", {"walls/*"}, "wall " + name
        );

        ::iceDEM::Wall w;
        w.name = name;
        w.point = toVec3(d.get<vector>("point"));
        w.normal = toVec3(unitVector(d, "normal"));
        w.material = materialOf(d);

        coreCall(d, "wall " + name, [&]{ world_->addWall(w); });
        wallNames_.append(name);
    }
}


void Foam::iceDEMCase::checkDerived() const
{
    const auto& mats = world_->materials();
    const dictionary& matDicts = properties_.subDict("materials");

    auto finitePositive = [](double x) { return x > 0 && std::isfinite(x); };

    // Effective moduli of every pair of materials
    for (size_t a = 0; a < mats.size(); ++a)
    {
        for (size_t b = a; b < mats.size(); ++b)
        {
            const ::iceDEM::PairCoefficients c =
                ::iceDEM::PairCoefficients::make
                (
                    mats[a], mats[b], ::iceDEM::PairProperties()
                );
            if (!finitePositive(c.Estar) || !finitePositive(c.Gstar))
            {
                FatalIOErrorInFunction(matDicts.subDict(mats[b].name))
                    << "Entries 'youngsModulus' of materials "
                    << mats[a].name.c_str() << " (" << mats[a].youngsModulus
                    << ") and " << mats[b].name.c_str() << " ("
                    << mats[b].youngsModulus << "): the effective moduli"
                    << " E* = " << c.Estar << ", G* = " << c.Gstar
                    << " overflow or underflow double precision" << nl
                    << exit(FatalIOError);
            }
        }
    }

    // Masses and inertia of the bodies
    const dictionary& bodyDicts = iceField_.subDict("bodies");
    const auto& bodies = world_->bodies();
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        const ::iceDEM::Body& b = bodies[i];
        if
        (
            !finitePositive(b.mass)
         || !finitePositive(b.invInertia.minCoeff())
         || !std::isfinite(b.invInertia.maxCoeff())
         || !b.x.allFinite() || !b.v.allFinite() || !b.L.allFinite()
        )
        {
            const word& name = bodyNames_[i];
            FatalIOErrorInFunction(bodyDicts.subDict(name))
                << "Body " << name << ": mass " << b.mass
                << ", inverse principal moments of inertia ("
                << b.invInertia.x() << ' ' << b.invInertia.y() << ' '
                << b.invInertia.z() << ") from the entry 'density' ("
                << mats[b.material].density << ") of material "
                << mats[b.material].name.c_str()
                << " in constant/iceDEMProperties and the body's size,"
                << " position, velocity or omega here: not finite and"
                << " positive in double precision" << nl
                << exit(FatalIOError);
        }
    }

    // Energies (squares of the speeds) and positions the contact detection
    // can resolve: |x| eps below the dilation radius
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        const ::iceDEM::Body& b = bodies[i];
        const scalar energy =
            0.5*b.mass*b.v.squaredNorm() + 0.5*b.omega().dot(b.L);
        const scalar r = world_->shapeOf(int(i)).radius();
        const word& name = bodyNames_[i];
        if (!std::isfinite(energy))
        {
            FatalIOErrorInFunction(bodyDicts.subDict(name))
                << "Body " << name << ": entries 'velocity' and 'omega' give"
                << " a kinetic energy beyond double precision" << nl
                << exit(FatalIOError);
        }
        if (!(b.x.norm()*std::numeric_limits<double>::epsilon() < r))
        {
            FatalIOErrorInFunction(bodyDicts.subDict(name))
                << "Body " << name << ": its position (entries 'centre',"
                << " 'outline', 'zBottom' or 'points') is too far from the"
                << " origin for double precision to resolve its dilation"
                << " radius " << r << " (|x| eps < radius)" << nl
                << exit(FatalIOError);
        }
    }

    // The Hertz contact time that the time-step check uses
    if (bodies.size())
    {
        // The core starts from the largest double: left there, a body's
        // estimate overflowed (or was NaN)
        const scalar tc = world_->estimatedContactTime();
        if (!finitePositive(tc) || tc >= std::numeric_limits<double>::max())
        {
            FatalIOErrorInFunction(matDicts)
                << "The Hertz contact time estimate over- or underflows"
                << " double precision (" << tc << " s): the"
                << " entries 'youngsModulus' and 'density' of the materials"
                << " (or 'contactCheckVelocity') are beyond what double"
                << " precision resolves" << nl
                << exit(FatalIOError);
        }
    }
}


void Foam::iceDEMCase::setPrescribed(scalar t)
{
    for (const prescribedBody& p : prescribed_)
    {
        const scalar tau = t - p.t0;
        const ::iceDEM::Vec3 x = p.x0 + tau*p.v;
        const scalar w = p.omega.norm();
        ::iceDEM::Quat q = p.q0;
        if (w > 0)
        {
            q = ::iceDEM::Quat
                (
                    Eigen::AngleAxisd(w*tau, p.omega/w)
                )*p.q0;
            q.normalize();
        }
        label index = p.index;
        if (inflow_)
        {
            // Removed floes move the indices down: follow the id
            const auto& bodies = world_->bodies();
            index = std::min(index, label(bodies.size()) - 1);
            while (index > 0 && bodies[index].id != p.id) --index;
        }
        world_->setPrescribedState(index, x, q, p.v, p.omega);
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::iceDEMCase::iceDEMCase
(
    const Time& runTime,
    const flowVelocityFactory& resolvedFlow
)
:
    runTime_(runTime),
    properties_
    (
        IOobject
        (
            "iceDEMProperties",
            runTime.constant(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    ),
    iceField_
    (
        IOobject
        (
            "iceField",
            runTime.constant(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    ),
    g_(Zero),
    movePrescribed_(true),
    water_(false),
    dragType_("none"),
    restarted_(false)
{
    // OpenFOAM merges a keyword given twice: two bodies of one name
    checkDuplicateKeywords(properties_, properties_.objectPath());
    checkDuplicateKeywords(iceField_, iceField_.objectPath());

    checkEntries
    (
        properties_, "constant/iceDEMProperties", {""}, "the top level"
    );
    checkEntries(iceField_, "constant/iceField", {""}, "the top level");

    // Gravity: constant/g as in every OpenFOAM case
    {
        IOobject gIO
        (
            "g",
            runTime.constant(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        );
        if (!gIO.typeHeaderOk<uniformDimensionedVectorField>(true))
        {
            FatalErrorInFunction
                << "Cannot read " << gIO.objectPath() << nl
                << "    Gravity comes from constant/g (class"
                << " uniformDimensionedVectorField; dimensions [0 1 -2 0 0"
                << " 0 0]; value (0 0 -9.81);), value (0 0 0) switches it"
                << " off" << nl
                << exit(FatalError);
        }
        uniformDimensionedVectorField g(gIO);
        if (g.dimensions() != dimAcceleration)
        {
            FatalErrorInFunction
                << gIO.objectPath() << ": dimensions " << g.dimensions()
                << " are not those of an acceleration " << dimAcceleration
                << nl << exit(FatalError);
        }
        g_ = g.value();
    }

    world_.reset
    (
        coreCall
        (
            properties_, "constant/iceDEMProperties",
            [&]{ return new ::iceDEM::World(readSettings()); }
        )
    );

    {
        // Masses and inertia of huge entries overflow here: checked below
        floatingPointHold hold;
        readMaterials();
        readWalls();
        readBodies();
        readInteractions();
        readWater(resolvedFlow);
        readDomain();
        checkDerived();
    }

    Info<< "iceDEM: " << bodyNames_.size() << " bodies, "
        << wallNames_.size() << " walls, " << materialIndex_.size()
        << " materials, contactModel "
        << world_->settings().contact.model.c_str()
        << ", deltaT " << world_->settings().timeStep
        << ", g " << g_;
    if (water_)
    {
        Info<< ", water on, drag " << dragType_;
    }
    Info<< nl << endl;
}


// * * * * * * * * * * * * * * * * Destructor  * * * * * * * * * * * * * * //

Foam::iceDEMCase::~iceDEMCase()
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

Foam::word Foam::iceDEMCase::name(label i) const
{
    if (i < 0)
    {
        const label w = -1 - i;
        return
            w < wallNames_.size() ? wallNames_[w] : word("wall" + Foam::name(w));
    }
    if (inflow_ && i < label(world_->bodies().size()))
    {
        // Indices move with inflow/outflow; ids do not
        const label id = world_->bodies()[i].id;
        const auto iter = idName_.cfind(id);
        return iter.found() ? *iter : word("inflow" + Foam::name(id));
    }
    return
        i < bodyNames_.size() ? bodyNames_[i] : word("body" + Foam::name(i));
}


const Foam::dictionary& Foam::iceDEMCase::outputDict() const
{
    return properties_.optionalSubDict("output");
}


void Foam::iceDEMCase::appendBodyName(const word& name)
{
    if (bodyNames_.size() + 1 != label(world_->bodies().size()))
    {
        FatalErrorInFunction
            << "Body name " << name << " given for body "
            << bodyNames_.size() << " of " << world_->bodies().size()
            << ": name every added body right after adding it" << nl
            << exit(FatalError);
    }
    // With inflow/outflow the solver finds its bodies again by id (their
    // indices move); the name goes with the id (start)
    bodyNames_.append(name);
}


void Foam::iceDEMCase::removeBodies(const std::vector<bool>& remove)
{
    if (state_.valid())
    {
        FatalErrorInFunction
            << "Bodies can only be removed before the DEM starts" << nl
            << exit(FatalError);
    }
    wordList kept;
    forAll(bodyNames_, i)
    {
        if (size_t(i) >= remove.size() || !remove[i])
        {
            kept.append(bodyNames_[i]);
        }
    }
    coreCall
    (
        iceField_, "removing bodies",
        [&]{ world_->removeBodies(remove); }
    );
    bodyNames_.transfer(kept);
}


void Foam::iceDEMCase::start()
{
    state_.reset(new iceDEMState(runTime_, *this));

    // Names by id before a restart changes the set of bodies
    if (inflow_)
    {
        const auto& bodies = world_->bodies();
        forAll(bodyNames_, i)
        {
            if (i < label(bodies.size()))
            {
                idName_.set(bodies[i].id, bodyNames_[i]);
            }
        }
    }
    if (state_->found())
    {
        state_->apply(*world_);
        if (state_->dict().isDict("coupling"))
        {
            couplingState_ = state_->dict().subDict("coupling");
        }
        restarted_ = true;
        Info<< "iceDEM: restart from " << state_->objectPath()
            << " (DEM time " << world_->time() << ", "
            << world_->contactRecords().size() << " contacts)" << nl << endl;
    }
    else
    {
        world_->setTime(runTime_.value());
    }

    // Prescribed bodies start from their current pose
    if (movePrescribed_)
    {
        const auto& bodies = world_->bodies();
        for (label i = 0; i < label(bodies.size()); ++i)
        {
            const ::iceDEM::Body& b = bodies[i];
            if (b.motion == ::iceDEM::BodyMotion::prescribed)
            {
                prescribedBody p;
                p.index = i;
                p.id = b.id;
                p.x0 = b.x;
                p.q0 = b.q;
                p.v = b.v;
                p.omega = b.omega();
                p.t0 = world_->time();
                prescribed_.append(p);
            }
        }
    }

    try
    {
        world_->initialise(restarted_);
    }
    catch (const std::exception& err)
    {
        // The time-step check names a settings entry; the rest is about
        // the bodies
        const ::iceDEM::Error* ice =
            dynamic_cast<const ::iceDEM::Error*>(&err);
        const bool settings =
            ice && !ice->entry().empty()
         && properties_.found(ice->entry(), keyType::LITERAL);

        string context("Cannot start the DEM");
        if (!settings && bodyNames_.size())
        {
            context += " (body indices follow constant/iceField:";
            const label n = min(bodyNames_.size(), label(20));
            for (label i = 0; i < n; ++i)
            {
                context += " " + Foam::name(i) + " = " + bodyNames_[i];
                context += (i + 1 < n ? "," : "");
            }
            context += (n < bodyNames_.size() ? ", ...)" : ")");
        }

        const bool state =
            restarted_ && ice && ice->entry() == "contacts";

        coreError
        (
            state
          ? state_->dict()
          : settings
          ? static_cast<const dictionary&>(properties_)
          : static_cast<const dictionary&>(iceField_),
            err,
            context
        );
    }

    for (const std::string& msg : world_->warnings())
    {
        IOWarningInFunction(properties_)
            << msg.c_str() << nl << endl;
    }
    startInflowOutflow();
}


void Foam::iceDEMCase::addStepObserver
(
    const std::shared_ptr<stepObserver>& o
) const
{
    observers_.push_back(o);
}


void Foam::iceDEMCase::stepDone(scalar h) const
{
    for (const auto& w : observers_)
    {
        if (const auto o = w.lock())
        {
            o->demStep(*this, h);
        }
    }
}


void Foam::iceDEMCase::advanceTo(scalar t)
{
    ::iceDEM::World& w = *world_;
    const scalar dt = w.settings().timeStep;

    // Steps of exactly dt: a last step within tol of dt is taken as dt and
    // the DEM time set to t, so the step lengths do not depend on the
    // round-off of t (a restarted run reads t from the time name) and a
    // restart reproduces the uninterrupted run bit for bit. Only a genuine
    // remainder (controlDict deltaT not a multiple of the DEM step) gives a
    // shorter last step.
    const scalar tol = 1e-6*dt;
    const bool move = movePrescribed_ && prescribed_.size();

    try
    {
        while (t - w.time() > tol)
        {
            const scalar tPrev = w.time();
            const scalar remaining = t - tPrev;
            const bool last = remaining < dt + tol;

            if (move)
            {
                setPrescribed(last ? t : w.time() + dt);
            }

            if (!last)
            {
                w.step();
            }
            else if (remaining > dt - tol)
            {
                w.step();
                w.setTime(t);
            }
            else
            {
                w.advanceTo(t);
            }
            stepDone((last ? t : w.time()) - tPrev);
        }
        w.setTime(t);
        w.checkFinite();
        writeInflowOutflow();
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction
            << "DEM stopped at time " << w.time()
            << " (advancing to " << t << "): " << err.what() << nl
            << exit(FatalError);
    }
}


// ************************************************************************* //
