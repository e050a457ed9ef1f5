/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    The checks of quantities derived from the entries once everything is
    read: effective moduli of the material pairs, masses and inertia of the
    bodies, their energies and positions against double precision, and the
    Hertz contact time; each FatalIOError names the entries at fault.
\*---------------------------------------------------------------------------*/

#include "iceDEMCase.H"

#include <cmath>
#include <limits>

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::iceDEMCase::checkDerived() const
{
    const auto& mats = world_->materials();
    const dictionary& matDicts = properties_.subDict("materials");

    auto finitePositive = [](double x) { return x > 0 && std::isfinite(x); };

    // Effective moduli of every pair of materials
    for (size_t a = 0; a < mats.size(); ++a)
    {
        for (size_t b = a; b < mats.size(); ++b)
        {
            const ::iceDEM::PairCoefficients c =
                ::iceDEM::PairCoefficients::make
                (
                    mats[a], mats[b], ::iceDEM::PairProperties()
                );
            if (!finitePositive(c.Estar) || !finitePositive(c.Gstar))
            {
                FatalIOErrorInFunction(matDicts.subDict(mats[b].name))
                    << "Entries 'youngsModulus' of materials "
                    << mats[a].name.c_str() << " (" << mats[a].youngsModulus
                    << ") and " << mats[b].name.c_str() << " ("
                    << mats[b].youngsModulus << "): the effective moduli"
                    << " E* = " << c.Estar << ", G* = " << c.Gstar
                    << " overflow or underflow double precision" << nl
                    << exit(FatalIOError);
            }
        }
    }

    // Masses and inertia of the bodies
    const dictionary& bodyDicts = iceField_.subDict("bodies");
    const auto& bodies = world_->bodies();
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        const ::iceDEM::Body& b = bodies[i];
        if
        (
            !finitePositive(b.mass)
         || !finitePositive(b.invInertia.minCoeff())
         || !std::isfinite(b.invInertia.maxCoeff())
         || !b.x.allFinite() || !b.v.allFinite() || !b.L.allFinite()
        )
        {
            const word& name = bodyNames_[i];
            FatalIOErrorInFunction(bodyDicts.subDict(name))
                << "Body " << name << ": mass " << b.mass
                << ", inverse principal moments of inertia ("
                << b.invInertia.x() << ' ' << b.invInertia.y() << ' '
                << b.invInertia.z() << ") from the entry 'density' ("
                << mats[b.material].density << ") of material "
                << mats[b.material].name.c_str()
                << " in constant/iceDEMProperties and the body's size,"
                << " position, velocity or omega here: not finite and"
                << " positive in double precision" << nl
                << exit(FatalIOError);
        }
    }

    // Energies (squares of the speeds) and positions the contact detection
    // can resolve: |x| eps below the dilation radius
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        const ::iceDEM::Body& b = bodies[i];
        const scalar energy =
            0.5*b.mass*b.v.squaredNorm() + 0.5*b.omega().dot(b.L);
        const scalar r = world_->shapeOf(int(i)).radius();
        const word& name = bodyNames_[i];
        if (!std::isfinite(energy))
        {
            FatalIOErrorInFunction(bodyDicts.subDict(name))
                << "Body " << name << ": entries 'velocity' and 'omega' give"
                << " a kinetic energy beyond double precision" << nl
                << exit(FatalIOError);
        }
        if (!(b.x.norm()*std::numeric_limits<double>::epsilon() < r))
        {
            FatalIOErrorInFunction(bodyDicts.subDict(name))
                << "Body " << name << ": its position (entries 'centre',"
                << " 'outline', 'zBottom' or 'points') is too far from the"
                << " origin for double precision to resolve its dilation"
                << " radius " << r << " (|x| eps < radius)" << nl
                << exit(FatalIOError);
        }
    }

    // The Hertz contact time that the time-step check uses
    if (bodies.size())
    {
        // The core starts from the largest double: left there, a body's
        // estimate overflowed (or was NaN)
        const scalar tc = world_->estimatedContactTime();
        if (!finitePositive(tc) || tc >= std::numeric_limits<double>::max())
        {
            FatalIOErrorInFunction(matDicts)
                << "The Hertz contact time estimate over- or underflows"
                << " double precision (" << tc << " s): the"
                << " entries 'youngsModulus' and 'density' of the materials"
                << " (or 'contactCheckVelocity') are beyond what double"
                << " precision resolves" << nl
                << exit(FatalIOError);
        }
    }
}


void Foam::iceDEMCase::checkBodyForceInterval() const
{
    const ::iceDEM::WorldSettings& s = world_->settings();
    const label k = s.bodyForceInterval;
    if (k == 1)
    {
        return;
    }
    const dictionary& d = properties_;
    if (!water_)
    {
        IOWarningInFunction(d)
            << "Entry 'bodyForceInterval' (" << k << ") has no effect:"
            << " without 'water' there are no body forces to evaluate"
            << " less often" << nl << endl;
        return;
    }
    const scalar H = k*s.timeStep;

    // The bounds of WorldStep.C at the floes' poses in constant/iceField:
    // resonance with the contacts (2/3 of the Hertz contact time, a third
    // of the contact's period) and stability of the slow part (omega H < 2
    // for the fastest hydrostatic mode); floes an inflow inserts are
    // checked by the DEM as they join
    const ::iceDEM::BodyForceLimits limits =
        world_->bodyForceLimits(0, label(world_->bodies().size()));
    const scalar tc = limits.contactTime;
    const scalar contactLimit = limits.contactLimit();
    const scalar T = limits.period;
    const scalar hydroLimit = limits.periodLimit();

    if (H > contactLimit || H > hydroLimit)
    {
        FatalIOErrorInFunction(d)
            << "Entry 'bodyForceInterval' of constant/iceDEMProperties ("
            << k << ") with 'deltaT' " << s.timeStep << " s gives an outer"
            << " step of " << H << " s for the body forces: it must not"
            << " exceed " << contactLimit << " s, 2/3 of the estimated"
            << " Hertz contact time " << tc << " s (resonance with the"
            << " contacts), nor " << hydroLimit << " s, 1/pi of the"
            << " shortest heave, roll or pitch period of the floes " << T
            << " s (stability of the hydrostatic modes): at most"
            << " bodyForceInterval "
            << label(std::floor(min(contactLimit, hydroLimit)/s.timeStep))
            << nl << exit(FatalIOError);
    }
    Info<< "iceDEM: multi-rate step: body forces every " << k
        << " DEM steps (" << H << " s; limits " << contactLimit
        << " s from the contact time, " << hydroLimit
        << " s from the hydrostatic periods";
    if (inflow_)
    {
        Info<< "; the floes the inflow inserts are checked as they join:"
            << " the run stops at one beyond them";
    }
    Info<< ")" << nl;
}


// ************************************************************************* //
