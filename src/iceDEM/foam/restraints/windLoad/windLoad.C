/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

\*---------------------------------------------------------------------------*/

#include "windLoad.H"
#include "windDict.H"
#include "addToRunTimeSelectionTable.H"
#include "sixDoFRigidBodyMotion.H"
#include "Tuple2.H"

#include <cmath>

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace sixDoFRigidBodyMotionRestraints
{
    defineTypeNameAndDebug(windLoad, 0);

    addToRunTimeSelectionTable
    (
        sixDoFRigidBodyMotionRestraint,
        windLoad,
        dictionary
    );
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::sixDoFRigidBodyMotionRestraints::windLoad::windLoad
(
    const word& name,
    const dictionary& sDoFRBMRDict
)
:
    sixDoFRigidBodyMotionRestraint(name, sDoFRBMRDict),
    wind_(),
    rhoAir_(1.3),
    Cd_(0),
    area_(0),
    hasCentre_(false),
    centre_(Zero)
{
    read(sDoFRBMRDict);
}


// * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * * //

void Foam::sixDoFRigidBodyMotionRestraints::windLoad::restrain
(
    const sixDoFRigidBodyMotion& motion,
    vector& restraintPosition,
    vector& restraintForce,
    vector& restraintMoment
) const
{
    restraintPosition =
        hasCentre_ ? motion.transform(centre_) : motion.centreOfRotation();
    restraintMoment = Zero;

    const ::iceDEM::Vec3 Ua = wind_.at(motion.time().value());
    const vector v = motion.velocity(restraintPosition);
    restraintForce = toVector
    (
        ::iceDEM::bluffWindForce(rhoAir_, Cd_, area_, Ua, toVec3(v))
    );

    if (motion.report())
    {
        Info<< " wind load force " << restraintForce << endl;
    }
}


bool Foam::sixDoFRigidBodyMotionRestraints::windLoad::read
(
    const dictionary& sDoFRBMRDict
)
{
    sixDoFRigidBodyMotionRestraint::read(sDoFRBMRDict);

    const dictionary& d = sDoFRBMRCoeffs_;
    checkEntries
    (
        d, "constant/dynamicMeshDict",
        {"sixDoFRigidBodyMotionCoeffs/restraints/*(sixDoFRigidBodyMotionRestraint windLoad)"},
        "restraint " + name_ + " (windLoad)"
    );
    wind_ = readWindHistory(d);
    rhoAir_ = nonNegative(d, "rhoAir", 1.3);
    if (!d.found("Cd", keyType::LITERAL) || !d.found("area", keyType::LITERAL))
    {
        FatalIOErrorInFunction(d)
            << "Restraint " << name_ << " (windLoad) needs the entries 'Cd'"
            << " (drag coefficient, >= 0) and 'area' (projected area of the"
            << " hull above water [m2], >= 0)" << nl << exit(FatalIOError);
    }
    Cd_ = nonNegative(d, "Cd", 0);
    area_ = nonNegative(d, "area", 0);
    hasCentre_ = d.found("centreOfPressure", keyType::LITERAL);
    if (hasCentre_)
    {
        centre_ = d.get<point>("centreOfPressure");
        if (!std::isfinite(mag(centre_)))
        {
            FatalIOErrorInFunction(d)
                << "Entry 'centreOfPressure' is " << centre_
                << ": it must be a finite point [m]" << nl
                << exit(FatalIOError);
        }
    }
    Info<< "Restraint " << name_ << " (windLoad): rhoAir " << rhoAir_
        << ", Cd " << Cd_ << ", area " << area_ << " m2, "
        << wind_.table().size() << " wind row(s)" << endl;

    return true;
}


void Foam::sixDoFRigidBodyMotionRestraints::windLoad::write(Ostream& os) const
{
    os.writeEntry("rhoAir", rhoAir_);
    os.writeEntry("Cd", Cd_);
    os.writeEntry("area", area_);
    if (hasCentre_)
    {
        os.writeEntry("centreOfPressure", centre_);
    }
    if (wind_.table().size() == 1)
    {
        os.writeEntry("type", word("uniform"));
        os.writeEntry("velocity", toVector(wind_.table()[0].second));
    }
    else
    {
        List<Tuple2<scalar, vector>> rows(wind_.table().size());
        forAll(rows, k)
        {
            rows[k].first() = wind_.table()[k].first;
            rows[k].second() = toVector(wind_.table()[k].second);
        }
        os.writeEntry("type", word("table"));
        os.writeEntry("table", rows);
    }
}


// ************************************************************************* //
