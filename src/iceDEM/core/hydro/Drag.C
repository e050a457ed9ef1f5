/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "Drag.H"
#include "WaterClip.H"
#include "WaterFrame.H"

#include <cmath>
#include <string>
#include <vector>

namespace iceDEM
{

namespace
{

// Conical product rule on a triangle (apex a, edge b-c): p = a + t((1 - s)
// (b - a) + s (c - a)), dA = 2 A t dt ds, with 2-point Gauss-Jacobi in t
// (weight t on [0, 1]: nodes (6 -+ sqrt 6)/10, weights (9 -+ sqrt 6)/36)
// and 3-point Gauss-Legendre in s (weights 5/18, 8/18, 5/18 on [0, 1]):
// 6 points, exact for polynomials of degree 3. The skin integrand
// |u_t| u_t of a spin about the apex is t^2 g(s) with g smooth (|q| q along
// the edge): exact in t, and the moment of a square's spin-down within
// 5.5e-4 (2 points in s: 1.8e-2), tests/unit/test_drag.C.
constexpr double coneT[2] = {0.35505102572168219, 0.84494897427831781};
constexpr double coneWT[2] = {0.18195861825602283, 0.31804138174397717};
constexpr double coneS[3] =
    {0.11270166537925831, 0.5, 0.88729833462074169};
constexpr double coneWS[3] =
    {0.27777777777777778, 0.44444444444444444, 0.27777777777777778};

} // anonymous namespace


namespace
{

//- Area and centroid of the planar polygon q[0..m) (normal n); false for
//  no positive area
bool polygonCentroid
(
    const Vec3* q,
    int m,
    const Vec3& n,
    double& area,
    Vec3& centroid
)
{
    centroid.setZero();
    area = 0;
    for (int k = 1; k + 1 < m; ++k)
    {
        const double a = 0.5*((q[k] - q[0]).cross(q[k + 1] - q[0])).dot(n);
        area += a;
        centroid += (a/3.0)*(q[0] + q[k] + q[k + 1]);
    }
    if (!(area > 0)) return false;
    centroid /= area;
    return true;
}

//- The tangential part of u on a plane of unit normal n
inline Vec3 tangential(const Vec3& u, const Vec3& n)
{
    return u - u.dot(n)*n;
}

//- The preamble of the skin integrals: zeroes I and Ir and finds the
//  centroid of the polygon q[0..m) (normal n); false for a polygon of fewer
//  than 3 or more than SubmergedFace::maxVertices + 1 vertices or of no
//  positive area
bool skinPolygon
(
    const Vec3* q,
    int m,
    const Vec3& n,
    Vec3& I,
    Vec3& Ir,
    Vec3& centroid
)
{
    I.setZero();
    Ir.setZero();
    double area;
    return
        m >= 3 && m <= SubmergedFace::maxVertices + 1
     && polygonCentroid(q, m, n, area, centroid);
}

} // anonymous namespace


bool skinIntegralConical
(
    const Vec3* q,
    int m,
    const Vec3& n,
    const Vec3& w,
    const Vec3& omega,
    Vec3& I,
    Vec3& Ir
)
{
    Vec3 centroid;
    if (!skinPolygon(q, m, n, I, Ir, centroid)) return false;

    // u_t is linear: its value at the centroid and its change towards each
    // vertex (e_k = q_k - centroid)
    Vec3 e[SubmergedFace::maxVertices + 1];
    Vec3 du[SubmergedFace::maxVertices + 1];
    const Vec3 utc = tangential(w + omega.cross(centroid), n);
    for (int k = 0; k < m; ++k)
    {
        e[k] = q[k] - centroid;
        du[k] = tangential(omega.cross(e[k]), n);
    }
    Vec3 M = Vec3::Zero();
    for (int k = 0; k < m; ++k)
    {
        const int k1 = k + 1 == m ? 0 : k + 1;
        const Vec3& eb = e[k];
        const Vec3& ec = e[k1];
        const double A2 = (eb.cross(ec)).dot(n);
        // Sum of the integrand and of its moments about the centroid, as
        // eb x Gb + ec x Gc
        Vec3 It = Vec3::Zero(), Gb = Vec3::Zero(), Gc = Vec3::Zero();
        for (int i = 0; i < 2; ++i)
        {
            for (int j = 0; j < 3; ++j)
            {
                const double tb = coneT[i]*(1 - coneS[j]);
                const double tc = coneT[i]*coneS[j];
                const Vec3 ut = utc + tb*du[k] + tc*du[k1];
                const double wgt = A2*coneWT[i]*coneWS[j];
                const Vec3 dI = (wgt*ut.norm())*ut;
                It += dI;
                Gb += tb*dI;
                Gc += tc*dI;
            }
        }
        I += It;
        M += eb.cross(Gb) + ec.cross(Gc);
    }
    Ir = M + centroid.cross(I);
    return true;
}


namespace
{

//- A polygon in its plane's axes, for the skin integrals: ex (any unit
//  vector across n) and ey = n x ex, the vertices' coordinates (x, y)
//  relative to the centroid, the centroid (in q's frame) and the largest
//  squared centroid-vertex distance. The integrands are functions of the
//  position in the plane, so two coordinates a vertex carry them: an
//  edge's outward normal is tau x n = (tau_y, -tau_x), no cross product
struct SkinPlane
{
    static constexpr int cap = SubmergedFace::maxVertices + 1;
    Vec3 ex, ey;
    Vec3 centroid;
    int m = 0;
    double x[cap], y[cap];
    double a2 = 0;

