/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "domain/InflowOutflow.H"
#include "World.H"
#include "domain/Domain.H"

#include <algorithm>
#include <cmath>
#include <iterator>
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
    if (!(s.field.tolerance > 0 && s.field.tolerance < 1))
    {
        throw Error("the inflow generator's tolerance must be in (0, 1)", "tolerance");
    }
    if (!fieldConcentrationAllowed(s.field.concentration, s.field.tolerance))
    {
        throw Error
        (
            "the inflow " + concentrationRangeText(s.field.concentration, s.field.tolerance),
            "concentration"
        );
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

    // Lanes across the drift
    const VoronoiFieldSettings& f = s.field;
    latLo_ = s.axis == 0 ? f.ymin : f.xmin;
    const double latHi = s.axis == 0 ? f.ymax : f.xmax;
    if (!(std::isfinite(latLo_) && std::isfinite(latHi) && latHi > latLo_))
    {
        throw Error("the inflow's lateral bounds need finite lo < hi", "lateral");
    }
    if (std::isnan(settings_.windowLateralLo))
    {
        settings_.windowLateralLo = latLo_;
        settings_.windowLateralHi = latHi;
    }
    if
    (
        !(settings_.windowLateralLo >= latLo_ && settings_.windowLateralHi <= latHi)
     || !(settings_.windowLateralHi > settings_.windowLateralLo)
    )
    {
        throw Error
        (
            "the concentration window across the drift needs lo < hi within"
            " the lateral bounds", "windowLateral"
        );
    }
    if (std::isnan(settings_.laneWidth)) settings_.laneWidth = s.stripWidth;
    if (!(settings_.laneWidth > 0) || !std::isfinite(settings_.laneWidth))
    {
        throw Error("laneWidth must be > 0", "laneWidth");
    }
    nLanes_ = std::max(1, int(std::lround((latHi - latLo_)/settings_.laneWidth)));
    laneWidth_ = (latHi - latLo_)/nLanes_;
    settings_.laneWidth = laneWidth_;
    laneBound_.assign(nLanes_, 0.0);
}


int InflowOutflow::laneOf(double lateral) const
{
    const double u = (lateral - latLo_)/laneWidth_;
    if (!(u >= 0) || u >= nLanes_) return -1;
    return std::min(nLanes_ - 1, int(u));
}


