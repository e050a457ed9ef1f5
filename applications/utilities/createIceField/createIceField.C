/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Application
    createIceField

Group
    grpPreProcessingUtilities

Description
    Broken ice field from a 2D Voronoi tessellation (Liu & Ji 2018, section
    2.2): random seed points, optional Lloyd relaxation, Voronoi cells
    clipped to an l*sqrt(c) x w*sqrt(c) rectangle and moved apart by
    1/sqrt(c) so that they cover the fraction c of the region, floes in
    exclusion zones removed. The method, the concentration with exclusion
    zones and the reproducibility are described in
    src/iceDEM/core/field/VoronoiField.H; the floe core (outline shrunk by
    the dilation radius r, thickness h - 2r) in field/IceFloe.H.

    Reads system/createIceFieldDict and writes
      - constant/iceField: the floes as 'type prism' bodies
        (doc/caseFiles.md), read by iceDEMFoam and iceFloatingFoam. An
        existing constant/iceField is kept unless -overwrite is given. It
        is written to constant/iceField.writing and renamed into place: a
        kill never leaves half a field under its name;
      - VTK/iceField.vtk: the true floe prisms (legacy VTK polydata) and
        VTK/exclusionZones.vtk (the zones as polylines at the water level);
      - a PNG top view (default iceField.png in the case directory): floes
        filled, exclusion zones outlined, region border;
    and prints the report: number of floes, achieved concentration (floe
    area / free area, where free area = region minus exclusion zones), floe
    area mean and standard deviation, edge-count histogram.

Usage
    \b createIceField [OPTION]

    Options:
      - \par -dict \<file\>
        Read this dictionary instead of system/createIceFieldDict

      - \par -overwrite
        Replace an existing constant/iceField

    system/createIceFieldDict (defaults in brackets; lengths in m):
    \verbatim
    region                          // required
    {
        min     (-300 -200);        // lower-left corner
        max     (300 200);          // upper-right corner
    }
    nFloes          200;            // number of Voronoi cells (floes before
                                    // removing those in exclusion zones), or
    meanFloeArea    150;            // [m2] instead: nFloes = round(c l w / A)
                                    // (exactly one of the two)
    concentration   0.6;            // required, in (0, 1): floe area / free area
    thickness       1.0;            // required: a value [m], or a distribution:
    // thickness { distribution uniform; min 0.8; max 1.2; }
    // thickness { distribution normal; mean 1; standardDeviation 0.2;
    //             min 0.6; max 1.4; maxDraws 1000; }  (truncated normal:
    //             redrawn until in [min, max], at most maxDraws times)
    radius          0.05;           // required: dilation radius r > 0;
                                    // thickness (or min) must exceed 4r
    seed            1;              // [1] random seed (>= 0): same seed, same field
    lloydIterations 0;              // [0] Lloyd relaxation steps (more regular)
    floeNumbering   hilbert;        // [hilbert] floes numbered along a Hilbert
                                    // curve (faster DEM on large fields), or
                                    // seed: in the random order of the seeds
    velocity        (0 0 0);        // [(0 0 0)] initial velocity of every floe [m/s]
    iceDensity      900;            // [900] kg/m3, floating: zBottom =
    waterDensity    1025;           // [1025]  waterLevel - (iceDensity/waterDensity) h
    waterLevel      0;              // [0] z of the water plane [m]
    material        ice;            // [ice] material name written for every floe
    motion          free;           // [free] motion written for every floe
    namePrefix      floe;           // [floe] body names floe0, floe1, ...

    exclusionZones                  // [none] areas kept free of ice; zones
    {                               // must not overlap or touch each other
        hull    { type circle; centre (0 0); radius 45; }
        channel { type polygon; points ((100 -10) (300 -10) (300 10) (100 10)); }
    }

    minCoreEdgeRatio     1;         // [1] edges whose core edge would be
                                    // shorter than this times r are collapsed
    minCoreWidthRatio    2;         // [2] (>= 2) cells whose core is thinner than
                                    // this times r are dropped (too small)
    correctConcentration yes;       // [yes] correct for the floes removed at
                                    // exclusion zones and small cells
    maxCorrections       10;        // [10] at most this many corrections
    concentrationTolerance 1e-3;    // [1e-3] relative target of the correction
    concentrationResolution 1e-9;   // [1e-9] rounding of the corrected value
    tolerance            1e-9;      // [1e-9] relative geometric tolerance
    checkCores           yes;       // [yes] build every floe's DEM element
                                    // (DilatedShape) to check it is valid

    writeVTK             yes;       // [yes] VTK/iceField.vtk, VTK/exclusionZones.vtk
    circleSegments       128;       // [128] sides of a circle in the VTK file
    image                           // [on] PNG top view
    {
        write       yes;            // [yes]
        file        "iceField.png"; // [iceField.png] relative to the case
        width       1200;           // [1200] pixels; height from aspect ratio
        water       (20 60 110);    // [(20 60 110)] RGB 0-255
        ice         (235 240 245);  // [(235 240 245)]
        floeEdge    (140 150 165);  // [(140 150 165)]
        zone        (220 40 40);    // [(220 40 40)] exclusion zone outline
        border      (0 0 0);        // [(0 0 0)] region border
        lineWidth   2;              // [2] pixels, zones and border
    }
    \endverbatim

    Bad input stops with a FatalIOError naming the file and the entry:
    concentration outside (0, 1), thickness <= 4r, minCoreWidthRatio < 2,
    region too small for one floe, exclusion zones covering the region or
    overlapping each other, negative densities, unknown thickness
    distribution or zone type.

