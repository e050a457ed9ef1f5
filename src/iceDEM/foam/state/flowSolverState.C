/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.
\*---------------------------------------------------------------------------*/

#include "flowSolverState.H"
#include "completeTime.H"
#include "IOdictionary.H"
#include "pairGAMGAgglomeration.H"
#include "GAMGAgglomeration.H"
#include "lduPrimitiveMesh.H"

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

//- One level of pair agglomeration of a probe (a chain of three cells, a
//  lone fourth): its clusters are numbered in the direction of the
//  process-wide flag, and the call flips the flag (pairGAMGAgglomeration::
//  forward_ is private; its public static agglomerate() is the way in).
//  Forwards the chain is cluster 0 and the lone cell 1; backwards the chain
//  is found first and the numbering reversed, so the lone cell is 0
bool agglomerateProbe()
{
    labelList lower({0, 1});
    labelList upper({1, 2});
    const lduPrimitiveMesh probe(4, lower, upper, UPstream::worldComm, true);
    label nCoarse = 0;
    const tmp<labelField> map =
        pairGAMGAgglomeration::agglomerate
        (
            nCoarse, probe.lduAddr(), scalarField(2, 1.0)
        );
    return map()[3] == 1;
}


//- The flag, left as it was (two probes: the second flips it back)
bool pairAgglomerationForward()
{
    const bool forward = agglomerateProbe();
    if (agglomerateProbe() == forward)
    {
        FatalErrorInFunction
            << "GAMG's pair agglomeration did not alternate its direction"
            << " between two levels (an OpenFOAM other than v1912?): its"
            << " state cannot be kept for a restart" << exit(FatalError);
    }
    return forward;
}


void setPairAgglomerationForward(const bool forward)
{
    if (pairAgglomerationForward() != forward)
    {
        agglomerateProbe();
    }
}


const char* const forwardEntry = "pairAgglomerationForward";

Foam::IOobject stateIO(const Foam::Time& runTime, Foam::IOobject::readOption r)
{
    return Foam::IOobject
    (
        Foam::flowSolverState::fileName, runTime.timeName(), "uniform",
        runTime, r, Foam::IOobject::NO_WRITE, false
    );
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Functions  * * * * * * * * * * * * * * * //

const char* const Foam::flowSolverState::fileName = "flowSolverState";


void Foam::flowSolverState::write(const fvMesh& mesh)
{
    const Time& runTime = mesh.time();
    IOdictionary dict(stateIO(runTime, IOobject::NO_READ));
    dict.add(forwardEntry, Switch(pairAgglomerationForward()));
    if
    (
        !completeTime::atomicWrite
        (
            dict, IOstream::ASCII, IOstream::currentVersion,
            IOstream::UNCOMPRESSED
        )
    )
    {
        FatalErrorInFunction
            << "Could not write " << dict.objectPath() << exit(FatalError);
    }

    // The levels in use were built from the flag as it was at the mesh's
    // last change, not as written: built again from it at the next solve,
    // as a restart from this time builds them
    GAMGAgglomeration::Delete(mesh);
}


void Foam::flowSolverState::read(const Time& runTime)
{
    IOobject io(stateIO(runTime, IOobject::MUST_READ));
    if (!io.typeHeaderOk<IOdictionary>(true))
    {
        return;     // initial conditions, or a time of another writer
    }
    const IOdictionary dict(io);
    const bool forward = dict.get<bool>(forwardEntry);
    setPairAgglomerationForward(forward);
    Info<< "Flow solver state from " << dict.objectPath().relative(runTime.path())
        << ": " << forwardEntry << ' ' << Switch(forward) << nl << endl;
}


// ************************************************************************* //