void InflowOutflow::update(World& world)
{
    if (lastUpdate_ >= 0 && world.time() - lastUpdate_ < settings_.interval*(1 - 1e-9))
    {
        return;
    }
    const bool first = lastUpdate_ < 0;
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

    // Inflow, lane by lane (InflowOutflow.H): b, the lane's upstream
    // boundary, follows the mean displacement of its last strip's floes
    // still in the world; a lane without them starts against its floes
    const int n = nLanes_;
    const int a = settings_.axis;
    const int lateral = 1 - a;
    std::vector<double> g(n, settings_.downstream);
    std::vector<double> shift(n, 0.0);
    std::vector<int> count(n, 0);
    {
        const std::vector<Body>& bodies = world.bodies();
        for (std::size_t i = 0; i < bodies.size(); ++i)
        {
            if (!bodies[i].isFree()) continue;
            const auto it = lastStrips_.find(bodies[i].id);
            if (it != lastStrips_.end())
            {
                shift[it->second.first] += along(bodies[i].x) - it->second.second;
                ++count[it->second.first];
            }
            const int k = laneOf(bodies[i].x[lateral]);
            if (k >= 0) g[k] = std::min(g[k], upstreamPoint(world, int(i)));
        }
    }

    // At the start the initial field's floes within a strip width of each
    // lane's upstream edge stand for the lane's last strip (bound: that
    // edge), so the first strips follow their bulk too, not the slowest
    if (first)
    {
        const std::vector<Body>& bodies = world.bodies();
        for (std::size_t i = 0; i < bodies.size(); ++i)
        {
            if (!bodies[i].isFree()) continue;
            const int k = laneOf(bodies[i].x[lateral]);
            if (k < 0 || lastStrips_.count(bodies[i].id)) continue;
            if (upstreamPoint(world, int(i)) < g[k] + settings_.stripWidth)
            {
                lastStrips_[bodies[i].id] = {k, along(bodies[i].x)};
            }
        }
        for (int k = 0; k < n; ++k) laneBound_[k] = g[k];
    }

    for (int k = 0; k < n; ++k)
    {
        double b = count[k] > 0 ? laneBound_[k] + shift[k]/count[k] : g[k];
        while (b - settings_.upstream >= settings_.stripWidth)
        {
            VoronoiFieldSettings f = settings_.field;
            // The lane's strip [b - w, b) in s, in world coordinates
            const double s0 = b - settings_.stripWidth;
            const double lo = settings_.sign > 0 ? s0 : -b;
            const double hi = settings_.sign > 0 ? b : -s0;
            const double latLo = latLo_ + k*laneWidth_;
            const double latHi = k == n - 1
              ? (lateral == 0 ? settings_.field.xmax : settings_.field.ymax)
              : latLo_ + (k + 1)*laneWidth_;
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

            // This lane's last strip becomes the new one
            for (auto it = lastStrips_.begin(); it != lastStrips_.end();)
            {
                it = it->second.first == k ? lastStrips_.erase(it) : std::next(it);
            }
            for (const Floe& floe : floes)
            {
                DilatedShape S(floe.core(), floe.radius);
                if (reachesABody(world, S))
                {
                    ++floesDropped_;
                    continue;
                }
                int shape;
                if (freeShapes_.empty())
                {
                    shape = world.addShape(S);
                }
                else
                {
                    shape = freeShapes_.back();
                    freeShapes_.pop_back();
                    world.replaceShape(shape, S);
                }
                const int id = int(nextId_++);
                const int i = world.insertBodyInRun
                (
                    shape, settings_.material, Vec3::Zero(), Quat::Identity(),
                    floe.velocity, Vec3::Zero(), id
                );
                lastStrips_[id] = {k, along(world.bodies()[i].x)};
                inserted_[id] = floe;
                ++floesIn_;
            }
            ++strips_;
            // The generator keeps its floes off the region's bounds: the
            // next strip continues this one's region as the pack carries
            // it, not its floes (which would close the gap at every seam
            // and raise the concentration by about gap/stripWidth)
            laneBound_[k] = s0;
            b = s0;
        }
    }
}