SourceFiles
    createIceField.C
    iceFieldWriters.C
    iceFieldImage.C

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "caseEntries.H"
#include "Time.H"
#include "IOdictionary.H"
#include "OSspecific.H"
#include "vector2D.H"
#include "Switch.H"

#include "field/VoronoiField.H"
#include "geometry/DilatedShape.H"
#include "iceFieldWriters.H"
#include "iceFieldImage.H"

#include <cstdio>
#include <sstream>

using namespace Foam;
using Foam::iceDEMChecks::checkEntries;

// * * * * * * * * * * * * * * * * Functions * * * * * * * * * * * * * * * //

namespace
{

//- Stop with a FatalIOError for a core error, located at the sub-dictionary
//  the entry names when there is one
[[noreturn]] void fatalCoreError
(
    const dictionary& dict,
    const iceDEM::Error& err,
    const std::string& context = ""
)
{
    const word entryName(err.entry());
    const dictionary* sub =
        entryName.empty() ? nullptr : dict.findDict(entryName, keyType::LITERAL);
    FatalIOErrorInFunction(sub ? *sub : dict)
        << "entry '" << entryName.c_str() << "': " << context.c_str()
        << err.what() << nl
        << exit(FatalIOError);
    std::abort();   // not reached: exit(FatalIOError) throws or exits
}

iceDEM::Vec2 toVec2(const vector2D& v)
{
    return iceDEM::Vec2(v.x(), v.y());
}

iceDEM::Rgb readColour
(
    const dictionary& dict,
    const word& key,
    const iceDEM::Rgb& deflt
)
{
    const vector v = dict.getOrDefault<vector>
    (
        key, vector(deflt[0], deflt[1], deflt[2])
    );
    iceDEM::Rgb c;
    for (direction k = 0; k < 3; ++k)
    {
        if (v[k] < 0 || v[k] > 255)
        {
            FatalIOErrorInFunction(dict)
                << "entry '" << key << "': colour components must be in "
                << "[0, 255], got " << v << nl << exit(FatalIOError);
        }
        c[k] = std::uint8_t(std::lround(v[k]));
    }
    return c;
}

//- Settings of the generator from the dictionary
iceDEM::VoronoiFieldSettings readSettings(const dictionary& dict)
{
    iceDEM::VoronoiFieldSettings s;

    // Every keyword must be one the generator reads (a misspelt optional
    // entry would otherwise leave its default in place without a word)
    checkEntries(dict, "system/createIceFieldDict", {""}, "the top level");

    const dictionary& region = dict.subDict("region");
    checkEntries(region, "system/createIceFieldDict", {"region"}, "region");
    const vector2D lo = region.get<vector2D>("min");
    const vector2D hi = region.get<vector2D>("max");
    s.xmin = lo.x();
    s.ymin = lo.y();
    s.xmax = hi.x();
    s.ymax = hi.y();

    const bool hasN = dict.found("nFloes", keyType::LITERAL);
    const bool hasA = dict.found("meanFloeArea", keyType::LITERAL);
    if (hasN == hasA)
    {
        FatalIOErrorInFunction(dict)
            << "entries 'nFloes' and 'meanFloeArea': give exactly one of them"
            << " (number of floes, or mean floe area in m2)" << nl
            << exit(FatalIOError);
    }
    if (hasN)
    {
        const label n = dict.get<label>("nFloes");
        if (n < 1)
        {
            FatalIOErrorInFunction(dict)
                << "entry 'nFloes': must be >= 1, got " << n << nl
                << exit(FatalIOError);
        }
        s.nFloes = n;
    }
    else
    {
        s.nFloes = 0;
        s.meanFloeArea = dict.get<scalar>("meanFloeArea");
    }

    s.concentration = dict.get<scalar>("concentration");

    // Thickness: a value or a distribution sub-dictionary
    if (const dictionary* td = dict.findDict("thickness", keyType::LITERAL))
    {
        const word dist = td->get<word>("distribution");
        try
        {
            s.thickness.distribution =
                iceDEM::thicknessDistributionFromName(dist);
        }
        catch (const iceDEM::Error& err)
        {
            fatalCoreError(dict, err);
        }
        using D = iceDEM::ThicknessSettings::Distribution;
        checkEntries
        (
            *td, "system/createIceFieldDict",
            {
                s.thickness.distribution == D::constant
              ? "thickness(distribution constant)"
              : s.thickness.distribution == D::uniform
              ? "thickness(distribution uniform)"
              : "thickness(distribution normal)"
            },
            "thickness"
        );
        switch (s.thickness.distribution)
        {
            case D::constant:
                s.thickness.value = td->get<scalar>("value");
                break;
            case D::uniform:
                s.thickness.min = td->get<scalar>("min");
                s.thickness.max = td->get<scalar>("max");
                break;
            case D::normal:
                s.thickness.mean = td->get<scalar>("mean");
                s.thickness.standardDeviation =
                    td->get<scalar>("standardDeviation");
                s.thickness.min = td->get<scalar>("min");
                s.thickness.max = td->get<scalar>("max");
                s.thickness.maxDraws =
                    td->getOrDefault<label>("maxDraws", s.thickness.maxDraws);
                break;
        }
    }
    else
    {
        s.thickness.distribution =
            iceDEM::ThicknessSettings::Distribution::constant;
        s.thickness.value = dict.get<scalar>("thickness");
    }

    s.radius = dict.get<scalar>("radius");

    const label seed = dict.getOrDefault<label>("seed", 1);
    if (seed < 0)
    {
        FatalIOErrorInFunction(dict)
            << "entry 'seed': must be >= 0, got " << seed << nl
            << exit(FatalIOError);
    }
    s.seed = std::uint64_t(seed);

    s.lloydIterations =
        dict.getOrDefault<label>("lloydIterations", s.lloydIterations);

    const word numbering = dict.getOrDefault<word>
    (
        "floeNumbering", iceDEM::floeNumberingName(s.floeNumbering)
    );
    try
    {
        s.floeNumbering = iceDEM::floeNumberingFromName(numbering);
    }
    catch (const iceDEM::Error& err)
    {
        fatalCoreError(dict, err);
    }

    const vector U = dict.getOrDefault<vector>("velocity", vector::zero);
    s.velocity = iceDEM::Vec3(U.x(), U.y(), U.z());

    s.iceDensity = dict.getOrDefault<scalar>("iceDensity", s.iceDensity);
    s.waterDensity = dict.getOrDefault<scalar>("waterDensity", s.waterDensity);
    s.waterLevel = dict.getOrDefault<scalar>("waterLevel", s.waterLevel);

    s.minCoreEdgeRatio =
        dict.getOrDefault<scalar>("minCoreEdgeRatio", s.minCoreEdgeRatio);
    s.minCoreWidthRatio =
        dict.getOrDefault<scalar>("minCoreWidthRatio", s.minCoreWidthRatio);
    s.correctConcentration = dict.getOrDefault<Switch>
    (
        "correctConcentration", Switch(s.correctConcentration)
    );
    s.maxCorrections =
        dict.getOrDefault<label>("maxCorrections", s.maxCorrections);
    s.concentrationTolerance = dict.getOrDefault<scalar>
    (
        "concentrationTolerance", s.concentrationTolerance
    );
    s.concentrationResolution = dict.getOrDefault<scalar>
    (
        "concentrationResolution", s.concentrationResolution
    );
    s.tolerance = dict.getOrDefault<scalar>("tolerance", s.tolerance);

    // Exclusion zones
    if (const dictionary* zd = dict.findDict("exclusionZones", keyType::LITERAL))
    {
        for (const entry& e : *zd)
        {
            if (!e.isDict())
            {
                FatalIOErrorInFunction(*zd)
                    << "entry 'exclusionZones': '" << e.keyword()
                    << "' is not a dictionary; each zone is"
                    << " name { type circle; centre (x y); radius R; } or"
                    << " name { type polygon; points ((x y) ...); }" << nl
                    << exit(FatalIOError);
            }
            const dictionary& z = e.dict();
            iceDEM::ExclusionZone zone;
            zone.name = e.keyword();
            const word type = z.get<word>("type");
            if (type == "circle" || type == "polygon")
            {
                checkEntries
                (
                    z, "system/createIceFieldDict",
                    {
                        type == "circle"
                      ? "exclusionZones/*(type circle)"
                      : "exclusionZones/*(type polygon)"
                    },
                    "exclusion zone " + e.keyword()
                );
            }
            if (type == "circle")
            {
                zone.type = iceDEM::ExclusionZone::Type::circle;
                zone.centre = toVec2(z.get<vector2D>("centre"));
                zone.radius = z.get<scalar>("radius");
            }
            else if (type == "polygon")
            {
                zone.type = iceDEM::ExclusionZone::Type::polygon;
                for (const vector2D& p : z.get<List<vector2D>>("points"))
                {
                    zone.points.push_back(toVec2(p));
                }
            }
            else
            {
                FatalIOErrorInFunction(z)
                    << "entry 'exclusionZones': zone '" << e.keyword()
                    << "' has unknown type '" << type
                    << "'; valid: circle polygon" << nl
                    << exit(FatalIOError);
            }
            s.exclusionZones.push_back(zone);
        }
    }
    else if (dict.found("exclusionZones", keyType::LITERAL))
    {
        FatalIOErrorInFunction(dict)
            << "entry 'exclusionZones': must be a dictionary of zones" << nl
            << exit(FatalIOError);
    }

    return s;
}

std::string fmt(double x)
{
    std::ostringstream os;
    os.precision(6);
    os << x;
    return os.str();
}

} // anonymous namespace


