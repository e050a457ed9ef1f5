/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

\*---------------------------------------------------------------------------*/

#include "rigidLidMotionSolver.H"
#include "structureMotion.H"
#include "dictionaryChecks.H"
#include "addToRunTimeSelectionTable.H"
#include "uniformDimensionedFields.H"
#include "verticalModes.H"
#include "forces.H"
#include "volFields.H"

namespace Foam
{
    defineTypeNameAndDebug(rigidLidMotionSolver, 0);
    addToRunTimeSelectionTable(motionSolver, rigidLidMotionSolver, dictionary);
}


namespace
{

//- The coefficients, checked before OpenFOAM's sixDoFRigidBodyMotion reads
//  them (it takes any number, and a zero mass or a huge state crashes the
//  first step): the keywords and the ranges of caseEntriesList.H, the
//  sub-dictionaries, the rotations, and the entries nothing uses
//  (innerDistance, outerDistance) are numbers. Coefficients at the top
//  level of dynamicMeshDict (no Coeffs dictionary) share it with the
//  mesh's own entries and are not checked.
const Foam::dictionary& checkedCoeffs
(
    const Foam::dictionary& dict,
    const Foam::word& coeffsName,
    const Foam::dictionary& coeffs
)
{
    using namespace Foam;
    if (!dict.isDict(coeffsName))
    {
        return coeffs;
    }
    iceDEMChecks::checkEntries
    (
        coeffs, "constant/dynamicMeshDict",
        {"rigidLidSixDoFRigidBodyMotionCoeffs"},
        "rigidLidSixDoFRigidBodyMotionCoeffs"
    );
    for (const char* key : {"innerDistance", "outerDistance"})
    {
        if (coeffs.found(key, keyType::LITERAL))
        {
            const scalar v = coeffs.get<scalar>(key);
            if (!std::isfinite(v))
            {
                FatalIOErrorInFunction(coeffs)
                    << "Entry '" << key << "' is " << v << ": a finite"
                    << " number (ignored: nothing is interpolated)" << nl
                    << exit(FatalIOError);
            }
        }
    }
    iceDEMChecks::rotationTensor(coeffs, "orientation");
    iceDEMChecks::rotationTensor(coeffs, "initialOrientation");
    return coeffs;
}

} // End anonymous namespace


Foam::dictionary Foam::rigidLidMotionSolver::stateDict
(
    const polyMesh& mesh,
    const dictionary& coeffs
)
{
    IOobject io
    (
        "sixDoFRigidBodyMotionState",
        mesh.time().timeName(),
        "uniform",
        mesh,
        IOobject::MUST_READ,
        IOobject::NO_WRITE,
        false
    );
    if (io.typeHeaderOk<IOdictionary>(true))
    {
        return IOdictionary(io);
    }
    return coeffs;
}


Foam::rigidLidMotionSolver::rigidLidMotionSolver
(
    const polyMesh& mesh,
    const IOdictionary& dict
)
:
    points0MotionSolver(mesh, dict, typeName),
    motion_
    (
        checkedCoeffs(dict, typeName + "Coeffs", coeffDict()),
        stateDict(mesh, coeffDict()),
        mesh.time()
    ),
    patches_(coeffDict().get<wordRes>("patches")),
    rhoName_(coeffDict().getOrDefault<word>("rho", "rho")),
    rhoInf_(1),
    Q0_(iceDEMChecks::rotationTensor(coeffDict(), "orientation")),
    curTimeIndex_(-1),
    verticalModesChecked_(false),
    flowForce_(Zero),
    flowMoment_(Zero),
    forceEvents_(label(-1))
{
    // The only mesh motion a rigid lid allows
    iceDEMChecks::selectName
    (
        coeffDict(), "meshMotion", wordList({"planar"}), "planar"
    );
    if (rhoName_ == "rhoInf")
    {
        rhoInf_ = iceDEMChecks::positive(coeffDict(), "rhoInf");
    }
    if (mesh.boundaryMesh().patchSet(patches_).empty())
    {
        FatalIOErrorInFunction(coeffDict())
            << "Entry 'patches' in " << coeffDict().name()
            << ": no patch of the mesh matches " << patches_ << nl
            << exit(FatalIOError);
    }
    if (!moveAllCells())
    {
        FatalIOErrorInFunction(coeffDict())
            << "Entry 'cellZone' in " << coeffDict().name()
            << ": rigidLidSixDoFRigidBodyMotion moves the whole mesh"
            << " rigidly; remove the entry" << nl << exit(FatalIOError);
    }
    // A misspelt optional entry would be ignored (the stock motion reads
    // its entries with defaults): checked with the ranges in checkedCoeffs
}


Foam::FixedList<Foam::label, 4> Foam::rigidLidMotionSolver::flowEvents()
const
{
    // polyMesh::movePoints and every non-const access to a field give
    // them a new event number
    FixedList<label, 4> events;
    const wordList names({"points", "p", "U", "nut"});
    forAll(names, i)
    {
        const regIOobject* obj = mesh().findObject<regIOobject>(names[i]);
        events[i] = obj ? obj->eventNo() : -1;
    }
    return events;
}


