/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

Application
    iceFloatingFoam

Group
    iceDEM

Description
    Transient incompressible current below a rigid lid at the waterline
    around a floating structure moved by OpenFOAM's sixDoFRigidBodyMotion
    (dynamicMotionSolverFvMesh): PIMPLE on the moving mesh, any turbulence
    model of the standard framework, MRF and fvOptions.

    The structure (hull patch) feels the fluid force, gravity and the
    restraints of constant/dynamicMeshDict; libiceDEM adds hullHydrostatics
    (buoyancy: the kinematic pressure p has no hydrostatic part),
    spreadMooring and iceLoad (the DEM ice load, registered on the Time
    database by this solver). Load libiceDEM with  libs ("libiceDEM.so");
    in controlDict.

    With constant/iceDEMProperties the DEM of libiceDEM runs inside the
    time step (iceDEMCoupling): the floes of constant/iceField, the
    structure as prescribed DEM bodies (one per convex piece of
    constant/structureDict), buoyancy and drag (empirical: uniform current;
    resolved: the velocity field U sampled at every drag point). A case
    without it runs the flow and the structure alone.

    One step (DESIGN.md, explicit coupling, ice load lagged one step):
      0. the ice load averaged over the previous DEM interval is registered
         on the Time database (iceLoadForce, iceLoadMoment) for the iceLoad
         restraint; the old sixDoF state is kept;
      1. mesh.update(): the sixDoF motion and the mesh motion (with
         flowSolveInterval > 1: the sixDoF motion every step, the mesh
         only on the steps that solve the flow);
      2. PIMPLE: U, p and turbulence on the moved mesh;
      3. DEM: sub-cycles from t - deltaT to t with its own step, the
         structure's pose interpolated between the old and new sixDoF
         states; the ice impulse on the structure averaged into the load
         of the next step;
      4. outputs: postProcessing/hullMotion (centre of mass, roll pitch yaw,
         velocities) and the surge/heave periods in the log,
         postProcessing/iceLoad, postProcessing/iceDEM, and at write times
         the DEM state (<time>/uniform/iceDEMState, restart).

    With -noFlow the structure moves alone (no mesh, no fluid force), driven
    from the same dynamicMeshDict, with the same DEM coupling: the moored
    DEM-only study (the structure moves exactly as in the coupled solver
    minus the fluid force), and the analytic checks of the restraints.

Usage
    iceFloatingFoam [-noFlow] [-parallel] [OpenFOAM options]

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "clockTime.H"
#include "cpuTime.H"
#include "dynamicFvMesh.H"
#include "dynamicMotionSolverFvMesh.H"
#include "sixDoFRigidBodyMotionSolver.H"
#include "rigidLidMotionSolver.H"
#include "stockMotionUnderLid.H"
#include "singlePhaseTransportModel.H"
#include "turbulentTransportModel.H"
#include "pimpleControl.H"
#include "CorrectPhi.H"
#include "fvOptions.H"

#include "structureMotion.H"
#include "hullMotionLog.H"
#include "iceDEMCoupling.H"
#include "runWithoutFlow.H"
#include "completeTime.H"
#include "completeTimeWriter.H"
#include "flowSolverState.H"
#include "dictionaryChecks.H"

#include <memory>

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{

//- The sixDoF motion of the structure, or nullptr when the mesh is not moved
//  by sixDoFRigidBodyMotion or rigidLidSixDoFRigidBodyMotion
static const sixDoFRigidBodyMotion* structureMotionOf
(
    const dynamicFvMesh& mesh
)
{
    const auto* dm = dynamic_cast<const dynamicMotionSolverFvMesh*>(&mesh);
    if (!dm)
    {
        return nullptr;
    }
    const auto* solver =
        dynamic_cast<const sixDoFRigidBodyMotionSolver*>(&dm->motion());
    if (solver)
    {
        return &solver->motion();
    }
    const auto* rigidLid =
        dynamic_cast<const rigidLidMotionSolver*>(&dm->motion());
    return rigidLid ? &rigidLid->motion() : nullptr;
}


//- The motion solver of a dynamicMotionSolverFvMesh (nullptr for other
//  dynamic meshes), to move the structure and the mesh separately
static motionSolver* meshMotionOf(dynamicFvMesh& mesh)
{
    auto* dm = dynamic_cast<dynamicMotionSolverFvMesh*>(&mesh);

    // The mesh owns its (non-const) motion solver and hands it out const
    return dm ? &const_cast<motionSolver&>(dm->motion()) : nullptr;
}

} // End namespace Foam


// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Incompressible current below a rigid lid around a floating structure"
        " moved by sixDoFRigidBodyMotion (ice load, hydrostatics and mooring"
        " from libiceDEM restraints)."
    );
    argList::addBoolOption
    (
        "noFlow",
        "Move the structure alone with the case's dynamicMeshDict: no mesh,"
        " no fluid force (analytic checks of the restraints)"
    );

    #include "addCheckCaseOptions.H"
    #include "setRootCaseLists.H"
    // Started from the last complete time (a run killed while writing)
    autoPtr<Time> runTimePtr(completeTime::createTime(args));
    Time& runTime = runTimePtr();

    // A zero or negative deltaT would never reach endTime
    iceDEMChecks::checkTimeControls(runTime);

    if (args.found("noFlow"))
    {
        Info<< "\n-noFlow: the structure without fluid" << endl;
        return runWithoutFlow(runTime);
    }

    #include "createDynamicFvMesh.H"
    #include "initContinuityErrs.H"
    #include "createDyMControls.H"
    #include "readGravitationalAcceleration.H"
    (void)g;    // registered for sixDoFRigidBodyMotion, which looks it up
    #include "createFields.H"
    #include "createUfIfPresent.H"
    // The old-time levels the time loop keeps (its first change of U in a
    // step, the boundary update after a mesh motion, stores them): made
    // now from the fields read, or a restart would make them later, from
    // fields already changed (restart = uninterrupted run)
    U.oldTime();
    if (Uf.valid())
    {
        Uf->oldTime();
    }
    #include "CourantNo.H"
    #include "setInitialDeltaT.H"

    turbulence->validate();

    // What the flow's solution depends on beyond the fields (a restart)
    flowSolverState::read(runTime);

    // What a restart from the times written reproduces: binary fields are
    // exact, but a patch whose values are all equal is written as text
    // with writePrecision digits (README, known limits of restarts)
    if
    (
        runTime.writeFormat() == IOstream::ASCII
     || IOstream::defaultPrecision() < 17
    )
    {
        Info<< "iceDEM: writeFormat "
            << (runTime.writeFormat() == IOstream::ASCII ? "ascii" : "binary")
            << ", writePrecision " << IOstream::defaultPrecision()
            << ": a restart from this run's times equals the uninterrupted"
            << " run to the digits written, not to the bit (binary and 17"
            << " make it exact)" << nl << endl;
    }

    const sixDoFRigidBodyMotion* hullPtr = structureMotionOf(mesh);
    motionSolver* meshMotion = meshMotionOf(mesh);
    const auto* stockMotion =
        dynamic_cast<const sixDoFRigidBodyMotionSolver*>(meshMotion);
    if (stockMotion)
    {
        checkStockMotionUnderLid(*stockMotion);
    }
    if (!hullPtr)
    {
        WarningInFunction
            << "The mesh is not moved by sixDoFRigidBodyMotion"
            << " (dynamicMotionSolverFvMesh + motionSolver"
            << " sixDoFRigidBodyMotion): no structure motion output." << endl;
    }
    autoPtr<hullMotionLog> motionLog;
    if (hullPtr)
    {
        motionLog.reset(new hullMotionLog(runTime));
    }

    // The DEM (constant/iceDEMProperties present)
    std::unique_ptr<iceDEMCoupling> dem;
    if (iceDEMCoupling::present(runTime))
    {
        dem.reset(new iceDEMCoupling(runTime, &mesh, hullPtr));
    }
    else
    {
        Info<< "No constant/iceDEMProperties: flow and structure without"
            << " ice" << nl;
    }

    // * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

    // Write times marked complete last, with the flow solver's state
    // before OpenFOAM's objects and the stock motion solver's state again
    // after them, with 17 digits (it writes it at writePrecision; the
    // rigid-lid solver writes 17 itself); SIGTERM: write and stop
    completeTimeWriter writer
    (
        runTime,
        [&mesh]() { flowSolverState::write(mesh); },
        [&runTime, stockMotion]()
        {
            if (stockMotion)
            {
                writeExactMotionState(runTime, stockMotion->motion());
            }
        }
    );

    Info<< "\nStarting time loop\n" << endl;

    // Wall time per CFD step: flow solve, mesh motion (sixDoF + mesh), DEM
    // (with, separately, the resolved-velocity sampling inside it)
    // and the same in CPU time of the process (all threads): the split on
    // a machine shared with other jobs, where wall times are inflated
    clockTime stepClock;
    cpuTime cpuClock;

    while (runTime.run())
    {
        #include "readFlowSolveInterval.H"
        scalar tFlow = 0, tMesh = 0, tDem = 0;
        scalar cFlow = 0, cMesh = 0, cDem = 0;
        #include "readDyMControls.H"
        #include "CourantNo.H"
        #include "setDeltaT.H"

        ++runTime;

        Info<< "Time = " << runTime.timeName() << nl << endl;

        // Ice load of the previous DEM interval for the iceLoad restraint
        // (the DEM is replicated on every processor: the same load on all)
        if (dem)
        {
            dem->beginStep();
        }

        // The flow is solved every flowSolveInterval-th step (a steady
        // current), over the time since its last solution: flow step =
        // flowSolveInterval x deltaT; the structure and the DEM still
        // advance every deltaT. In between, the flow fields and the mesh are
        // kept and the fluid force of the last solution acts (its pressure
        // holds the flow's reaction to the hull's mean acceleration over the
        // flow step: the same impulse). The mesh follows the structure at
        // the flow steps, over the flow step (moveStructure.H): its flux is
        // the mean mesh velocity over the step the flow is solved for.
        const scalar deltaT = runTime.deltaTValue();
        const bool solveFlow = (runTime.timeIndex() % flowSolveInterval == 0);
        if (flowSolveInterval > 1)
        {
            #include "moveStructure.H"
        }
        if (dem && solveFlow)
        {
            // deltaT is now the flow step: the flow takes the two-way source
            dem->beginFlowSolve();
        }

        // --- Pressure-velocity PIMPLE corrector loop
        while (solveFlow && pimple.loop())
        {
            if
            (
                flowSolveInterval == 1
             && (pimple.firstIter() || moveMeshOuterCorrectors)
            )
            {
                #include "moveMesh.H"
            }

            stepClock.timeIncrement();
            cpuClock.cpuTimeIncrement();
            #include "UEqn.H"

            // --- Pressure corrector loop
            while (pimple.correct())
            {
                #include "pEqn.H"
            }

            if (pimple.turbCorr())
            {
                laminarTransport.correct();
                turbulence->correct();
            }
            tFlow += stepClock.timeIncrement();
            cFlow += cpuClock.cpuTimeIncrement();
        }
        if (solveFlow && flowSolveInterval > 1)
        {
            runTime.setDeltaT(deltaT, false);
        }

        // DEM sub-cycle over the step; the ice load of the next step
        if (dem)
        {
            stepClock.timeIncrement();
            cpuClock.cpuTimeIncrement();
            dem->solve();
            tDem = stepClock.timeIncrement();
            cDem = cpuClock.cpuTimeIncrement();
        }
        const scalar tSampling = dem ? dem->samplingSeconds() : 0;
        Info<< "Step wall time: flow " << tFlow << " s, mesh motion " << tMesh
            << " s, velocity sampling " << tSampling << " s, DEM "
            << tDem - tSampling << " s" << nl
            << "Step cpu time: flow " << cFlow << " s, mesh motion " << cMesh
            << " s, DEM with sampling " << cDem << " s" << nl;

        if (motionLog.valid())
        {
            motionLog->write(*hullPtr);
        }

        writer.write();

        runTime.printExecutionTime(Info);
    }

    Info<< "End\n" << endl;

    return 0;
}


// ************************************************************************* //
