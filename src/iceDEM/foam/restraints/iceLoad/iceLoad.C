/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

\*---------------------------------------------------------------------------*/

#include "iceLoad.H"
#include "addToRunTimeSelectionTable.H"
#include "caseEntries.H"
#include "sixDoFRigidBodyMotion.H"
#include "uniformDimensionedFields.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace sixDoFRigidBodyMotionRestraints
{
    defineTypeNameAndDebug(iceLoad, 0);

    addToRunTimeSelectionTable
    (
        sixDoFRigidBodyMotionRestraint,
        iceLoad,
        dictionary
    );
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::sixDoFRigidBodyMotionRestraints::iceLoad::iceLoad
(
    const word& name,
    const dictionary& sDoFRBMRDict
)
:
    sixDoFRigidBodyMotionRestraint(name, sDoFRBMRDict),
    forceName_("iceLoadForce"),
    momentName_("iceLoadMoment"),
    reportedAbsent_(false)
{
    read(sDoFRBMRDict);
}


// * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * * //

void Foam::sixDoFRigidBodyMotionRestraints::iceLoad::restrain
(
    const sixDoFRigidBodyMotion& motion,
    vector& restraintPosition,
    vector& restraintForce,
    vector& restraintMoment
) const
{
    const Time& runTime = motion.time();

    restraintPosition = motion.centreOfRotation();
    restraintForce = Zero;
    restraintMoment = Zero;

    const auto* F =
        runTime.findObject<uniformDimensionedVectorField>(forceName_);
    const auto* M =
        runTime.findObject<uniformDimensionedVectorField>(momentName_);

    if (F)
    {
        restraintForce = F->value();
    }
    if (M)
    {
        restraintMoment = M->value();
    }

    if ((!F || !M) && !reportedAbsent_)
    {
        reportedAbsent_ = true;
        Info<< "Restraint " << name_ << " (iceLoad):";
        if (!F)
        {
            Info<< ' ' << forceName_.c_str();
        }
        if (!M)
        {
            Info<< ' ' << momentName_.c_str();
        }
        Info<< " not registered: zero ice load" << endl;
    }

    if (motion.report())
    {
        Info<< " ice load force " << restraintForce
            << " moment " << restraintMoment << endl;
    }
}


bool Foam::sixDoFRigidBodyMotionRestraints::iceLoad::read
(
    const dictionary& sDoFRBMRDict
)
{
    sixDoFRigidBodyMotionRestraint::read(sDoFRBMRDict);
    iceDEMChecks::checkEntries
    (
        sDoFRBMRCoeffs_, "constant/dynamicMeshDict",
        {"sixDoFRigidBodyMotionCoeffs/restraints/*(sixDoFRigidBodyMotionRestraint iceLoad)"},
        "restraint " + name_
    );

    forceName_ = sDoFRBMRCoeffs_.lookupOrDefault<word>("force", "iceLoadForce");
    momentName_ =
        sDoFRBMRCoeffs_.lookupOrDefault<word>("moment", "iceLoadMoment");

    return true;
}


void Foam::sixDoFRigidBodyMotionRestraints::iceLoad::write(Ostream& os) const
{
    os.writeEntry("force", forceName_);
    os.writeEntry("moment", momentName_);
}


// ************************************************************************* //
