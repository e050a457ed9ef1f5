/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "NarrowPhase.H"

#include <cmath>
#include <limits>
#include <sstream>

namespace iceDEM
{

namespace
{

//- Tolerance of the normal-cone windows (the vectors are unit vectors)
constexpr double coneTolerance = 1e-9;

//- Two contacts closer than this fraction of r_A + r_B, with the same
//  normal, are one geometric contact
constexpr double coincidenceTolerance = 1e-9;

//- Inside the normal cone of vertex v, within tol: n . d_k <= tol for every
//  edge leaving v. nBody is outward from the shape.
inline bool inVertexCone
(
    const DilatedShape& S,
    int v,
    const Vec3& nBody,
    double tol
)
{
    const ConvexPolyhedron& P = S.core();
    const auto& dirs = S.vertexEdgeDirections();
    for (int k = P.vertexEdgeBegin(v); k < P.vertexEdgeEnd(v); ++k)
    {
        if (nBody.dot(dirs[k]) > tol)
        {
            return false;
        }
    }
    return true;
}

//- For a vertex touching an edge with unit direction t: inside the vertex's
//  cone, where an edge at the vertex that is nearly parallel to t
//  (|d x t| < parallelSin) may lean towards the contact by up to parallelSin.
//  A non-parallel edge leaning towards it brings its interior closer: the
//  edge-edge pair owns that contact.
inline bool inVertexConeForEdge
(
    const DilatedShape& S,
    int v,
    const Vec3& nBody,
    const Vec3& tBody,
    double parallelSin
)
{
    const ConvexPolyhedron& P = S.core();
    const auto& dirs = S.vertexEdgeDirections();
    for (int k = P.vertexEdgeBegin(v); k < P.vertexEdgeEnd(v); ++k)
    {
        const double lean = nBody.dot(dirs[k]);
        if (lean > coneTolerance)
        {
            if (lean > parallelSin || dirs[k].cross(tBody).norm() >= parallelSin)
            {
                return false;
            }
        }
    }
    return true;
}

//- Inside the normal wedge of edge e: strictly (not on a face's normal,
//  which the vertex-face pairs own) or inclusive
inline bool inEdgeCone
(
    const DilatedShape& S,
    int e,
    const Vec3& nBody,
    bool strict
)
{
    const double t = strict ? -coneTolerance : coneTolerance;
    return nBody.dot(S.edgeInward(e, 0)) < t && nBody.dot(S.edgeInward(e, 1)) < t;
}

//- Point (principal frame) inside face f, boundary included
inline bool insideFace
(
    const DilatedShape& S,
    int f,
    const Vec3& q,
    double tol
)
{
    const ConvexPolyhedron& P = S.core();
    const int n = P.faces()[f].count;
    for (int k = 0; k < n; ++k)
    {
        const double s = (q - P.vertices()[P.faceVertex(f, k)]).dot(S.faceEdgeNormal(f, k));
        if (s > tol)
        {
            return false;
        }
    }
    return true;
}


//- Collects contacts and the closest valid feature pair
class Collector
{
    FoundContact* out_;
    int maxOut_;
    double rA_, rB_;

public:
    int n = 0;
    //- Infinity, not the largest double: squaring it must not overflow
    //  (OpenFOAM traps floating-point overflow)
    double minDistance = std::numeric_limits<double>::infinity();
    Vec3 minDirection = Vec3::Zero();

    Collector(FoundContact* out, int maxOut, double rA, double rB)
    :
        out_(out), maxOut_(maxOut), rA_(rA), rB_(rB)
    {}

