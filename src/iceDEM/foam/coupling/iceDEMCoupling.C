/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "iceDEMCoupling.H"
#include "resolvedFlowVelocity.H"
#include "iceDragReaction.H"
#include "fvMatrices.H"
#include "floatingStructure.H"
#include "dictionaryChecks.H"

#include "contact/NarrowPhase.H"
#include "geometry/DilatedShape.H"
#include "hydro/FlowVelocity.H"

#include "IOdictionary.H"
#include "OSspecific.H"
#include "boundBox.H"
#include "postProcessingFile.H"

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

//- World-frame core vertices of body i
std::vector<::iceDEM::Vec3> worldCoreVertices
(
    const ::iceDEM::World& w,
    int i
)
{
    const ::iceDEM::Body& b = w.bodies()[i];
    const ::iceDEM::Mat3 R = b.rotation();
    const auto& V = w.shapeOf(i).core().vertices();
    std::vector<::iceDEM::Vec3> out(V.size());
    for (size_t k = 0; k < V.size(); ++k)
    {
        out[k] = R*V[k] + b.x;
    }
    return out;
}


//- The convex polyhedron P with every face moved inwards by r: vertices
//  from the intersections of three moved face planes that lie inside all of
//  them, points closer than 1e-6 of the size merged (where four or more
//  faces meet, as at the rings of a faceted hull, the moved planes meet in
//  clusters of nearly equal points), then the convex hull
::iceDEM::ConvexPolyhedron shrink
(
    const ::iceDEM::ConvexPolyhedron& P,
    double r
)
{
    const auto& F = P.faces();
    double size = 0;
    for (const auto& v : P.vertices())
    {
        size = std::max(size, (v - P.vertices()[0]).norm());
    }
    const double insideTol = 1e-9*size;
    const double mergeTol = 1e-6*size;

    std::vector<::iceDEM::Vec3> pts;
    const int nf = static_cast<int>(F.size());
    for (int i = 0; i < nf; ++i)
    {
        for (int j = i + 1; j < nf; ++j)
        {
            for (int k = j + 1; k < nf; ++k)
            {
                ::iceDEM::Mat3 A;
                A.row(0) = F[i].normal.transpose();
                A.row(1) = F[j].normal.transpose();
                A.row(2) = F[k].normal.transpose();
                if (std::abs(A.determinant()) < 1e-10)
                {
                    continue;
                }
                const ::iceDEM::Vec3 x = A.partialPivLu().solve
                (
                    ::iceDEM::Vec3
                    (
                        F[i].offset - r, F[j].offset - r, F[k].offset - r
                    )
                );
                bool inside = true;
                for (const auto& f : F)
                {
                    if (f.normal.dot(x) - f.offset + r > insideTol)
                    {
                        inside = false;
                        break;
                    }
                }
                if (!inside)
                {
                    continue;
                }
                bool dup = false;
                for (const auto& q : pts)
                {
                    if ((q - x).norm() < mergeTol)
                    {
                        dup = true;
                        break;
                    }
                }
                if (!dup)
                {
                    pts.push_back(x);
                }
            }
        }
    }
    return ::iceDEM::ConvexPolyhedron::hull(pts);
}


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

