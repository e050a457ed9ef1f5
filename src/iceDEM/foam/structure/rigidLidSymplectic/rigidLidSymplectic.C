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


void Foam::sixDoFSolvers::rigidLidSymplectic::checkDampingResolved
(
    const word& name,
    const modeCoeffs& c,
    const scalar inertia,
    const scalar u,
    const scalar deltaT
) const
{
    const scalar b = c.rate(u, inertia);
    if (b*deltaT < 2)
    {
        return;
    }
    FatalIOErrorInFunction(dict_)
        << "Entries 'linearDamping' and 'quadraticDamping' of " << name
        << " in " << dict_.name() << ": at the " << name << " velocity "
        << u << " the damping rate (B + Q|u|)/(m + A) = " << b << " 1/s"
        << " (B " << c.linearDamping << ", Q " << c.quadraticDamping
        << ", m " << inertia << ", A " << c.addedMass << ") times the"
        << " structure's step deltaT = " << deltaT << " s (system/"
        << "controlDict) is " << b*deltaT << ", at least 2: the explicit"
        << " damping reverses and amplifies the motion at every step."
        << " Reduce deltaT below " << 2/b << " s or the damping." << nl
        << exit(FatalIOError);
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

    checkDampingResolved("heave", heave_, body_.mass(), v().z(), deltaT);
    checkDampingResolved("roll", roll_, I.xx(), omegaBody.x(), deltaT);
    checkDampingResolved("pitch", pitch_, I.yy(), omegaBody.y(), deltaT);

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
