/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "NarrowPhase.H"
#include "prefetch.H"

#include <algorithm>
#include <cmath>
#include <cstdint>
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

//- Sine of the angle below which nearly parallel edges give no contact at
//  all: their closest points are computed to within about 4 eps/sin^2 of
//  the edge length (the cancellation in sa, tb), which must stay below the
//  feature-pair lists' round-off allowance listTolerance (R_A + R_B) >=
//  listTolerance |edge|/2 (here: a fifth of it at most). Parallel edges
//  have the same distance along their common part, which the contacts of
//  its ends carry.
constexpr double parallelRoundOffSin = 1e-4;

//- Edge pairs at or below this sine stay in the feature-pair lists whatever
//  their closest points (PairSearch::linesCrossOutside): the bound on how
//  far the list's motion turns their common normal, 4 phi/sin, grows
//  without limit as the edges become parallel and would prune nothing
constexpr double listPruneMinSin = 0.01;

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
    for (int k = P.vertexEdgeBegin(v); k < P.vertexEdgeEnd(v); ++k)
    {
        // n . (+-t) = +-(n . t) bit for bit
        const double lean =
            S.vertexEdgeSign(v, k)*nBody.dot(S.edgeDirection(P.vertexEdges()[k]));
        if (lean > tol)
        {
            return false;
        }
    }
    return true;
}

//- Fade of a patch-corner contact across the tolerance band of its window,
//  x = (how far the window is left)/parallelEdgeSin: 1 for x <= 0, 0 for
//  x >= 1, C1 in between (so that the weight's couple is continuous too)
inline double bandFade(double x)
{
    if (!(x > 0)) return 1;
    if (!(x < 1)) return 0;
    return (1 - x)*(1 - x)*(1 + 2*x);
}

//- d bandFade/dx
inline double bandFadeSlope(double x)
{
    if (!(x > 0) || !(x < 1)) return 0;
    return -6*x*(1 - x);
}

