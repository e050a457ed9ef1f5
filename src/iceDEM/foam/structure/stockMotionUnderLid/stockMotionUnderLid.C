/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.
\*---------------------------------------------------------------------------*/

#include "stockMotionUnderLid.H"
#include "motionConstraints.H"
#include "mathematicalConstants.H"

// * * * * * * * * * * * * * * * * Functions  * * * * * * * * * * * * * * * //

void Foam::checkStockMotionUnderLid(const sixDoFRigidBodyMotionSolver& solver)
{
    const FixedList<bool, 3> free(freeVerticalModes(solver.motion()));
    const bool heave = free[0], roll = free[1], pitch = free[2];
    if (!(heave || roll || pitch))
    {
        return;
    }

    FatalIOErrorInFunction(solver.coeffDict())
        << "Entry 'constraints' of " << solver.coeffDict().name()
        << " leaves the structure free in"
        << (heave ? " heave" : "") << (roll ? " roll" : "")
        << (pitch ? " pitch" : "") << "." << nl
        << "With the flow, motionSolver sixDoFRigidBodyMotion moves the mesh"
        << " near the structure with it; the rigid lid at the waterline"
        << " cannot follow heave, roll or pitch (its cells fold and the run"
        << " ends in a floating point exception)." << nl
        << "Hold them with constraints, e.g." << nl
        << "    constraints" << nl
        << "    {" << nl
        << "        horizontal { sixDoFRigidBodyMotionConstraint plane;"
        << " normal (0 0 1); }" << nl
        << "        yawOnly    { sixDoFRigidBodyMotionConstraint axis;"
        << " axis (0 0 1); }" << nl
        << "    }" << nl
        << "or use motionSolver rigidLidSixDoFRigidBodyMotion (all six"
        << " degrees of freedom, the mesh follows surge, sway and yaw), or"
        << " run iceFloatingFoam -noFlow (the structure without fluid)."
        << exit(FatalIOError);
}


void Foam::checkMorphedMesh
(
    const polyMesh& mesh,
    const sixDoFRigidBodyMotionSolver& solver
)
{
    // true: some face pyramid has a negative volume (reduced over ranks)
    if (!mesh.checkFacePyramids(false))
    {
        return;
    }

    const sixDoFRigidBodyMotion& motion = solver.motion();
    const dictionary& coeffs = solver.coeffDict();
    const vector shift = motion.centreOfMass() - motion.initialCentreOfMass();
    // The design orientation as the motion reads it (its own copy is private)
    const tensor design
    (
        coeffs.getOrDefault<tensor>
        (
            "initialOrientation",
            coeffs.getOrDefault<tensor>("orientation", tensor::I)
        )
    );
    const tensor turn = motion.orientation() & design.T();
    const scalar yawDeg =
        atan2(turn.yx(), turn.xx())*180/constant::mathematical::pi;

    FatalIOErrorInFunction(coeffs)
        << "At t = " << mesh.time().timeName() << " the mesh that "
        << "motionSolver sixDoFRigidBodyMotion morphs around the structure"
        << " has folded (cells turned inside out): the structure has moved "
        << shift << " m and turned " << yawDeg << " deg (yaw) from its"
        << " design pose, more than the band between 'innerDistance' ("
        << coeffs.get<scalar>("innerDistance") << " m) and 'outerDistance' ("
        << coeffs.get<scalar>("outerDistance") << " m) in " << coeffs.name()
        << " can take." << nl
        << "Moor or restrain the structure, widen the band (a larger"
        << " outerDistance, within the domain), or use motionSolver"
        << " rigidLidSixDoFRigidBodyMotion, which moves the whole mesh"
        << " rigidly with the structure."
        << exit(FatalIOError);
}


// ************************************************************************* //
