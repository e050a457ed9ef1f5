/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "NarrowPhase.H"

#include <algorithm>
#include <limits>

namespace iceDEM
{


int findWallContacts
(
    const BodyView& A,
    const Vec3& point,
    const Vec3& normal,
    FoundContact* out,
    int maxOut,
    double* separation
)
{
    const DilatedShape& S = *A.shape;
    const double r = S.radius();
    const int nV = static_cast<int>(S.core().vertices().size());
    int n = 0;
    double minDist = std::numeric_limits<double>::max();
    for (int v = 0; v < nV; ++v)
    {
        const Vec3& p = A.vertices[v];
        const double dist = normal.dot(p - point);
        minDist = std::min(minDist, dist);
        if (dist >= r) continue;
        if (n >= maxOut)
        {
            throw Error("too many contacts between an element and a wall");
        }
        FoundContact& c = out[n++];
        c.g.type = FeaturePair::vertexWall;
        c.g.normal = -normal;
        c.g.overlap = r - dist;
        c.g.point = p - normal*(r - 0.5*c.g.overlap);
        c.g.radiusI = r;
        c.g.radiusJ = 0;
        c.g.sinAngle = 1;
        c.g.weight = 1;
        c.g.weightGradient.setZero();
        c.g.weightGradientX.setZero();
        c.featureA = featureKey(kVertex, v);
        c.featureB = featureKey(kPlane, 0);
    }
    if (separation && n == 0)
    {
        *separation = minDist - r - separationTolerance*S.boundingRadius();
    }
    return n;
}

} // namespace iceDEM