bool InflowOutflow::reachesABody(const World& world, const DilatedShape& S) const
{
    // Plan outlines: convex hulls of the cores' world vertices projected
    // on the water plane (Andrew's monotone chain)
    auto planHull = [](std::vector<Vec2>& p, std::vector<Vec2>& hull)
    {
        std::sort
        (
            p.begin(), p.end(),
            [](const Vec2& u, const Vec2& v)
            { return u.x() < v.x() || (u.x() == v.x() && u.y() < v.y()); }
        );
        auto cross = [](const Vec2& o, const Vec2& u, const Vec2& v)
        { return (u - o).x()*(v - o).y() - (u - o).y()*(v - o).x(); };
        hull.assign(2*p.size(), Vec2::Zero());
        std::size_t m = 0;
        for (std::size_t i = 0; i < p.size(); ++i)
        {
            while (m >= 2 && cross(hull[m - 2], hull[m - 1], p[i]) <= 0) --m;
            hull[m++] = p[i];
        }
        for (std::size_t i = p.size() - 1, t = m + 1; i-- > 0;)
        {
            while (m >= t && cross(hull[m - 2], hull[m - 1], p[i]) <= 0) --m;
            hull[m++] = p[i];
        }
        hull.resize(m > 1 ? m - 1 : m);
    };
    // Largest gap between two convex outlines along the edge normals of
    // either: a lower bound of their distance
    auto gap = [](const std::vector<Vec2>& A, const std::vector<Vec2>& B, const Vec2& shift)
    {
        double best = -std::numeric_limits<double>::max();
        for (int pass = 0; pass < 2; ++pass)
        {
            const std::vector<Vec2>& P = pass == 0 ? A : B;
            for (std::size_t e = 0; e < P.size(); ++e)
            {
                const Vec2 d = P[(e + 1) % P.size()] - P[e];
                const double len = d.norm();
                if (!(len > 0)) continue;
                const Vec2 nrm(d.y()/len, -d.x()/len);
                double aMin = std::numeric_limits<double>::max(), aMax = -aMin;
                double bMin = aMin, bMax = -aMin;
                for (const Vec2& p : A)
                {
                    aMin = std::min(aMin, nrm.dot(p)); aMax = std::max(aMax, nrm.dot(p));
                }
                for (const Vec2& q : B)
                {
                    const double t = nrm.dot(q + shift);
                    bMin = std::min(bMin, t); bMax = std::max(bMax, t);
                }
                best = std::max(best, std::max(bMin - aMax, aMin - bMax));
            }
        }
        return best;
    };
    auto outline = [&](const DilatedShape& T, const Mat3& R, const Vec3& x, std::vector<Vec2>& hull)
    {
        std::vector<Vec2> p;
        for (const Vec3& v : T.core().vertices())
        {
            const Vec3 w = R*v + x;
            p.push_back(Vec2(w.x(), w.y()));
        }
        planHull(p, hull);
    };

    // The new floe's pose: inserted at position 0, orientation identity
    const Mat3 Rs = S.principalToInput().toRotationMatrix();
    const Vec3 xs = S.centroidInput();
    std::vector<Vec2> mine, other;
    outline(S, Rs, xs, mine);

    // Across a periodic side too (the strips span the lateral extent)
    const int lateral = 1 - settings_.axis;
    const Domain* domain = world.domain();
    const double L =
        domain && domain->periodic(lateral) ? domain->length(lateral) : 0;
    const std::vector<Body>& bodies = world.bodies();
    for (std::size_t j = 0; j < bodies.size(); ++j)
    {
        const DilatedShape& T = world.shapeOf(int(j));
        const double reach = S.radius() + T.radius();
        const double sphere = S.boundingRadius() + T.boundingRadius();
        bool outlined = false;
        for (int k = -1; k <= 1; ++k)
        {
            if (k != 0 && L == 0) continue;
            Vec3 d = bodies[j].x - xs;
            d[lateral] += k*L;
            if (d.squaredNorm() >= sphere*sphere) continue;
            if (!outlined)
            {
                outline(T, bodies[j].rotation(), bodies[j].x, other);
                outlined = true;
            }
            Vec2 shift = Vec2::Zero();
            shift[lateral] = k*L;
            if (!(gap(mine, other, shift) > reach)) return true;
        }
    }
    return false;
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


InflowOutflowState InflowOutflow::state() const
{
    InflowOutflowState s;
    s.floesIn = floesIn_;
    s.floesOut = floesOut_;
    s.strips = strips_;
    s.nextId = nextId_;
    s.lastUpdate = lastUpdate_;
    s.floesDropped = floesDropped_;
    s.laneBounds = laneBound_;
    for (const auto& e : lastStrips_)
    {
        s.stripIds.push_back(e.first);
        s.stripLanes.push_back(e.second.first);
        s.stripAlong.push_back(e.second.second);
    }
    return s;
}


void InflowOutflow::restore(const InflowOutflowState& s, std::map<int, Floe> floes)
{
    if (!(s.floesIn >= 0 && s.floesOut >= 0 && s.strips >= 0 && s.floesDropped >= 0))
    {
        throw Error("negative inflow/outflow counts in the state", "inflowOutflow");
    }
    if (!s.laneBounds.empty() && int(s.laneBounds.size()) != nLanes_)
    {
        std::ostringstream msg;
        msg << "the state has " << s.laneBounds.size() << " inflow lanes, the"
            << " domain " << nLanes_ << " (laneWidth changed?)";
        throw Error(msg.str(), "laneBounds");
    }
    if
    (
        s.stripLanes.size() != s.stripIds.size()
     || s.stripAlong.size() != s.stripIds.size()
    )
    {
        throw Error("the last strips' ids, lanes and positions differ in length", "stripIds");
    }
    floesIn_ = s.floesIn;
    floesOut_ = s.floesOut;
    strips_ = s.strips;
    nextId_ = s.nextId;
    lastUpdate_ = s.lastUpdate;
    floesDropped_ = s.floesDropped;
    // A state without lanes: every lane starts against its floes
    laneBound_.assign(nLanes_, 0.0);
    lastStrips_.clear();
    if (!s.laneBounds.empty())
    {
        laneBound_ = s.laneBounds;
        for (std::size_t k = 0; k < s.stripIds.size(); ++k)
        {
            if (s.stripLanes[k] < 0 || s.stripLanes[k] >= nLanes_)
            {
                throw Error("a last strip's lane is out of range", "stripLanes");
            }
            lastStrips_[s.stripIds[k]] = {s.stripLanes[k], s.stripAlong[k]};
        }
    }
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
    const int lateral = 1 - a;
    const double latLo = settings_.windowLateralLo;
    const double latHi = settings_.windowLateralHi;
    const double s0 = settings_.windowLo;
    const double s1 = settings_.windowHi;
    // Across a periodic side a floe on the seam lies partly in the window's
    // image one period away
    const Domain* domain = world.domain();
    const double period =
        domain && domain->periodic(lateral) ? domain->length(lateral) : 0;
    const int images = period > 0 ? 1 : 0;

    const std::vector<Body>& bodies = world.bodies();
    std::vector<Vec2> outline;
    double area = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        const Body& b = bodies[i];
        if (!b.isFree()) continue;
        const DilatedShape& S = world.shapeOf(int(i));
        const double s = along(b.x);
        const double reach = S.boundingRadius() + S.radius();
        if (s + reach < s0 || s - reach >= s1) continue;

        const Mat3 R = b.rotation();
        const PolyhedronView core = S.core().view();
        const ArrayView<Vec3> vertices = core.vertices();
        double zLo = std::numeric_limits<double>::max();
        double zHi = -zLo;
        for (const Vec3& v : vertices)
        {
            // Height along the body's vertical: prisms stay upright in the
            // input frame; the core's extent along the rotated z axis
            const double z = (R*v)[2];
            zLo = std::min(zLo, z);
            zHi = std::max(zHi, z);
        }
        const double h = zHi - zLo + 2*S.radius();
        if (!(h > 0)) continue;

        // The share of the core's plan outline inside the window: the
        // upward faces of a convex polyhedron projected on the horizontal
        // plane tile its outline, each clipped to the window (a floe on
        // the window's edge counts by the part inside, not by its centre)
        double whole = 0, inside = 0;
        for (const PolyhedronView::Face face : core.faces())
        {
            if ((R*face.normal)[2] <= 0) continue;
            outline.clear();
            for (int k = 0; k < face.count; ++k)
            {
                const Vec3 p =
                    b.x + R*vertices[core.faceVertices()[face.begin + k]];
                outline.emplace_back(along(p), p[lateral]);
            }
            whole += std::abs(polygonSignedArea(outline));
            for (int m = -images; m <= images; ++m)
            {
                inside += polygonRectangleArea
                (
                    outline, s0, s1, latLo + m*period, latHi + m*period
                );
            }
        }
        if (whole > 0) area += S.facetedVolume()/h*inside/whole;
    }
    return area/((s1 - s0)*(latHi - latLo));
}

} // namespace iceDEM