void Foam::rigidLidMotionSolver::flowForce(vector& F, vector& M)
{
    const point cofR = motion_.centreOfRotation();
    const FixedList<label, 4> events = flowEvents();

    // The moment is taken about the design centre of mass, a point fixed
    // by the dictionary, and moved to the current centre of rotation below
    // in both cases: a force kept from an earlier evaluation and one
    // evaluated now (the first step after a restart) give the same bits
    const point momentRef = motion_.initialCentreOfMass();

    if (events != forceEvents_)
    {
        // The pressure and viscous stress on the patches: the viscous part
        // evaluates the turbulence model's stress over the whole mesh
        const Time& t = mesh().time();
        dictionary forcesDict;
        forcesDict.add("type", functionObjects::forces::typeName);
        forcesDict.add("patches", patches_);
        forcesDict.add("rhoInf", rhoInf_);
        forcesDict.add("rho", rhoName_);
        forcesDict.add("CofR", momentRef);
        functionObjects::forces f("forces", t, forcesDict);
        f.calcForcesMoment();

        flowForce_ = f.forceEff();
        flowMoment_ = f.momentEff();
        forceEvents_ = events;

        DebugInfo
            << typeName << ": fluid force evaluated at t = " << t.timeName()
            << " (events of points, p, U, nut: " << events << ")" << endl;
    }

    // Unchanged mesh and fields (a step without a flow solution and without
    // mesh motion): the same force; its moment moved to the current centre
    F = flowForce_;
    M = flowMoment_ + ((momentRef - cofR) ^ flowForce_);
}


Foam::scalar Foam::rigidLidMotionSolver::yaw() const
{
    const tensor R(motion_.orientation() & Q0_.T());
    return atan2(R.yx(), R.xx());
}


Foam::tmp<Foam::pointField> Foam::rigidLidMotionSolver::curPoints() const
{
    const point c0 = motion_.initialCentreOfMass();
    const point c = motion_.centreOfMass();
    const scalar psi = yaw();
    const scalar cs = cos(psi);
    const scalar sn = sin(psi);

    const pointField& p0 = points0();
    tmp<pointField> tp(new pointField(p0.size()));
    pointField& p = tp.ref();
    forAll(p0, i)
    {
        const scalar dx = p0[i].x() - c0.x();
        const scalar dy = p0[i].y() - c0.y();
        p[i] = point(c.x() + cs*dx - sn*dy, c.y() + sn*dx + cs*dy, p0[i].z());
    }
    return tp;
}


void Foam::rigidLidMotionSolver::solve()
{
    const Time& t = mesh().time();

    bool firstIter = false;
    if (curTimeIndex_ != t.timeIndex())
    {
        motion_.newTime();
        curTimeIndex_ = t.timeIndex();
        firstIter = true;
    }

    vector g(Zero);
    if (t.foundObject<uniformDimensionedVectorField>("g"))
    {
        g = t.lookupObject<uniformDimensionedVectorField>("g").value();
    }

    // The density field: incompressible flow has none (p is kinematic)
    if (rhoName_ != "rhoInf" && !mesh().foundObject<volScalarField>(rhoName_))
    {
        FatalIOErrorInFunction(coeffDict())
            << "Entry 'rho' (" << rhoName_ << ") in " << coeffDict().name()
            << ": no density field '" << rhoName_ << "' in this flow. With"
            << " a kinematic pressure (iceFloatingFoam) give 'rho rhoInf;"
            << " rhoInf <density [kg/m3]>;'" << nl << exit(FatalIOError);
    }

    // The flow's force and moment about the centre of rotation; only the
    // horizontal force and the yaw moment act on the structure
    vector F, Mom;
    flowForce(F, Mom);

    const scalar m = motion_.mass();

    motion_.update
    (
        firstIter,
        vector(F.x(), F.y(), 0) + m*g,
        vector(0, 0, Mom.z()) + m*(motion_.momentArm() ^ g),
        t.deltaTValue(),
        t.deltaT0Value()
    );

    // The restraints recorded their stiffness in this update, at the pose
    // it reached (verticalModes.H); the periods logged after the first
    checkVerticalModesResolved(motion_, coeffDict(), !verticalModesChecked_);
    verticalModesChecked_ = true;
}


bool Foam::rigidLidMotionSolver::writeObject
(
    IOstream::streamFormat fmt,
    IOstream::versionNumber ver,
    IOstream::compressionType cmp,
    const bool valid
) const
{
    // 17 digits, not writePrecision: a restart continues the uninterrupted
    // run to the bit
    writeExactMotionState(mesh().time(), motion_);
    return true;
}


bool Foam::rigidLidMotionSolver::read()
{
    if (points0MotionSolver::read())
    {
        motion_.read(coeffDict());
        return true;
    }
    return false;
}


// ************************************************************************* //
