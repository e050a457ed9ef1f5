/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "NarrowPhase.H"
#include "candidateLists.H"

#include <algorithm>
#include <limits>

namespace iceDEM
{

using namespace narrowPhase;

namespace
{

//- The extent [lo, hi] of n points w along the axis a
void extentAlong(const Vec3& a, const Vec3* w, int n, double& lo, double& hi)
{
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    for (int i = 0; i < n; ++i)
    {
        const double p = a.dot(w[i]);
        lo = std::min(lo, p);
        hi = std::max(hi, p);
    }
}

//- The deepest term (of positive weight after the first, as the next
//  step's axis has always been chosen)
int deepestTerm(const FoundContact* out, int n)
{
    int deepest = 0;
    for (int k = 1; k < n; ++k)
    {
        if (out[k].g.weight > 0 && out[k].g.overlap > out[deepest].g.overlap) deepest = k;
    }
    return deepest;
}

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

    // featureSkin 0: no list (the full search on every call)
    if (list && !(s.featureSkin > 0)) list->count = -1;

    TermCollector col(out, maxOut, SA.radius(), SB.radius());

    // 1. The pair's candidate list (candidateLists.H) holds while the two
    //    cores have moved less than its limit relative to each other since
    //    its build. A pair that touched at its last search walks it first:
    //    if it still touches, the separating axes below cannot separate it
    //    (below), or need only show that they do not
    double m = -1;
    RelativePose now{Vec3::Zero(), Quat::Identity()};
    if (list && s.featureSkin > 0)
    {
        now = relativePose(A, B);
        if (list->count >= 0)
        {
            m = relativeMotionBound
            (
                list->t, list->Q, now.t, now.Q,
                SA.boundingRadius(), SB.boundingRadius()
            );
        }
    }
    const bool holds = list && s.featureSkin > 0 && m >= 0 && m < list->limit;
    bool walked = false;
    if (holds && list->touched)
    {
        walkList(col, A, B, list->entries, list->count, m);
        walked = true;
    }
    const bool touching = walked && col.n > 0;

    // A term deeper than the rounding of a gap: no axis below can separate
    // the pair (a term is the distance of a point of each core, and the gap
    // along a unit axis is at most that distance; the computed gap and
    // distance differ from theirs by a few units in the last place of the
    // coordinates, 64 of them allowed). The walk's terms stand, as they
    // would after the axes
    if (touching)
    {
        const int deepest = deepestTerm(out, col.n);
        const double coordinates =
            A.x.cwiseAbs().maxCoeff() + B.x.cwiseAbs().maxCoeff()
          + SA.boundingRadius() + SB.boundingRadius();
        const double rounding = 64*std::numeric_limits<double>::epsilon()*coordinates;
        if (out[deepest].g.overlap > rounding)
        {
            axis = out[deepest].g.normal;
            return col.n;
        }
    }

