/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "domain/InflowOutflow.H"
#include "World.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace iceDEM
{

InflowOutflow::InflowOutflow(const InflowOutflowSettings& s)
:
    settings_(s)
{
    if (!(s.axis == 0 || s.axis == 1) || !(s.sign == 1 || s.sign == -1))
    {
        throw Error("the inflow/outflow direction must be +-x or +-y", "direction");
    }
    if (!(std::isfinite(s.upstream) && std::isfinite(s.downstream) && s.downstream > s.upstream))
    {
        throw Error("the inflow/outflow bounds need upstream < downstream along the drift", "domain");
    }
    if (!(s.stripWidth > 0) || s.stripWidth > s.downstream - s.upstream)
    {
        throw Error("stripWidth must be > 0 and at most the domain's length", "stripWidth");
    }
    if (!(s.interval > 0))
    {
        throw Error("the update interval must be > 0", "interval");
    }
    if (!(s.field.concentration > 0 && s.field.concentration <= 1))
    {
        throw Error("the inflow concentration must be in (0, 1]", "concentration");
    }
}


void InflowOutflow::update(World& world)
{
    if (lastUpdate_ >= 0 && world.time() - lastUpdate_ < settings_.interval*(1 - 1e-9))
    {
        return;
    }
    lastUpdate_ = world.time();

    // Outflow
    {
        const std::vector<Body>& bodies = world.bodies();
        std::vector<bool> remove(bodies.size(), false);
        int n = 0;
        for (std::size_t i = 0; i < bodies.size(); ++i)
        {
            if (bodies[i].isFree() && along(bodies[i].x) > settings_.downstream)
            {
                remove[i] = true;
                ++n;
            }
        }
        if (n > 0)
        {
            world.removeBodiesInRun(remove);
            floesOut_ += n;
        }
    }

    // Inflow: the most upstream point of the free bodies
    const std::vector<Body>& bodies = world.bodies();
    double g = settings_.downstream;
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        const Body& b = bodies[i];
        if (!b.isFree()) continue;
        const DilatedShape& S = world.shapeOf(int(i));
        const Mat3 R = b.rotation();
        for (const Vec3& v : S.core().vertices())
        {
            g = std::min(g, along(R*v + b.x) - S.radius());
        }
    }

    const int a = settings_.axis;
    const int lateral = 1 - a;
    while (g - settings_.upstream >= settings_.stripWidth)
    {
        VoronoiFieldSettings f = settings_.field;
        // The strip [g - w, g) in s, in world coordinates
        const double s0 = g - settings_.stripWidth;
        const double lo = settings_.sign > 0 ? s0 : -g;
        const double hi = settings_.sign > 0 ? g : -s0;
        double latLo = lateral == 0 ? f.xmin : f.ymin;
        double latHi = lateral == 0 ? f.xmax : f.ymax;
        if (a == 0)
        {
            f.xmin = lo; f.xmax = hi; f.ymin = latLo; f.ymax = latHi;
        }
        else
        {
            f.ymin = lo; f.ymax = hi; f.xmin = latLo; f.xmax = latHi;
        }
        f.seed = settings_.field.seed + std::uint64_t(strips_);
        VoronoiFieldReport report;
        const std::vector<Floe> floes = generateVoronoiField(f, report);
        for (const Floe& floe : floes)
        {
            const int shape = world.addShape(DilatedShape(floe.core(), floe.radius));
            world.insertBodyInRun(shape, settings_.material, Vec3::Zero(), Quat::Identity(), floe.velocity);
        }
        floesIn_ += static_cast<long>(floes.size());
        ++strips_;
        g = s0;
    }
}

} // namespace iceDEM
