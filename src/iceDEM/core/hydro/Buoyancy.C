/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "Buoyancy.H"
#include "WaterFrame.H"
#include "WaterClip.H"
#include "FloeDamping.H"

#include <cmath>
#include <string>

namespace iceDEM
{

void checkWaterSettings(const WaterSettings& s)
{
    if (!(s.density > 0) || !std::isfinite(s.density))
    {
        throw Error
        (
            "water: density " + std::to_string(s.density)
          + " must be positive [kg/m3]",
            "density"
        );
    }
    if (!std::isfinite(s.level))
    {
        throw Error("water: level must be a finite number [m]", "level");
    }
}


Buoyancy::Buoyancy(const WaterSettings& water)
:
    water_(water)
{
    checkWaterSettings(water_);
}


const char* Buoyancy::name() const
{
    return "buoyancy";
}


double Buoyancy::shortestPeriod(const World& world, int begin, int end) const
{
    return shortestHydrostaticPeriod(world, water_, begin, end);
}


void Buoyancy::addForces
(
    const World& world,
    int begin,
    int end,
    Vec3* force,
    Vec3* torque
) const
{
    const double weight = water_.density*world.settings().gravity.norm();
    if (weight == 0)
    {
        return;
    }

    const std::vector<Body>& bodies = world.bodies();
    for (int i = begin; i < end; ++i)
    {
        const Body& b = bodies[i];
        // A structure's hydrostatics belong to its own motion (sixDoF)
        if (!b.isFree()) continue;
        // The floe's frame, shared with drag and floe damping
        const SubmergedVolume& sub = frameVolume
        (
            outerForModels(world.shapeOf(i)),
            waterFrame(world, i, water_.level)
        );
        if (sub.volume > 0)
        {
            const Vec3 F(0, 0, weight*sub.volume);
            force[i] += F;
            torque[i] += (sub.centroid - b.x).cross(F);
        }
    }
}

} // namespace iceDEM
