/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

Application
    createStructure

Description
    Builds the floating structure from its one definition,
    constant/structureDict (see floatingStructure), and writes what the
    other tools read:

      - constant/triSurface/hull.stl: the closed hull surface
        (snappyHexMesh or topoSet cut the hull patch from it);
      - constant/hullMassProperties: mass (from the displaced volume at the
        draft), centreOfMass, momentOfInertia, to #include in
        constant/dynamicMeshDict;
      - constant/hullPieces: the convex pieces (vertex lists) of the DEM
        rigid body.

    It prints the hydrostatic checks: displaced volume against mass/rho_w,
    the waterplane area against the derivative of the displaced volume with
    the water level, and the heave stiffness rho_w |g| A_wp (g from
    constant/g when present).

Usage
    createStructure [-dict <file>] [-surfaceName <name>]

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "IFstream.H"
#include "OFstream.H"
#include "OSspecific.H"
#include "floatingStructure.H"
#include "uniformDimensionedFields.H"

using namespace Foam;

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Build the floating structure from constant/structureDict: hull STL,"
        " mass properties for dynamicMeshDict, convex pieces for the DEM"
    );
    argList::noParallel();
    argList::addOption
    (
        "dict",
        "file",
        "Structure dictionary (default: constant/structureDict)"
    );
    argList::addOption
    (
        "surfaceName",
        "name",
        "Name of the STL and of its solid (default: hull)"
    );

    #include "setRootCase.H"
    #include "createTime.H"

    const fileName dictFile
    (
        args.lookupOrDefault<fileName>
        (
            "dict",
            runTime.path()/runTime.constant()/"structureDict"
        )
    );
    const word surfaceName(args.lookupOrDefault<word>("surfaceName", "hull"));

    IFstream is(dictFile);
    if (!is.good())
    {
        FatalErrorInFunction
            << "Cannot open the structure dictionary " << dictFile << nl
            << exit(FatalError);
    }
    dictionary dict(is);
    dict.name() = dictFile;

    const floatingStructure hull(dict);
    hull.report(Info);

    // Hydrostatic checks
    const floatingStructure::submergedPart sub = hull.submerged();
    const scalar dz = 1e-4*hull.draft();
    const scalar Vup =
        floatingStructure::clip(hull.points(), hull.faces(), hull.level() + dz)
       .volume;
    const scalar Vdown =
        floatingStructure::clip(hull.points(), hull.faces(), hull.level() - dz)
       .volume;
    const scalar dVdz = (Vup - Vdown)/(2*dz);

    Info<< nl << "Hydrostatic checks" << nl
        << "    displaced volume " << sub.volume << " m3, mass/rho_w "
        << hull.mass()/hull.rhoWater() << " m3" << nl
        << "    waterplane area " << sub.waterplaneArea
        << " m2, dV/dlevel " << dVdz << " m2, relative difference "
        << mag(dVdz - sub.waterplaneArea)/sub.waterplaneArea << nl;

    IOobject gIO
    (
        "g",
        runTime.constant(),
        runTime,
        IOobject::MUST_READ,
        IOobject::NO_WRITE,
        false
    );
    if (gIO.typeHeaderOk<uniformDimensionedVectorField>(true))
    {
        const uniformDimensionedVectorField g(gIO);
        Info<< "    heave stiffness rho_w |g| A_wp "
            << hull.rhoWater()*mag(g.value())*sub.waterplaneArea << " N/m"
            << nl;
    }
    else
    {
        Info<< "    (no constant/g: heave stiffness not reported)" << nl;
    }

    // Outputs
    const fileName constantDir(runTime.path()/runTime.constant());
    mkDir(constantDir/"triSurface");

    const fileName stlFile(constantDir/"triSurface"/(surfaceName + ".stl"));
    hull.writeSTL(stlFile, surfaceName);

    {
        OFstream os(constantDir/"hullMassProperties");
        os.precision(12);
        hull.writeMassProperties(os);
    }
    {
        OFstream os(constantDir/"hullPieces");
        os.precision(12);
        hull.writePieces(os);
    }

    Info<< nl << "Wrote " << stlFile << nl
        << "      " << constantDir/"hullMassProperties"
        << " (#include in dynamicMeshDict)" << nl
        << "      " << constantDir/"hullPieces" << nl
        << nl << "End" << nl << endl;

    return 0;
}


// ************************************************************************* //
