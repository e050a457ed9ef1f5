/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    The case: construction (gravity, then every part of the input read into
    the world: iceDEMCaseSettings.C, iceDEMCaseBodies.C, iceDEMCaseHydro.C,
    iceDEMCaseDomain.C; derived checks in iceDEMCaseChecks.C), body names,
    the start (restart state) and the advance of the DEM with its
    prescribed bodies and step observers.
\*---------------------------------------------------------------------------*/

#include "iceDEMCase.H"
#include "iceDEMState.H"
#include "dictionaryChecks.H"

#include "uniformDimensionedFields.H"

#include <algorithm>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(iceDEMCase, 0);
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

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
        checkBodyForceInterval();
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
    reportThreads();
}


// * * * * * * * * * * * * * * * * Destructor  * * * * * * * * * * * * * * //

Foam::iceDEMCase::~iceDEMCase()
{}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::iceDEMCase::reportThreads() const
{
    #ifdef _OPENMP
    const int threads = omp_get_max_threads();
    const int processors = omp_get_num_procs();
    Info<< "iceDEM: " << threads << " OpenMP threads" << nl << endl;
    if (threads > processors)
    {
        // Allowed (the results do not depend on the number of threads),
        // but threads that wait for a processor hold up each step's barriers
        WarningInFunction
            << threads << " OpenMP threads (OMP_NUM_THREADS or -threads) on "
            << processors << " processor(s) available to this process: the"
            << " threads share processors and the DEM runs slower than on "
            << processors << " thread(s); its results are the same" << endl;
    }
    #else
    Info<< "iceDEM: built without OpenMP (1 thread)" << nl << endl;
    #endif
}


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
    DynamicList<word> kept(bodyNames_.size());
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
        // A first run, or ice added to a flow that ran before it
        world_->setTime(runTime_.value());
        Info<< "iceDEM: the ice starts from constant/iceField at t = "
            << runTime_.value() << " (no " << runTime_.timeName()
            << "/uniform/iceDEMState)" << nl << endl;
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

    reportWarnings();
    startInflowOutflow();
}


void Foam::iceDEMCase::reportWarnings()
{
    for (const std::string& msg : world_->warnings())
    {
        if (warned_.insert(msg).second)
        {
            IOWarningInFunction(properties_)
                << msg.c_str() << nl << endl;
        }
    }
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


Foam::string Foam::iceDEMCase::entryContext(const std::exception& err) const
{
    const ::iceDEM::Error* ice = dynamic_cast<const ::iceDEM::Error*>(&err);
    if (ice && !ice->entry().empty() && properties_.found(ice->entry(), keyType::LITERAL))
    {
        return " (entry '" + ice->entry() + "' of " + properties_.objectPath() + ")";
    }
    return string();
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
            << entryContext(err).c_str() << nl
            << exit(FatalError);
    }
}


// ************************************************************************* //