void Foam::iceDEMCoupling::addStructure(const dictionary& sd)
{
    checkEntries(sd, "constant/iceDEMProperties", {"structure"}, "structure");

    ::iceDEM::World& w = case_->world();

    const word matName = sd.get<word>("material");
    const int material = w.materialIndex(matName);
    if (material < 0)
    {
        wordList names;
        for (const ::iceDEM::Material& m : w.materials())
        {
            names.append(word(m.name));
        }
        FatalIOErrorInFunction(sd)
            << "Entry 'material': unknown material '" << matName << "'" << nl
            << "    Materials: " << flatOutput(names) << nl
            << exit(FatalIOError);
    }
    const scalar r = positive(sd, "radius");
    const word dictName = sd.getOrDefault<word>("dict", "structureDict");
    if (!isFile(runTime_.globalPath()/"constant"/dictName))
    {
        FatalIOErrorInFunction(sd)
            << "Entry 'dict': no file constant/" << dictName << " (the"
            << " structure dictionary)" << nl << exit(FatalIOError);
    }

    // The one definition of the structure (the case root's constant/, also
    // in parallel)
    const floatingStructure structure
    (
        floatingStructure::read(runTime_.globalPath(), dictName)
    );
    fixedCoR_ = structure.centreOfMass();

    firstPiece_ = label(w.bodies().size());

    // DEM pieces: every convex piece of the structure split at its
    // horizontal rings into segments between consecutive rings (a vertex of
    // a segment joins three faces, so moving the faces inwards by r gives
    // a clean core; where four faces meet the inner polyhedron has slivers)
    List<pointField> segments;
    forAll(structure.pieces(), pi)
    {
        const pointField& pts = structure.pieces()[pi];
        const scalar tol = 1e-9*(boundBox(pts, false).mag() + 1);
        DynamicList<scalar> levels;
        for (const point& p : pts)
        {
            bool known = false;
            for (const scalar z : levels)
            {
                known = known || mag(p.z() - z) < tol;
            }
            if (!known)
            {
                levels.append(p.z());
            }
        }
        Foam::sort(levels);
        if (levels.size() < 3)
        {
            segments.append(pts);
            continue;
        }
        for (label k = 0; k + 1 < levels.size(); ++k)
        {
            DynamicList<point> seg;
            for (const point& p : pts)
            {
                if (p.z() > levels[k] - tol && p.z() < levels[k + 1] + tol)
                {
                    seg.append(p);
                }
            }
            segments.append(pointField(seg));
        }
    }
    nPieces_ = segments.size();

    forAll(segments, pi)
    {
        const pointField& pts = segments[pi];
        std::vector<::iceDEM::Vec3> v(pts.size());
        forAll(pts, k)
        {
            v[k] = toVec3(pts[k]);
        }
        const string what
        (
            "structure segment " + Foam::name(pi) + " of constant/" + dictName
        );

        const ::iceDEM::ConvexPolyhedron piece =
            coreCall(sd, what, [&]{ return ::iceDEM::ConvexPolyhedron::hull(v); });

        const scalar width = piece.minWidth();
        if (!(2*r < width))
        {
            FatalIOErrorInFunction(sd)
                << "Entry 'radius' " << r << ": " << what.c_str()
                << " is " << width << " m thin at its thinnest; the radius"
                << " must be below half of that (the DEM core is the piece"
                << " shrunk by the radius)" << nl
                << exit(FatalIOError);
        }

        // Core: the piece shrunk by r, so the dilated body's outer faces
        // are the piece's faces
        const ::iceDEM::ConvexPolyhedron core =
            coreCall(sd, what, [&]{ return shrink(piece, r); });

        const label index = label(w.bodies().size());
        coreCall
        (
            sd, what,
            [&]
            {
                const int shape =
                    w.addShape(::iceDEM::DilatedShape(core, r));
                w.addBody
                (
                    shape,
                    material,
                    ::iceDEM::Vec3::Zero(),
                    ::iceDEM::Quat::Identity(),
                    ::iceDEM::Vec3::Zero(),
                    ::iceDEM::Vec3::Zero(),
                    ::iceDEM::BodyMotion::prescribed,
                    index
                );
            }
        );
        case_->appendBodyName("hull" + Foam::name(pi));
        pieceIds_.push_back(w.bodies()[index].id);

        pieceX0_.push_back(w.bodies()[index].x);
        pieceQ0_.push_back(w.bodies()[index].q);
    }

    Info<< "iceDEM: structure from constant/" << dictName.c_str() << ": "
        << structure.pieces().size() << " convex piece(s), " << nPieces_
        << " segment(s) between rings as prescribed DEM bodies (material "
        << matName.c_str() << ", radius " << r << " m)" << nl;
}


void Foam::iceDEMCoupling::findPieces()
{
    if (!nPieces_)
    {
        return;
    }
    const ::iceDEM::World& w = case_->world();
    const label n = label(w.bodies().size());
    if (firstPiece_ < n && w.bodies()[firstPiece_].id == pieceIds_[0])
    {
        return;
    }
    firstPiece_ = w.indexOfId(pieceIds_[0], int(firstPiece_));
    for (label p = 0; p < nPieces_; ++p)
    {
        if
        (
            firstPiece_ < 0 || firstPiece_ + p >= n
         || w.bodies()[firstPiece_ + p].id != pieceIds_[p]
        )
        {
            FatalErrorInFunction
                << "The structure's DEM bodies (ids " << pieceIds_[0] << " ...)"
                << " are no longer together in the DEM" << exit(FatalError);
        }
    }
}