// * * * * * * * * * * * * * * * * * Main  * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Broken ice field from a 2D Voronoi tessellation: reads"
        " system/createIceFieldDict, writes constant/iceField,"
        " VTK/iceField.vtk and a PNG top view, prints the field statistics"
    );
    argList::noParallel();
    #include "addDictOption.H"
    argList::addBoolOption
    (
        "overwrite",
        "Replace an existing constant/iceField"
    );

    #include "setRootCase.H"
    #include "createTime.H"

    const word dictName("createIceFieldDict");
    #include "setSystemRunTimeDictionaryIO.H"

    Info<< "Reading " << dictIO.objectPath() << nl << endl;
    IOdictionary dict(dictIO);

    const bool overwrite = args.found("overwrite");
    const fileName caseDir = runTime.path();
    const fileName iceFieldFile = caseDir/runTime.constant()/"iceField";
    if (isFile(iceFieldFile) && !overwrite)
    {
        FatalErrorInFunction
            << iceFieldFile << " exists; use -overwrite to replace it" << nl
            << exit(FatalError);
    }

    // Settings
    const iceDEM::VoronoiFieldSettings settings = readSettings(dict);
    const word material = dict.getOrDefault<word>("material", "ice");
    const word motion = dict.getOrDefault<word>("motion", "free");
    const word namePrefix = dict.getOrDefault<word>("namePrefix", "floe");
    const bool checkCores = dict.getOrDefault<Switch>("checkCores", true);
    const bool writeVTK = dict.getOrDefault<Switch>("writeVTK", true);
    const label circleSegments =
        dict.getOrDefault<label>("circleSegments", 128);
    if (circleSegments < 3)
    {
        FatalIOErrorInFunction(dict)
            << "entry 'circleSegments': must be >= 3, got " << circleSegments
            << nl << exit(FatalIOError);
    }
    if (motion != "free" && motion != "fixed" && motion != "prescribed")
    {
        FatalIOErrorInFunction(dict)
            << "entry 'motion': unknown motion '" << motion
            << "'; valid: free fixed prescribed" << nl
            << exit(FatalIOError);
    }

    // Generate
    iceDEM::VoronoiFieldReport report;
    std::vector<iceDEM::Floe> floes;
    try
    {
        floes = iceDEM::generateVoronoiField(settings, report);
    }
    catch (const iceDEM::Error& err)
    {
        fatalCoreError(dict, err);
    }

    {
        std::ostringstream os;
        report.print(os);
        Info<< os.str().c_str() << endl;
    }

    // Every floe must make a valid DEM element (the solvers build the same)
    if (checkCores)
    {
        for (std::size_t i = 0; i < floes.size(); ++i)
        {
            try
            {
                iceDEM::DilatedShape shape(floes[i].core(), floes[i].radius);
            }
            catch (const iceDEM::Error& err)
            {
                fatalCoreError
                (
                    dict,
                    err,
                    "floe " + std::to_string(i) + " is not a valid DEM element: "
                );
            }
        }
        Info<< "Checked the DEM element (core prism, dilation radius) of "
            << floes.size() << " floes" << nl << endl;
    }

    // constant/iceField
    {
        mkDir(iceFieldFile.path());
        std::vector<std::string> comment
        {
            "Voronoi ice field: " + std::to_string(report.nFloes) + " floes",
            "concentration target " + fmt(report.targetConcentration)
          + " achieved " + fmt(report.concentration)
          + " (floe area / free area)",
            "region [" + fmt(settings.xmin) + ", " + fmt(settings.xmax)
          + "] x [" + fmt(settings.ymin) + ", " + fmt(settings.ymax)
          + "], seed " + std::to_string(settings.seed)
          + ", lloydIterations " + std::to_string(settings.lloydIterations),
            "outline: true floe outline (counter-clockwise); the DEM core is"
            " the outline shrunk by radius, from zBottom + radius, thickness"
            " - 2 radius"
        };
        // Written beside and renamed into place: a kill leaves the old
        // file or the new one, never half of one (kullukPack's runStudy
        // takes an iceField as a finished set-up when it resumes)
        const fileName writing(iceFieldFile + ".writing");
        if
        (
            !iceDEM::writeIceFieldDict
            (
                writing, floes, namePrefix, material, motion, comment
            )
        )
        {
            FatalErrorInFunction
                << "cannot write " << writing << exit(FatalError);
        }
        if (std::rename(writing.c_str(), iceFieldFile.c_str()) != 0)
        {
            FatalErrorInFunction
                << "cannot rename " << writing << " to " << iceFieldFile
                << exit(FatalError);
        }
        Info<< "Wrote " << iceFieldFile << endl;
    }

    // VTK
    if (writeVTK)
    {
        const fileName vtkDir = caseDir/"VTK";
        mkDir(vtkDir);
        const fileName vtkFile = vtkDir/"iceField.vtk";
        if (!iceDEM::writeIceFieldVtk(vtkFile, floes))
        {
            FatalErrorInFunction
                << "cannot write " << vtkFile << exit(FatalError);
        }
        Info<< "Wrote " << vtkFile << endl;
        if (!settings.exclusionZones.empty())
        {
            const fileName zoneFile = vtkDir/"exclusionZones.vtk";
            if
            (
                !iceDEM::writeZonesVtk
                (
                    zoneFile,
                    settings.exclusionZones,
                    settings.waterLevel,
                    circleSegments
                )
            )
            {
                FatalErrorInFunction
                    << "cannot write " << zoneFile << exit(FatalError);
            }
            Info<< "Wrote " << zoneFile << endl;
        }
    }

    // PNG top view
    {
        const dictionary& img = dict.optionalSubDict("image");
        if (dict.isDict("image"))
        {
            checkEntries(img, "system/createIceFieldDict", {"image"}, "image");
        }
        const bool writeImage = img.getOrDefault<Switch>("write", true);
        if (writeImage)
        {
            const fileName file =
                caseDir/img.getOrDefault<fileName>("file", "iceField.png");
            const label width = img.getOrDefault<label>("width", 1200);
            const label lineWidth = img.getOrDefault<label>("lineWidth", 2);
            if (width < 1 || width > 100000 || lineWidth < 1)
            {
                FatalIOErrorInFunction(img)
                    << "entries 'width' (1 to 100000) and 'lineWidth' (>= 1)"
                    << " of 'image': got " << width << " and " << lineWidth
                    << nl << exit(FatalIOError);
            }
            const iceDEM::Rgb water = readColour(img, "water", {20, 60, 110});
            const iceDEM::Rgb ice = readColour(img, "ice", {235, 240, 245});
            const iceDEM::Rgb edge =
                readColour(img, "floeEdge", {140, 150, 165});
            const iceDEM::Rgb zoneColour =
                readColour(img, "zone", {220, 40, 40});
            const iceDEM::Rgb border = readColour(img, "border", {0, 0, 0});

            iceDEM::RgbImage image
            (
                width,
                settings.xmin, settings.xmax,
                settings.ymin, settings.ymax,
                water
            );
            for (const iceDEM::Floe& f : floes)
            {
                image.fillConvexPolygon(f.outline, ice);
                image.drawPolygon(f.outline, edge, 1);
            }
            for (const iceDEM::ExclusionZone& z : settings.exclusionZones)
            {
                if (z.type == iceDEM::ExclusionZone::Type::circle)
                {
                    image.drawCircle(z.centre, z.radius, zoneColour, lineWidth);
                }
                else
                {
                    image.drawPolygon(z.points, zoneColour, lineWidth);
                }
            }
            // Region border, drawn inside the image
            for (label k = 0; k < lineWidth; ++k)
            {
                for (int i = 0; i < image.width(); ++i)
                {
                    image.set(i, k, border);
                    image.set(i, image.height() - 1 - k, border);
                }
                for (int j = 0; j < image.height(); ++j)
                {
                    image.set(k, j, border);
                    image.set(image.width() - 1 - k, j, border);
                }
            }
            if (!image.writePng(file))
            {
                FatalErrorInFunction
                    << "cannot write " << file << exit(FatalError);
            }
            Info<< "Wrote " << file << " (" << image.width() << " x "
                << image.height() << " pixels)" << endl;
        }
    }

    Info<< nl << "End" << nl << endl;

    return 0;
}


// ************************************************************************* //
