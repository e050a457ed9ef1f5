/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    iceDEMCoupling: the structure's DEM pieces. Built from
    constant/structureDict (addStructure), found again by id after the
    inflow/outflow moved their indices (findPieces), the floes inside the
    hull removed before the start (removeFloesInStructure), the pieces'
    poses from the sixDoF state (captureInitialConfiguration, omegaOf,
    setPiecePoses) and the check of the iceLoad restraint
    (checkRestraint).
\*---------------------------------------------------------------------------*/

#include "iceDEMCoupling.H"
#include "floatingStructure.H"
#include "dictionaryChecks.H"

#include "contact/NarrowPhase.H"
#include "geometry/DilatedShape.H"

#include "IOdictionary.H"
#include "OSspecific.H"
#include "boundBox.H"

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

        // The piece at least minOuterWidthInRadii r thin, so its core (the
        // piece shrunk by r) is an element (strictly: the shrink rounds)
        const scalar width = piece.minWidth();
        const scalar inRadii = ::iceDEM::DilatedShape::minOuterWidthInRadii;
        if (!(inRadii*r < width))
        {
            FatalIOErrorInFunction(sd)
                << "Entry 'radius' " << r << ": " << what.c_str()
                << " is " << width << " m thin at its thinnest; the radius"
                << " must be below 1/" << inRadii << " of that (the DEM core"
                << " is the piece shrunk by the radius, and a dilated body's"
                << " radius is at most half its core's thinnest width)" << nl
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


// ************************************************************************* //
