/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "iceDEMCoupling.H"
#include "resolvedFlowVelocity.H"
#include "iceDragReaction.H"
#include "fvMatrices.H"
#include "dictionaryChecks.H"

#include "hydro/FlowVelocity.H"

#include "OSspecific.H"
#include "postProcessingFile.H"

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

//- d.set(key, value) with the value's doubles exact: a dictionary entry is
//  made through text at the default precision (writePrecision), which
//  would round what a restart reads back
template<class T>
void setExact(Foam::dictionary& d, const Foam::word& key, const T& value)
{
    const unsigned precision = Foam::IOstream::defaultPrecision();
    Foam::IOstream::defaultPrecision(17);
    d.set(key, value);
    Foam::IOstream::defaultPrecision(precision);
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::iceDEMCoupling::publishLoad()
{
    forceField_->value() = pendingForce_;
    momentField_->value() = pendingMoment_;

    dictionary& cs = case_->couplingState();
    setExact(cs, "iceLoadForce", pendingForce_);
    setExact(cs, "iceLoadMoment", pendingMoment_);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::iceDEMCoupling::iceDEMCoupling
(
    const Time& runTime,
    const fvMesh* mesh,
    const sixDoFRigidBodyMotion* motion
)
:
    runTime_(runTime),
    mesh_(mesh),
    motion_(motion),
    flow_(),
    case_(),
    output_(),
    firstPiece_(0),
    nPieces_(0),
    CoR0_(Zero),
    Q0init_(tensor::I),
    oldState_(),
    fixedCoR_(Zero),
    pendingForce_(Zero),
    pendingMoment_(Zero)
{
    iceDEMCase::flowVelocityFactory factory;
    if (mesh_)
    {
        factory = [this](const dictionary& dd)
        {
            flow_ = std::make_shared<resolvedFlowVelocity>(*mesh_, dd);
            return std::shared_ptr<const ::iceDEM::FlowVelocity>(flow_);
        };
    }
    case_.reset(new iceDEMCase(runTime, factory));

    const dictionary& props = case_->properties();

    if (flow_ && flow_->twoWay() && case_->inflowOutflow())
    {
        // The two-way impulses are kept per floe and face until the flow
        // takes them: a floe removed in the sub-cycle would take its share
        // out of the momentum balance
        FatalIOErrorInFunction(props)
            << "Entry 'domain' (type inflowOutflow) of constant/"
            << "iceDEMProperties: not available yet with drag { twoWay true; }"
            << " (a removed floe's drag impulse would leave the momentum"
            << " balance); use a periodic domain or twoWay false" << nl
            << exit(FatalIOError);
    }

    word forceName("iceLoadForce");
    word momentName("iceLoadMoment");
    if (props.found("coupling", keyType::LITERAL))
    {
        const dictionary& cd = props.subDict("coupling");
        checkEntries
        (
            cd, "constant/iceDEMProperties", {"coupling"}, "coupling"
        );
        forceName = cd.getOrDefault<word>("force", forceName);
        momentName = cd.getOrDefault<word>("moment", momentName);
    }

    if (props.found("structure", keyType::LITERAL))
    {
        addStructure(props.subDict("structure"));
    }
    else
    {
        Info<< "iceDEM: no 'structure' in constant/iceDEMProperties: the"
            << " floes do not meet the structure" << nl;
    }

    if (motion_)
    {
        captureInitialConfiguration();
    }

    removeFloesInStructure();

    // The pieces at the structure's current pose
    if (nPieces_)
    {
        const sixDoFRigidBodyMotionState* s =
            motion_ ? &motion_->state() : nullptr;
        setPiecePoses(1, s, s);
    }

    case_->prescribedMotion(false);

    // The first force evaluation (start) samples the initial flow
    if (flow_)
    {
        flow_->update();
    }
    case_->start();
    findPieces();       // a restart with inflow/outflow moves them

    // The design configuration: captured from the motion at the start of a
    // run, where the rotation is the initial one, and kept in the state,
    // so a restart uses the same doubles (recovered at a rotated pose they
    // would differ by round-off, and the pieces' poses with them)
    if (motion_)
    {
        dictionary& cs = case_->couplingState();
        if (case_->restarted() && cs.found("structureCentreOfRotation0"))
        {
            CoR0_ = cs.get<vector>("structureCentreOfRotation0");
            Q0init_ = cs.get<tensor>("structureOrientation0");
        }
        setExact(cs, "structureCentreOfRotation0", CoR0_);
        setExact(cs, "structureOrientation0", Q0init_);
    }

    if (flow_ && flow_->twoWay())
    {
        reaction_.reset
        (
            new iceDragReaction
            (
                *mesh_,
                *flow_,
                props.subDict("water").get<scalar>("density")
            )
        );
    }

    if (case_->restarted())
    {
        const dictionary& cs = case_->couplingState();
        pendingForce_ = cs.getOrDefault<vector>("iceLoadForce", Zero);
        pendingMoment_ = cs.getOrDefault<vector>("iceLoadMoment", Zero);
        if (reaction_ && cs.found("dragSourceInterval"))
        {
            // The written source holds this much DEM time of impulse that
            // the flow has not taken (flowSolveInterval > 1)
            reaction_->restartInterval(cs.get<scalar>("dragSourceInterval"));
        }
        if (reaction_ && cs.found("dragFaces"))
        {
            // The kick forces are those of the state's multi-rate interval
            // (a state without the entry: the single rate); World corrects
            // its bodies' kicks to a new interval from the restart pose's
            // forces, which the saved face drag cannot follow exactly
            const label kState = cs.getOrDefault<label>("dragKickInterval", 1);
            const label k = case_->world().bodyForceInterval();
            if (kState != k)
            {
                FatalIOErrorInFunction(props)
                    << "Entry 'bodyForceInterval' of constant/iceDEMProperties"
                    << " (" << k << ") differs from the restart state's ("
                    << kState << ") with two-way drag (drag { twoWay true; }):"
                    << " the face drag returned to the flow would no longer be"
                    << " the floes' drag impulse. Restart with bodyForceInterval "
                    << kState << ", or start the run anew" << nl
                    << exit(FatalIOError);
            }
            // The kick force of the last step before the write (the
            // restart's first evaluation samples a later flow field)
            flow_->setFaceDrag
            (
                cs.get<labelList>("dragFaces"),
                cs.get<List<vector>>("dragFaceForces"),
                cs.get<List<scalar>>("dragFaceCoefficients")
            );
        }
        Info<< "iceDEM: pending ice load from the state: force "
            << pendingForce_ << " N, moment " << pendingMoment_ << " N m"
            << nl;
    }

    forceField_.reset
    (
        new uniformDimensionedVectorField
        (
            IOobject
            (
                forceName,
                runTime.timeName(),
                runTime,
                IOobject::NO_READ,
                IOobject::NO_WRITE
            ),
            dimensionedVector(forceName, dimForce, pendingForce_)
        )
    );
    momentField_.reset
    (
        new uniformDimensionedVectorField
        (
            IOobject
            (
                momentName,
                runTime.timeName(),
                runTime,
                IOobject::NO_READ,
                IOobject::NO_WRITE
            ),
            dimensionedVector(momentName, dimForce*dimLength, pendingMoment_)
        )
    );
    publishLoad();

    output_.reset(new iceDEMOutput(*case_));
    output_->write(true);

    if (Pstream::master())
    {
        const fileName dir
        (
            runTime.globalPath()/"postProcessing"/"iceLoad"
           /runTime.timeName(runTime.startTime().value())
        );
        mkDir(dir);
        loadFile_.reset
        (
            new OFstream(newOutputFile(runTime, dir, "iceLoad.dat"))
        );
        loadFile_().precision
        (
            case_->outputDict().getOrDefault<label>("precision", 12)
        );
        loadFile_()
            << "# Ice load on the structure, averaged over each time step"
            << " (applied at the next step)" << nl
            << "# F [N], M [N m] about the centre of rotation, global axes;"
            << " contacts: most floe-structure contacts in a DEM sub-step"
            << nl
            << "# time Fx Fy Fz Mx My Mz contacts" << endl;
    }

    checkRestraint();

    Info<< "iceDEM: coupled to " << (mesh_ ? "the flow" : "-noFlow")
        << ", drag " << case_->dragType().c_str()
        << ", DEM output in " << output_->path() << nl << endl;
}


// * * * * * * * * * * * * * * * * Destructor  * * * * * * * * * * * * * * //

Foam::iceDEMCoupling::~iceDEMCoupling()
{}


// * * * * * * * * * * * * * * * Static Functions  * * * * * * * * * * * * //

bool Foam::iceDEMCoupling::present(const Time& runTime)
{
    return isFile(runTime.globalPath()/"constant"/"iceDEMProperties");
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void Foam::iceDEMCoupling::beginStep()
{
    forceField_->value() = pendingForce_;
    momentField_->value() = pendingMoment_;

    if (motion_)
    {
        oldState_.reset(new sixDoFRigidBodyMotionState(motion_->state()));
    }
}


void Foam::iceDEMCoupling::beginFlowSolve()
{
    if (reaction_)
    {
        reaction_->flowTakesSource();
    }
}


void Foam::iceDEMCoupling::solve()
{
    ::iceDEM::World& w = case_->world();

    const scalar t1 = runTime_.value();
    const scalar t0 = w.time();
    const scalar span = t1 - t0;

    if (reaction_)
    {
        // The impulse the implicit part gave the flow in the flow step
        reaction_->correct();
    }
    if (flow_)
    {
        flow_->update();
    }

    const sixDoFRigidBodyMotionState* s1 =
        motion_ ? &motion_->state() : nullptr;
    const sixDoFRigidBodyMotionState* s0 =
        oldState_.valid() ? oldState_.get() : s1;

    const scalar dt = w.settings().timeStep;
    const scalar tol = 1e-6*dt;

    ::iceDEM::Vec3 impulseF = ::iceDEM::Vec3::Zero();
    ::iceDEM::Vec3 impulseM = ::iceDEM::Vec3::Zero();
    label maxContacts = 0;
    label steps = 0;

    try
    {
        while (t1 - w.time() > tol)
        {
            const scalar tPrev = w.time();
            const scalar remaining = t1 - tPrev;
            const bool last = remaining < dt + tol;
            const scalar tNext = last ? t1 : tPrev + dt;

            ::iceDEM::Vec3 CoR = toVec3(fixedCoR_);
            if (nPieces_)
            {
                const scalar s = span > 0 ? (tNext - t0)/span : 1;
                CoR = toVec3(setPiecePoses(s, s0, s1));
            }

            // Steps of exactly dt (see iceDEMCase::advanceTo)
            scalar hStep = dt;
            if (!last)
            {
                w.step();
            }
            else if (remaining > dt - tol)
            {
                w.step();
                w.setTime(t1);
            }
            else
            {
                w.advanceTo(t1);    // one step of 'remaining'
                hStep = remaining;
            }
            ++steps;
            if (reaction_)
            {
                // The step evaluated the body forces if it ended an outer
                // step of the multi-rate schedule (its phase is back at 0)
                flow_->accumulate
                (
                    hStep,
                    w.bodyForcePhase() == 0 ? w.bodyForceInterval() : 0
                );
            }

            findPieces();   // inflow/outflow may have removed floes
            const scalar h = (last ? t1 : w.time()) - tPrev;
            case_->stepDone(h);

            // A piece's force and torque are its contact load (no model
            // acts on a prescribed body, no gravity); unlike contactLoad
            // they survive the neighbour list's rebuild after a removal
            ::iceDEM::Vec3 F = ::iceDEM::Vec3::Zero();
            ::iceDEM::Vec3 M = ::iceDEM::Vec3::Zero();
            bool touching = false;
            for (label p = 0; p < nPieces_; ++p)
            {
                const ::iceDEM::Body& b = w.bodies()[firstPiece_ + p];
                if (b.force.squaredNorm() > 0 || b.torque.squaredNorm() > 0)
                {
                    touching = true;
                    F += b.force;
                    M += b.torque + (b.x - CoR).cross(b.force);
                }
            }
            impulseF += h*F;
            impulseM += h*M;

            if (touching)
            {
                // Contacts on the hull pieces (pieces never touch each other)
                label n = 0;
                for (label p = 0; p < nPieces_; ++p)
                {
                    n += w.bodyContactCount(firstPiece_ + p);
                }
                maxContacts = max(maxContacts, n);
            }
        }
        w.setTime(t1);
        w.checkFinite();
        case_->writeInflowOutflow();
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction
            << "DEM stopped at time " << w.time()
            << " (advancing to " << t1 << "): " << err.what() << nl
            << case_->entryContext(err).c_str() << nl
            << exit(FatalError);
    }

    if (span > 0)
    {
        pendingForce_ = toVector(impulseF/span);
        pendingMoment_ = toVector(impulseM/span);
    }
    else
    {
        pendingForce_ = Zero;
        pendingMoment_ = Zero;
    }
    publishLoad();

    if (reaction_)
    {
        // Over the flow step the source acts for (the DEM interval span
        // differs from it by round-off of the time values only)
        reaction_->update(runTime_.deltaTValue());

        labelList nFaces;
        List<vector> F;
        List<scalar> K;
        flow_->getFaceDrag(nFaces, F, K);
        dictionary& cs = case_->couplingState();
        cs.set("dragFaces", nFaces);
        setExact(cs, "dragFaceForces", F);
        setExact(cs, "dragFaceCoefficients", K);
        setExact(cs, "dragSourceInterval", reaction_->interval());
        cs.set("dragKickInterval", label(w.bodyForceInterval()));
    }

    if (loadFile_.valid())
    {
        loadFile_()
            << t1 << ' '
            << pendingForce_.x() << ' ' << pendingForce_.y() << ' '
            << pendingForce_.z() << ' '
            << pendingMoment_.x() << ' ' << pendingMoment_.y() << ' '
            << pendingMoment_.z() << ' ' << maxContacts << endl;
    }

    output_->write();

    Info<< "iceDEM: " << steps << " DEM steps, contacts "
        << w.contactCount() << " (" << w.contactPairCount() << " pairs),"
        << " on the structure " << maxContacts << nl
        << "    ice load " << pendingForce_ << " N, moment "
        << pendingMoment_ << " N m" << nl;

    if (flow_)
    {
        const resolvedFlowVelocity::statistics st = flow_->stats();
        const label perEval =
            st.evaluations ? st.points/st.evaluations : 0;
        Info<< "    resolved drag: " << perEval
            << " points per sampling (" << st.evaluations << " samplings), "
            << st.outside
            << " of " << st.points << " outside the mesh (far-field current)";
        if (st.images)
        {
            Info<< ", " << st.images << " at a periodic image";
        }
        if (st.unprepared)
        {
            Info<< ", " << st.unprepared << " not prepared";
        }
        Info<< nl;
    }
}


Foam::tmp<Foam::fvVectorMatrix> Foam::iceDEMCoupling::momentumSource
(
    const volVectorField& U
) const
{
    if (!reaction_)
    {
        FatalErrorInFunction
            << "momentumSource() without two-way coupling" << nl
            << exit(FatalError);
    }
    return reaction_->source(U);
}


Foam::tmp<Foam::volVectorField> Foam::iceDEMCoupling::explicitMomentumSource
(
    const volVectorField& U
) const
{
    if (!reaction_)
    {
        FatalErrorInFunction
            << "explicitMomentumSource() without two-way coupling" << nl
            << exit(FatalError);
    }
    return reaction_->explicitSource(U);
}


Foam::scalar Foam::iceDEMCoupling::samplingSeconds() const
{
    return flow_ ? flow_->stats().seconds : 0;
}


// ************************************************************************* //
