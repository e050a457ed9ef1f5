/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

\*---------------------------------------------------------------------------*/

#include "rigidLidSymplectic.H"
#include "dictionaryChecks.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace sixDoFSolvers
{
    defineTypeNameAndDebug(rigidLidSymplectic, 0);
    addToRunTimeSelectionTable(sixDoFSolver, rigidLidSymplectic, dictionary);
}
}


Foam::sixDoFSolvers::rigidLidSymplectic::modeCoeffs
Foam::sixDoFSolvers::rigidLidSymplectic::readMode
(
    const dictionary& dict,
    const word& name
)
{
    modeCoeffs c;
    if (!dict.found(name))
    {
        return c;
    }
    if (!dict.isDict(name))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << name << "' in " << dict.name()
            << " must be a dictionary { addedMass ..; linearDamping ..;"
            << " quadraticDamping ..; }" << nl << exit(FatalIOError);
    }
    const dictionary& d = dict.subDict(name);
    iceDEMChecks::checkEntries
    (
        d, "constant/dynamicMeshDict",
        {"*/solver(type rigidLidSymplectic)/*"},
        "rigidLidSymplectic " + name
    );
    c.addedMass = iceDEMChecks::nonNegative(d, "addedMass", 0);
    c.linearDamping = iceDEMChecks::nonNegative(d, "linearDamping", 0);
    c.quadraticDamping = iceDEMChecks::nonNegative(d, "quadraticDamping", 0);
    return c;
}


Foam::sixDoFSolvers::rigidLidSymplectic::rigidLidSymplectic
(
    const dictionary& dict,
    sixDoFRigidBodyMotion& body
)
:
    sixDoFSolver(dict, body),
    heave_(),
    roll_(),
    pitch_()
{
    iceDEMChecks::checkEntries
    (
        dict, "constant/dynamicMeshDict",
        {"*/solver(type rigidLidSymplectic)"},
        "solver (rigidLidSymplectic)"
    );
    heave_ = readMode(dict, "heave");
    roll_ = readMode(dict, "roll");
    pitch_ = readMode(dict, "pitch");
}


void Foam::sixDoFSolvers::rigidLidSymplectic::solve
(
    bool firstIter,
    const vector& fGlobal,
    const vector& tauGlobal,
    scalar deltaT,
    scalar deltaT0
)
{
    // First half step: velocities from the old accelerations (which already
    // carry the added mass), then the new position and orientation
    v() = tConstraints() & (v0() + aDamp()*0.5*deltaT0*a0());
    pi() = rConstraints() & (pi0() + aDamp()*0.5*deltaT0*tau0());

    centreOfRotation() = centreOfRotation0() + deltaT*v();

    const Tuple2<tensor, vector> Qpi = rotate(Q0(), pi(), deltaT);
    Q() = Qpi.first();
    pi() = rConstraints() & Qpi.second();

    // Damping of the vertical modes at the half-step velocities: heave in
    // the global frame, roll and pitch about the body axes
    const diagTensor& I = body_.momentOfInertia();
    const vector omegaBody(pi().x()/I.xx(), pi().y()/I.yy(), pi().z()/I.zz());

    const vector fDamp(0, 0, heave_.damping(v().z()));
    const vector tauDampBody
    (
        roll_.damping(omegaBody.x()),
        pitch_.damping(omegaBody.y()),
        0
    );

    // Accelerations from all loads (restraints added by the stock motion)
    updateAcceleration(fGlobal + fDamp, tauGlobal + (Q() & tauDampBody));

    // Added mass of the vertical modes (a is global, tau in the body frame)
    const scalar M = body_.mass();
    a().z() *= M/(M + heave_.addedMass);
    tau().x() *= I.xx()/(I.xx() + roll_.addedMass);
    tau().y() *= I.yy()/(I.yy() + pitch_.addedMass);

    // Second half step
    v() += tConstraints() & aDamp()*0.5*deltaT*a();
    pi() += rConstraints() & aDamp()*0.5*deltaT*tau();
}


// ************************************************************************* //
