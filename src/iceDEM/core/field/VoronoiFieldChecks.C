/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Voronoi field: the checks of the settings (each error names its entry)
    and the number of Voronoi cells, from nFloes or meanFloeArea, with the
    size checks that a mean cell holds a core for the dilation radius.
\*---------------------------------------------------------------------------*/

#include "field/voronoiFieldDetail.H"

#include <algorithm>
#include <cmath>
#include <limits>

namespace iceDEM
{

using namespace voronoiDetail;

//- Number of Voronoi cells
int voronoiDetail::cellCount(const VoronoiFieldSettings& s)
{
    if (s.nFloes > 0)
    {
        return s.nFloes;
    }
    const double A = (s.xmax - s.xmin)*(s.ymax - s.ymin);
    const double n = std::round(s.concentration*A/s.meanFloeArea);
    if (!(n >= 1))
    {
        throw Error
        (
            "region too small for one floe: concentration*area = "
          + str(s.concentration*A) + " m2 is less than half of meanFloeArea "
          + str(s.meanFloeArea) + " m2",
            "meanFloeArea"
        );
    }
    if (n > double(std::numeric_limits<int>::max()))
    {
        throw Error("meanFloeArea gives too many floes", "meanFloeArea");
    }
    return int(n);
}


void checkVoronoiFieldSettings(const VoronoiFieldSettings& s)
{
    auto finite = [](double x) { return std::isfinite(x); };

    if
    (
        !finite(s.xmin) || !finite(s.xmax) || !finite(s.ymin)
     || !finite(s.ymax) || !(s.xmax > s.xmin) || !(s.ymax > s.ymin)
    )
    {
        throw Error
        (
            "region must have max > min in x and y (finite), got ["
          + str(s.xmin) + ", " + str(s.xmax) + "] x [" + str(s.ymin) + ", "
          + str(s.ymax) + "]",
            "region"
        );
    }
    // Before the concentration, whose bound it sets
    if (!(s.tolerance > 0 && s.tolerance < 1))
    {
        throw Error("tolerance must be in (0, 1)", "tolerance");
    }
    if (!fieldConcentrationAllowed(s.concentration, s.tolerance))
    {
        throw Error
        (
            concentrationRangeText(s.concentration, s.tolerance),
            "concentration"
        );
    }
    if (!(s.radius > 0) || !finite(s.radius))
    {
        throw Error("radius must be > 0, got " + str(s.radius), "radius");
    }
    if (s.nFloes <= 0 && !(s.meanFloeArea > 0 && finite(s.meanFloeArea)))
    {
        throw Error
        (
            "give nFloes > 0 or meanFloeArea > 0 (got meanFloeArea "
          + str(s.meanFloeArea) + ")",
            "meanFloeArea"
        );
    }
    if (s.lloydIterations < 0)
    {
        throw Error("lloydIterations must be >= 0", "lloydIterations");
    }
    if (!(s.minCoreEdgeRatio >= 0) || !finite(s.minCoreEdgeRatio))
    {
        throw Error("minCoreEdgeRatio must be >= 0", "minCoreEdgeRatio");
    }
    // A thinner core is no dilated element: a floe kept with it would stop
    // the field (checkCores) or the solver reading it
    const double leastWidth = DilatedShape::minCoreWidthInRadii;
    if (!(s.minCoreWidthRatio >= leastWidth) || !finite(s.minCoreWidthRatio))
    {
        throw Error
        (
            "minCoreWidthRatio must be >= " + str(leastWidth) + ", got "
          + str(s.minCoreWidthRatio) + ": a dilated element's radius is at most"
            " half its core's thinnest width",
            "minCoreWidthRatio"
        );
    }
    if (s.maxCorrections < 0)
    {
        throw Error("maxCorrections must be >= 0", "maxCorrections");
    }
    if (!(s.concentrationTolerance > 0))
    {
        throw Error
        (
            "concentrationTolerance must be > 0", "concentrationTolerance"
        );
    }
    if (!(s.concentrationResolution > 0 && s.concentrationResolution < 1))
    {
        throw Error
        (
            "concentrationResolution must be in (0, 1)",
            "concentrationResolution"
        );
    }
    if (!(s.iceDensity > 0) || !finite(s.iceDensity))
    {
        throw Error
        (
            "iceDensity must be > 0, got " + str(s.iceDensity), "iceDensity"
        );
    }
    if (!(s.waterDensity > 0) || !finite(s.waterDensity))
    {
        throw Error
        (
            "waterDensity must be > 0, got " + str(s.waterDensity),
            "waterDensity"
        );
    }
    if (!(s.iceDensity < s.waterDensity))
    {
        throw Error
        (
            "iceDensity " + str(s.iceDensity)
          + " must be less than waterDensity " + str(s.waterDensity)
          + " for the floes to float",
            "iceDensity"
        );
    }
    if (!finite(s.waterLevel))
    {
        throw Error("waterLevel must be finite", "waterLevel");
    }
    if (!finite(s.velocity.x()) || !finite(s.velocity.y()) || !finite(s.velocity.z()))
    {
        throw Error("velocity must be finite", "velocity");
    }

    checkThickness(s.thickness, s.radius, s.tolerance);

    // Size: the tessellation rectangle and a mean cell must hold a core
    {
        const double l = s.xmax - s.xmin;
        const double w = s.ymax - s.ymin;
        const double sc = std::sqrt(s.concentration);
        const double minCell =
            2*s.radius
          + std::max(s.minCoreEdgeRatio, s.minCoreWidthRatio)*s.radius;
        if (!(std::min(l, w)*sc > minCell))
        {
            throw Error
            (
                "region too small for one floe: the tessellated rectangle "
                "(sides times sqrt(concentration)) is not wider than "
                "2r + max(minCoreEdgeRatio, minCoreWidthRatio) r = "
              + str(minCell) + " m",
                "region"
            );
        }
        const int n = cellCount(s);
        const double meanCell = s.concentration*l*w/n;
        if (!(std::sqrt(meanCell) > minCell))
        {
            throw Error
            (
                "floes too small for the dilation radius: mean floe area "
              + str(meanCell) + " m2 is not larger than (2r + max("
                "minCoreEdgeRatio, minCoreWidthRatio) r)^2 = "
              + str(minCell*minCell) + " m2",
                s.nFloes > 0 ? "nFloes" : "meanFloeArea"
            );
        }
    }

    checkExclusionZones(s);
}


double maxFieldConcentration(double tolerance)
{
    return 1/((1 + tolerance)*(1 + tolerance));
}


bool fieldConcentrationAllowed(double concentration, double tolerance)
{
    return concentration > 0 && concentration <= maxFieldConcentration(tolerance);
}


std::string concentrationRangeText(double concentration, double tolerance)
{
    return
        "concentration must be in (0, 1), got " + str(concentration)
      + ": at 1 the floes tile the region and touch their neighbours, which"
        " the DEM does not allow at the start (the largest is 1/(1 +"
        " tolerance)^2, 1 - " + str(1 - maxFieldConcentration(tolerance))
      + " at the tolerance " + str(tolerance) + ")";
}


} // namespace iceDEM