void Foam::iceDEMCoupling::removeFloesInStructure()
{
    if (!nPieces_)
    {
        return;
    }

    const ::iceDEM::World& w = case_->world();
    const int N = static_cast<int>(w.bodies().size());

    std::vector<std::vector<::iceDEM::Vec3>> pieceVerts(nPieces_);
    for (label p = 0; p < nPieces_; ++p)
    {
        pieceVerts[p] = worldCoreVertices(w, firstPiece_ + p);
    }

    ::iceDEM::NarrowPhaseSettings nps;
    nps.parallelEdgeSin = w.settings().parallelEdgeSin;
    nps.mergeSharePower = w.settings().mergeSharePower;

    std::vector<bool> remove(N, false);
    DynamicList<word> removed;

    for (int i = 0; i < N; ++i)
    {
        const ::iceDEM::Body& bi = w.bodies()[i];
        if (!bi.isFree())
        {
            continue;
        }
        const std::vector<::iceDEM::Vec3> vi = worldCoreVertices(w, i);
        const ::iceDEM::BodyView A
        {
            &w.shapeOf(i), vi.data(), bi.rotation(), bi.x
        };

        for (label p = 0; p < nPieces_ && !remove[i]; ++p)
        {
            const int j = firstPiece_ + p;
            const ::iceDEM::Body& bj = w.bodies()[j];
            const ::iceDEM::BodyView B
            {
                &w.shapeOf(j), pieceVerts[p].data(), bj.rotation(), bj.x
            };

            bool touch = false;
            try
            {
                touch = ::iceDEM::coresIntersect(A, B);
                if (!touch)
                {
                    ::iceDEM::Vec3 axis = ::iceDEM::Vec3::Zero();
                    ::iceDEM::FoundContact found
                    [
                        ::iceDEM::World::maxContactsPerPair
                    ];
                    touch =
                        ::iceDEM::findContacts
                        (
                            A, B, nps, axis, found,
                            ::iceDEM::World::maxContactsPerPair
                        ) > 0;
                }
            }
            catch (const std::exception&)
            {
                touch = true;   // too many contacts: deep inside
            }
            if (touch)
            {
                remove[i] = true;
                removed.append(case_->name(i));
            }
        }
    }

    if (removed.size())
    {
        Info<< "iceDEM: removed " << removed.size() << " floe(s) inside or"
            << " touching the structure at its design pose:";
        const label nShow = min(removed.size(), label(50));
        for (label k = 0; k < nShow; ++k)
        {
            Info<< ' ' << removed[k].c_str();
        }
        if (nShow < removed.size())
        {
            Info<< " ...";
        }
        Info<< nl;

        case_->removeBodies(remove);
        firstPiece_ -= removed.size();
    }
    else
    {
        Info<< "iceDEM: no floe inside the structure" << nl;
    }
}


void Foam::iceDEMCoupling::captureInitialConfiguration()
{
    // transform(p) = CoR + R (p - CoR0), R = Q initialQ^T (sixDoF keeps
    // initialQ and CoR0 private: recover them from transform())
    const sixDoFRigidBodyMotion& m = *motion_;
    const point c = m.transform(point::zero);
    ::iceDEM::Mat3 R;
    for (direction k = 0; k < 3; ++k)
    {
        vector e(Zero);
        e[k] = 1;
        R.col(k) = toVec3(m.transform(point(e)) - c);
    }
    const ::iceDEM::Vec3 CoR = toVec3(m.centreOfRotation());
    CoR0_ = toVector(R.transpose()*(CoR - toVec3(c)));

    const ::iceDEM::Mat3 Q0 = R.transpose()*toMat3(m.orientation());
    Q0init_ = tensor
    (
        Q0(0, 0), Q0(0, 1), Q0(0, 2),
        Q0(1, 0), Q0(1, 1), Q0(1, 2),
        Q0(2, 0), Q0(2, 1), Q0(2, 2)
    );
}


Foam::vector Foam::iceDEMCoupling::omegaOf
(
    const sixDoFRigidBodyMotionState& s
) const
{
    return s.Q() & (inv(motion_->momentOfInertia()) & s.pi());
}


