/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "domain/Domain.H"
#include "World.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace iceDEM
{

namespace
{
    const char* axisName(int d) { return d == 0 ? "x" : "y"; }

    //- f(w, r) for every core vertex of the bodies ids at their present
    //  poses (w in the world frame) with the body's dilation radius r
    template<class F>
    void forEachCoreVertex(const World& world, const std::vector<int>& ids, F f)
    {
        for (const int i : ids)
        {
            const Body& b = world.bodies()[i];
            const DilatedShape& S = world.shapeOf(i);
            const Mat3 R = b.rotation();
            for (const Vec3& v : S.core().vertices())
            {
                f(Vec3(R*v + b.x), S.radius());
            }
        }
    }
}


Domain::Domain(const DomainSettings& s)
:
    settings_(s)
{
    for (int d = 0; d < 2; ++d)
    {
        if (!s.periodic[d]) continue;
        if (!(std::isfinite(s.lo[d]) && std::isfinite(s.hi[d]) && s.hi[d] > s.lo[d]))
        {
            std::ostringstream msg;
            msg << "periodic bounds in " << axisName(d) << " (" << s.lo[d] << " "
                << s.hi[d] << ") must be finite with min < max";
            throw Error(msg.str(), "domain");
        }
        length_[d] = s.hi[d] - s.lo[d];
    }
}


int Domain::compose(int a, int b)
{
    const int sx = imageX(a) + imageX(b);
    const int sy = imageY(a) + imageY(b);
    if (sx < -1 || sx > 1 || sy < -1 || sy > 1) return -1;
    return imageCode(sx, sy);
}


int Domain::wrap(Vec3& x) const
{
    int s[2] = {0, 0};
    for (int d = 0; d < 2; ++d)
    {
        if (!settings_.periodic[d]) continue;
        // One period at a time: a body moves far less than a period per step
        if (x[d] < settings_.lo[d])
        {
            x[d] += length_[d];
            s[d] = 1;
        }
        else if (x[d] >= settings_.hi[d])
        {
            x[d] -= length_[d];
            s[d] = -1;
        }
    }
    return imageCode(s[0], s[1]);
}


void Domain::ghosts
(
    const std::vector<Body>& bodies,
    const std::vector<int>& which,
    double reach,
    std::vector<Ghost>& out
) const
{
    const bool px = settings_.periodic[0];
    const bool py = settings_.periodic[1];
    for (int i : which)
    {
        const Vec3& x = bodies[i].x;
        for (int code = 0; code < 9; ++code)
        {
            if (code == noImage) continue;
            const int sx = imageX(code);
            const int sy = imageY(code);
            if ((sx != 0 && !px) || (sy != 0 && !py)) continue;
            const Vec3 y = x + shift(code);
            bool near = true;
            for (int d = 0; d < 2 && near; ++d)
            {
                if (!settings_.periodic[d]) continue;
                near = y[d] > settings_.lo[d] - reach && y[d] < settings_.hi[d] + reach;
            }
            if (near) out.push_back(Ghost{i, code, y});
        }
    }
}


void Domain::check
(
    const World& world,
    double skin,
    std::vector<std::string>& warnings
)
{
    if (!active()) return;
    const std::vector<Body>& bodies = world.bodies();

    // Reach of a pair of the largest free bodies; the structure's bodies
    double rMax = 0;
    structure_.clear();
    structureMoves_ = false;
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        if (bodies[i].isFree())
        {
            rMax = std::max(rMax, world.shapeOf(int(i)).boundingRadius());
        }
        else
        {
            structure_.push_back(int(i));
            structureMoves_ =
                structureMoves_ || bodies[i].motion == BodyMotion::prescribed;
        }
    }
    reach_ = 2*rMax + skin;

    for (int d = 0; d < 2; ++d)
    {
        if (!settings_.periodic[d]) continue;
        const double L = length_[d];
        if (L < 2*reach_)
        {
            std::ostringstream msg;
            msg << "the periodic length in " << axisName(d) << " (" << L
                << " m) is smaller than twice the reach of a pair of the"
                << " largest floes, 2 (2 R + skin) = " << 2*reach_ << " m (R = "
                << rMax << " m: largest bounding radius; skin " << skin
                << " m): a floe would meet its own image. Enlarge the domain";
            throw Error(msg.str(), "domain");
        }
    }

    checkStructure(world);

    // A moving structure's extent along x or y reaches at most its
    // horizontal diameter as it turns about the vertical (the largest
    // horizontal distance of two of its dilated vertices)
    if (structureMoves_)
    {
        // The structure's core vertices in plan and their dilation radii
        std::vector<Vec3> plan;
        forEachCoreVertex
        (
            world, structure_,
            [&](const Vec3& w, double r) { plan.emplace_back(w.x(), w.y(), r); }
        );
        double diameter = 0;
        for (std::size_t a = 0; a < plan.size(); ++a)
        {
            for (std::size_t b = a; b < plan.size(); ++b)
            {
                diameter = std::max
                (
                    diameter,
                    std::hypot(plan[a].x() - plan[b].x(), plan[a].y() - plan[b].y())
                  + plan[a].z() + plan[b].z()
                );
            }
        }
        for (int d = 0; d < 2; ++d)
        {
            if (!settings_.periodic[d] || length_[d] >= diameter + 2*reach_) continue;
            std::ostringstream msg;
            msg << "the structure moves, and its horizontal diameter ("
                << diameter << " m: its largest extent along "
                << axisName(d) << " as it turns) plus twice the reach of a"
                << " pair of floes (" << 2*reach_ << " m) exceeds the"
                << " periodic length in " << axisName(d) << " ("
                << length_[d] << " m): the run stops (entry 'domain') at"
                << " the step where its extent no longer fits. Enlarge the"
                << " domain to be safe";
            warnings.push_back(msg.str());
        }
    }

    for (const Wall& w : world.walls())
    {
        for (int d = 0; d < 2; ++d)
        {
            if (settings_.periodic[d] && std::abs(w.normal[d]) > 1e-12)
            {
                std::ostringstream msg;
                msg << "wall " << w.name << " is not parallel to the periodic"
                    << " direction " << axisName(d) << " (normal "
                    << w.normal.transpose() << "): walls may only bound"
                    << " the non-periodic directions";
                throw Error(msg.str(), "domain");
            }
        }
    }
}


