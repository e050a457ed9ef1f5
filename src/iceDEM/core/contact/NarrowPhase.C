/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "NarrowPhase.H"
#include "pairSearch.H"
#include "narrowPhaseMerge.H"

#include <algorithm>
#include <limits>

namespace iceDEM
{

using namespace narrowPhase;

namespace
{

//- 3a (vertexOnA) or 3b: the candidate vertices of one element on the
//  candidate faces of the other, listed and evaluated
template<bool vertexOnA>
void vertexFaceLoop
(
    PairSearch& search,
    ListBuilder& builder,
    const int* candV,
    int nCandV,
    const bool* isCandFaceF,
    int nFF
)
{
    for (int ci = 0; ci < nCandV; ++ci)
    {
        const int i = candV[ci];
        const Vec3 p = vertexOnA ? search.vertexAInB(i) : search.vertexBInA(i);
        for (int f = 0; f < nFF; ++f)
        {
            if (!isCandFaceF[f]) continue;
            if (vertexOnA)
            {
                builder.visit(vertexFaceAB, i, f, p);
                search.vertexFace(i, f, p);
            }
            else
            {
                builder.visit(faceVertexAB, f, i, p);
                search.faceVertex(f, i, p);
            }
        }
    }
}

//- 3d (vertexOnA) or 3e: the candidate vertices of one element on the
//  candidate edges of the other
template<bool vertexOnA, class IsCandEdge>
void vertexEdgeLoop
(
    PairSearch& search,
    ListBuilder& builder,
    const int* candV,
    int nCandV,
    const IsCandEdge& isCandEdgeF,
    int nEF
)
{
    for (int ci = 0; ci < nCandV; ++ci)
    {
        for (int e = 0; e < nEF; ++e)
        {
            if (!isCandEdgeF(e)) continue;
            if (vertexOnA)
            {
                builder.visit(vertexEdgeAB, candV[ci], e);
                search.vertexEdge(candV[ci], e);
            }
            else
            {
                builder.visit(edgeVertexAB, e, candV[ci]);
                search.edgeVertex(e, candV[ci]);
            }
        }
    }
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

    // The feature-pair list holds while the cores have moved less than
    // featureSkin relative to each other since it was built (a bound that
    // depends on the present relative pose only, not on the path, nor on
    // the pair's common motion: NarrowPhase.H); evaluated when
    // the first axis does not separate the cores
    // The motion bound in both frames: the smaller decides (the list holds
    // while it is below featureSkin - eta, and skips an entry while it is
    // below the entry's certificate), the larger is charged to the
    // certificates renewed by the walk
    if (!(s.featureSkin > 0)) list = nullptr;
    int listHolds = -1;
    double motion = 0, motionMax = 0;
    auto useList = [&]()
    {
        if (listHolds < 0)
        {
            listHolds = 0;
            if (list && list->count >= 0)
            {
                const RelativePose now = relativePose(A, B);
                const double eta = listTolerance*(SA.boundingRadius() + SB.boundingRadius());
                const double chord = relativeChord(list->Q, now.Q);
                const double mB = motionOfBInA(list->t, now.t, chord, SB.boundingRadius());
                const double mA = motionOfAInB(list->t, list->Q, now.t, now.Q, chord, SA.boundingRadius());
                motion = std::min(mB, mA);
                motionMax = std::max(mB, mA);
                listHolds = motion < s.featureSkin - eta;
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
        // 2-3. The listed feature pairs, in the full search's order, those
        //     certified apart skipped; their lapsed certificates renewed
        //     into the caller's buffer (if any)
        if (search.evaluateList(list->entries, list->count, list->buffer, motion, motionMax))
        {
            list->entries = list->buffer;
        }
    }
    else
    {
        // A new list, if any: the feature pairs closer than listReach
        const double listReach = rs + (list ? s.featureSkin : 0);
        if (list)
        {
            const RelativePose now = relativePose(A, B);
            list->t = now.t;
            list->Q = now.Q;
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

        // 3a. Vertex of A on a face of B, 3b. vertex of B on a face of A
        vertexFaceLoop<true>(search, builder, candA, nCandA, isCandFaceB, nFB);
        vertexFaceLoop<false>(search, builder, candB, nCandB, isCandFaceA, nFA);

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

        // 3d. Vertex of A on an edge of B, 3e. vertex of B on an edge of A
        vertexEdgeLoop<true>(search, builder, candA, nCandA, edgeB, int(EB.size()));
        vertexEdgeLoop<false>(search, builder, candB, nCandB, edgeA, int(EA.size()));

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

    // Corners of a patch near each other share their weight (the merge
    // partition, narrowPhaseMerge.H)
    partitionMerges(out, col.n, SA.radius(), SB.radius(), s.mergeSharePower);

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