Foam::vector Foam::iceDEMCoupling::setPiecePoses
(
    scalar s,
    const sixDoFRigidBodyMotionState* s0,
    const sixDoFRigidBodyMotionState* s1
)
{
    ::iceDEM::World& w = case_->world();

    if (!s0 || !s1 || !motion_)
    {
        for (label p = 0; p < nPieces_; ++p)
        {
            w.setPrescribedState
            (
                firstPiece_ + p, pieceX0_[p], pieceQ0_[p],
                ::iceDEM::Vec3::Zero(), ::iceDEM::Vec3::Zero()
            );
        }
        return fixedCoR_;
    }

    const ::iceDEM::Vec3 CoR =
        (1 - s)*toVec3(s0->centreOfRotation()) + s*toVec3(s1->centreOfRotation());

    const ::iceDEM::Quat qa(toMat3(s0->Q()));
    const ::iceDEM::Quat qb(toMat3(s1->Q()));
    const ::iceDEM::Quat qs = qa.normalized().slerp(s, qb.normalized());

    const ::iceDEM::Mat3 R =
        qs.toRotationMatrix()*toMat3(Q0init_).transpose();
    const ::iceDEM::Quat qR = ::iceDEM::Quat(R).normalized();

    const ::iceDEM::Vec3 v = (1 - s)*toVec3(s0->v()) + s*toVec3(s1->v());
    const ::iceDEM::Vec3 omega =
        (1 - s)*toVec3(omegaOf(*s0)) + s*toVec3(omegaOf(*s1));

    const ::iceDEM::Vec3 c0 = toVec3(CoR0_);
    for (label p = 0; p < nPieces_; ++p)
    {
        const ::iceDEM::Vec3 x = CoR + R*(pieceX0_[p] - c0);
        w.setPrescribedState
        (
            firstPiece_ + p,
            x,
            qR*pieceQ0_[p],
            v + omega.cross(x - CoR),
            omega
        );
    }
    return toVector(CoR);
}


void Foam::iceDEMCoupling::publishLoad()
{
    forceField_->value() = pendingForce_;
    momentField_->value() = pendingMoment_;

    dictionary& cs = case_->couplingState();
    setExact(cs, "iceLoadForce", pendingForce_);
    setExact(cs, "iceLoadMoment", pendingMoment_);
}


void Foam::iceDEMCoupling::checkRestraint() const
{
    if (!motion_)
    {
        if (nPieces_)
        {
            Info<< "iceDEM: the structure is fixed at its design pose (no"
                << " sixDoF motion); the ice load is written, not applied"
                << nl;
        }
        return;
    }

    IOobject io
    (
        "dynamicMeshDict",
        runTime_.constant(),
        runTime_,
        IOobject::MUST_READ,
        IOobject::NO_WRITE,
        false
    );
    if (!io.typeHeaderOk<IOdictionary>(true))
    {
        return;
    }
    const IOdictionary dmd(io);
    const dictionary& coeffs = dmd.optionalSubDict
    (
        dmd.getOrDefault<word>("motionSolver", "sixDoFRigidBodyMotion")
      + "Coeffs"
    );
    const dictionary* rd = coeffs.findDict("restraints");

    bool found = false;
    if (rd)
    {
        for (const entry& e : *rd)
        {
            if
            (
                e.isDict()
             && e.dict().getOrDefault<word>
                (
                    "sixDoFRigidBodyMotionRestraint", word::null
                ) == "iceLoad"
             && e.dict().getOrDefault<word>("force", "iceLoadForce")
             == forceField_->name()
             && e.dict().getOrDefault<word>("moment", "iceLoadMoment")
             == momentField_->name()
            )
            {
                found = true;
            }
        }
    }
    if (!found)
    {
        WarningInFunction
            << "No restraint of type iceLoad reading "
            << forceField_->name() << '/' << momentField_->name()
            << " in the restraints of " << io.objectPath() << ":" << nl
            << "    the ice load is computed and written but does not move"
            << " the structure" << endl;
    }
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

    if (flow_ && case_->inflowOutflow())
    {
        // The resolved flow keeps per-floe caches by index (its samples,
        // cells and fits), which removals and insertions would mix up
        FatalIOErrorInFunction(props)
            << "Entry 'domain' (type inflowOutflow) of constant/"
            << "iceDEMProperties: not available yet with drag type resolved"
            << " (its per-floe caches follow body indices); use the"
            << " empirical drag or iceFloatingFoam -noFlow" << nl
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
            // The face drag of the last evaluation before the write (the
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
                flow_->accumulate(hStep);
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