    //- cA: closest point on A's core; n: unit normal A -> B; dist: core
    //  distance; rI, rJ: radii in the order the contact law wants
    void add
    (
        FeaturePair type,
        std::uint32_t fa,
        std::uint32_t fb,
        const Vec3& cA,
        const Vec3& normal,
        double dist,
        double rI,
        double rJ,
        double sinAngle = 1
    )
    {
        if (dist < minDistance)
        {
            minDistance = dist;
            minDirection = normal;
        }
        const double overlap = rA_ + rB_ - dist;
        if (!(overlap > 0))
        {
            return;
        }
        // A configuration on a window boundary (e.g. aligned corners) can
        // reach the same contact through two feature pairs: count it once
        const Vec3 point = cA + normal*(rA_ - 0.5*overlap);
        const double samePoint = coincidenceTolerance*(rA_ + rB_);
        for (int k = 0; k < n; ++k)
        {
            if
            (
                (out_[k].g.point - point).squaredNorm() < samePoint*samePoint
             && out_[k].g.normal.dot(normal) > 1 - coneTolerance
            )
            {
                return;
            }
        }
        if (n >= maxOut_)
        {
            std::ostringstream msg;
            msg << "more than " << maxOut_ << " contacts between two elements";
            throw Error(msg.str());
        }
        FoundContact& c = out_[n++];
        c.g.type = type;
        c.g.normal = normal;
        c.g.point = point;
        c.g.overlap = overlap;
        c.g.radiusI = rI;
        c.g.radiusJ = rJ;
        c.g.sinAngle = sinAngle;
        c.featureA = fa;
        c.featureB = fb;
    }
};

} // anonymous namespace


int findContacts
(
    const BodyView& A,
    const BodyView& B,
    const NarrowPhaseSettings& s,
    Vec3& axis,
    FoundContact* out,
    int maxOut
)
{
    const DilatedShape& SA = *A.shape;
    const DilatedShape& SB = *B.shape;
    const ConvexPolyhedron& PA = SA.core();
    const ConvexPolyhedron& PB = SB.core();
    const int nA = static_cast<int>(PA.vertices().size());
    const int nB = static_cast<int>(PB.vertices().size());
    const double rA = SA.radius();
    const double rB = SB.radius();
    const double rs = rA + rB;
    const Vec3* wA = A.vertices;
    const Vec3* wB = B.vertices;

    // 1. Separating axes: the hint, then the line of centres
    Vec3 axes[2];
    int nAxes = 0;
    if (axis.squaredNorm() > 0.5)
    {
        axes[nAxes++] = axis;
    }
    const Vec3 d = B.x - A.x;
    if (d.squaredNorm() > 0)
    {
        axes[nAxes++] = d.normalized();
    }
    if (nAxes == 0)
    {
        axes[nAxes++] = Vec3::UnitX();
    }

    double bestGap = -std::numeric_limits<double>::max();
    Vec3 best = axes[0];
    double bestMaxA = 0, bestMinB = 0;
    for (int k = 0; k < nAxes; ++k)
    {
        const Vec3& a = axes[k];
        double maxA = -std::numeric_limits<double>::max();
        double minB = std::numeric_limits<double>::max();
        for (int i = 0; i < nA; ++i) maxA = std::max(maxA, a.dot(wA[i]));
        for (int j = 0; j < nB; ++j) minB = std::min(minB, a.dot(wB[j]));
        const double gap = minB - maxA;
        if (gap >= rs)
        {
            axis = a;
            return 0;
        }
        if (gap > bestGap)
        {
            bestGap = gap;
            best = a;
            bestMaxA = maxA;
            bestMinB = minB;
        }
    }

    // 2. Features inside the slab of the best axis (exact culling: a point
    //    farther than rs from the other core's slab cannot touch it)
    int candA[maxShapeVertices], candB[maxShapeVertices];
    bool isCandA[maxShapeVertices], isCandB[maxShapeVertices];
    int nCandA = 0, nCandB = 0;
    const double loA = bestMinB - rs;
    const double hiB = bestMaxA + rs;
    for (int i = 0; i < nA; ++i)
    {
        isCandA[i] = best.dot(wA[i]) >= loA;
        if (isCandA[i]) candA[nCandA++] = i;
    }
    for (int j = 0; j < nB; ++j)
    {
        isCandB[j] = best.dot(wB[j]) <= hiB;
        if (isCandB[j]) candB[nCandB++] = j;
    }

    Collector col(out, maxOut, rA, rB);

    // Feature pairs at or beyond this distance can neither touch nor improve
    // the closest pair found so far (the next step's axis): skipped before
    // the window tests
    auto reach = [&col, rs]() { return std::max(rs, col.minDistance); };
    auto sqr = [](double x) { return x*x; };
    const double parallelSin2 = s.parallelEdgeSin*s.parallelEdgeSin;
    const Mat3 RAt = A.R.transpose();
    const Mat3 RBt = B.R.transpose();
    const double tolA = 1e-12*SA.boundingRadius();
    const double tolB = 1e-12*SB.boundingRadius();
    const double tiny = 1e-14*(SA.boundingRadius() + SB.boundingRadius());

    auto faceHasCandidate = [](const ConvexPolyhedron& P, int f, const bool* isCand)
    {
        for (int k = 0; k < P.faces()[f].count; ++k)
        {
            if (isCand[P.faceVertex(f, k)]) return true;
        }
        return false;
    };

    // 3a. Vertex of A on a face of B (face boundary included)
    for (int ci = 0; ci < nCandA; ++ci)
    {
        const int i = candA[ci];
        const Vec3 p = RBt*(wA[i] - B.x);
        for (int f = 0; f < int(PB.faces().size()); ++f)
        {
            const auto& face = PB.faces()[f];
            const double dist = face.normal.dot(p) - face.offset;
            if (!(dist > 0) || dist >= reach()) continue;
            if (!faceHasCandidate(PB, f, isCandB)) continue;
            const Vec3 q = p - dist*face.normal;
            if (!insideFace(SB, f, q, tolB)) continue;
            const Vec3 n = -(B.R*face.normal);
            if (!inVertexCone(SA, i, RAt*n, s.parallelEdgeSin)) continue;
            col.add
            (
                FeaturePair::vertexFace, featureKey(kVertex, i), featureKey(kFace, f),
                wA[i], n, dist, rA, rB
            );
        }
    }

    // 3b. Vertex of B on a face of A (face boundary excluded)
    for (int cj = 0; cj < nCandB; ++cj)
    {
        const int j = candB[cj];
        const Vec3 p = RAt*(wB[j] - A.x);
        for (int f = 0; f < int(PA.faces().size()); ++f)
        {
            const auto& face = PA.faces()[f];
            const double dist = face.normal.dot(p) - face.offset;
            if (!(dist > 0) || dist >= reach()) continue;
            if (!faceHasCandidate(PA, f, isCandA)) continue;
            const Vec3 q = p - dist*face.normal;
            if (!insideFace(SA, f, q, tolA)) continue;
            const Vec3 n = A.R*face.normal;
            if (!inVertexCone(SB, j, -(RBt*n), s.parallelEdgeSin)) continue;
            col.add
            (
                FeaturePair::vertexFace, featureKey(kFace, f), featureKey(kVertex, j),
                A.R*q + A.x, n, dist, rB, rA
            );
        }
    }

    // Candidate edges: at least one end in the slab
    const auto& EA = PA.edges();
    const auto& EB = PB.edges();

    // 3c. Edge-edge, not parallel, closest points inside both edges
    for (int a = 0; a < int(EA.size()); ++a)
    {
        if (!isCandA[EA[a][0]] && !isCandA[EA[a][1]]) continue;
        const Vec3& p1 = wA[EA[a][0]];
        const Vec3 d1 = wA[EA[a][1]] - p1;
        const double a11 = d1.squaredNorm();
        for (int b = 0; b < int(EB.size()); ++b)
        {
            if (!isCandB[EB[b][0]] && !isCandB[EB[b][1]]) continue;
            const Vec3& p2 = wB[EB[b][0]];
            const Vec3 d2 = wB[EB[b][1]] - p2;
            const double a22 = d2.squaredNorm();
            const Vec3 r = p1 - p2;
            const double a12 = d1.dot(d2);
            const double b1 = d1.dot(r);
            const double b2 = d2.dot(r);
            // den = |d1 x d2|^2: (nearly) parallel edges give no edge-edge
            // contact, and are rejected before dividing by it
            const double den = a11*a22 - a12*a12;
            if (!(den > parallelSin2*a11*a22)) continue;
            const double sa = (a12*b2 - a22*b1)/den;
            const double tb = (a11*b2 - a12*b1)/den;
            if (!(sa > 0 && sa < 1 && tb > 0 && tb < 1)) continue;
            const Vec3 c1 = p1 + sa*d1;
            const Vec3 diff = p2 + tb*d2 - c1;
            const double dist2 = diff.squaredNorm();
            if (dist2 >= sqr(reach())) continue;
            const double sinAngle = d1.cross(d2).norm()/std::sqrt(a11*a22);
            const double dist = std::sqrt(dist2);
            if (dist < tiny) continue;
            const Vec3 n = diff/dist;
            if (!inEdgeCone(SA, a, RAt*n, false) || !inEdgeCone(SB, b, -(RBt*n), false)) continue;
            col.add
            (
                FeaturePair::edgeEdge, featureKey(kEdge, a), featureKey(kEdge, b),
                c1, n, dist, rA, rB, sinAngle
            );
        }
    }

    // 3d. Vertex of A on an edge of B
    for (int ci = 0; ci < nCandA; ++ci)
    {
        const int i = candA[ci];
        const Vec3& p = wA[i];
        for (int b = 0; b < int(EB.size()); ++b)
        {
            if (!isCandB[EB[b][0]] && !isCandB[EB[b][1]]) continue;
            const Vec3& e0 = wB[EB[b][0]];
            const Vec3 de = wB[EB[b][1]] - e0;
            const double t = (p - e0).dot(de)/de.squaredNorm();
            if (!(t > 0 && t < 1)) continue;
            const Vec3 diff = e0 + t*de - p;
            const double dist2 = diff.squaredNorm();
            if (dist2 >= sqr(reach())) continue;
            const double dist = std::sqrt(dist2);
            if (dist < tiny) continue;
            const Vec3 n = diff/dist;
            if
            (
                !inEdgeCone(SB, b, -(RBt*n), true)
             || !inVertexConeForEdge(SA, i, RAt*n, RAt*de.normalized(), s.parallelEdgeSin)
            ) continue;
            col.add
            (
                FeaturePair::vertexEdge, featureKey(kVertex, i), featureKey(kEdge, b),
                p, n, dist, rA, rB
            );
        }
    }

    // 3e. Vertex of B on an edge of A
    for (int cj = 0; cj < nCandB; ++cj)
    {
        const int j = candB[cj];
        const Vec3& p = wB[j];
        for (int a = 0; a < int(EA.size()); ++a)
        {
            if (!isCandA[EA[a][0]] && !isCandA[EA[a][1]]) continue;
            const Vec3& e0 = wA[EA[a][0]];
            const Vec3 de = wA[EA[a][1]] - e0;
            const double t = (p - e0).dot(de)/de.squaredNorm();
            if (!(t > 0 && t < 1)) continue;
            const Vec3 c = e0 + t*de;
            const Vec3 diff = p - c;
            const double dist2 = diff.squaredNorm();
            if (dist2 >= sqr(reach())) continue;
            const double dist = std::sqrt(dist2);
            if (dist < tiny) continue;
            const Vec3 n = diff/dist;
            if
            (
                !inEdgeCone(SA, a, RAt*n, true)
             || !inVertexConeForEdge(SB, j, -(RBt*n), RBt*de.normalized(), s.parallelEdgeSin)
            ) continue;
            col.add
            (
                FeaturePair::vertexEdge, featureKey(kEdge, a), featureKey(kVertex, j),
                c, n, dist, rB, rA
            );
        }
    }

    // 3f. Vertex-vertex (normal strictly inside both vertex cones)
    for (int ci = 0; ci < nCandA; ++ci)
    {
        const int i = candA[ci];
        for (int cj = 0; cj < nCandB; ++cj)
        {
            const int j = candB[cj];
            const Vec3 diff = wB[j] - wA[i];
            const double dist2 = diff.squaredNorm();
            if (dist2 >= sqr(reach())) continue;
            const double dist = std::sqrt(dist2);
            if (dist < tiny) continue;
            const Vec3 n = diff/dist;
            if (!inVertexCone(SA, i, RAt*n, coneTolerance) || !inVertexCone(SB, j, -(RBt*n), coneTolerance)) continue;
            col.add
            (
                FeaturePair::vertexVertex, featureKey(kVertex, i), featureKey(kVertex, j),
                wA[i], n, dist, rA, rB
            );
        }
    }

    // Next step's axis: the deepest contact's normal, else the direction of
    // the closest feature pair (a separating axis of convex cores)
    if (col.n > 0)
    {
        int deepest = 0;
        for (int k = 1; k < col.n; ++k)
        {
            if (out[k].g.overlap > out[deepest].g.overlap) deepest = k;
        }
        axis = out[deepest].g.normal;
    }
    else if (col.minDirection.squaredNorm() > 0)
    {
        axis = col.minDirection;
    }
    else
    {
        axis = best;
    }
    return col.n;
}


int findWallContacts
(
    const BodyView& A,
    const Vec3& point,
    const Vec3& normal,
    FoundContact* out,
    int maxOut
)
{
    const DilatedShape& S = *A.shape;
    const double r = S.radius();
    const int nV = static_cast<int>(S.core().vertices().size());
    int n = 0;
    for (int v = 0; v < nV; ++v)
    {
        const Vec3& p = A.vertices[v];
        const double dist = normal.dot(p - point);
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
        c.featureA = featureKey(kVertex, v);
        c.featureB = featureKey(kPlane, 0);
    }
    return n;
}


bool coresIntersect(const BodyView& A, const BodyView& B)
{
    const int nA = static_cast<int>(A.shape->core().vertices().size());
    const int nB = static_cast<int>(B.shape->core().vertices().size());

    auto separates = [&](const Vec3& a)
    {
        const double len = a.norm();
        if (len < 1e-12) return false;
        double maxA = -std::numeric_limits<double>::max();
        double minA = std::numeric_limits<double>::max();
        double maxB = maxA, minB = minA;
        for (int i = 0; i < nA; ++i)
        {
            const double p = a.dot(A.vertices[i]);
            maxA = std::max(maxA, p);
            minA = std::min(minA, p);
        }
        for (int j = 0; j < nB; ++j)
        {
            const double p = a.dot(B.vertices[j]);
            maxB = std::max(maxB, p);
            minB = std::min(minB, p);
        }
        return minB >= maxA || minA >= maxB;
    };

    for (const auto& f : A.shape->core().faces())
    {
        if (separates(A.R*f.normal)) return false;
    }
    for (const auto& f : B.shape->core().faces())
    {
        if (separates(B.R*f.normal)) return false;
    }
    for (const auto& ea : A.shape->core().edges())
    {
        const Vec3 da = A.vertices[ea[1]] - A.vertices[ea[0]];
        for (const auto& eb : B.shape->core().edges())
        {
            if (separates(da.cross(B.vertices[eb[1]] - B.vertices[eb[0]])))
            {
                return false;
            }
        }
    }
    return true;
}

} // namespace iceDEM