//- Weight of vertex v on a face, normal nBody (away from S, S's frame): the
//  product over the edges at v of bandFade(lean/sin0), lean = n . d_k the
//  edge's lean towards the face; 0 (no contact) if an edge leans by sin0 or
//  more. grad: dw/dphi_S, its derivative with respect to a rotation of S
//  (n is fixed in the other body), S's frame: d(lean_k)/dphi_S = d_k x n
inline double vertexBandWeight
(
    const DilatedShape& S,
    int v,
    const Vec3& nBody,
    double sin0,
    Vec3& grad
)
{
    const ConvexPolyhedron& P = S.core();
    double w = 1;
    Vec3 g = Vec3::Zero();
    for (int k = P.vertexEdgeBegin(v); k < P.vertexEdgeEnd(v); ++k)
    {
        const Vec3 d = S.vertexEdgeSign(v, k)*S.edgeDirection(P.vertexEdges()[k]);
        const double lean = nBody.dot(d);
        if (!(lean > coneTolerance)) continue;
        const double x = lean/sin0;
        const double h = bandFade(x);
        if (!(h > 0)) return 0;
        w *= h;
        g += (bandFadeSlope(x)/(sin0*h))*d.cross(nBody);
    }
    grad = w*g;
    return w;
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
    for (int k = P.vertexEdgeBegin(v); k < P.vertexEdgeEnd(v); ++k)
    {
        const Vec3& d = S.edgeDirection(P.vertexEdges()[k]);
        const double lean = S.vertexEdgeSign(v, k)*nBody.dot(d);
        if (lean > coneTolerance)
        {
            // |(+-d) x t| = |d x t|
            if (lean > parallelSin || d.cross(tBody).norm() >= parallelSin)
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


//- Start the cache misses of the core data of S that a list walk reads, all
//  at once: the core's geometry block (vertices, then face planes), the
//  edge lengths (edge directions) and the shared topology (face loops,
//  edges, adjacency; shared by all floes of the same shape of prism, so
//  usually cached already). The walk reads them one after the other through
//  indices (a face, then its loop, then its vertices and edges), so that
//  otherwise every miss waits for the one before it
inline void prefetchShape(const DilatedShape& S)
{
    const ConvexPolyhedron& P = S.core();
    const PolyhedronTopology& T = P.topology();
    if (T.nFaces() == 0 || T.nEdges() == 0) return;
    prefetchRange(P.vertices().data(), P.geometryBytes());
    prefetchVector(S.edgeLengths());
    prefetchVector(T.faces());
    prefetchVector(T.faceVertices());
    prefetchVector(T.faceEdges());
    prefetchVector(T.edges());
    prefetchVector(T.edgeFaces());
    prefetchVector(T.vertexEdgeStart());
    prefetchVector(T.vertexEdges());
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
        double sinAngle = 1,
        double weight = 1,
        const Vec3& weightGradient = Vec3::Zero()
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
        c.g.weight = weight;
        c.g.weightGradient = weightGradient;
        c.featureA = fa;
        c.featureB = fb;
    }
};


//- The six kinds of feature pairs, in the order of the full search. Index a
//  is always a feature of A, b one of B.
enum PairKind : std::uint32_t
{
    vertexFaceAB = 0,   //!< 3a. vertex a of A, face b of B
    faceVertexAB,       //!< 3b. face a of A, vertex b of B
    edgeEdgeAB,         //!< 3c. edge a of A, edge b of B
    vertexEdgeAB,       //!< 3d. vertex a of A, edge b of B
    edgeVertexAB,       //!< 3e. edge a of A, vertex b of B
    vertexVertexAB      //!< 3f. vertex a of A, vertex b of B
};

// Entry of a FeaturePairList: kind (3 bits) | a (15 bits) | b (14 bits).
// A convex polyhedron has at most 3V - 6 edges and 2V - 4 faces.
static_assert(3*maxShapeVertices < (1 << 14), "feature index does not fit a list entry");

inline std::uint32_t listEntry(PairKind k, int a, int b)
{
    return (std::uint32_t(k) << 29) | (std::uint32_t(a) << 14) | std::uint32_t(b);
}

//- Round-off allowance of the list's motion test, times R_A + R_B (covers
//  the windows' tolerances, 1e-12 R, and the rounding of the distances)
constexpr double listTolerance = 1e-6;


//- Squared distance from p to the segment e0 + t de, t in [0, 1]
inline double pointSegmentDistance2(const Vec3& p, const Vec3& e0, const Vec3& de)
{
    const double t = std::min(1.0, std::max(0.0, (p - e0).dot(de)/de.squaredNorm()));
    return (e0 + t*de - p).squaredNorm();
}

//- Squared distance between the segments p1 + s d1 and p2 + t d2: the
//  minimum over the parameter square is at the stationary point if that is
//  inside, else on its boundary (an end of one segment against the other).
//  Every candidate is the distance of two points of the segments; for nearly
//  parallel segments the stationary point may be lost to round-off, which
//  misses the minimum by at most about |d| sqrt(eps).
inline double segmentDistance2
(
    const Vec3& p1,
    const Vec3& d1,
    const Vec3& p2,
    const Vec3& d2
)
{
    double d2min = std::min
    (
        std::min(pointSegmentDistance2(p1, p2, d2), pointSegmentDistance2(p1 + d1, p2, d2)),
        std::min(pointSegmentDistance2(p2, p1, d1), pointSegmentDistance2(p2 + d2, p1, d1))
    );
    const Vec3 r = p1 - p2;
    const double a11 = d1.squaredNorm();
    const double a22 = d2.squaredNorm();
    const double a12 = d1.dot(d2);
    const double den = a11*a22 - a12*a12;
    if (den > 0)
    {
        const double b1 = d1.dot(r);
        const double b2 = d2.dot(r);
        const double sa = (a12*b2 - a22*b1)/den;
        const double tb = (a11*b2 - a12*b1)/den;
        if (sa > 0 && sa < 1 && tb > 0 && tb < 1)
        {
            d2min = std::min(d2min, (p2 + tb*d2 - p1 - sa*d1).squaredNorm());
        }
    }
    return d2min;
}

//- Lower bound of the distance from p (principal frame of S) to face f: the
//  largest of the distances to its plane and to the outer sides of its
//  edges' lines in the plane (the face lies in all these half-spaces)
inline double pointFaceDistanceBound(const DilatedShape& S, int f, const Vec3& p)
{
    const ConvexPolyhedron& P = S.core();
    const auto& face = P.faces()[f];
    double d = std::abs(face.normal.dot(p) - face.offset);
    for (int k = 0; k < face.count; ++k)
    {
        d = std::max(d, (p - P.vertices()[P.faceVertex(f, k)]).dot(S.faceEdgeNormal(f, k)));
    }
    return d;
}


//- One search between A and B: each feature pair is evaluated by one
//  function (the windows, then the Collector), whether the full search
//  enumerates it or a feature-pair list names it
class PairSearch
{
    const BodyView& A_;
    const BodyView& B_;
    const DilatedShape& SA_;
    const DilatedShape& SB_;
    const ConvexPolyhedron& PA_;
    const ConvexPolyhedron& PB_;
    const Vec3* wA_;
    const Vec3* wB_;
    const double rA_, rB_, rs_;
    const double parallelSin_, parallelSin2_;
    const Mat3 RAt_, RBt_;
    const double tolA_, tolB_, tiny_;

    //- Feature pairs at or beyond this distance can neither touch nor
    //  improve the closest pair found so far (the next step's axis):
    //  skipped before the window tests
    double reach() const { return std::max(rs_, col.minDistance); }

public:

    Collector col;

    PairSearch
    (
        const BodyView& A,
        const BodyView& B,
        const NarrowPhaseSettings& s,
        FoundContact* out,
        int maxOut
    )
    :
        A_(A), B_(B),
        SA_(*A.shape), SB_(*B.shape),
        PA_(SA_.core()), PB_(SB_.core()),
        wA_(A.vertices), wB_(B.vertices),
        rA_(SA_.radius()), rB_(SB_.radius()), rs_(rA_ + rB_),
        parallelSin_(s.parallelEdgeSin),
        parallelSin2_(s.parallelEdgeSin*s.parallelEdgeSin),
        RAt_(A.R.transpose()), RBt_(B.R.transpose()),
        tolA_(1e-12*SA_.boundingRadius()),
        tolB_(1e-12*SB_.boundingRadius()),
        tiny_(1e-14*(SA_.boundingRadius() + SB_.boundingRadius())),
        col(out, maxOut, rA_, rB_)
    {}

    //- Vertex i of A in B's principal frame, and vertex j of B in A's
    Vec3 vertexAInB(int i) const { return RBt_*(wA_[i] - B_.x); }
    Vec3 vertexBInA(int j) const { return RAt_*(wB_[j] - A_.x); }

    //- 3a. Vertex i of A on face f of B (face boundary included);
    //  p = vertexAInB(i)
    void vertexFace(int i, int f, const Vec3& p)
    {
        const auto& face = PB_.faces()[f];
        const double dist = face.normal.dot(p) - face.offset;
        if (!(dist > 0) || dist >= reach()) return;
        const Vec3 q = p - dist*face.normal;
        if (!insideFace(SB_, f, q, tolB_)) return;
        const Vec3 n = -(B_.R*face.normal);
        Vec3 grad;
        const double w = vertexBandWeight(SA_, i, RAt_*n, parallelSin_, grad);
        if (!(w > 0)) return;
        // The vertex on A = i: dw/dphi_j = -dw/dphi_A
        col.add
        (
            FeaturePair::vertexFace, featureKey(kVertex, i), featureKey(kFace, f),
            wA_[i], n, dist, rA_, rB_, 1, w, -(A_.R*grad)
        );
    }

    //- 3b. Vertex j of B on face f of A; p = vertexBInA(j)
    void faceVertex(int f, int j, const Vec3& p)
    {
        const auto& face = PA_.faces()[f];
        const double dist = face.normal.dot(p) - face.offset;
        if (!(dist > 0) || dist >= reach()) return;
        const Vec3 q = p - dist*face.normal;
        if (!insideFace(SA_, f, q, tolA_)) return;
        const Vec3 n = A_.R*face.normal;
        Vec3 grad;
        const double w = vertexBandWeight(SB_, j, -(RBt_*n), parallelSin_, grad);
        if (!(w > 0)) return;
        col.add
        (
            FeaturePair::vertexFace, featureKey(kFace, f), featureKey(kVertex, j),
            A_.R*q + A_.x, n, dist, rB_, rA_, 1, w, B_.R*grad
        );
    }

    //- Closest points of edge a of A and edge b of B, world frame
    struct EdgeCrossing
    {
        Vec3 c1;            //!< on edge a
        Vec3 diff;          //!< from c1 to the closest point on edge b
        Vec3 d1, d2;        //!< edge vectors
        double a11, a22;    //!< their squared lengths
        bool parallel;      //!< sin of their angle <= parallelEdgeSin
    };

    //- The closest points of edges a and b when they lie strictly inside
    //  both edges; false as well for edges within parallelRoundOffSin of
    //  parallel (rejected before dividing by den = |d1 x d2|^2)
    bool edgeCrossing(int a, int b, EdgeCrossing& x) const
    {
        const auto& EA = PA_.edges();
        const auto& EB = PB_.edges();
        const Vec3& p1 = wA_[EA[a][0]];
        x.d1 = wA_[EA[a][1]] - p1;
        x.a11 = x.d1.squaredNorm();
        const Vec3& p2 = wB_[EB[b][0]];
        x.d2 = wB_[EB[b][1]] - p2;
        x.a22 = x.d2.squaredNorm();
        const Vec3 r = p1 - p2;
        const double a12 = x.d1.dot(x.d2);
        const double b1 = x.d1.dot(r);
        const double b2 = x.d2.dot(r);
        const double den = x.a11*x.a22 - a12*a12;
        x.parallel = !(den > parallelSin2_*x.a11*x.a22);
        if (x.parallel && !(den > parallelRoundOffSin*parallelRoundOffSin*x.a11*x.a22))
        {
            return false;
        }
        // sa = na/den and tb = nb/den in (0, 1), tested before dividing
        // (den > 0 here): for positive finite n and den, n < den if and
        // only if the rounded n/den < 1
        const double na = a12*b2 - x.a22*b1;
        if (!(na > 0 && na < den)) return false;
        const double nb = x.a11*b2 - a12*b1;
        if (!(nb > 0 && nb < den)) return false;
        const double sa = na/den;
        const double tb = nb/den;
        x.c1 = p1 + sa*x.d1;
        x.diff = p2 + tb*x.d2 - x.c1;
        return true;
    }

    //- Edge a of A and edge b of B, nearly parallel (parallelRoundOffSin <
    //  sin <= parallelEdgeSin), closest points strictly inside both edges and
    //  the normal strictly inside both wedges: the single closest point of
    //  the cores, an edge-edge contact (as edgeEdge finds it)
    bool parallelEdgesTouch(int a, int b) const
    {
        EdgeCrossing x;
        if (!edgeCrossing(a, b, x) || !x.parallel) return false;
        const double dist = std::sqrt(x.diff.squaredNorm());
        if (dist < tiny_) return false;
        const Vec3 n = x.diff/dist;
        return inEdgeCone(SA_, a, RAt_*n, true) && inEdgeCone(SB_, b, -(RBt_*n), true);
    }

    //- True if an edge e at vertex v of S leans towards the contact (nBody:
    //  the normal away from S, in S's frame; inVertexConeForEdge allows it
    //  when e is nearly parallel to the touched edge) and touches(e): e and
    //  the touched edge give the nearly parallel edge-edge contact, which
    //  then owns this one (same point as it leaves the edge's end)
    template<class EdgePairTouches>
    bool leaningEdgeOwns
    (
        const DilatedShape& S,
        int v,
        const Vec3& nBody,
        EdgePairTouches touches
    ) const
    {
        const ConvexPolyhedron& P = S.core();
        for (int k = P.vertexEdgeBegin(v); k < P.vertexEdgeEnd(v); ++k)
        {
            const int e = P.vertexEdges()[k];
            if (S.vertexEdgeSign(v, k)*nBody.dot(S.edgeDirection(e)) > coneTolerance && touches(e))
            {
                return true;
            }
        }
        return false;
    }

    //- 3c. Edge a of A and edge b of B, closest points inside both edges
    void edgeEdge(int a, int b)
    {
        // Nearly parallel edges (sin <= parallelEdgeSin) give an edge-edge
        // contact only where no other pair can: closest points strictly
        // inside both edges and the normal strictly inside both wedges (not
        // on a face's normal), i.e. the single closest point of the two
        // cores
        EdgeCrossing x;
        if (!edgeCrossing(a, b, x)) return;
        const double dist2 = x.diff.squaredNorm();
        const double rch = reach();
        if (dist2 >= rch*rch) return;
        const double dist = std::sqrt(dist2);
        if (dist < tiny_) return;
        const Vec3 n = x.diff/dist;
        const double sinAngle = x.d1.cross(x.d2).norm()/std::sqrt(x.a11*x.a22);
        if (x.parallel)
        {
            if (!inEdgeCone(SA_, a, RAt_*n, true) || !inEdgeCone(SB_, b, -(RBt_*n), true)) return;
            col.add
            (
                FeaturePair::edgeEdge, featureKey(kEdge, a), featureKey(kEdge, b),
                x.c1, n, dist, rA_, rB_, sinAngle
            );
            return;
        }
        // Crossing edges: the normal inside both wedges, or past one of
        // their faces' normals by up to parallelEdgeSin: the crossing is then
        // a corner of a patch (the other edge lying nearly parallel on that
        // face; its other corner is a vertex-face contact, in its own band),
        // weighted down to 0 across the band. n = +-(u1 x u2)/|u1 x u2|
        // depends on the edges' directions only, and so does the weight: its
        // gradient is a couple, dw/dphi_B = sum of the factors' slopes times
        // d(mu)/dphi_B, derived from d n = (I - n n^T) d(u1 x u2)/|u1 x u2|
        const Vec3 u1 = x.d1/std::sqrt(x.a11);
        const Vec3 u2 = x.d2/std::sqrt(x.a22);
        const double sigma = u1.cross(u2).dot(n) > 0 ? 1 : -1;
        double w = 1;
        Vec3 grad = Vec3::Zero();
        for (int side = 0; side < 2; ++side)
        {
            // A face of edge a: mu = n . in, dmu/dphi_B = u2 x (g x u1),
            // g = sigma (I - n n^T) in/|u1 x u2|
            const Vec3 inA = A_.R*SA_.edgeInward(a, side);
            const double muA = n.dot(inA);
            if (muA > coneTolerance)
            {
                const double h = bandFade(muA/parallelSin_);
                if (!(h > 0)) return;
                w *= h;
                const Vec3 g = (sigma/sinAngle)*(inA - muA*n);
                grad += (bandFadeSlope(muA/parallelSin_)/(parallelSin_*h))*u2.cross(g.cross(u1));
            }
            // A face of edge b: mu = -n . in, dmu/dphi_B = -u1 x (u2 x g),
            // g = -sigma (I - n n^T) in/|u1 x u2|
            const Vec3 inB = B_.R*SB_.edgeInward(b, side);
            const double muB = -n.dot(inB);
            if (muB > coneTolerance)
            {
                const double h = bandFade(muB/parallelSin_);
                if (!(h > 0)) return;
                w *= h;
                const Vec3 g = (-sigma/sinAngle)*(inB + muB*n);
                grad -= (bandFadeSlope(muB/parallelSin_)/(parallelSin_*h))*u1.cross(u2.cross(g));
            }
        }
        col.add
        (
            FeaturePair::edgeEdge, featureKey(kEdge, a), featureKey(kEdge, b),
            x.c1, n, dist, rA_, rB_, sinAngle, w, w*grad
        );
    }

    //- 3d. Vertex i of A on edge b of B
    void vertexEdge(int i, int b)
    {
        const auto& EB = PB_.edges();
        const Vec3& p = wA_[i];
        const Vec3& e0 = wB_[EB[b][0]];
        const Vec3 de = wB_[EB[b][1]] - e0;
        const double t = (p - e0).dot(de)/de.squaredNorm();
        if (!(t > 0 && t < 1)) return;
        const Vec3 diff = e0 + t*de - p;
        const double dist2 = diff.squaredNorm();
        const double rch = reach();
        if (dist2 >= rch*rch) return;
        const double dist = std::sqrt(dist2);
        if (dist < tiny_) return;
        const Vec3 n = diff/dist;
        if
        (
            !inEdgeCone(SB_, b, -(RBt_*n), true)
         || !inVertexConeForEdge(SA_, i, RAt_*n, RAt_*de.normalized(), parallelSin_)
         || leaningEdgeOwns(SA_, i, RAt_*n, [&](int e) { return parallelEdgesTouch(e, b); })
        ) return;
        col.add
        (
            FeaturePair::vertexEdge, featureKey(kVertex, i), featureKey(kEdge, b),
            p, n, dist, rA_, rB_
        );
    }

    //- 3e. Vertex j of B on edge a of A
    void edgeVertex(int a, int j)
    {
        const auto& EA = PA_.edges();
        const Vec3& p = wB_[j];
        const Vec3& e0 = wA_[EA[a][0]];
        const Vec3 de = wA_[EA[a][1]] - e0;
        const double t = (p - e0).dot(de)/de.squaredNorm();
        if (!(t > 0 && t < 1)) return;
        const Vec3 c = e0 + t*de;
        const Vec3 diff = p - c;
        const double dist2 = diff.squaredNorm();
        const double rch = reach();
        if (dist2 >= rch*rch) return;
        const double dist = std::sqrt(dist2);
        if (dist < tiny_) return;
        const Vec3 n = diff/dist;
        if
        (
            !inEdgeCone(SA_, a, RAt_*n, true)
         || !inVertexConeForEdge(SB_, j, -(RBt_*n), RBt_*de.normalized(), parallelSin_)
         || leaningEdgeOwns(SB_, j, -(RBt_*n), [&](int e) { return parallelEdgesTouch(a, e); })
        ) return;
        col.add
        (
            FeaturePair::vertexEdge, featureKey(kEdge, a), featureKey(kVertex, j),
            c, n, dist, rB_, rA_
        );
    }

    //- 3f. Vertex i of A and vertex j of B (normal strictly inside both
    //  vertex cones)
    void vertexVertex(int i, int j)
    {
        const Vec3 diff = wB_[j] - wA_[i];
        const double dist2 = diff.squaredNorm();
        const double rch = reach();
        if (dist2 >= rch*rch) return;
        const double dist = std::sqrt(dist2);
        if (dist < tiny_) return;
        const Vec3 n = diff/dist;
        if (!inVertexCone(SA_, i, RAt_*n, coneTolerance) || !inVertexCone(SB_, j, -(RBt_*n), coneTolerance)) return;
        col.add
        (
            FeaturePair::vertexVertex, featureKey(kVertex, i), featureKey(kVertex, j),
            wA_[i], n, dist, rA_, rB_
        );
    }

    //- The listed feature pairs, in order. A vertex transformed into the
    //  other body's frame serves the entries that follow it with the same
    //  vertex (the full search lists them together)
    void evaluateList(const std::uint32_t* entries, int count)
    {
        int lastA = -1, lastB = -1;
        Vec3 pA = Vec3::Zero(), pB = Vec3::Zero();
        for (int k = 0; k < count; ++k)
        {
            const std::uint32_t entry = entries[k];
            const int a = int((entry >> 14) & 0x7fff);
            const int b = int(entry & 0x3fff);
            switch (PairKind(entry >> 29))
            {
                case vertexFaceAB:
                    if (a != lastA) { pA = vertexAInB(a); lastA = a; }
                    vertexFace(a, b, pA);
                    break;
                case faceVertexAB:
                    if (b != lastB) { pB = vertexBInA(b); lastB = b; }
                    faceVertex(a, b, pB);
                    break;
                case edgeEdgeAB: edgeEdge(a, b); break;
                case vertexEdgeAB: vertexEdge(a, b); break;
                case edgeVertexAB: edgeVertex(a, b); break;
                case vertexVertexAB: vertexVertex(a, b); break;
            }
        }
    }

    //- True if a lower bound of the distance between the cores' features
    //  of the pair is below d (for the list: d = r_A + r_B + featureSkin);
    //  p: vertexAInB(a) for 3a, vertexBInA(b) for 3b, else unused
    bool near(PairKind kind, int a, int b, const Vec3& p, double d) const
    {
        const auto& EA = PA_.edges();
        const auto& EB = PB_.edges();
        switch (kind)
        {
            case vertexFaceAB: return pointFaceDistanceBound(SB_, b, p) < d;
            case faceVertexAB: return pointFaceDistanceBound(SA_, a, p) < d;
            case edgeEdgeAB:
            {
                const Vec3& p1 = wA_[EA[a][0]];
                const Vec3& p2 = wB_[EB[b][0]];
                return segmentDistance2(p1, wA_[EA[a][1]] - p1, p2, wB_[EB[b][1]] - p2) < d*d;
            }
            case vertexEdgeAB:
            {
                const Vec3& e0 = wB_[EB[b][0]];
                return pointSegmentDistance2(wA_[a], e0, wB_[EB[b][1]] - e0) < d*d;
            }
            case edgeVertexAB:
            {
                const Vec3& e0 = wA_[EA[a][0]];
                return pointSegmentDistance2(wB_[b], e0, wA_[EA[a][1]] - e0) < d*d;
            }
            case vertexVertexAB: return (wB_[b] - wA_[a]).squaredNorm() < d*d;
        }
        return true;
    }

    //- True if a window of the pair fails now by a margin that the motion
    //  allowed to the list cannot close, i.e. the pair gives no contact as
    //  long as the list holds. Its windows failing before Collector::add, it
    //  does not change the closest pair either: the list need not hold it.
    //  Windows bounded here: those of a vertex's position in the other
    //  body's frame, P (3a, 3b: the sides of the face and the face's plane;
    //  3d, 3e: the ends of the edge), which are distances along fixed
    //  directions of that frame. While the list holds (m_A + m_B <
    //  featureSkin - eta) the vertex moves by at most m_V and the point of
    //  the other body O at P by at most m_O max(1, |P|/R_O), so P moves by
    //  less than featureSkin max(1, |P|/R_O) - eta; that margin, and eta
    //  for the rounding. p: vertexAInB(a) for 3a, vertexBInA(b) for 3b
    bool outsideWindow(PairKind kind, int a, int b, const Vec3& p, double skin) const
    {
        const auto& EA = PA_.edges();
        const auto& EB = PB_.edges();
        switch (kind)
        {
            case vertexFaceAB: return outsideFace(SB_, b, p, skin);
            case faceVertexAB: return outsideFace(SA_, a, p, skin);
            case edgeEdgeAB: return linesCrossOutside(a, b, skin);
            case vertexEdgeAB:
            {
                const Vec3& e0 = wB_[EB[b][0]];
                return outsideEdge
                (
                    wA_[a], e0, wB_[EB[b][1]] - e0,
                    skin*std::max(1.0, vertexAInB(a).norm()/SB_.boundingRadius())
                );
            }
            case edgeVertexAB:
            {
                const Vec3& e0 = wA_[EA[a][0]];
                return outsideEdge
                (
                    wB_[b], e0, wA_[EA[a][1]] - e0,
                    skin*std::max(1.0, vertexBInA(b).norm()/SA_.boundingRadius())
                );
            }
            default: return false;
        }
    }

    //- The closest points X (on a), Y (on b) of the lines of edge a of A
    //  and edge b of B lie outside edge a or edge b by more than the motion
    //  the list allows can bring them back: the window of edgeEdge (0 < sa,
    //  tb < 1) fails while the list holds. With u1, u2 the edges' unit
    //  directions, s the sine of their angle and sigma the position of X
    //  along a from its first end E0, the signed distance of E0 from the
    //  plane through line b with normal m = (u1 - (u1.u2) u2)/s is -sigma s
    //  (X - Y is normal to both lines). Relative to A, B turns by at most
    //  phi = chord_A + chord_B < featureSkin/min(R_A, R_B) (chord = 2
    //  sin(angle/2) <= m/R), which turns m by at most 4 phi/s (|u1 - (u1.u2)
    //  u2| changes by at most 2 phi, and |a/|a| - b/|b|| <= 2 |a - b|/|b|),
    //  and Y, a point of B, moves by less than featureSkin max(1, |Y -
    //  x_A|/R_A, |Y - x_B|/R_B): the distance changes by less than |E0 - Y|
    //  4 phi/s + that, |E0 - Y| <= |sigma| + |X - Y|. Alike for the other end
    //  of a, and for the ends of b (in B's frame, X moving). The rounding of
    //  sa and tb (about 4 eps/s^2 of the edge length for s >= 1e-4) and of
    //  these bounds is covered by listTolerance (R_A + R_B)
    bool linesCrossOutside(int a, int b, double skin) const
    {
        const auto& EA = PA_.edges();
        const auto& EB = PB_.edges();
        const Vec3& p1 = wA_[EA[a][0]];
        const Vec3& p2 = wB_[EB[b][0]];
        const Vec3 d1 = wA_[EA[a][1]] - p1;
        const Vec3 d2 = wB_[EB[b][1]] - p2;
        const double L1 = std::sqrt(d1.squaredNorm());
        const double L2 = std::sqrt(d2.squaredNorm());
        const Vec3 u1 = d1/L1;
        const Vec3 u2 = d2/L2;
        const double sinAngle = std::sqrt(u1.cross(u2).squaredNorm());
        if (!(sinAngle > listPruneMinSin)) return false;
        const double c = u1.dot(u2);
        const Vec3 w = p2 - p1;
        const double s2 = sinAngle*sinAngle;
        const double sigma = (u1.dot(w) - c*u2.dot(w))/s2;
        const double tau = (c*u1.dot(w) - u2.dot(w))/s2;
        const Vec3 X = p1 + sigma*u1;
        const Vec3 Y = p2 + tau*u2;
        const double gap = std::sqrt((X - Y).squaredNorm());
        const double RA = SA_.boundingRadius();
        const double RB = SB_.boundingRadius();
        const double turn = 4*skin/(std::min(RA, RB)*sinAngle);
        const double slack = listTolerance*(RA + RB);
        auto moves = [&](const Vec3& y)
        {
            return skin*std::max
            (
                1.0,
                std::max(std::sqrt((y - A_.x).squaredNorm())/RA, std::sqrt((y - B_.x).squaredNorm())/RB)
            );
        };
        // Ends of a against the plane through line b (Y moving), then the
        // ends of b against the plane through line a (X moving)
        const double mY = moves(Y) + slack;
        if (-sigma*sinAngle >= (std::abs(sigma) + gap)*turn + mY) return true;
        if ((sigma - L1)*sinAngle >= (std::abs(sigma - L1) + gap)*turn + mY) return true;
        const double mX = moves(X) + slack;
        if (-tau*sinAngle >= (std::abs(tau) + gap)*turn + mX) return true;
        if ((tau - L2)*sinAngle >= (std::abs(tau - L2) + gap)*turn + mX) return true;
        return false;
    }

    //- Point p (principal frame of S) behind the plane of face f, or
    //  outside one of its sides, by at least skin max(1, |p|/R): the window
    //  of vertexFace and faceVertex (dist > 0, insideFace) fails while the
    //  list holds. The side distances are those insideFace computes: (q -
    //  v_k) . (t x n), with q - p along n, which is normal to t x n
    static bool outsideFace(const DilatedShape& S, int f, const Vec3& p, double skin)
    {
        const ConvexPolyhedron& P = S.core();
        const auto& face = P.faces()[f];
        const double margin = skin*std::max(1.0, p.norm()/S.boundingRadius());
        const double dist = face.normal.dot(p) - face.offset;
        if (-dist >= margin) return true;
        const Vec3 q = p - dist*face.normal;
        for (int k = 0; k < face.count; ++k)
        {
            if ((q - P.vertices()[P.faceVertex(f, k)]).dot(S.faceEdgeNormal(f, k)) >= margin)
            {
                return true;
            }
        }
        return false;
    }

    //- Point p beyond an end of the edge e0 + t de by at least margin (its
    //  projection on the edge's line): the window of vertexEdge and
    //  edgeVertex (0 < t < 1) fails while the list holds
    static bool outsideEdge(const Vec3& p, const Vec3& e0, const Vec3& de, double margin)
    {
        const double len = std::sqrt(de.squaredNorm());
        const double along = (p - e0).dot(de)/len;
        return along <= -margin || along >= len + margin;
    }
};


//- Records the feature pairs of a full search into a FeaturePairList
class ListBuilder
{
    PairSearch& search_;
    FeaturePairList* list_;     //!< null: not recording (none, or overflowed)
    double reach_;
    double skin_;

public:

    ListBuilder(PairSearch& search, FeaturePairList* list, double reach, double skin)
    :
        search_(search), list_(list), reach_(reach), skin_(skin)
    {
        if (list_)
        {
            list_->count = 0;
            list_->entries = list_->buffer;
        }
    }

    bool recording() const { return list_ != nullptr; }

    //- Keep the pair if it is near and its windows may pass while the list
    //  holds (before its evaluation: same order)
    void visit(PairKind kind, int a, int b, const Vec3& p = Vec3::Zero())
    {
        if (!list_ || !search_.near(kind, a, b, p, reach_)) return;
        if (search_.outsideWindow(kind, a, b, p, skin_)) return;
        if (list_->count == FeaturePairList::capacity)
        {
            list_->count = -1;  // too many: this pair goes without a list
            list_ = nullptr;
            return;
        }
        list_->buffer[list_->count++] = listEntry(kind, a, b);
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
    int maxOut,
    FeaturePairList* list,
    double* separation
)
{
    const DilatedShape& SA = *A.shape;
    const DilatedShape& SB = *B.shape;
    const ConvexPolyhedron& PA = SA.core();
    const ConvexPolyhedron& PB = SB.core();
    const int nA = static_cast<int>(PA.vertices().size());
    const int nB = static_cast<int>(PB.vertices().size());
    const double rs = SA.radius() + SB.radius();
    const Vec3* wA = A.vertices;
    const Vec3* wB = B.vertices;

    // The feature-pair list holds while the cores have moved less than
    // featureSkin relative to each other since it was built (a bound that
    // depends on the present poses only, not on the path); evaluated when
    // the first axis does not separate the cores
    if (!(s.featureSkin > 0)) list = nullptr;
    int listHolds = -1;
    auto useList = [&]()
    {
        if (listHolds < 0)
        {
            listHolds = 0;
            if (list && list->count >= 0)
            {
                const double moved =
                    motionBound(list->xA, list->qA, A.x, A.q, SA.boundingRadius())
                  + motionBound(list->xB, list->qB, B.x, B.q, SB.boundingRadius());
                const double eta = listTolerance*(SA.boundingRadius() + SB.boundingRadius());
                listHolds = moved < s.featureSkin - eta;
            }
        }
        return listHolds == 1;
    };

    // 1. Separating axes: the hint, then the line of centres (not while the
    //    list holds: the listed pairs give the contacts of a full search
    //    whatever the axes say, which only save work, and the hint, the
    //    last contact normal or closest pair's direction, is the axis that
    //    separates such a pair)
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

    // A pair with a list is likely to walk it: its shapes' data first
    if (list && list->count > 0)
    {
        prefetchShape(SB);
        prefetchShape(SA);
    }

    double bestGap = -std::numeric_limits<double>::max();
    Vec3 best = axes[0];
    double bestMaxA = 0, bestMinB = 0;
    for (int k = 0; k < nAxes; ++k)
    {
        if ((k > 0 || (list && list->touched)) && useList()) break;
        const Vec3& a = axes[k];
        double maxA = -std::numeric_limits<double>::max();
        double minB = std::numeric_limits<double>::max();
        for (int i = 0; i < nA; ++i) maxA = std::max(maxA, a.dot(wA[i]));
        for (int j = 0; j < nB; ++j) minB = std::min(minB, a.dot(wB[j]));
        const double gap = minB - maxA;
        if (gap >= rs)
        {
            axis = a;
            if (separation)
            {
                *separation =
                    gap - rs - listTolerance*(SA.boundingRadius() + SB.boundingRadius());
            }
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

    PairSearch search(A, B, s, out, maxOut);
    Collector& col = search.col;

    if (useList())
    {
        // 2-3. The listed feature pairs, in the full search's order
        search.evaluateList(list->entries, list->count);
    }
    else
    {
        // A new list, if any: the feature pairs closer than listReach
        const double listReach = rs + (list ? s.featureSkin : 0);
        if (list)
        {
            list->xA = A.x;
            list->xB = B.x;
            list->qA = A.q;
            list->qB = B.q;
        }
        ListBuilder builder(search, list, listReach, s.featureSkin);

        // 2. Features inside the slab of the best axis (exact culling: a
        //    point farther than listReach from the other core's slab cannot
        //    touch it, nor be listed)
        int candA[maxShapeVertices], candB[maxShapeVertices];
        bool isCandA[maxShapeVertices], isCandB[maxShapeVertices];
        int nCandA = 0, nCandB = 0;
        const double loA = bestMinB - listReach;
        const double hiB = bestMaxA + listReach;
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

        // Candidate faces and edges: at least one vertex in the slab
        auto faceHasCandidate = [](const ConvexPolyhedron& P, int f, const bool* isCand)
        {
            for (int k = 0; k < P.faces()[f].count; ++k)
            {
                if (isCand[P.faceVertex(f, k)]) return true;
            }
            return false;
        };
        const auto& EA = PA.edges();
        const auto& EB = PB.edges();
        auto edgeA = [&](int a) { return isCandA[EA[a][0]] || isCandA[EA[a][1]]; };
        auto edgeB = [&](int b) { return isCandB[EB[b][0]] || isCandB[EB[b][1]]; };
        const int nFA = static_cast<int>(PA.faces().size());
        const int nFB = static_cast<int>(PB.faces().size());
        bool isCandFaceA[2*maxShapeVertices], isCandFaceB[2*maxShapeVertices];
        for (int f = 0; f < nFA; ++f) isCandFaceA[f] = faceHasCandidate(PA, f, isCandA);
        for (int f = 0; f < nFB; ++f) isCandFaceB[f] = faceHasCandidate(PB, f, isCandB);

        // 3a. Vertex of A on a face of B
        for (int ci = 0; ci < nCandA; ++ci)
        {
            const int i = candA[ci];
            const Vec3 p = search.vertexAInB(i);
            for (int f = 0; f < nFB; ++f)
            {
                if (!isCandFaceB[f]) continue;
                builder.visit(vertexFaceAB, i, f, p);
                search.vertexFace(i, f, p);
            }
        }

        // 3b. Vertex of B on a face of A
        for (int cj = 0; cj < nCandB; ++cj)
        {
            const int j = candB[cj];
            const Vec3 p = search.vertexBInA(j);
            for (int f = 0; f < nFA; ++f)
            {
                if (!isCandFaceA[f]) continue;
                builder.visit(faceVertexAB, f, j, p);
                search.faceVertex(f, j, p);
            }
        }

        // 3c. Edge-edge
        for (int a = 0; a < int(EA.size()); ++a)
        {
            if (!edgeA(a)) continue;
            for (int b = 0; b < int(EB.size()); ++b)
            {
                if (!edgeB(b)) continue;
                builder.visit(edgeEdgeAB, a, b);
                search.edgeEdge(a, b);
            }
        }

        // 3d. Vertex of A on an edge of B
        for (int ci = 0; ci < nCandA; ++ci)
        {
            for (int b = 0; b < int(EB.size()); ++b)
            {
                if (!edgeB(b)) continue;
                builder.visit(vertexEdgeAB, candA[ci], b);
                search.vertexEdge(candA[ci], b);
            }
        }

        // 3e. Vertex of B on an edge of A
        for (int cj = 0; cj < nCandB; ++cj)
        {
            for (int a = 0; a < int(EA.size()); ++a)
            {
                if (!edgeA(a)) continue;
                builder.visit(edgeVertexAB, a, candB[cj]);
                search.edgeVertex(a, candB[cj]);
            }
        }

        // 3f. Vertex-vertex
        for (int ci = 0; ci < nCandA; ++ci)
        {
            for (int cj = 0; cj < nCandB; ++cj)
            {
                builder.visit(vertexVertexAB, candA[ci], candB[cj]);
                search.vertexVertex(candA[ci], candB[cj]);
            }
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
        c.featureA = featureKey(kVertex, v);
        c.featureB = featureKey(kPlane, 0);
    }
    if (separation && n == 0)
    {
        *separation = minDist - r - listTolerance*S.boundingRadius();
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
