/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "WaterFrame.H"
#include "World.H"

#include <limits>

namespace iceDEM
{

namespace
{

//- The wet polygons of every face into frame (and with Dry the dry ones,
//  as frameDry makes them, from the same split of each cut face); a face
//  beyond the clip's buffers leaves the frame unframed
template<bool Dry>
void frameFaces(const PolyhedronView& P, WaterFrame& frame)
{
    const int nf = static_cast<int>(P.faces().size());
    if (Dry)
    {
        frame.nDry = 0;
        frame.dryBegin[0] = 0;
    }
    int endDry = 0;

    constexpr int cap = SubmergedFace::maxVertices;
    Vec3 p[cap];
    int end = 0;
    const auto faces = P.faces();
    const int* faceVertices = P.faceVertices().data();
    // Face f's wet (dry) polygon, written at the end of the frame's list,
    // joins the list
    const auto addWet = [&](int f, int m, bool whole)
    {
        end += m;
        frame.wetFace[frame.nWet] = f;
        frame.wetWhole[frame.nWet] = whole;
        frame.wetBegin[++frame.nWet] = end;
    };
    const auto addDry = [&](int f, int md, bool whole)
    {
        endDry += md;
        frame.dryFace[frame.nDry] = f;
        frame.dryWhole[frame.nDry] = whole;
        frame.dryBegin[++frame.nDry] = endDry;
    };
    for (int f = 0; f < nf; ++f)
    {
        const auto face = faces[f];
        const int n = face.count;
        if (n + 1 > cap)
        {
            // Beyond the clip's buffers: the general paths
            frame.framed = false;
            frame.nWet = 0;
            frame.nDry = 0;
            return;
        }
        const int* fv = faceVertices + face.begin;
        if (!Dry)
        {
            // The wet side alone: the heights first, so that a face above
            // the plane is not gathered, one below is copied once, to its
            // wet polygon, and a cut one is clipped in place (the same
            // polygons as below, bit for bit)
            int nBelow = 0;
            for (int k = 0; k < n; ++k)
            {
                nBelow += frame.h[fv[k]] < 0;
            }
            if (nBelow == 0)
            {
                continue;
            }
            Vec3* q = frame.wetVertex + end;
            double* hq = frame.wetHeight + end;
            int m = n;
            if (nBelow == n)
            {
                for (int k = 0; k < n; ++k)
                {
                    q[k] = frame.r[fv[k]];
                    hq[k] = frame.h[fv[k]];
                }
            }
            else
            {
                m = clipNegativeAt
                (
                    frame.r, frame.h, [fv](int k) { return fv[k]; }, n, q, hq
                );
                if (m == 0) continue;
            }
            addWet(f, m, nBelow == n);
            continue;
        }
        // Both sides: the heights first, as on the wet side alone, so that
        // a face wholly above or below is copied once, to its polygon, and
        // a cut one is split reading the frame's vertices in place (the
        // same polygons as from a gathered copy, bit for bit)
        const auto at = [fv](int k) { return fv[k]; };
        int nBelow = 0, nAbove = 0;
        for (int k = 0; k < n; ++k)
        {
            const double hk = frame.h[fv[k]];
            nBelow += hk < 0;
            nAbove += hk > 0;
        }
        if (nAbove > 0)
        {
            // The dry polygon, as frameDry makes it
            Vec3* qd = frame.dryVertex + endDry;
            int md = n;
            if (nAbove == n)
            {
                for (int k = 0; k < n; ++k)
                {
                    qd[k] = frame.r[fv[k]];
                }
            }
            else if (nBelow > 0)
            {
                // Cut by the waterline: wet and dry polygons in one split
                Vec3* q = frame.wetVertex + end;
                double* hq = frame.wetHeight + end;
                int m;
                splitPolygonAt(frame.r, frame.h, at, n, q, hq, m, qd, md);
                if (md > 0) addDry(f, md, false);
                if (m > 0) addWet(f, m, false);
                continue;
            }
            else
            {
                // Vertices on the plane, none below: the dry clip alone
                double sNeg[cap];
                double sOut[cap];
                for (int k = 0; k < n; ++k)
                {
                    p[k] = frame.r[fv[k]];
                    sNeg[k] = -frame.h[fv[k]];
                }
                md = clipNegative(p, sNeg, n, qd, sOut);
            }
            if (md > 0) addDry(f, md, nAbove == n);
        }
        if (nBelow == 0)
        {
            continue;
        }
        Vec3* q = frame.wetVertex + end;
        double* hq = frame.wetHeight + end;
        int m = n;
        if (nBelow == n)
        {
            // A face entirely below is its own wet polygon
            for (int k = 0; k < n; ++k)
            {
                q[k] = frame.r[fv[k]];
                hq[k] = frame.h[fv[k]];
            }
        }
        else
        {
            m = clipNegativeAt(frame.r, frame.h, at, n, q, hq);
            if (m == 0) continue;
        }
        addWet(f, m, nBelow == n);
    }
}

} // anonymous namespace


void computeWaterFrame
(
    const PolyhedronView& P,
    const Mat3& R,
    const Vec3& x,
    double level,
    WaterFrame& frame,
    bool withDry,
    const PrismCaps* caps
)
{
    frame.hasVolume = false;
    frame.hasDry = false;
    frame.nWet = 0;
    frame.wetBegin[0] = 0;
    frame.R = R;
    frame.caps = caps;
    frame.x = x;
    frame.level = level;

    const auto V = P.vertices();
    const int nv = static_cast<int>(V.size());
    const int nf = static_cast<int>(P.faces().size());
    frame.nv = nv;
    frame.framed = nv <= maxClipVertices && nf <= WaterFrame::maxFaces;
    if (!frame.framed)
    {
        return;
    }

    // World axes relative to x (round-off scales with the size of the body,
    // not with its distance from the origin), heights h = z - level
    const double h0 = x.z() - level;
    double hMin = std::numeric_limits<double>::max();
    double hMax = -hMin;
    for (int k = 0; k < nv; ++k)
    {
        frame.r[k] = R*V[k];
        frame.h[k] = frame.r[k].z() + h0;
        hMin = std::min(hMin, frame.h[k]);
        hMax = std::max(hMax, frame.h[k]);
    }
    frame.hMin = hMin;
    frame.hMax = hMax;
    if (!(hMin < 0))
    {
        return;
    }

    // Both sides in one pass where a wind reads the dry one and the plane
    // cuts the body (else frameDry, when asked); the windless loop is
    // compiled without the dry side's work
    if (withDry && hMax > 0)
    {
        frameFaces<true>(P, frame);
        frame.hasDry = frame.framed;
        frame.dryValid = frame.framed;
    }
    else
    {
        frameFaces<false>(P, frame);
    }
}


namespace
{

//- A thread's water frame and its room for a derived outer polyhedron (no
//  allocation once it has grown to the largest floe; the world keeps them
//  for models that read them)
struct FrameSlot
{
    WaterFrame frame;
    PolyhedronBuffer outerBuffer;
};

//- This thread's slot (one per thread: the models call waterFrame body by
//  body). Not inlined, so that waterFrame finds the slot's address once: in
//  a shared library each use of a thread-local's address is a call of
//  __tls_get_addr, which GCC repeats at every use rather than keep the
//  address (2.4 % of the floating field's instructions, about four calls
//  per waterFrame; tests/benchmark/README.md, forty-third round)
[[gnu::noinline]] FrameSlot& thisThreadsSlot()
{
    static thread_local FrameSlot slot;
    return slot;
}

} // anonymous namespace


[[gnu::noinline]] PolyhedronBuffer& modelsOuterBuffer()
{
    static thread_local PolyhedronBuffer buffer;
    return buffer;
}


const WaterFrame& waterFrame(const World& world, int i, double level)
{
    FrameSlot& slot = thisThreadsSlot();
    WaterFrame& frame = slot.frame;

    const Body& b = world.bodies()[i];
    // Whether a wind read the last frame's dry side (of this world): then
    // it will read this one's too, and both sides come from one split
    // (the same polygons as frameDry's, so the path taken changes nothing)
    const bool withDry =
        frame.hasDry && frame.worldInstance == world.instance();
    if
    (
        frame.worldInstance == world.instance()
     && frame.evaluation == world.evaluation()
     && frame.body == i
     && frame.level == level
     && frame.x == b.x
     && frame.q.coeffs() == b.q.coeffs()
    )
    {
        return frame;
    }

    // Invalidate first: an Error below leaves no half-computed frame behind
    frame.worldInstance = -1;
    const DilatedShape& shape = world.shapeOf(i);
    computeWaterFrame
    (
        shape.outer(slot.outerBuffer), b.rotation(), b.x, level, frame, withDry,
        shape.prismCaps()
    );
    frame.worldInstance = world.instance();
    frame.evaluation = world.evaluation();
    frame.body = i;
    frame.q = b.q;
    return frame;
}


const SubmergedVolume& frameVolume
(
    const PolyhedronView& P,
    const WaterFrame& frame
)
{
    if (frame.hasVolume)
    {
        return frame.volume;
    }
    SubmergedVolume& result = frame.volume;
    frame.hasVolume = true;
    frame.prismBottom = -1;
    frame.prismBottomPlane = nullptr;

    // As submergedVolume: the truncated prism, else the wet polygons; the
    // tetrahedra where the sums would cancel (entirely below); polyhedra
    // too large to frame take submergedVolume itself
    if (!frame.valid())
    {
        result = submergedVolume(P, frame.R, frame.x, frame.level);
        return result;
    }
    result.volume = 0;
    result.centroid = frame.x;
    if (!frame.wet())
    {
        return result;
    }
    if (frame.hMax < 0)
    {
        result = submergedVolumeByTetrahedra
        (
            P, frame.R, frame.x, frame.level
        );
        return result;
    }
    if (frame.caps)
    {
        // A floe: its kept lower cap, no search of the faces and no loop
        // over the cap's vertices
        const int k = lowerCapBelow(*frame.caps, P, frame.R, frame.h);
        if (k >= 0)
        {
            const FacePlane& cap = frame.caps->cap[k];
            frame.prismBottom = cap.face;
            frame.prismBottomPlane = &cap;
            result = truncatedPrismVolume(cap, frame.R, frame.x, frame.level);
            return result;
        }
    }
    const int bottom = truncatedPrismBottom(P, frame.R, frame.h);
    if (bottom >= 0)
    {
        frame.prismBottom = bottom;
        result = truncatedPrismVolume
        (
            P, frame.R, frame.r, frame.h, bottom, frame.x
        );
        return result;
    }
    WetVolumeSums sums;
    for (int k = 0; k < frame.nWet; ++k)
    {
        const int b = frame.wetBegin[k];
        sums.add
        (
            frame.wetVertex + b, frame.wetHeight + b, frame.wetBegin[k + 1] - b
        );
    }
    result = sums.result(frame.x, frame.x.z() - frame.level);
    return result;
}

bool frameDry
(
    const PolyhedronView& P,
    const WaterFrame& frame
)
{
    if (frame.hasDry)
    {
        return frame.dryValid;
    }
    frame.hasDry = true;
    frame.dryValid = false;
    frame.nDry = 0;
    frame.dryBegin[0] = 0;
    if (!frame.valid())
    {
        return false;
    }
    if (!frame.dry())
    {
        frame.dryValid = true;
        return true;
    }

    // As the wet side, with -h: vertices with h = 0 count as below
    constexpr int cap = SubmergedFace::maxVertices;
    Vec3 p[cap];
    double s[cap];
    double sOut[cap];
    int end = 0;
    const int nf = static_cast<int>(P.faces().size());
    for (int f = 0; f < nf; ++f)
    {
        const int n = P.faces()[f].count;
        if (n + 1 > cap)
        {
            frame.nDry = 0;
            return false;
        }
        int nAbove = 0;
        for (int k = 0; k < n; ++k)
        {
            const int v = P.faceVertex(f, k);
            p[k] = frame.r[v];
            s[k] = -frame.h[v];
            nAbove += s[k] < 0;
        }
        if (nAbove == 0)
        {
            continue;
        }
        Vec3* q = frame.dryVertex + end;
        int m = n;
        if (nAbove == n)
        {
            // A face entirely above is its own dry polygon
            for (int k = 0; k < n; ++k)
            {
                q[k] = p[k];
            }
        }
        else
        {
            m = clipNegative(p, s, n, q, sOut);
            if (m == 0) continue;
        }
        end += m;
        frame.dryFace[frame.nDry] = f;
        frame.dryWhole[frame.nDry] = nAbove == n;
        frame.dryBegin[++frame.nDry] = end;
    }
    frame.dryValid = true;
    return true;
}

} // namespace iceDEM
