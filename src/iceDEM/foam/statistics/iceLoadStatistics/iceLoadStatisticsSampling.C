/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    What a sample of iceLoadStatistics reads from the DEM: the structure
    bodies and walls it selects (connect), the loads integrated over the
    DEM sub-steps (accumulator, an iceDEMCase::stepObserver), the floes'
    momentum and the mooring line tensions.
\*---------------------------------------------------------------------------*/

#include "iceLoadStatistics.H"
#include "iceDEMState.H"
#include "structureSelection.H"

#include "IOField.H"


// * * * * * * * * * * * * * * * Accumulator * * * * * * * * * * * * * * * //

void Foam::functionObjects::iceLoadStatistics::accumulator::loads
(
    const ::iceDEM::World& w,
    ::iceDEM::Vec3& f,
    ::iceDEM::Vec3& wl,
    ::iceDEM::Vec3& d
)
{
    f.setZero();
    for (std::size_t k = 0; k < bodies.size(); ++k)
    {
        label& b = bodies[k];
        if (b >= label(w.bodies().size()) || w.bodies()[b].id != ids[k])
        {
            b = w.indexOfId(int(ids[k]), int(b));
            if (b < 0)
            {
                FatalErrorInFunction
                    << "Structure body id " << ids[k] << " is no longer in"
                    << " the DEM" << exit(FatalError);
            }
        }
        // A structure body's force is its contact load (no model acts on
        // it, no gravity); unlike contactLoad it survives the neighbour
        // list's rebuild when inflow/outflow removes floes
        f += w.bodies()[b].force;
    }
    wl.setZero();
    if (!walls.empty())
    {
        w.wallContactForces(wallForce);
        for (const label k : walls)
        {
            wl += wallForce[k];
        }
    }
    d = w.modelForceOnFreeBodies();
}


void Foam::functionObjects::iceLoadStatistics::accumulator::demStep
(
    const iceDEMCase& demCase,
    scalar h
)
{
    ::iceDEM::Vec3 f, wl, d;
    loads(demCase.world(), f, wl, d);
    F += h*f;
    W += h*wl;
    D += h*d;
    const ::iceDEM::Vec3 g = d - f - wl;
    // The step's two half kicks used the last step's net force and this
    // one's; the sums above take this one's for the whole step
    if (netKnown)
    {
        E += 0.5*h*(net - g);
    }
    net = g;
    netKnown = true;
    duration += h;
    ++steps;
}


void Foam::functionObjects::iceLoadStatistics::accumulator::reset()
{
    F.setZero();
    W.setZero();
    D.setZero();
    E.setZero();
    duration = 0;
    steps = 0;
}


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::functionObjects::iceLoadStatistics::connect()
{
    connected_ = true;

    if (!time_.foundObject<iceDEMState>("iceDEMState"))
    {
        noCase_ = true;
        WarningInFunction
            << "Function object " << name() << ": no iceDEM case in this"
            << " run (no constant/iceDEMProperties): no ice load statistics"
            << endl;
        return;
    }
    const iceDEMCase& c =
        time_.lookupObject<iceDEMState>("iceDEMState").demCase();
    const ::iceDEM::World& w = c.world();

    // The structure: selected bodies, or every body that is not free
    wordList unused;
    for
    (
        const label i
      : iceDEMStatistics::selectStructure
        (
            c, structureGiven_, structureSel_, dict_, name(), unused
        )
    )
    {
        acc_->bodies.push_back(i);
        acc_->ids.push_back(w.bodies()[i].id);
    }

    // Walls: selected, or all
    wordList unusedWalls;
    const wordList& wn = c.wallNames();
    forAll(wn, k)
    {
        if (!wallsGiven_ || wallSel_.match(wn[k]))
        {
            acc_->walls.push_back(k);
        }
        else
        {
            unusedWalls.append(wn[k]);
        }
    }
    if (wallsGiven_)
    {
        for (const wordRe& r : wallSel_)
        {
            bool any = false;
            forAll(wn, k) { any = any || r.match(wn[k]); }
            if (!any)
            {
                FatalIOErrorInFunction(dict_)
                    << "Entry 'walls' of function object " << name()
                    << ": '" << r << "' matches no wall. Walls: " << wn
                    << nl << exit(FatalIOError);
            }
        }
    }
    acc_->wallForce.resize(w.walls().size());

    if (unused.size() || unusedWalls.size())
    {
        WarningInFunction
            << "Function object " << name() << ": bodies " << unused
            << " and walls " << unusedWalls << " are neither in"
            << " 'structure' nor in 'walls': the load they take is missing"
            << " from the force balance" << endl;
    }
    if (acc_->bodies.empty())
    {
        WarningInFunction
            << "Function object " << name() << ": no structure body (every"
            << " body is free): the structure load is zero" << endl;
    }

    c.addStepObserver(acc_);
    P0_ = floeMomentum();
    {
        // The force the first step's first half kick takes
        ::iceDEM::Vec3 f, wl, d;
        acc_->loads(w, f, wl, d);
        acc_->net = d - f - wl;
        acc_->netKnown = true;
    }

    Info<< type() << ' ' << name() << ": structure bodies "
        << acc_->bodies.size() << ", walls " << acc_->walls.size()
        << ", transient ";
    if (autoTransient_) Info<< "auto (MSER-5)";
    else Info<< transient_ << " s";
    Info<< ", " << batches_ << " batches" << endl;
}


::iceDEM::Vec3
Foam::functionObjects::iceLoadStatistics::floeMomentum() const
{
    const ::iceDEM::World& w =
        time_.lookupObject<iceDEMState>("iceDEMState").demCase().world();
    ::iceDEM::Vec3 P = ::iceDEM::Vec3::Zero();
    for (const ::iceDEM::Body& b : w.bodies())
    {
        if (b.isFree()) P += b.mass*b.v;
    }
    return P;
}


bool Foam::functionObjects::iceLoadStatistics::readTensions(scalarList& T)
{
    T.clear();
    if (!Pstream::master())
    {
        return false;
    }
    if (!tensionsFound_)
    {
        tensionsFound_ = true;
        wordList restraints(mooring_);
        if (!mooringGiven_)
        {
            wordList names(time_.sortedNames<IOField<scalar>>());
            for (const word& n : names)
            {
                if (n.size() > 9 && n.substr(n.size() - 9) == ":tensions")
                {
                    restraints.append(n.substr(0, n.size() - 9));
                }
            }
        }
        for (const word& r : restraints)
        {
            const word key(r + ":tensions");
            if (!time_.foundObject<IOField<scalar>>(key))
            {
                FatalIOErrorInFunction(dict_)
                    << "Entry 'mooring' of function object " << name()
                    << ": '" << r << "' is not a spreadMooring restraint"
                    << " of this run (constant/dynamicMeshDict)" << nl
                    << exit(FatalIOError);
            }
            const label n = time_.lookupObject<IOField<scalar>>(key).size();
            for (label i = 0; i < n; ++i)
            {
                tensionNames_.append(r + ".T" + Foam::name(i));
            }
        }
        mooring_ = restraints;
        T_.resize(tensionNames_.size());
    }

    for (const word& r : mooring_)
    {
        T.append(time_.lookupObject<IOField<scalar>>(r + ":tensions"));
    }
    return T.size() > 0;
}


// ************************************************************************* //
