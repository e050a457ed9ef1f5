/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "IceClearance.H"
#include "types.H"

#include <cmath>
#include <string>

namespace iceDEM
{
namespace statistics
{

IceClearance::IceClearance(const Settings& settings)
:
    set_(settings)
{
    auto finitePositive = [](double v) { return std::isfinite(v) && v > 0; };
    if (!finitePositive(set_.underRadius))
    {
        throw Error
        (
            "the radius of the waterline circle must be a finite number > 0 [m],"
            " found " + std::to_string(set_.underRadius), "underRadius"
        );
    }
    if (!std::isfinite(set_.nearRadius) || !(set_.nearRadius > set_.underRadius))
    {
        throw Error
        (
            "the gate's half-width must be finite and larger than underRadius ("
          + std::to_string(set_.underRadius) + " m), found "
          + std::to_string(set_.nearRadius), "nearRadius"
        );
    }
    if (!finitePositive(set_.maxStep))
    {
        throw Error
        (
            "the largest motion between samples must be a finite number > 0 [m],"
            " found " + std::to_string(set_.maxStep), "maxStep"
        );
    }
    const double n = std::hypot(set_.dirX, set_.dirY);
    if (!std::isfinite(n) || !(n > 0))
    {
        throw Error
        (
            "the drift direction needs a finite, nonzero horizontal part",
            "direction"
        );
    }
    set_.dirX /= n;
    set_.dirY /= n;
}


void IceClearance::sample
(
    double ax,
    double ay,
    const std::vector<Floe>& floes,
    bool count
)
{
    ++stamp_;
    now_ = Snapshot();
    const double dx = set_.dirX, dy = set_.dirY;
    const double under = set_.underRadius, nearR = set_.nearRadius;

    for (const Floe& f : floes)
    {
        const double rx = f.x - ax, ry = f.y - ay;
        const double s = rx*dx + ry*dy;
        const double l = -rx*dy + ry*dx;
        // hypot: no overflow for the far floes of a huge domain
        const double r = std::hypot(rx, ry);
        const bool isNear = r < nearR;
        const bool submerged = isNear && f.top < 0;
        if (isNear) ++now_.near;
        if (r < under) ++now_.under;
        if (submerged) ++now_.submergedNear;

        auto it = tracks_.find(f.id);
        if (it == tracks_.end())
        {
            tracks_.emplace(f.id, Track{s, l, submerged, stamp_});
            continue;
        }
        Track& T = it->second;
        const bool forward = T.s < 0 && s >= 0;
        const bool backward = T.s >= 0 && s < 0;
        const bool moved =
            std::abs(s - T.s) < set_.maxStep && std::abs(l - T.l) < set_.maxStep;
        bool crossed = false;
        if ((forward || backward) && moved)
        {
            crossed = true;
            // Lateral position where the centre crossed the line s = 0
            const double lc = T.l + (l - T.l)*(-T.s/(s - T.s));
            if (count && std::abs(lc) < nearR)
            {
                const long sign = forward ? 1 : -1;
                if (std::abs(lc) < under)
                {
                    counts_.passedUnder += sign;
                    counts_.volumeUnder += sign*f.volume;
                }
                else
                {
                    counts_.passedAround += sign;
                    counts_.volumeAround += sign*f.volume;
                }
                if (T.submerged || submerged) counts_.passedSubmerged += sign;
            }
        }
        T.submerged = crossed ? false : (isNear && (T.submerged || submerged));
        T.s = s;
        T.l = l;
        T.stamp = stamp_;
    }

    // Floes gone (outflow): forget them
    if (tracks_.size() > floes.size())
    {
        for (auto it = tracks_.begin(); it != tracks_.end();)
        {
            if (it->second.stamp != stamp_) it = tracks_.erase(it);
            else ++it;
        }
    }
}


} // End namespace statistics
} // End namespace iceDEM
