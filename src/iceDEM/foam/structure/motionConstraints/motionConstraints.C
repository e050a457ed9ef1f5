/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.
\*---------------------------------------------------------------------------*/

#include "motionConstraints.H"
#include "sixDoFSolver.H"

// * * * * * * * * * * * * * * * Local Classes * * * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

//- A solver that is never asked to solve: its protected accessors read
//  the motion's constraint tensors
class constraintTensors : public sixDoFSolver
{
public:

    explicit constraintTensors(const sixDoFRigidBodyMotion& motion)
    :
        sixDoFSolver(dictionary(), const_cast<sixDoFRigidBodyMotion&>(motion))
    {}

    autoPtr<sixDoFSolver> clone() const override
    {
        return autoPtr<sixDoFSolver>(new constraintTensors(body_));
    }

    void solve(bool, const vector&, const vector&, scalar, scalar) override
    {}

    using sixDoFSolver::tConstraints;
    using sixDoFSolver::rConstraints;
};

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Functions  * * * * * * * * * * * * * * * //

Foam::tensor Foam::translationConstraints(const sixDoFRigidBodyMotion& motion)
{
    return constraintTensors(motion).tConstraints();
}


Foam::tensor Foam::rotationConstraints(const sixDoFRigidBodyMotion& motion)
{
    return constraintTensors(motion).rConstraints();
}


Foam::FixedList<bool, 3> Foam::freeVerticalModes
(
    const sixDoFRigidBodyMotion& motion
)
{
    const constraintTensors c(motion);
    return FixedList<bool, 3>
    ({
        mag(c.tConstraints() & vector(0, 0, 1)) > 0,
        mag(c.rConstraints() & vector(1, 0, 0)) > 0,
        mag(c.rConstraints() & vector(0, 1, 0)) > 0
    });
}


// ************************************************************************* //