    //- The point of the plane at (u, v) from the centroid
    Vec3 inPlane(double u, double v) const { return u*ex + v*ey; }
};

//- The plane of the polygon q[0..m) (normal n); false for fewer than 3 or
//  more than SubmergedFace::maxVertices + 1 vertices or no positive area
bool skinPlane(const Vec3* q, int m, const Vec3& n, SkinPlane& P)
{
    if (m < 3 || m > SkinPlane::cap) return false;
    P.m = m;
    P.ex = n.unitOrthogonal();
    P.ey = n.cross(P.ex);
    // Coordinates from q[0], then the fan's area and centroid from there
    for (int k = 0; k < m; ++k)
    {
        const Vec3 e = q[k] - q[0];
        P.x[k] = e.dot(P.ex);
        P.y[k] = e.dot(P.ey);
    }
    double A2 = 0, cx = 0, cy = 0;
    for (int k = 1; k + 1 < m; ++k)
    {
        const double a = P.x[k]*P.y[k + 1] - P.x[k + 1]*P.y[k];
        A2 += a;
        cx += a*(P.x[k] + P.x[k + 1]);
        cy += a*(P.y[k] + P.y[k + 1]);
    }
    if (!(A2 > 0)) return false;
    cx /= 3*A2;
    cy /= 3*A2;
    P.centroid = q[0] + P.inPlane(cx, cy);
    P.a2 = 0;
    for (int k = 0; k < m; ++k)
    {
        P.x[k] -= cx;
        P.y[k] -= cy;
        P.a2 = std::max(P.a2, P.x[k]*P.x[k] + P.y[k]*P.y[k]);
    }
    return true;
}

//- The skin integrals in closed form (skinIntegralClosedForm) on the plane
//  P of normal n; U = (Ux, Uy) the tangential velocity at the centroid,
//  Om = omega.n (nonzero)
void skinClosedForm
(
    const SkinPlane& P,
    const Vec3& n,
    double Ux,
    double Uy,
    double Om,
    Vec3& I,
    Vec3& Ir
)
{
    // On the plane, u_t = U + Omega n x e (e from the centroid): a rotation
    // by Omega about the point e0 = n x U/Omega, so with d = e - e0,
    // |u_t| u_t = Omega |Omega| |d| n x d and
    //   int |u_t| u_t dA = Omega |Omega| n x G,   G = int |d| d dA,
    //   int e x |u_t| u_t dA = Omega |Omega| (e0 x (n x G) + n H),
    //   H = int |d|^3 dA.
    // By the divergence theorem (|d| d = grad |d|^3/3, div(d |d|^3) =
    // 5 |d|^3) both are sums over the edges of J = int_edge |d|^3 ds:
    //   G = 1/3 sum J nu,   H = 1/5 sum J p,
    // nu the edge's outward normal, p = d.nu its distance from e0, and with
    // t along the edge, r = |d| = sqrt(t^2 + p^2):
    //   J = [t r^3/4 + 3 p^2 t r/8 + 3 p^4/8 asinh(t/|p|)] between its ends.
    // In the plane's axes n x (a, b) = (-b, a): e0 = (-Uy, Ux)/Omega
    const double e0x = -Uy/Om, e0y = Ux/Om;
    const int m = P.m;
    double dx[SkinPlane::cap], dy[SkinPlane::cap], r[SkinPlane::cap];
    for (int k = 0; k < m; ++k)
    {
        dx[k] = P.x[k] - e0x;
        dy[k] = P.y[k] - e0y;
        r[k] = std::sqrt(dx[k]*dx[k] + dy[k]*dy[k]);
    }
    double Gx = 0, Gy = 0, H = 0;
    for (int k = 0; k < m; ++k)
    {
        const int k1 = k + 1 == m ? 0 : k + 1;
        const double Ex = dx[k1] - dx[k], Ey = dy[k1] - dy[k];
        const double L2 = Ex*Ex + Ey*Ey;
        if (!(L2 > 0)) continue;
        const double invL = 1/std::sqrt(L2);
        const double tx = Ex*invL, ty = Ey*invL;
        const double p = dx[k]*ty - dy[k]*tx;
        const double p2 = p*p;
        const double t1 = dx[k]*tx + dy[k]*ty, t2 = dx[k1]*tx + dy[k1]*ty;
        const double r1 = r[k], r2 = r[k1];
        double J =
            0.25*(t2*r2*r2*r2 - t1*r1*r1*r1)
          + 0.375*p2*(t2*r2 - t1*r1);
        if (p2 > 0)
        {
            // asinh(t2/|p|) - asinh(t1/|p|) = log(f(t2)/f(t1)) with
            // f = t + r, written p^2/(r - t) for t < 0 (no cancellation).
            // An end on the centre of rotation (a floe turning about its
            // vertex) has f = 0 and r = 0: p is round-off there and the
            // term's limit zero (it was log(0), a floating-point trap)
            const double f1 = t1 >= 0 ? t1 + r1 : p2/(r1 - t1);
            const double f2 = t2 >= 0 ? t2 + r2 : p2/(r2 - t2);
            if (f1 > 0 && f2 > 0) J += 0.375*p2*p2*std::log(f2/f1);
        }
        // nu = (ty, -tx); the sums' 1/3 and 1/5 after the loop
        Gx += J*ty;
        Gy -= J*tx;
        H += J*p;
    }
    Gx /= 3.0;
    Gy /= 3.0;
    H /= 5.0;
    const double s = Om*std::abs(Om);
    // n x G = (-Gy, Gx); e0 x (n x G) = (e0.G) n
    I = s*P.inPlane(-Gy, Gx);
    Ir = P.centroid.cross(I) + (s*(e0x*Gx + e0y*Gy + H))*n;
}

//- The skin integrals' expansion about the centroid's velocity
//  (skinIntegralExpansion) on the plane P of normal n; U = (Ux, Uy) the
//  tangential velocity at the centroid (nonzero), Om = omega.n
void skinExpansion
(
    const SkinPlane& P,
    const Vec3& n,
    double Ux,
    double Uy,
    double Om,
    Vec3& I,
    Vec3& Ir
)
{
    // On the plane u_t = U + Omega n x e (e from the centroid). In the
    // axes eu = U/|U|, ev = n x eu (e = x eu + y ev) and with c = Omega/|U|,
    // u_t/|U| = (1 + d_u) eu + d_v ev, d_u = -c y, d_v = c x, and exactly
    //   |u_t| u_t/|U|^2 = p sqrt(p^2 + d_v^2) eu + d_v sqrt(p^2 + d_v^2) ev,
    // p = 1 + d_u. Expanded in d (|d| <= |c| a):
    //   eu: p^2 + d_v^2/2        (error -d_v^4/(8 p^2))
    //   ev: d_v p + d_v^3/2      (error about -d_u d_v^3/2),
    // a cubic in (x, y) whose integrals over the polygon are its moments
    // about the centroid (first moments zero), up to the fourth for the
    // moment e x |u_t| u_t:
    //   I/|U|^2 = (A + c^2 (Syy + Sxx/2)) eu + (c^3 Sxxx/2 - c^2 Sxy) ev,
    //   n.int e x |u_t| u_t dA/|U|^2
    //     = c (Sxx + 2 Syy) - c^2 (3/2 Sxxy + Syyy) + c^3 Sxxxx/2.
    // Relative error at most about 5/8 (|c| a)^4 (a the largest centroid-
    // vertex distance): 6e-9 where skinIntegral takes it (|c| a < 1/100).
    const double s2 = Ux*Ux + Uy*Uy;
    const double s = std::sqrt(s2);
    // eu and ev = n x eu in the plane's axes
    const double eux = Ux/s, euy = Uy/s;
    const double c = Om/s;

    // The polygon's moments about its centroid by its edges: each edge and
    // the centroid span a triangle of twice-area D, over which
    // int x^k dA = D/((k + 1)(k + 2)) sum_{i=0..k} x0^i x1^(k-i)
    const int m = P.m;
    double x0 = P.x[m - 1]*eux + P.y[m - 1]*euy;
    double y0 = P.y[m - 1]*eux - P.x[m - 1]*euy;
    double A2 = 0, Sxx = 0, Syy = 0, Sxy = 0, Sxxx = 0, Sxxy = 0, Syyy = 0,
        Sxxxx = 0;
    for (int k = 0; k < m; ++k)
    {
        const double x1 = P.x[k]*eux + P.y[k]*euy;
        const double y1 = P.y[k]*eux - P.x[k]*euy;
        const double D = x0*y1 - x1*y0;
        const double xx0 = x0*x0, xx1 = x1*x1, x01 = x0*x1;
        const double yy0 = y0*y0, yy1 = y1*y1;
        A2 += D;
        Sxx += D*(xx0 + x01 + xx1);
        Syy += D*(yy0 + y0*y1 + yy1);
        Sxy += D*(2*x0*y0 + x0*y1 + x1*y0 + 2*x1*y1);
        Sxxx += D*(x0 + x1)*(xx0 + xx1);
        Sxxy += D*
        (
            xx0*(3*y0 + y1) + 2*x01*(y0 + y1) + xx1*(y0 + 3*y1)
        );
        Syyy += D*(y0 + y1)*(yy0 + yy1);
        Sxxxx += D*(xx0*xx0 + x01*(xx0 + x01 + xx1) + xx1*xx1);
        x0 = x1;
        y0 = y1;
    }
    const double A = 0.5*A2;
    Sxx /= 12;
    Syy /= 12;
    Sxy /= 24;
    Sxxx /= 20;
    Sxxy /= 60;
    Syyy /= 20;
    Sxxxx /= 30;

    const double c2 = c*c;
    const double Iu = s2*(A + c2*(Syy + 0.5*Sxx));
    const double Iv = s2*(c2*(0.5*c*Sxxx - Sxy));
    // Iu eu + Iv ev, ev = (-euy, eux)
    I = P.inPlane(Iu*eux - Iv*euy, Iu*euy + Iv*eux);
    const double Mn = s2*
    (
        c*(Sxx + 2*Syy) - c2*(1.5*Sxxy + Syyy) + 0.5*c2*c*Sxxxx
    );
    Ir = P.centroid.cross(I) + Mn*n;
}

//- The tangential velocity at the plane's centroid in its axes, and
//  Omega = omega.n
inline void centroidVelocity
(
    const SkinPlane& P,
    const Vec3& n,
    const Vec3& w,
    const Vec3& omega,
    double& Ux,
    double& Uy,
    double& Om
)
{
    const Vec3 u = w + omega.cross(P.centroid);
    Ux = u.dot(P.ex);
    Uy = u.dot(P.ey);
    Om = omega.dot(n);
}

} // anonymous namespace


bool skinIntegralExpansion
(
    const Vec3* q,
    int m,
    const Vec3& n,
    const Vec3& w,
    const Vec3& omega,
    Vec3& I,
    Vec3& Ir
)
{
    I.setZero();
    Ir.setZero();
    SkinPlane P;
    if (!skinPlane(q, m, n, P)) return false;
    double Ux, Uy, Om;
    centroidVelocity(P, n, w, omega, Ux, Uy, Om);
    // No tangential velocity at the centroid: the expansion has no axis
    // (skinIntegral takes it only where the spin about n vanishes too, and
    // then u_t vanishes on the polygon)
    if (!(Ux*Ux + Uy*Uy > 0)) return true;
    skinExpansion(P, n, Ux, Uy, Om, I, Ir);
    return true;
}


bool skinIntegralClosedForm
(
    const Vec3* q,
    int m,
    const Vec3& n,
    const Vec3& w,
    const Vec3& omega,
    Vec3& I,
    Vec3& Ir
)
{
    I.setZero();
    Ir.setZero();
    SkinPlane P;
    if (!skinPlane(q, m, n, P)) return false;
    double Ux, Uy, Om;
    centroidVelocity(P, n, w, omega, Ux, Uy, Om);
    if (Om == 0) return false;
    skinClosedForm(P, n, Ux, Uy, Om, I, Ir);
    return true;
}


bool skinIntegral
(
    const Vec3* q,
    int m,
    const Vec3& n,
    const Vec3& w,
    const Vec3& omega,
    Vec3& I,
    Vec3& Ir
)
{
    // The closed form loses (D/a)^2 of precision in the moment when the
    // centre of rotation is D far from a polygon of size a; there the field
    // is nearly uniform and its expansion about the centroid's velocity
    // errs by at most about 5/8 (a/D)^4 (skinExpansion)
    I.setZero();
    Ir.setZero();
    SkinPlane P;
    if (!skinPlane(q, m, n, P)) return false;
    double Ux, Uy, Om;
    centroidVelocity(P, n, w, omega, Ux, Uy, Om);
    const double D2 = Ux*Ux + Uy*Uy;
    const double k2 = skinUniformRatio*skinUniformRatio;
    if (Om*Om*P.a2*k2 > D2)
    {
        skinClosedForm(P, n, Ux, Uy, Om, I, Ir);
    }
    else if (D2 > 0)
    {
        skinExpansion(P, n, Ux, Uy, Om, I, Ir);
    }
    return true;
}


void addFacetDrag
(
    const Vec3* q,
    int m,
    double nx,
    double ny,
    double nz,
    bool skin,
    double coeff,
    const Vec3& w,
    const Vec3& omega,
    Vec3& F,
    Vec3& M
)
{
    const Vec3 nrm(nx, ny, nz);
    if (skin)
    {
        // Skin drag |u_t| u_t: not a polynomial, but in closed form for a
        // rigid-body field (skinIntegral)
        Vec3 I, Ir;
        if (skinIntegral(q, m, nrm, w, omega, I, Ir))
        {
            F -= coeff*I;
            M -= coeff*Ir;
        }
        return;
    }

    // Form drag where the facet leads: u_n = (w + omega x r).n is linear,
    // so the leading part is the polygon clipped at u_n = 0 and
    // int u_n^2 dA, int r u_n^2 dA are exact on its fan triangles: with
    // vertex values f_i, S = sum f_i, Q = sum_{i<=j} f_i f_j,
    // int lambda_i f^2 dA = A/30 (Q + f_i (f_i + S)) (barycentric lambda_i)
    constexpr int cap = SubmergedFace::maxVertices + 1;
    double s[cap];
    Vec3 lead[cap + 1];
    double sl[cap + 1];
    int nLead = 0;
    // u_n = w.n + (omega x r).n = w.n + r.(n x omega): one dot per vertex
    const double wn = w.dot(nrm);
    const Vec3 nxo = nrm.cross(omega);
    for (int k = 0; k < m; ++k)
    {
        s[k] = -(wn + q[k].dot(nxo));
        nLead += s[k] < 0;
    }
    if (nLead == 0)
    {
        return;
    }
    // Leading everywhere: the polygon itself
    int ml = m;
    const Vec3* lp = q;
    const double* ls = s;
    if (nLead < m)
    {
        ml = clipNegative(q, s, m, lead, sl);
        lp = lead;
        ls = sl;
    }
    double I = 0;
    Vec3 Ir = Vec3::Zero();
    for (int k = 1; k + 1 < ml; ++k)
    {
        const Vec3& a = lp[0];
        const Vec3& bb = lp[k];
        const Vec3& c = lp[k + 1];
        const double A = 0.5*((bb - a).cross(c - a)).dot(nrm);
        const double fa = -ls[0], fb = -ls[k], fc = -ls[k + 1];
        const double S = fa + fb + fc;
        const double Q =
            fa*fa + fb*fb + fc*fc + fa*fb + fb*fc + fc*fa;
        const double wa = A/30.0*(Q + fa*(fa + S));
        const double wb = A/30.0*(Q + fb*(fb + S));
        const double wc = A/30.0*(Q + fc*(fc + S));
        I += wa + wb + wc;
        Ir += wa*a + wb*bb + wc*c;
    }
    F -= (coeff*I)*nrm;
    M -= coeff*Ir.cross(nrm);
}


DragIntegration dragIntegrationFromName(const std::string& name)
{
    if (name == "exact") return DragIntegration::exact;
    if (name == "sampled") return DragIntegration::sampled;
    throw Error
    (
        "drag: integration '" + name + "' is not one of: exact sampled",
        "integration"
    );
}


void checkDragSettings(const DragSettings& s)
{
    if (!(s.formCoefficient >= 0) || !std::isfinite(s.formCoefficient))
    {
        throw Error
        (
            "drag: formCoefficient " + std::to_string(s.formCoefficient)
          + " must be zero or positive",
            "formCoefficient"
        );
    }
    if (!(s.skinCoefficient >= 0) || !std::isfinite(s.skinCoefficient))
    {
        throw Error
        (
            "drag: skinCoefficient " + std::to_string(s.skinCoefficient)
          + " must be zero or positive",
            "skinCoefficient"
        );
    }
    if (s.subdivision < 0 || s.subdivision > DragSettings::maxSubdivision)
    {
        throw Error
        (
            "drag: subdivision " + std::to_string(s.subdivision)
          + " must be in 0.." + std::to_string(DragSettings::maxSubdivision)
          + " (4^subdivision sample points per facet triangle)",
            "subdivision"
        );
    }
    if (!(s.bottomCosine > 0 && s.bottomCosine <= 1))
    {
        throw Error
        (
            "drag: bottomCosine " + std::to_string(s.bottomCosine)
          + " must be in (0, 1]",
            "bottomCosine"
        );
    }
}


Drag::Drag
(
    const WaterSettings& water,
    const DragSettings& settings,
    std::shared_ptr<const FlowVelocity> flow
)
:
    water_(water),
    settings_(settings),
    flow_(std::move(flow))
{
    checkWaterSettings(water_);
    checkDragSettings(settings_);
    if (!flow_)
    {
        throw Error("drag: no water velocity model given", "type");
    }
}


const char* Drag::name() const
{
    return "drag";
}


double Drag::facetCoefficient(const Vec3& n, bool& skin) const
{
    skin = std::abs(n.z()) >= settings_.bottomCosine;
    const double halfRho = 0.5*water_.density;
    return
        halfRho
       *(skin ? settings_.skinCoefficient : settings_.formCoefficient);
}


void Drag::bodyDrag(const World& world, int i, Vec3& F, Vec3& M) const
{
    constexpr int capacity = 1 << (2*DragSettings::maxSubdivision);

    F.setZero();
    M.setZero();

    const Body& b = world.bodies()[i];
    // This thread's room for derived outer polyhedra (no allocation once
    // it has grown to the largest floe)
    static thread_local PolyhedronBuffer outerBuffer;
    const PolyhedronView P = world.shapeOf(i).outer(outerBuffer);

    Vec3 current;
    if
    (
        settings_.integration == DragIntegration::exact
     && flow_->uniform(current)
    )
    {
        // The floe's frame, shared with buoyancy and floe damping (its R
        // is b.rotation() at this pose, bit for bit)
        const WaterFrame& frame = waterFrame(world, i, water_.level);
        if (frame.valid())
        {
            if (!frame.wet()) return;
            frameDrag(P, frame, b, b.omega(frame.R), current, F, M);
            return;
        }
    }
    const Mat3 R = b.rotation();
    const Vec3 omega = b.omega(R);

    // Two-way coupling: the drag per face for the flow (this thread's
    // buffers grow to the largest floe once, then allocate nothing)
    const bool collect = flow_->collectsFaceForces();
    static thread_local std::vector<Vec3> faceF;
    static thread_local std::vector<double> faceK;

    // Nothing below the water plane: no drag
    {
        const Vec3 up = R.row(2).transpose();
        bool wet = false;
        for (const Vec3& v : P.vertices())
        {
            if (up.dot(v) + b.x.z() < water_.level)
            {
                wet = true;
                break;
            }
        }
        if (!wet)
        {
            if (collect)
            {
                flow_->faceForces(i, 0, nullptr, nullptr);
            }
            return;
        }
    }

    const int nf = static_cast<int>(P.faces().size());
    if (collect)
    {
        if (int(faceF.size()) < nf)
        {
            faceF.resize(nf);
            faceK.resize(nf);
        }
        for (int f = 0; f < nf; ++f)
        {
            faceF[f].setZero();
            faceK[f] = 0;
        }
    }

    const int sub = settings_.subdivision;

    SubmergedFace face;
    Vec3 points[capacity];
    double areas[capacity];
    Vec3 u[capacity];

    for (int f = 0; f < nf; ++f)
    {
        if (!submergedFace(P, f, R, b.x, water_.level, face))
        {
            continue;
        }

        const Vec3& n = face.normal;
        bool skin;
        const double coeff = facetCoefficient(n, skin);
        if (coeff == 0)
        {
            continue;
        }

        for (int k = 0; k < face.nVertices; ++k)
        {
            const int m = faceTriangleSamples(face, k, sub, points, areas);
            flow_->velocity(i, points, m, u);

            for (int j = 0; j < m; ++j)
            {
                const Vec3 r = points[j] - b.x;
                const Vec3 ur = b.v + omega.cross(r) - u[j];
                const double un = ur.dot(n);

                Vec3 dF;
                double k;   // dF = -k u_r (skin), -k u_n n (form)
                if (skin)
                {
                    const Vec3 ut = ur - un*n;
                    k = coeff*areas[j]*ut.norm();
                    dF = -k*ut;
                }
                else if (un > 0)
                {
                    k = coeff*areas[j]*un;
                    dF = (-k*un)*n;
                }
                else
                {
                    continue;
                }
                F += dF;
                M += r.cross(dF);
                if (collect)
                {
                    faceF[f] += dF;
                    faceK[f] += k;
                }
            }
        }
    }

    if (collect)
    {
        flow_->faceForces(i, nf, faceF.data(), faceK.data());
    }
}


void Drag::frameDrag
(
    const PolyhedronView& P,
    const WaterFrame& frame,
    const Body& b,
    const Vec3& omega,
    const Vec3& current,
    Vec3& F,
    Vec3& M
) const
{
    F.setZero();
    M.setZero();
    if (!frame.wet())
    {
        return;
    }

    // Velocity relative to the water: w + omega x r, linear over a face
    const Vec3 w = b.v - current;

    // The wet polygons (vertices relative to the centroid)
    addPolygonsDrag
    (
        P, frame.R, frame.nWet, frame.wetFace, frame.wetBegin,
        frame.wetVertex, w, omega,
        [this](const Vec3& n, bool& skin)
        {
            return facetCoefficient(n, skin);
        },
        F, M
    );
}


void Drag::addForces
(
    const World& world,
    int begin,
    int end,
    Vec3* force,
    Vec3* torque
) const
{
    addFreeBodyForces
    (
        world, begin, end, force, torque,
        [&](int i, Vec3& F, Vec3& M) { bodyDrag(world, i, F, M); }
    );
}

} // namespace iceDEM
