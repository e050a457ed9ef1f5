/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Application
    iceDEMFoam

Group
    grpLagrangianSolvers

Description
    The dilated-polyhedron DEM of libiceDEM alone, no flow solve: floes and
    blocks (constant/iceField), plane walls, gravity (constant/g), water
    (buoyancy) and empirical drag with a uniform current
    (constant/iceDEMProperties). For fast studies and analytic checks.

    Times come from system/controlDict: every time step (deltaT there, the
    output interval) advances the DEM to the new time with sub-steps of the
    DEM step (deltaT of constant/iceDEMProperties; the last sub-step is
    shortened to land on the time exactly). At every write time the DEM
    state goes to <time>/uniform/iceDEMState; starting from a time with
    that file (startFrom latestTime) continues the run exactly.

    Outputs under postProcessing/iceDEM/<startTime>/ (see iceDEMOutput.H and
    doc/caseFiles.md): bodies.dat, energy.dat, VTK/ with bodies.vtk.series.
    Function objects of system/controlDict run after every time step (e.g.
    iceLoadStatistics: load statistics and the force balance).

    If the state of a body becomes non-finite the run stops naming the body
    and the time.

    A case whose constant/iceDEMProperties has a 'structure' (a floating
    structure from constant/structureDict, moored and moved by OpenFOAM's
    sixDoFRigidBodyMotion with constant/dynamicMeshDict) runs exactly as
    iceFloatingFoam -noFlow: the structure's motion and the DEM sub-cycled
    in every time step, without a mesh and without the fluid force.

Usage
    \b iceDEMFoam [OPTION]

    Options:
      - \par -threads \<N\>
        Number of OpenMP threads of the DEM (default: OMP_NUM_THREADS, else
        all cores). Results do not depend on it.

    Example:
    \verbatim
    iceDEMFoam -case cubeDrop -threads 2
    \endverbatim

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"

#include "iceDEMCase.H"
#include "iceDEMOutput.H"
#include "IOdictionary.H"
#include "runWithoutFlow.H"
#include "completeTime.H"
#include "completeTimeWriter.H"
#include "dictionaryChecks.H"

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace Foam;

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Dilated-polyhedron DEM of ice floes and blocks (libiceDEM) without"
        " a flow solve.\n"
        "Reads constant/iceDEMProperties, constant/iceField and constant/g;"
        " writes postProcessing/iceDEM/<startTime>/ and the DEM state in"
        " every written time directory (restart with startFrom latestTime)."
    );
    argList::noParallel();
    argList::addOption
    (
        "threads",
        "N",
        "Number of OpenMP threads of the DEM (default: OMP_NUM_THREADS or"
        " all cores); results do not depend on it"
    );

    #include "setRootCase.H"

    label nThreads = 0;
    if (args.readIfPresent("threads", nThreads))
    {
        if (nThreads < 1)
        {
            FatalErrorInFunction
                << "Option -threads " << nThreads
                << ": the number of threads must be >= 1" << nl
                << exit(FatalError);
        }
        #ifdef _OPENMP
        omp_set_num_threads(nThreads);
        #endif
    }

    // Started from the last complete time (a run killed while writing)
    autoPtr<Time> runTimePtr(completeTime::createTime(args));
    Time& runTime = runTimePtr();

    // A zero or negative deltaT would never reach endTime
    iceDEMChecks::checkTimeControls(runTime);

    // A moored structure: the same run as iceFloatingFoam -noFlow
    {
        const IOdictionary properties
        (
            IOobject
            (
                "iceDEMProperties",
                runTime.constant(),
                runTime,
                IOobject::READ_IF_PRESENT,   // missing: iceDEMCase says so
                IOobject::NO_WRITE,
                false
            )
        );
        if (properties.isDict("structure"))
        {
            Info<< "iceDEM: 'structure' in constant/iceDEMProperties: the"
                << " structure moved by sixDoFRigidBodyMotion"
                << " (constant/dynamicMeshDict) without fluid, as"
                << " iceFloatingFoam -noFlow" << nl;
            return runWithoutFlow(runTime);
        }
    }

    iceDEMCase demCase(runTime);
    demCase.start();

    iceDEMOutput output(demCase);
    output.write(true);

    const ::iceDEM::World& world = demCase.world();

    // Write times marked complete last; SIGTERM: write and stop
    completeTimeWriter writer(runTime);

    Info<< "iceDEM: output in " << output.path() << nl
        << "iceDEM: estimated Hertz contact time "
        << world.estimatedContactTime() << " s, DEM step "
        << world.settings().timeStep << " s" << nl
        << "\nStarting time loop\n" << endl;

    while (runTime.run())
    {
        ++runTime;

        Info<< "Time = " << runTime.timeName() << nl;

        const long steps0 = world.stepIndex();
        demCase.advanceTo(runTime.value());

        output.write();
        writer.write();

        const ::iceDEM::Energies e = world.energies();
        Info<< "    DEM steps " << (world.stepIndex() - steps0)
            << "  contacts " << world.contactCount()
            << " (" << world.contactPairCount() << " pairs)"
            << "  kinetic energy " << e.kinetic << " J" << nl
            << "    ExecutionTime = " << runTime.elapsedCpuTime() << " s"
            << "  ClockTime = " << runTime.elapsedClockTime() << " s"
            << nl << endl;
    }

    Info<< "End\n" << endl;

    return 0;
}


// ************************************************************************* //
