/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "runWithoutFlow.H"

#include "gravityMeshObject.H"
#include "structureMotion.H"
#include "hullMotionLog.H"
#include "iceDEMCoupling.H"
#include "completeTimeWriter.H"

#include <memory>

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int Foam::runWithoutFlow(Time& runTime)
{
    Info<< "\nReading g" << endl;
    (void)meshObjects::gravity::New(runTime);

    Info<< "\nStructure motion without fluid (no mesh is read)\n" << endl;

    structureMotion body(runTime);
    hullMotionLog motionLog(runTime);

    // The DEM (constant/iceDEMProperties present): drag type resolved has
    // no velocity field here (FatalIOError)
    std::unique_ptr<iceDEMCoupling> dem;
    if (iceDEMCoupling::present(runTime))
    {
        dem.reset(new iceDEMCoupling(runTime, nullptr, &body.motion()));
    }

    // Write times marked complete last, the sixDoF state (not registered)
    // with them; SIGTERM: write and stop
    completeTimeWriter writer(runTime, [&]{ body.write(); });

    Info<< "\nStarting time loop\n" << endl;

    while (runTime.run())
    {
        ++runTime;

        if (dem)
        {
            Info<< "Time = " << runTime.timeName() << nl;
        }

        // As with the flow: the lagged ice load, the motion, the DEM
        if (dem)
        {
            dem->beginStep();
        }
        body.step();
        if (dem)
        {
            dem->solve();
            Info<< nl;
        }
        motionLog.write(body.motion());

        writer.write();
    }

    Info<< "\nEnd\n" << endl;

    return 0;
}

// ************************************************************************* //
