/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

\*---------------------------------------------------------------------------*/

#include "structureMotion.H"
#include "uniformDimensionedFields.H"
#include "verticalModes.H"
#include "completeTime.H"

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

const Foam::dictionary& Foam::structureMotion::coeffs() const
{
    const word solver(dict_.get<word>("motionSolver"));
    if
    (
        solver != "sixDoFRigidBodyMotion"
     && solver != "rigidLidSixDoFRigidBodyMotion"
    )
    {
        FatalIOErrorInFunction(dict_)
            << "Entry 'motionSolver " << solver << "' in " << dict_.name()
            << ": the structure motion needs 'motionSolver"
            << " sixDoFRigidBodyMotion' or 'rigidLidSixDoFRigidBodyMotion'."
            << nl << exit(FatalIOError);
    }
    return dict_.optionalSubDict(solver + "Coeffs");
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::structureMotion::structureMotion(const Time& runTime)
:
    runTime_(runTime),
    dict_
    (
        IOobject
        (
            "dynamicMeshDict",
            runTime.constant(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    ),
    motion_(),
    curTimeIndex_(-1),
    verticalModesChecked_(false)
{
    IOobject stateIO
    (
        "sixDoFRigidBodyMotionState",
        runTime.timeName(),
        "uniform",
        runTime,
        IOobject::MUST_READ,
        IOobject::NO_WRITE,
        false
    );

    if (stateIO.typeHeaderOk<IOdictionary>(true))
    {
        Info<< "Reading the structure state from "
            << stateIO.objectPath() << endl;
        const IOdictionary state(stateIO);
        motion_.reset(new sixDoFRigidBodyMotion(coeffs(), state, runTime));
    }
    else
    {
        motion_.reset(new sixDoFRigidBodyMotion(coeffs(), coeffs(), runTime));
    }
}


// * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * * //

void Foam::structureMotion::step(const vector& force, const vector& moment)
{
    bool firstIter = false;
    if (curTimeIndex_ != runTime_.timeIndex())
    {
        motion_->newTime();
        curTimeIndex_ = runTime_.timeIndex();
        firstIter = true;
    }

    const auto* gPtr = runTime_.findObject<uniformDimensionedVectorField>("g");
    if (!gPtr)
    {
        FatalErrorInFunction
            << "No gravity field 'g' registered on the Time database"
            << " (constant/g)." << nl << exit(FatalError);
    }
    const vector g = gPtr->value();
    const scalar m = motion_->mass();

    motion_->update
    (
        firstIter,
        force + m*g,
        moment + m*(motion_->momentArm() ^ g),
        runTime_.deltaTValue(),
        runTime_.deltaT0Value()
    );

    // The restraints recorded their stiffness in this update, at the pose
    // it reached (verticalModes.H); the periods logged after the first
    checkVerticalModesResolved(motion_(), coeffs(), !verticalModesChecked_);
    verticalModesChecked_ = true;
}


void Foam::structureMotion::write() const
{
    writeExactMotionState(runTime_, motion_());
}


void Foam::writeExactMotionState
(
    const Time& runTime,
    const sixDoFRigidBodyMotion& motion
)
{
    IOdictionary state
    (
        IOobject
        (
            "sixDoFRigidBodyMotionState",
            runTime.timeName(),
            "uniform",
            runTime,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            false
        )
    );
    // 17 digits: the state's vectors and tensors become dictionary entries
    // through text (at the default precision, writePrecision) and are
    // written as text even in binary format; a restart must read back the
    // doubles of the uninterrupted run
    const unsigned precision = IOstream::defaultPrecision();
    IOstream::defaultPrecision(17);
    motion.state().write(state);
    IOstream::defaultPrecision(precision);
    if
    (
        !completeTime::atomicWrite
        (
            state,
            runTime.writeFormat(),
            runTime.writeVersion(),
            runTime.writeCompression(),
            17
        )
    )
    {
        FatalErrorInFunction
            << "Could not write " << state.objectPath() << exit(FatalError);
    }
}


// ************************************************************************* //
