/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.
\*---------------------------------------------------------------------------*/

#include "verticalModes.H"
#include "motionConstraints.H"
#include "rigidLidSymplectic.H"
#include "timeRegistry.H"
#include "IOField.H"
#include "mathematicalConstants.H"

#include <cmath>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

const word modesPrefix("verticalModes:");

const FixedList<word, 3> modeNames({"heave", "roll", "pitch"});

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Functions  * * * * * * * * * * * * * * * //

void Foam::addVerticalModes
(
    const Time& runTime,
    const word& restraint,
    const vector& stiffness,
    const vector& damping
)
{
    storeOnTime
    (
        runTime,
        modesPrefix + restraint,
        scalarField
        ({
            stiffness.x(), stiffness.y(), stiffness.z(),
            damping.x(), damping.y(), damping.z()
        })
    );
}


void Foam::checkVerticalModesResolved
(
    const sixDoFRigidBodyMotion& motion,
    const dictionary& coeffs,
    bool report
)
{
    const Time& runTime = motion.time();

    // The restraints' stiffness and damping, summed; none recorded:
    // nothing holds the vertical modes, nothing to resolve
    FixedList<scalar, 3> C(Zero), B(Zero);
    wordList from;
    const auto recorded = runTime.lookupClass<IOField<scalar>>();
    forAllConstIters(recorded, iter)
    {
        const IOField<scalar>& c = **iter;
        if (iter.key().startsWith(modesPrefix) && c.size() == 6)
        {
            from.append(iter.key().substr(modesPrefix.size()));
            for (label i = 0; i < 3; ++i)
            {
                C[i] += c[i];
                B[i] += c[i + 3];
            }
        }
    }
    if (from.empty())
    {
        return;
    }
    Foam::sort(from);
    string names;
    for (const word& w : from)
    {
        names += (names.empty() ? "" : " ") + w;
    }

    // The solver's added mass and damping (rigidLidSymplectic; the stock
    // integrators have neither), read by the solver's own reader
    FixedList<scalar, 3> A(Zero);
    const dictionary* solver = coeffs.findDict("solver");
    if
    (
        solver
     && solver->lookupOrDefault<word>("type", "")
     == sixDoFSolvers::rigidLidSymplectic::typeName
    )
    {
        for (label i = 0; i < 3; ++i)
        {
            const sixDoFSolvers::rigidLidSymplectic::modeCoeffs mode =
                sixDoFSolvers::rigidLidSymplectic::readMode
                (
                    *solver, modeNames[i]
                );
            A[i] = mode.addedMass;
            B[i] += mode.linearDamping;
        }
    }

    // The modes' inertia in global axes, and which the constraints free
    const tensor& Q = motion.orientation();
    const diagTensor& I = motion.momentOfInertia();
    const tensor J
    (
        Q & tensor(I.xx(), 0, 0, 0, I.yy(), 0, 0, 0, I.zz()) & Q.T()
    );
    const FixedList<scalar, 3> inertia({motion.mass(), J.xx(), J.yy()});
    const FixedList<bool, 3> free(freeVerticalModes(motion));
    const FixedList<word, 3> units({"N/m", "N m/rad", "N m/rad"});

    const scalar dt = runTime.deltaTValue();
    if (report)
    {
        Info<< "Structure: vertical modes' periods 2 pi sqrt((m + A)/C) (C"
            << " from " << names << ") at the structure's step " << dt
            << " s:";
        for (label i = 0; i < 3; ++i)
        {
            Info<< ' ' << modeNames[i];
            if (!free[i])
            {
                Info<< " held;";
            }
            else if (C[i] > 0)
            {
                const scalar T =
                    constant::mathematical::twoPi
                   *Foam::sqrt((inertia[i] + A[i])/C[i]);
                Info<< ' ' << T << " s (" << T/dt << " steps);";
            }
            else
            {
                Info<< " C = " << C[i] << ';';
            }
        }
        Info<< endl;
    }

    for (label i = 0; i < 3; ++i)
    {
        if (!free[i])
        {
            continue;
        }
        if (report && !(C[i] > 0))
        {
            WarningInFunction
                << "The structure's " << modeNames[i] << " stiffness ("
                << names << ") is " << C[i] << ' ' << units[i] << ": it is"
                << " not stable in " << modeNames[i] << " (it capsizes or"
                << " sinks)" << endl;
        }
        const scalar m = inertia[i] + A[i];
        const scalar omega2 = max(C[i], scalar(0))/m;
        const scalar b = B[i]/m;
        const scalar bound = omega2*sqr(dt) + 2*b*dt;
        if (bound < 4)
        {
            continue;
        }
        // The largest step of the bound, the root of omega^2 dt^2 + 2 b dt
        // = 4 (b up to the largest double: no square of it)
        const scalar dtMax = 4/(b + std::hypot(b, 2*Foam::sqrt(omega2)));
        FatalIOErrorInFunction(runTime.controlDict())
            << "Entry 'deltaT' of " << runTime.controlDict().name()
            << ": the structure's step " << dt << " s does not resolve its "
            << modeNames[i] << " at its pose at time " << runTime.timeName()
            << ": stiffness C = " << C[i] << ' ' << units[i]
            << " (restraints " << names << " in " << coeffs.name()
            << "), inertia m = " << inertia[i] << ", added mass A = " << A[i]
            << " and linear damping B = " << B[i] << " (the restraints' and"
            << " the solver's " << modeNames[i] << " entries). The symplectic"
            << " step is stable only for (omega deltaT)^2 + 2 (B/(m + A))"
            << " deltaT < 4, omega^2 = C/(m + A); here " << bound
            << ". Reduce deltaT below " << dtMax << " s";
        if (B[i] > 0)
        {
            FatalIOError
                << " (or the damping: the lines' or the solver's"
                << " linearDamping of " << modeNames[i] << ")";
        }
        FatalIOError<< '.' << nl << exit(FatalIOError);
    }
}


// ************************************************************************* //