    // 2. Separating axes: the hint, then the line of centres; the first
    //    that separates ends the search (a walk's terms dropped: the
    //    search is that of a separated pair). Where the walk found terms
    //    (none deeper than the rounding: above) an axis is dropped as soon
    //    as it cannot separate: its gap, min
    //    a.w_B - max a.w_A, is at most that of the vertices seen so far
    //    (rounding is monotone), and its other products (the best axis:
    //    the slab of a build or a full search, the hint where nothing
    //    touches) are not needed
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
        // Infinite, not the largest double: minB - maxA must not overflow
        // (OpenFOAM traps floating-point overflow)
        double maxA = -std::numeric_limits<double>::infinity();
        double minB = std::numeric_limits<double>::infinity();
        if (touching)
        {
            // The terms' vertices first (a vertex of each body in
            // contact), then both bodies' in turn, until a vertex of A and
            // one of B project less than R apart; else all are seen and
            // maxA, minB are the extremes
            for (int t = 0; t < col.n; ++t)
            {
                const std::uint32_t fa = out[t].featureA, fb = out[t].featureB;
                if ((fa >> 30) == kVertex) maxA = std::max(maxA, a.dot(wA[fa & 0x3fffffffu]));
                if ((fb >> 30) == kVertex) minB = std::min(minB, a.dot(wB[fb & 0x3fffffffu]));
            }
            int i = 0, j = 0;
            while (!(minB - maxA < rs) && (i < nA || j < nB))
            {
                if (i < nA) maxA = std::max(maxA, a.dot(wA[i++]));
                if (j < nB) minB = std::min(minB, a.dot(wB[j++]));
            }
            if (minB - maxA < rs) continue;
        }
        else
        {
            for (int i = 0; i < nA; ++i) maxA = std::max(maxA, a.dot(wA[i]));
            for (int j = 0; j < nB; ++j) minB = std::min(minB, a.dot(wB[j]));
        }
        const double gap = minB - maxA;
        if (gap >= rs)
        {
            axis = a;
            if (separation)
            {
                *separation =
                    gap - rs - separationTolerance*(SA.boundingRadius() + SB.boundingRadius());
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

    // The features inside the slab of the best axis widened by w (exact
    // culling: a vertex of P farther than R + w from Q's slab is farther
    // than R + w from Q; a point of Q within R + w of a vertex of P lies in
    // Q's slab widened by R + w, so the face or edge that holds it has a
    // vertex there, and the distance of a vertex to the candidate faces
    // and edges is its distance to the whole core whenever it is below
    // R + w)
    int candA[maxShapeVertices], candB[maxShapeVertices];
    bool isCandA[maxShapeVertices], isCandB[maxShapeVertices];
    int nCandA = 0, nCandB = 0;
    const auto& EA = PA.edges();
    const auto& EB = PB.edges();
    const int nFA = static_cast<int>(PA.faces().size());
    const int nFB = static_cast<int>(PB.faces().size());
    bool isCandFaceA[2*maxShapeVertices], isCandFaceB[2*maxShapeVertices];
    bool isCandEdgeA[3*maxShapeVertices], isCandEdgeB[3*maxShapeVertices];
    auto candidates = [&](double w)
    {
        const double loA = bestMinB - rs - w;
        const double hiB = bestMaxA + rs + w;
        nCandA = nCandB = 0;
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
        for (int f = 0; f < nFA; ++f) isCandFaceA[f] = faceHasCandidate(PA, f, isCandA);
        for (int f = 0; f < nFB; ++f) isCandFaceB[f] = faceHasCandidate(PB, f, isCandB);
        for (int e = 0; e < int(EA.size()); ++e) isCandEdgeA[e] = isCandA[EA[e][0]] || isCandA[EA[e][1]];
        for (int e = 0; e < int(EB.size()); ++e) isCandEdgeB[e] = isCandB[EB[e][0]] || isCandB[EB[e][1]];
    };

    // 3. The held list (walked above if the pair touched), else a new one:
    //    the same terms as the full search below, to the bit
    bool listed = walked;
    if (!walked && list && s.featureSkin > 0)
    {
        if (holds)
        {
            walkList(col, A, B, list->entries, list->count, m);
            listed = true;
        }
        else
        {
            list->count = -1;
            candidates(s.featureSkin + listSlack*rs);
            ListWriter writer(list->buffer, FeaturePairList::capacity, rs);
            const double reach = rs + s.featureSkin + writer.slack();
            bool listedA[maxShapeVertices], listedB[maxShapeVertices];
            double dMin = std::numeric_limits<double>::infinity();
            bool ok =
                listVertexGroups
                (
                    writer, A, B, candA, nCandA, isCandFaceB, isCandEdgeB,
                    reach, true, listedA, dMin
                )
             && listVertexGroups
                (
                    writer, B, A, candB, nCandB, isCandFaceA, isCandEdgeA,
                    reach, false, listedB, dMin
                );
            // The list's life (candidateLists.H): no listed vertex may
            // reach the other core's inside
            const double limit = std::min(s.featureSkin, dMin - writer.slack());
            ok = ok && limit > 0;
            for (int ci = 0; ok && ci < nCandA && !writer.overflow; ++ci)
            {
                const int i = candA[ci];
                if (!listedA[i]) continue;
                for (int cj = 0; cj < nCandB; ++cj)
                {
                    const int j = candB[cj];
                    if (!listedB[j]) continue;
                    const double dist = (wB[j] - wA[i]).norm();
                    if (dist < reach) writer.push(kVertexPair, i, j, dist);
                }
            }
            for (int a = 0; ok && a < int(EA.size()) && !writer.overflow; ++a)
            {
                if (!isCandEdgeA[a]) continue;
                const Vec3& p0 = wA[EA[a][0]];
                const Vec3& p1 = wA[EA[a][1]];
                Vec3 midA;
                double reachA;
                edgeReach(A, a, reach, midA, reachA);
                for (int b = 0; b < int(EB.size()); ++b)
                {
                    if (!isCandEdgeB[b]) continue;
                    Vec3 midB;
                    double halfB;
                    edgeBall(B, b, midB, halfB);
                    // Balls apart: a lower bound of the distance above reach
                    if (ballBeyond(midA, midB, halfB, reachA)) continue;
                    const double lb = segmentDistanceLowerBound(p0, p1, wB[EB[b][0]], wB[EB[b][1]]);
                    if (lb < reach) writer.push(kEdgePair, a, b, lb);
                }
            }
            if (ok && !writer.overflow)
            {
                list->count = writer.n;
                list->entries = list->buffer;
                list->t = now.t;
                list->Q = now.Q;
                list->limit = limit;
                walkList(col, A, B, list->entries, list->count, 0);
                listed = true;
            }
        }
    }

    if (!listed)
    {
        // 4. The full search: the terms (NarrowPhase.H) over the slab's
        //    candidates, vertices of A against B's core and of B against
        //    A's (one function, the roles swapped), less the vertex-vertex
        //    doubles, plus the edge-edge excess
        candidates(0);
        VertexClosest infoA[maxShapeVertices], infoB[maxShapeVertices];
        vertexTerms<true>(col, A, B, candA, nCandA, isCandFaceB, isCandEdgeB, infoA);
        vertexTerms<false>(col, B, A, candB, nCandB, isCandFaceA, isCandEdgeA, infoB);
        vertexVertexTerms(col, A, B, candA, nCandA, candB, nCandB, infoA, infoB);
        edgeEdgeTerms
        (
            col, A, B,
            [&](int e) { return isCandEdgeA[e]; },
            [&](int e) { return isCandEdgeB[e]; }
        );
    }

    // 5. Nothing touches, and neither axis above separated: the pair is
    //    searched again at every step unless something certifies it apart.
    //    The cores' face normals are tried (two convex polyhedra are
    //    separated along a face normal of one or a cross product of two
    //    edges; for two floes side by side mostly a side's normal); the
    //    widest gap beyond the radii certifies the pair (World skips it
    //    while its relative motion stays below the separation) and is the
    //    next search's hint. The terms are those of a search either way
    if (col.n == 0 && separation)
    {
        double gap = -std::numeric_limits<double>::infinity();
        Vec3 along = Vec3::Zero();
        auto tryAxis = [&](const Vec3& a)
        {
            double minA, maxA, minB, maxB;
            extentAlong(a, wA, nA, minA, maxA);
            extentAlong(a, wB, nB, minB, maxB);
            if (minB - maxA > gap) { gap = minB - maxA; along = a; }
            if (minA - maxB > gap) { gap = minA - maxB; along = -a; }
        };
        const auto facesA = PA.faces();
        const auto facesB = PB.faces();
        for (int f = 0; f < nFA; ++f) tryAxis(A.R*facesA[f].normal);
        for (int f = 0; f < nFB; ++f) tryAxis(B.R*facesB[f].normal);
        if (gap >= rs)
        {
            axis = along;
            *separation =
                gap - rs - separationTolerance*(SA.boundingRadius() + SB.boundingRadius());
            return 0;
        }
    }

    // Next step's axis: the deepest contact's normal, else the direction of
    // the closest feature pair (a separating axis of convex cores)
    if (col.n > 0)
    {
        axis = out[deepestTerm(out, col.n)].g.normal;
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



bool coresIntersect(const BodyView& A, const BodyView& B)
{
    const int nA = static_cast<int>(A.shape->core().vertices().size());
    const int nB = static_cast<int>(B.shape->core().vertices().size());

    auto separates = [&](const Vec3& a)
    {
        const double len = a.norm();
        if (len < 1e-12) return false;
        double minA, maxA, minB, maxB;
        extentAlong(a, A.vertices, nA, minA, maxA);
        extentAlong(a, B.vertices, nB, minB, maxB);
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
