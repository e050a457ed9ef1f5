/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "WaterClip.H"

#include <cmath>
#include <limits>
#include <string>

namespace iceDEM
{

namespace
{

//- Volume and first moment of a set of tetrahedra
struct VolumeSum
{
    double volume = 0;
    Vec3 first = Vec3::Zero();

    //- Add (sign +1) or remove (sign -1) the tetrahedron (a, b, c, d)
    void add(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
             double sign = 1)
    {
        const double v =
            sign*std::abs((b - a).dot((c - a).cross(d - a)))/6.0;
        volume += v;
        first += (0.25*v)*(a + b + c + d);
    }
};

//- Point where the edge from a (height sa < 0) to b (height sb >= 0)
//  crosses the plane
inline Vec3 cut(const Vec3& a, double sa, const Vec3& b, double sb)
{
    const double t = sa/(sa - sb);
    return a + t*(b - a);
}

//- Add the part of the tetrahedron p[0..3] with heights s[0..3] above the
//  plane that lies below it (s < 0)
void addClippedTetrahedron(const Vec3 p[4], const double s[4], VolumeSum& sum)
{
    int below[4];
    int above[4];
    int nb = 0;
    int na = 0;
    for (int k = 0; k < 4; ++k)
    {
        if (s[k] < 0)
        {
            below[nb++] = k;
        }
        else
        {
            above[na++] = k;
        }
    }

    switch (nb)
    {
        case 0:
        {
            return;
        }
        case 4:
        {
            sum.add(p[0], p[1], p[2], p[3]);
            return;
        }
        case 1:
        {
            // Corner tetrahedron at the vertex below
            const int i = below[0];
            sum.add
            (
                p[i],
                cut(p[i], s[i], p[above[0]], s[above[0]]),
                cut(p[i], s[i], p[above[1]], s[above[1]]),
                cut(p[i], s[i], p[above[2]], s[above[2]])
            );
            return;
        }
        case 3:
        {
            // Whole tetrahedron minus the corner at the vertex above
            const int j = above[0];
            sum.add(p[0], p[1], p[2], p[3]);
            sum.add
            (
                p[j],
                cut(p[below[0]], s[below[0]], p[j], s[j]),
                cut(p[below[1]], s[below[1]], p[j], s[j]),
                cut(p[below[2]], s[below[2]], p[j], s[j]),
                -1
            );
            return;
        }
        default:
        {
            // Two below (i1, i2), two above (j1, j2): a wedge with the
            // triangles A = (i1, cut(i1,j1), cut(i1,j2)) and
            // B = (i2, cut(i2,j1), cut(i2,j2)). Its three quadrilaterals are
            // planar (two lie in faces of the tetrahedron, one in the water
            // plane), so three tetrahedra with consistent diagonals fill it.
            const int i1 = below[0];
            const int i2 = below[1];
            const int j1 = above[0];
            const int j2 = above[1];
            const Vec3& A0 = p[i1];
            const Vec3 A1 = cut(p[i1], s[i1], p[j1], s[j1]);
            const Vec3 A2 = cut(p[i1], s[i1], p[j2], s[j2]);
            const Vec3& B0 = p[i2];
            const Vec3 B1 = cut(p[i2], s[i2], p[j1], s[j1]);
            const Vec3 B2 = cut(p[i2], s[i2], p[j2], s[j2]);
            sum.add(A0, A1, A2, B2);
            sum.add(A0, A1, B1, B2);
            sum.add(A0, B0, B1, B2);
            return;
        }
    }
}

} // anonymous namespace


SubmergedVolume submergedVolumeByTetrahedra
(
    const PolyhedronView& P,
    const Mat3& R,
    const Vec3& x,
    double level
)
{
    SubmergedVolume result;
    result.volume = 0;
    result.centroid = x;

    const auto V = P.vertices();
    const int nv = static_cast<int>(V.size());
    if (nv == 0)
    {
        return result;
    }

    // Height above the plane of a body point p: up.p + h0
    const Vec3 up = R.row(2).transpose();
    const double h0 = x.z() - level;

    double sMin = std::numeric_limits<double>::max();
    Vec3 centre = Vec3::Zero();
    for (int k = 0; k < nv; ++k)
    {
        sMin = std::min(sMin, up.dot(V[k]) + h0);
        centre += V[k];
    }
    if (sMin >= 0)
    {
        return result;
    }
    centre /= nv;

    // Tetrahedra relative to the interior point (round-off scales with the
    // size of the polyhedron, not with its distance from the origin)
    VolumeSum sum;
    Vec3 p[4];
    double s[4];
    p[0] = Vec3::Zero();
    s[0] = up.dot(centre) + h0;

    const int nf = static_cast<int>(P.faces().size());
    for (int f = 0; f < nf; ++f)
    {
        const int n = P.faces()[f].count;
        const Vec3& v0 = V[P.faceVertex(f, 0)];
        p[1] = v0 - centre;
        s[1] = up.dot(v0) + h0;
        for (int k = 1; k + 1 < n; ++k)
        {
            const Vec3& v1 = V[P.faceVertex(f, k)];
            const Vec3& v2 = V[P.faceVertex(f, k + 1)];
            p[2] = v1 - centre;
            s[2] = up.dot(v1) + h0;
            p[3] = v2 - centre;
            s[3] = up.dot(v2) + h0;
            addClippedTetrahedron(p, s, sum);
        }
    }

    if (sum.volume > 0)
    {
        result.volume = sum.volume;
        result.centroid = R*(centre + sum.first/sum.volume) + x;
    }
    return result;
}


int clipNegative
(
    const Vec3* p,
    const double* s,
    int n,
    Vec3* out,
    double* sOut
)
{
    return clipNegativeAt(p, s, [](int k) { return k; }, n, out, sOut);
}


void splitPolygon
(
    const Vec3* p,
    const double* s,
    int n,
    Vec3* neg,
    double* sNeg,
    int& nNeg,
    Vec3* pos,
    int& nPos
)
{
    splitPolygonAt(p, s, [](int k) { return k; }, n, neg, sNeg, nNeg, pos, nPos);
}


namespace
{

//- Whether face bottom of P lies entirely below the water and face top
//  not at all (vertex heights h): a prism's waterline on its sides only
bool capsAcrossWaterline
(
    const PolyhedronView& P,
    int bottom,
    int top,
    const double* h
)
{
    const auto faces = P.faces();
    const int* faceVertices = P.faceVertices().data();
    const int* fb = faceVertices + faces[bottom].begin;
    for (int k = 0; k < faces[bottom].count; ++k)
    {
        if (!(h[fb[k]] < 0)) return false;
    }
    const int* ft = faceVertices + faces[top].begin;
    for (int k = 0; k < faces[top].count; ++k)
    {
        if (h[ft[k]] < 0) return false;
    }
    return true;
}

} // anonymous namespace


int truncatedPrismBottom
(
    const PolyhedronView& P,
    const Mat3& R,
    const double* h
)
{
    // The cap candidate: the face whose normal is nearest the vertical
    // (the bottom or the top of a floating floe, whatever its outline)
    const auto faces = P.faces();
    const int nf = static_cast<int>(faces.size());
    const Vec3 up = R.row(2).transpose();
    int cap0 = 0;
    double best = -1;
    for (int f = 0; f < nf; ++f)
    {
        const double c = std::abs(up.dot(faces[f].normal));
        if (c > best)
        {
            best = c;
            cap0 = f;
        }
    }
    const Vec3& axis = faces[cap0].normal;
    int cap1 = -1;
    for (int f = 0; f < nf; ++f)
    {
        if (f == cap0) continue;
        const double d = faces[f].normal.dot(axis);
        if (d < -1 + prismTolerance && cap1 < 0)
        {
            cap1 = f;
        }
        else if (std::abs(d) > prismTolerance)
        {
            return -1;
        }
    }
    if (cap1 < 0)
    {
        return -1;
    }
    // The lower cap entirely below, the upper one not at all
    const double nz = up.dot(axis);
    const int bottom = nz < 0 ? cap0 : cap1;
    const int top = nz < 0 ? cap1 : cap0;
    return capsAcrossWaterline(P, bottom, top, h) ? bottom : -1;
}


SubmergedVolume submergedVolume
(
    const PolyhedronView& P,
    const Mat3& R,
    const Vec3& x,
    double level
)
{
    const auto V = P.vertices();
    const int nv = static_cast<int>(V.size());
    if (nv > maxClipVertices)
    {
        return submergedVolumeByTetrahedra(P, R, x, level);
    }

    SubmergedVolume result;
    result.volume = 0;
    result.centroid = x;

    // World-frame vertices relative to x (round-off scales with the size of
    // the body, not with its distance from the origin) and their heights
    // h = z - level
    Vec3 r[maxClipVertices];
    double h[maxClipVertices];
    const double h0 = x.z() - level;
    double hMin = std::numeric_limits<double>::max();
    double hMax = -hMin;
    for (int k = 0; k < nv; ++k)
    {
        r[k] = R*V[k];
        h[k] = r[k].z() + h0;
        hMin = std::min(hMin, h[k]);
        hMax = std::max(hMax, h[k]);
    }
    if (!(hMin < 0))
    {
        return result;
    }
    if (hMax < 0)
    {
        // Entirely below: every face counts, and the sums above cancel to
        // the body's own volume; the tetrahedra give it without the
        // cancellation
        return submergedVolumeByTetrahedra(P, R, x, level);
    }

    const int nf = static_cast<int>(P.faces().size());

    // A right prism (a floating floe) cut across its sides only: the
    // truncated prism
    {
        const int bottom = truncatedPrismBottom(P, R, h);
        if (bottom >= 0)
        {
            return truncatedPrismVolume(P, R, r, h, bottom, x);
        }
    }

    constexpr int cap = SubmergedFace::maxVertices;
    Vec3 p[cap];
    double s[cap];
    Vec3 q[cap];
    double hq[cap];

    WetVolumeSums sums;
    for (int f = 0; f < nf; ++f)
    {
        const int n = P.faces()[f].count;
        if (n + 1 > cap)
        {
            return submergedVolumeByTetrahedra(P, R, x, level);
        }
        int nBelow = 0;
        for (int k = 0; k < n; ++k)
        {
            const int v = P.faceVertex(f, k);
            p[k] = r[v];
            s[k] = h[v];
            nBelow += s[k] < 0;
        }
        if (nBelow == 0)
        {
            continue;
        }
        // A face entirely below is its own clipped polygon
        const bool whole = nBelow == n;
        const int m = whole ? n : clipNegative(p, s, n, q, hq);
        sums.add(whole ? p : q, whole ? s : hq, m);
    }
    return sums.result(x, h0);
}


int lowerCapBelow
(
    const PrismCaps& caps,
    const PolyhedronView& P,
    const Mat3& R,
    const double* h
)
{
    // As truncatedPrismBottom with cap0 the kept cap[0]
    const Vec3 up = R.row(2).transpose();
    const double nz = up.dot(caps.cap[0].normal);
    const int k = nz < 0 ? 0 : 1;
    return
        capsAcrossWaterline(P, caps.cap[k].face, caps.cap[1 - k].face, h)
      ? k : -1;
}


SubmergedVolume truncatedPrismVolume
(
    const FacePlane& bottom,
    const Mat3& R,
    const Vec3& x,
    double level
)
{
    // truncatedPrismVolume's integrals over the cap, with the height linear
    // on it: h = hc + gX X + gY Y (X, Y the cap's coordinates about its
    // centroid c, whose first moments vanish), r = c + X ex + Y ey:
    //   int h dA = A hc,
    //   int h r dA = A hc c + (gX Mxx + gY Mxy) ex + (gX Mxy + gY Myy) ey,
    //   int h^2 dA = A hc^2 + gX^2 Mxx + 2 gX gY Mxy + gY^2 Myy
    SubmergedVolume result;
    result.volume = 0;
    result.centroid = x;
    const Vec3 ex = R*bottom.ex;
    const Vec3 ey = R*bottom.ey;
    const Vec3 c = R*bottom.centroid;
    const Vec3 nb = R*bottom.normal;
    const double az = -nb.z();
    const double A = bottom.area;
    const double Mxx = bottom.moment2[0];
    const double Mxy = bottom.moment2[1];
    const double Myy = bottom.moment2[2];
    const double hc = c.z() + (x.z() - level);
    const double gX = ex.z(), gY = ey.z();
    const double I0 = A*hc;
    const Vec3 I1 =
        (A*hc)*c + (gX*Mxx + gY*Mxy)*ex + (gX*Mxy + gY*Myy)*ey;
    const double I2 =
        A*hc*hc + gX*gX*Mxx + 2*gX*gY*Mxy + gY*gY*Myy;
    const double vol = -I0/az;
    if (vol > 0)
    {
        result.volume = vol;
        result.centroid = x + (-I1/az - (0.5*I2/(az*az))*nb)/vol;
    }
    return result;
}


SubmergedVolume truncatedPrismVolume
(
    const PolyhedronView& P,
    const Mat3& R,
    const Vec3* r,
    const double* h,
    int bottom,
    const Vec3& x
)
{
    // With the field h a (a the prism's axis, out of the bottom cap), the
    // sides (a.n = 0) drop out of the divergence theorem as the water plane
    // does: a length l = -h/a_z along a above every bottom point,
    //   V = int_bottom l dA,  int r dV = int_bottom (r l + a l^2/2) dA.
    SubmergedVolume result;
    result.volume = 0;
    result.centroid = x;
    const Vec3 nb = R*P.faces()[bottom].normal;
    const double az = -nb.z();
    const int n = P.faces()[bottom].count;
    const int* fv = P.faceVertices().data() + P.faces()[bottom].begin;
    const Vec3& a = r[fv[0]];
    const double ha = h[fv[0]];
    double I0 = 0, I2 = 0;
    Vec3 I1 = Vec3::Zero();
    for (int k = 1; k + 1 < n; ++k)
    {
        const int vb = fv[k];
        const int vc = fv[k + 1];
        const Vec3& b = r[vb];
        const Vec3& c = r[vc];
        const double hb = h[vb], hc = h[vc];
        const double A = 0.5*((b - a).cross(c - a)).dot(nb);
        const double sh = ha + hb + hc;
        I0 += A*sh/3.0;
        I1 += (A/12.0)*(ha*a + hb*b + hc*c + sh*(a + b + c));
        I2 += (A/6.0)*(ha*ha + hb*hb + hc*hc + ha*hb + hb*hc + hc*ha);
    }
    const double vol = -I0/az;
    if (vol > 0)
    {
        result.volume = vol;
        result.centroid = x + (-I1/az - (0.5*I2/(az*az))*nb)/vol;
    }
    return result;
}


void WetVolumeSums::add(const Vec3* q, const double* hq, int m)
{
    // Fan from vertex 0; (q1 - q0) x (q2 - q0) . e_z = 2 A n_z
    for (int k = 1; k + 1 < m; ++k)
    {
        const Vec3& a = q[0];
        const Vec3& b = q[k];
        const Vec3& c = q[k + 1];
        const double az =
            0.5*((b.x() - a.x())*(c.y() - a.y())
           - (b.y() - a.y())*(c.x() - a.x()));
        const double ha = hq[0], hb = hq[k], hc = hq[k + 1];
        const double sh = ha + hb + hc;
        vol += az*sh/3.0;
        first += (az/12.0)*(ha*a + hb*b + hc*c + sh*(a + b + c));
        second +=
            (az/12.0)*(ha*ha + hb*hb + hc*hc + ha*hb + hb*hc + hc*ha);
    }
}


SubmergedVolume WetVolumeSums::result(const Vec3& x, double h0) const
{
    SubmergedVolume out;
    out.volume = 0;
    out.centroid = x;
    if (vol > 0)
    {
        out.volume = vol;
        out.centroid =
            x + Vec3(first.x()/vol, first.y()/vol, second/vol - h0);
    }
    return out;
}


namespace
{

//- The part of face f strictly on the kept side of the plane z = level:
//  below (keepBelow) or above it. s is the height on the side cut away, so
//  the same clip serves both (negating s is exact)
bool clippedFace
(
    const PolyhedronView& P,
    int f,
    const Mat3& R,
    const Vec3& x,
    double level,
    bool keepBelow,
    SubmergedFace& out
)
{
    const PolyhedronView::Face face = P.faces()[f];
    const int n = face.count;
    if (n + 1 > SubmergedFace::maxVertices)
    {
        throw Error
        (
            "water-plane clipping: face " + std::to_string(f) + " has "
          + std::to_string(n) + " vertices, more than the capacity "
          + std::to_string(SubmergedFace::maxVertices - 1)
          + " of SubmergedFace::maxVertices - 1"
        );
    }

    out.face = f;
    out.nVertices = 0;
    out.area = 0;

    const auto V = P.vertices();

    // Sutherland-Hodgman against the half-space s < 0 (world frame)
    Vec3 prev = R*V[P.faceVertex(f, n - 1)] + x;
    double sPrev = keepBelow ? prev.z() - level : level - prev.z();
    for (int k = 0; k < n; ++k)
    {
        const Vec3 cur = R*V[P.faceVertex(f, k)] + x;
        const double sCur = keepBelow ? cur.z() - level : level - cur.z();
        if (sCur < 0)
        {
            if (sPrev >= 0)
            {
                out.vertices[out.nVertices++] = cut(cur, sCur, prev, sPrev);
            }
            out.vertices[out.nVertices++] = cur;
        }
        else if (sPrev < 0)
        {
            out.vertices[out.nVertices++] = cut(prev, sPrev, cur, sCur);
        }
        prev = cur;
        sPrev = sCur;
    }

    if (out.nVertices < 3)
    {
        out.nVertices = 0;
        return false;
    }

    // Area and centroid by a fan from the first vertex (exact for a planar
    // polygon)
    out.normal = R*face.normal;
    const Vec3& q0 = out.vertices[0];
    Vec3 first = Vec3::Zero();
    double area = 0;
    for (int k = 1; k + 1 < out.nVertices; ++k)
    {
        const Vec3& q1 = out.vertices[k];
        const Vec3& q2 = out.vertices[k + 1];
        const double a = 0.5*((q1 - q0).cross(q2 - q0)).dot(out.normal);
        area += a;
        first += (a/3.0)*(q0 + q1 + q2);
    }
    if (!(area > 0))
    {
        out.nVertices = 0;
        return false;
    }
    out.area = area;
    out.centroid = first/area;
    return true;
}

} // End anonymous namespace


bool submergedFace
(
    const PolyhedronView& P,
    int f,
    const Mat3& R,
    const Vec3& x,
    double level,
    SubmergedFace& out
)
{
    return clippedFace(P, f, R, x, level, true, out);
}


bool emergedFace
(
    const PolyhedronView& P,
    int f,
    const Mat3& R,
    const Vec3& x,
    double level,
    SubmergedFace& out
)
{
    return clippedFace(P, f, R, x, level, false, out);
}


int triangleSamples
(
    const Vec3& a,
    const Vec3& b,
    const Vec3& c,
    int subdivision,
    Vec3* points,
    double* areas
)
{
    const int n = 1 << subdivision;
    const double subArea = 0.5*((b - a).cross(c - a)).norm()/(n*n);
    const Vec3 e1 = (b - a)/n;
    const Vec3 e2 = (c - a)/n;

    // Sub-triangles on the barycentric grid of spacing 1/n: the upright
    // ones (i, j), (i+1, j), (i, j+1) for i + j <= n - 1 and the inverted
    // ones (i+1, j), (i, j+1), (i+1, j+1) for i + j <= n - 2
    int m = 0;
    for (int i = 0; i < n; ++i)
    {
        for (int j = 0; i + j < n; ++j)
        {
            points[m] = a + (i + 1.0/3.0)*e1 + (j + 1.0/3.0)*e2;
            areas[m] = subArea;
            ++m;
            if (i + j + 2 <= n)
            {
                points[m] = a + (i + 2.0/3.0)*e1 + (j + 2.0/3.0)*e2;
                areas[m] = subArea;
                ++m;
            }
        }
    }
    return m;
}


int faceTriangleSamples
(
    const SubmergedFace& s,
    int k,
    int subdivision,
    Vec3* points,
    double* areas
)
{
    const int k1 = (k + 1 == s.nVertices) ? 0 : k + 1;
    return triangleSamples
    (
        s.centroid,
        s.vertices[k],
        s.vertices[k1],
        subdivision,
        points,
        areas
    );
}


int faceSamples
(
    const SubmergedFace& s,
    int subdivision,
    Vec3* points,
    double* areas,
    int capacity
)
{
    const int total = faceSampleCount(s, subdivision);
    if (total > capacity)
    {
        throw Error
        (
            "water clipping: face " + std::to_string(s.face) + " needs "
          + std::to_string(total) + " sample points at subdivision "
          + std::to_string(subdivision) + ", more than the buffer capacity "
          + std::to_string(capacity) + "; lower the subdivision",
            "subdivision"
        );
    }

    const int per = samplesPerTriangle(subdivision);
    for (int k = 0; k < s.nVertices; ++k)
    {
        faceTriangleSamples(s, k, subdivision, points + k*per, areas + k*per);
    }
    return total;
}

} // namespace iceDEM