void Domain::checkStructure(const World& world) const
{
    if (structure_.empty()) return;

    // Extent of the bodies that do not move freely, at their present pose
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max());
    Vec3 hi = -lo;
    forEachCoreVertex
    (
        world, structure_,
        [&](const Vec3& w, double r)
        {
            lo = lo.cwiseMin(w - Vec3::Constant(r));
            hi = hi.cwiseMax(w + Vec3::Constant(r));
        }
    );

    for (int d = 0; d < 2; ++d)
    {
        if (!settings_.periodic[d]) continue;
        if (lo[d] < settings_.lo[d] || hi[d] > settings_.hi[d])
        {
            std::ostringstream msg;
            msg << "the structure (the bodies that are not free) spans "
                << axisName(d) << " = " << lo[d] << " .. " << hi[d]
                << " m at its present pose and crosses a periodic side of"
                << " the domain (" << settings_.lo[d] << " "
                << settings_.hi[d] << "): it must lie inside the periodic"
                << " bounds";
            throw Error(msg.str(), "domain");
        }
        if (length_[d] < hi[d] - lo[d] + 2*reach_)
        {
            std::ostringstream msg;
            msg << "the periodic length in " << axisName(d) << " ("
                << length_[d] << " m) is smaller than the structure's extent ("
                << hi[d] - lo[d] << " m at its present pose) plus twice the"
                << " reach of a pair of floes (" << 2*reach_ << " m): a floe"
                << " could touch the structure on both sides. Enlarge the"
                << " domain";
            throw Error(msg.str(), "domain");
        }
    }
}

} // namespace iceDEM
