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
    if (std::isnan(settings_.windowLo))
    {
        settings_.windowLo = s.upstream + s.stripWidth;
        settings_.windowHi = std::min(s.downstream, s.upstream + 2*s.stripWidth);
    }
    if
    (
        !(std::isfinite(settings_.windowLo) && std::isfinite(settings_.windowHi))
     || !(settings_.windowHi > settings_.windowLo)
    )
    {
        throw Error("the concentration window needs finite lo < hi along the drift", "window");
    }
}


void InflowOutflow::update(World& world)
{
    if (lastUpdate_ >= 0 && world.time() - lastUpdate_ < settings_.interval*(1 - 1e-9))
    {
        return;
    }
    lastUpdate_ = world.time();
    if (nextId_ < 0)
    {
        nextId_ = 0;
        for (const Body& b : world.bodies()) nextId_ = std::max(nextId_, long(b.id) + 1);
    }

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
                if (inserted_.erase(bodies[i].id) > 0)
                {
                    freeShapes_.push_back(bodies[i].shape);
                }
                ++n;
            }
        }
        if (n > 0)
        {
            world.removeBodiesInRun(remove);
            floesOut_ += n;
        }
    }

    // Inflow: g, the most upstream point of the free bodies; the pack's
    // upstream boundary is gap_ upstream of it (the last strip's region
    // bound as the pack carries it)
    const std::vector<Body>& bodies = world.bodies();
    double g = settings_.downstream;
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        if (bodies[i].isFree()) g = std::min(g, upstreamPoint(world, int(i)));
    }

    const int a = settings_.axis;
    const int lateral = 1 - a;
    while (g - gap_ - settings_.upstream >= settings_.stripWidth)
    {
        VoronoiFieldSettings f = settings_.field;
        // The strip [b - w, b) in s, b = g - gap_, in world coordinates
        const double b = g - gap_;
        const double s0 = b - settings_.stripWidth;
        const double lo = settings_.sign > 0 ? s0 : -b;
        const double hi = settings_.sign > 0 ? b : -s0;
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
            int shape;
            if (freeShapes_.empty())
            {
                shape = world.addShape(DilatedShape(floe.core(), floe.radius));
            }
            else
            {
                shape = freeShapes_.back();
                freeShapes_.pop_back();
                world.replaceShape(shape, DilatedShape(floe.core(), floe.radius));
            }
            const int id = int(nextId_++);
            const int i = world.insertBodyInRun
            (
                shape, settings_.material, Vec3::Zero(), Quat::Identity(), floe.velocity,
                Vec3::Zero(), id
            );
            g = std::min(g, upstreamPoint(world, i));
            inserted_[id] = floe;
        }
        floesIn_ += static_cast<long>(floes.size());
        ++strips_;
        // The generator keeps its floes off the region's bounds: the next
        // strip goes against this one's region, not against its floes
        // (which would close the gap at every seam and raise the
        // concentration by gap/stripWidth)
        gap_ = g - s0;
    }
}


double InflowOutflow::upstreamPoint(const World& world, int i) const
{
    const Body& b = world.bodies()[i];
    const DilatedShape& S = world.shapeOf(i);
    const Mat3 R = b.rotation();
    double g = std::numeric_limits<double>::max();
    for (const Vec3& v : S.core().vertices())
    {
        g = std::min(g, along(R*v + b.x) - S.radius());
    }
    return g;
}


void InflowOutflow::restore(const InflowOutflowState& s, std::map<int, Floe> floes)
{
    if (!(s.floesIn >= 0 && s.floesOut >= 0 && s.strips >= 0))
    {
        throw Error("negative inflow/outflow counts in the state", "inflowOutflow");
    }
    floesIn_ = s.floesIn;
    floesOut_ = s.floesOut;
    strips_ = s.strips;
    nextId_ = s.nextId;
    lastUpdate_ = s.lastUpdate;
    if (!(std::isfinite(s.gap) && s.gap >= 0))
    {
        throw Error("the inflow's strip gap in the state must be >= 0", "stripGap");
    }
    gap_ = s.gap;
    inserted_ = std::move(floes);
}


int InflowOutflow::addInsertedBody(World& world, int id, const Floe& floe) const
{
    const int shape = world.addShape(DilatedShape(floe.core(), floe.radius));
    return world.addBody
    (
        shape, settings_.material, Vec3::Zero(), Quat::Identity(), floe.velocity,
        Vec3::Zero(), BodyMotion::free, id
    );
}


double InflowOutflow::upstreamConcentration(const World& world) const
{
    const int a = settings_.axis;
    const VoronoiFieldSettings& f = settings_.field;
    const double latLo = a == 0 ? f.ymin : f.xmin;
    const double latHi = a == 0 ? f.ymax : f.xmax;
    const double s0 = settings_.windowLo;
    const double s1 = settings_.windowHi;
    const std::vector<Body>& bodies = world.bodies();
    double area = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        const Body& b = bodies[i];
        if (!b.isFree()) continue;
        const double s = along(b.x);
        const double l = b.x[1 - a];
        if (s < s0 || s >= s1 || l < latLo || l >= latHi) continue;
        const DilatedShape& S = world.shapeOf(int(i));
        double zLo = std::numeric_limits<double>::max();
        double zHi = -zLo;
        for (const Vec3& v : S.core().vertices())
        {
            // Height along the body's vertical: prisms stay upright in the
            // input frame; the core's extent along the rotated z axis
            const double z = (b.rotation()*v)[2];
            zLo = std::min(zLo, z);
            zHi = std::max(zHi, z);
        }
        const double h = zHi - zLo + 2*S.radius();
        if (h > 0) area += S.facetedVolume()/h;
    }
    return area/((s1 - s0)*(latHi - latLo));
}

} // namespace iceDEM
