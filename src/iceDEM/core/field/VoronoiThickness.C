/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Voronoi field, step 7 (VoronoiField.H): the thickness distribution
    (constant, uniform, truncated normal), its draws and its checks.
\*---------------------------------------------------------------------------*/

#include "field/voronoiFieldDetail.H"

#include <cmath>

namespace iceDEM
{

using namespace voronoiDetail;

ThicknessSettings::Distribution thicknessDistributionFromName
(
    const std::string& name
)
{
    using D = ThicknessSettings::Distribution;
    if (name == "constant")
    {
        return D::constant;
    }
    if (name == "uniform")
    {
        return D::uniform;
    }
    if (name == "normal")
    {
        return D::normal;
    }
    throw Error
    (
        "unknown thickness distribution '" + name
      + "'; valid: 3(constant normal uniform)",
        "thickness"
    );
}


//- One thickness draw
double voronoiDetail::drawThickness(const ThicknessSettings& t, FieldRandom& rng)
{
    using D = ThicknessSettings::Distribution;
    switch (t.distribution)
    {
        case D::constant:
            return t.value;
        case D::uniform:
            return rng.uniform(t.min, t.max);
        case D::normal:
        {
            for (int k = 0; k < t.maxDraws; ++k)
            {
                const double h = t.mean + t.standardDeviation*rng.normal();
                if (h >= t.min && h <= t.max)
                {
                    return h;
                }
            }
            throw Error
            (
                "normal thickness: no draw in [min, max] = [" + str(t.min)
              + ", " + str(t.max) + "] after maxDraws = "
              + std::to_string(t.maxDraws) + " draws; widen the bounds",
                "thickness"
            );
        }
    }
    return t.value;
}


void voronoiDetail::checkThickness
(
    const ThicknessSettings& t,
    double radius,
    double tolerance
)
{
    auto finite = [](double x) { return std::isfinite(x); };

    using D = ThicknessSettings::Distribution;
    // As floeCore
    const std::string tooThin = thinFloeText(radius);
    if (t.distribution == D::constant)
    {
        if (!thickEnough(t.value, radius, tolerance))
        {
            throw Error("thickness " + str(t.value) + tooThin, "thickness");
        }
    }
    else
    {
        if (!thickEnough(t.min, radius, tolerance))
        {
            throw Error
            (
                "thickness min " + str(t.min) + tooThin, "thickness"
            );
        }
        if (!(t.max > t.min) || !finite(t.max))
        {
            throw Error
            (
                "thickness max " + str(t.max) + " must be > min "
              + str(t.min),
                "thickness"
            );
        }
        if (t.distribution == D::normal)
        {
            if (!(t.standardDeviation > 0) || !finite(t.standardDeviation))
            {
                throw Error
                (
                    "thickness standardDeviation must be > 0",
                    "thickness"
                );
            }
            if (!(t.mean >= t.min && t.mean <= t.max))
            {
                throw Error
                (
                    "thickness mean " + str(t.mean) + " must lie in [min, max]",
                    "thickness"
                );
            }
            if (t.maxDraws < 1)
            {
                throw Error("thickness maxDraws must be >= 1", "thickness");
            }
        }
    }
}


} // namespace iceDEM
