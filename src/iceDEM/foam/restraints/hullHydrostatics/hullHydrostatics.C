/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

\*---------------------------------------------------------------------------*/

#include "hullHydrostatics.H"
#include "addToRunTimeSelectionTable.H"
#include "caseEntries.H"
#include "sixDoFRigidBodyMotion.H"
#include "verticalModes.H"
#include "uniformDimensionedFields.H"
#include "IFstream.H"
#include "quaternion.H"
#include "transformField.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace sixDoFRigidBodyMotionRestraints
{
    defineTypeNameAndDebug(hullHydrostatics, 0);

    addToRunTimeSelectionTable
    (
        sixDoFRigidBodyMotionRestraint,
        hullHydrostatics,
        dictionary
    );
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::sixDoFRigidBodyMotionRestraints::hullHydrostatics::hullHydrostatics
(
    const word& name,
    const dictionary& sDoFRBMRDict
)
:
    sixDoFRigidBodyMotionRestraint(name, sDoFRBMRDict),
    structureFile_(),
    tolerance_(1e-6),
    points0_(),
    faces_(),
    rhoWater_(0),
    level_(0),
    mass_(0),
    centreOfMass_(Zero),
    checked_(false)
{
    read(sDoFRBMRDict);
}


// * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * * //

Foam::vector Foam::sixDoFRigidBodyMotionRestraints::hullHydrostatics::gravity
(
    const Time& runTime,
    const dictionary& dict
)
{
    const auto* g = runTime.findObject<uniformDimensionedVectorField>("g");
    if (!g)
    {
        FatalIOErrorInFunction(dict)
            << "Restraint " << dict.name() << " needs gravity: no 'g' field"
            << " is registered on the Time database." << nl
            << "iceFloatingFoam registers constant/g; another solver must"
            << " register it on Time as well." << nl
            << exit(FatalIOError);
    }
    return g->value();
}


void Foam::sixDoFRigidBodyMotionRestraints::hullHydrostatics::check
(
    const sixDoFRigidBodyMotion& motion
) const
{
    checked_ = true;

    const scalar dm = mag(motion.mass() - mass_);
    const scalar size = max(mag(max(points0_) - min(points0_)), SMALL);
    const scalar dx = mag(motion.initialCentreOfMass() - centreOfMass_);

    if (dm > tolerance_*mass_ || dx > tolerance_*size)
    {
        FatalIOErrorInFunction(sDoFRBMRCoeffs_)
            << "Restraint " << name_ << " (hullHydrostatics): the body in"
            << " dynamicMeshDict (mass " << motion.mass() << ", centreOfMass "
            << motion.initialCentreOfMass() << ") is not the structure of "
            << structureFile_ << " (mass " << mass_ << ", centreOfMass "
            << centreOfMass_ << ")." << nl
            << "Run createStructure and #include constant/hullMassProperties"
            << " in dynamicMeshDict." << nl
            << exit(FatalIOError);
    }
}


Foam::vector
Foam::sixDoFRigidBodyMotionRestraints::hullHydrostatics::verticalStiffness
(
    const sixDoFRigidBodyMotion& motion,
    const pointField& pts
) const
{
    const vector g = gravity(motion.time(), sDoFRBMRCoeffs_);
    const point G = motion.centreOfMass();

    // Buoyancy's vertical force and its moments about G (the weight has
    // none about G) at the pose moved by a heave, a roll or a pitch
    const auto restoring = [&](const pointField& p)
    {
        const floatingStructure::submergedPart sub =
            floatingStructure::clip(p, faces_, level_);
        const vector F = -rhoWater_*sub.volume*g;
        const vector M = (sub.centroid - G) ^ F;
        return vector(F.z(), M.x(), M.y());
    };
    const auto rotated = [&](const vector& axis, scalar angle)
    {
        const tensor R(quaternion(axis, angle).R());
        return pointField(G + transform(R, pointField(pts - G)));
    };
    const auto raised = [&](scalar dz)
    {
        return pointField(pts + vector(0, 0, dz));
    };

    // Central differences of the exact clip (piecewise polynomial in the
    // pose): steps small against the hull, large against round-off. A
    // hull whose profile has a kink at the waterline (a cone below a
    // column) has a one-sided stiffness each way, the difference averages
    // them: within the waterplane area's slope times dz/4
    const scalar dz = 1e-6*mag(max(points0_) - min(points0_));
    const scalar da = 1e-6;
    const vector ex(1, 0, 0), ey(0, 1, 0);
    const vector up(restoring(raised(dz)) - restoring(raised(-dz)));
    const vector roll(restoring(rotated(ex, da)) - restoring(rotated(ex, -da)));
    const vector pitch(restoring(rotated(ey, da)) - restoring(rotated(ey, -da)));
    return vector(-up.x()/(2*dz), -roll.y()/(2*da), -pitch.z()/(2*da));
}


void Foam::sixDoFRigidBodyMotionRestraints::hullHydrostatics::restrain
(
    const sixDoFRigidBodyMotion& motion,
    vector& restraintPosition,
    vector& restraintForce,
    vector& restraintMoment
) const
{
    if (!checked_)
    {
        check(motion);
    }
    // The hull at the motion's pose; its stiffness at every evaluation (the
    // structure's check of its vertical modes follows each step)
    const pointField pts(motion.transform(points0_));
    addVerticalModes(motion.time(), name_, verticalStiffness(motion, pts), Zero);

    const vector g = gravity(motion.time(), sDoFRBMRCoeffs_);
    const floatingStructure::submergedPart sub =
        floatingStructure::clip(pts, faces_, level_);

    restraintPosition = sub.centroid;
    restraintForce = -rhoWater_*sub.volume*g;
    restraintMoment = Zero;

    if (motion.report())
    {
        Info<< " submerged volume " << sub.volume
            << " centre of buoyancy " << sub.centroid
            << " buoyancy " << restraintForce << endl;
    }
}


bool Foam::sixDoFRigidBodyMotionRestraints::hullHydrostatics::read
(
    const dictionary& sDoFRBMRDict
)
{
    sixDoFRigidBodyMotionRestraint::read(sDoFRBMRDict);
    iceDEMChecks::checkEntries
    (
        sDoFRBMRCoeffs_, "constant/dynamicMeshDict",
        {"sixDoFRigidBodyMotionCoeffs/restraints/*(sixDoFRigidBodyMotionRestraint hullHydrostatics)"},
        "restraint " + name_
    );

    structureFile_ = sDoFRBMRCoeffs_.lookupOrDefault<fileName>
    (
        "structure",
        "$FOAM_CASE/constant/structureDict"
    );
    structureFile_.expand();

    tolerance_ = sDoFRBMRCoeffs_.lookupOrDefault<scalar>("tolerance", 1e-6);
    if (!(tolerance_ > 0))
    {
        FatalIOErrorInFunction(sDoFRBMRDict)
            << "Entry 'tolerance " << tolerance_ << "' of restraint " << name_
            << " in " << sDoFRBMRDict.name() << " must be positive." << nl
            << exit(FatalIOError);
    }

    IFstream is(structureFile_);
    if (!is.good())
    {
        FatalIOErrorInFunction(sDoFRBMRDict)
            << "Restraint " << name_ << " in " << sDoFRBMRDict.name()
            << ": cannot open the structure dictionary '" << structureFile_
            << "' (entry 'structure', default"
            << " \"$FOAM_CASE/constant/structureDict\")." << nl
            << exit(FatalIOError);
    }
    dictionary dict(is);
    dict.name() = structureFile_;

    const floatingStructure hull(dict);
    points0_ = hull.points();
    faces_ = hull.faces();
    rhoWater_ = hull.rhoWater();
    level_ = hull.level();
    mass_ = hull.mass();
    centreOfMass_ = hull.centreOfMass();
    checked_ = false;

    return true;
}


void Foam::sixDoFRigidBodyMotionRestraints::hullHydrostatics::write
(
    Ostream& os
) const
{
    os.writeEntry("structure", structureFile_);
    os.writeEntry("tolerance", tolerance_);
}


// ************************************************************************* //
