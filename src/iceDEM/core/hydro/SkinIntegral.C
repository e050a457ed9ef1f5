/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "SkinIntegral.H"

#include <algorithm>
#include <cmath>

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

//- The tangential part of u on a plane of unit normal n
inline Vec3 tangential(const Vec3& u, const Vec3& n)
{
    return u - u.dot(n)*n;
}

//- A polygon in its plane's axes, for the skin integrals: ex (any unit
//  vector across n) and ey = n x ex, the vertices' coordinates (x, y)
//  relative to the centroid, the centroid (in the polygon's frame) and the
//  largest squared centroid-vertex distance. The integrands are functions
//  of the position in the plane, so two coordinates a vertex carry them: an
//  edge's outward normal is tau x n = (tau_y, -tau_x), no cross product.
//  The coordinates are a world polygon's (skinPlane) or a whole face's,
//  kept in the body frame (FacePlane)
struct PlaneView
{
    const double* x;
    const double* y;
    //- The edges' unit tangents (edge k from vertex k to k + 1), kept with
    //  a whole face's plane (FacePlane); null: the closed form finds them
    const double* tx = nullptr;
    const double* ty = nullptr;
    int m;
    Vec3 ex, ey;
    Vec3 centroid;
    double a2;

    //- The vector of the plane of components (u, v)
    Vec3 inPlane(double u, double v) const { return u*ex + v*ey; }
};

//- Room for a world polygon's coordinates
constexpr int planeCapacity = SubmergedFace::maxVertices + 1;

//- The plane of the polygon q[0..m) (normal n), its coordinates into x and
//  y; false for fewer than 3 or more than planeCapacity vertices or no
//  positive area
bool skinPlane
(
    const Vec3* q,
    int m,
    const Vec3& n,
    double* x,
    double* y,
    PlaneView& P
)
{
    if (m > planeCapacity) return false;
    P.x = x;
    P.y = y;
    P.m = m;
    return planeCoordinates(q, m, n, x, y, P.ex, P.ey, P.centroid, P.a2);
}


//- The skin integrals in closed form (skinIntegralClosedForm) on the plane
//  P of normal n; U = (Ux, Uy) the tangential velocity at the centroid,
//  Om = omega.n (nonzero)
void skinClosedForm
(
    const PlaneView& P,
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
    // The edges' tangents do not depend on e0: a whole face keeps them
    double txFound[planeCapacity], tyFound[planeCapacity];
    const double* tk = P.tx;
    const double* tl = P.ty;
    if (!tk)
    {
        edgeTangents(P.x, P.y, m, txFound, tyFound);
        tk = txFound;
        tl = tyFound;
    }
    double dx[planeCapacity], dy[planeCapacity], r[planeCapacity];
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
        const double tx = tk[k], ty = tl[k];
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

//- A polygon's area and moments about its centroid in the axes eu, ev of
//  the skin expansion (x along eu, y along ev)
struct AxisMoments
{
    double A, Sxx, Syy, Sxy, Sxxx, Sxxy, Syyy, Sxxxx;
};

//- The skin integrals' expansion about the centroid's velocity
//  (skinIntegralExpansion) on the plane P of normal n with the moments S
//  in the axes eu = (eux, euy), ev = n x eu of the plane; s2 = |U|^2
//  (nonzero) and c = Omega/|U|
void expansionIntegrals
(
    const PlaneView& P,
    const Vec3& n,
    double s2,
    double eux,
    double euy,
    double c,
    const AxisMoments& S,
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
    const double c2 = c*c;
    const double Iu = s2*(S.A + c2*(S.Syy + 0.5*S.Sxx));
    const double Iv = s2*(c2*(0.5*c*S.Sxxx - S.Sxy));
    // Iu eu + Iv ev, ev = (-euy, eux)
    I = P.inPlane(Iu*eux - Iv*euy, Iu*euy + Iv*eux);
    const double Mn = s2*
    (
        c*(S.Sxx + 2*S.Syy) - c2*(1.5*S.Sxxy + S.Syyy) + 0.5*c2*c*S.Sxxxx
    );
    Ir = P.centroid.cross(I) + Mn*n;
}

//- The expansion (expansionIntegrals) with the moments summed over the
//  polygon's edges; U = (Ux, Uy) the tangential velocity at the centroid
//  (nonzero), Om = omega.n
void skinExpansion
(
    const PlaneView& P,
    const Vec3& n,
    double Ux,
    double Uy,
    double Om,
    Vec3& I,
    Vec3& Ir
)
{
    const double s2 = Ux*Ux + Uy*Uy;
    const double s = std::sqrt(s2);
    // eu and ev = n x eu in the plane's axes
    const double eux = Ux/s, euy = Uy/s;

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
    const AxisMoments S
    {
        0.5*A2, Sxx/12, Syy/12, Sxy/24, Sxxx/20, Sxxy/60, Syyy/20, Sxxxx/30
    };
    expansionIntegrals(P, n, s2, eux, euy, Om/s, S, I, Ir);
}

//- The tangential velocity at the plane's centroid in its axes, and
//  Omega = omega.n
inline void centroidVelocity
(
    const PlaneView& P,
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

//- skinIntegral's switch on the plane P (I, Ir zero on entry): the closed
//  form where the centre of rotation lies within skinUniformRatio radii of
//  the centroid, else expansion(Ux, Uy, Om) (no tangential velocity at the
//  centroid and no spin about n: u_t vanishes, nothing added). The closed
//  form loses (D/a)^2 of precision in the moment when the centre of
//  rotation is D far from a polygon of size a; there the field is nearly
//  uniform and its expansion about the centroid's velocity errs by at most
//  about 5/8 (a/D)^4 (expansionIntegrals)
template<class Expansion>
void switchedSkin
(
    const PlaneView& P,
    const Vec3& n,
    const Vec3& w,
    const Vec3& omega,
    Vec3& I,
    Vec3& Ir,
    const Expansion& expansion
)
{
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
        expansion(Ux, Uy, Om);
    }
}

} // anonymous namespace


namespace
{

//- The preamble of the skin integrals of the polygon q[0..m): I and Ir
//  zeroed, the polygon's plane found (false for none), then onPlane(P)
template<class OnPlane>
bool skinOnPolygon
(
    const Vec3* q,
    int m,
    const Vec3& n,
    Vec3& I,
    Vec3& Ir,
    const OnPlane& onPlane
)
{
    I.setZero();
    Ir.setZero();
    double x[planeCapacity], y[planeCapacity];
    PlaneView P;
    if (!skinPlane(q, m, n, x, y, P)) return false;
    return onPlane(P);
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
    return skinOnPolygon(q, m, n, I, Ir, [&](const PlaneView& P)
    {
        const Vec3& centroid = P.centroid;
        // u_t is linear: its value at the centroid and its change towards
        // each vertex (e_k = q_k - centroid)
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
            // Sum of the integrand and of its moments about the centroid,
            // as eb x Gb + ec x Gc
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
    });
}


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
    return skinOnPolygon(q, m, n, I, Ir, [&](const PlaneView& P)
    {
        double Ux, Uy, Om;
        centroidVelocity(P, n, w, omega, Ux, Uy, Om);
        // No tangential velocity at the centroid: the expansion has no
        // axis (skinIntegral takes it only where the spin about n vanishes
        // too, and then u_t vanishes on the polygon)
        if (Ux*Ux + Uy*Uy > 0) skinExpansion(P, n, Ux, Uy, Om, I, Ir);
        return true;
    });
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
    return skinOnPolygon(q, m, n, I, Ir, [&](const PlaneView& P)
    {
        double Ux, Uy, Om;
        centroidVelocity(P, n, w, omega, Ux, Uy, Om);
        if (Om == 0) return false;
        skinClosedForm(P, n, Ux, Uy, Om, I, Ir);
        return true;
    });
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
    return skinOnPolygon(q, m, n, I, Ir, [&](const PlaneView& P)
    {
        switchedSkin
        (
            P, n, w, omega, I, Ir,
            [&](double Ux, double Uy, double Om)
            {
                skinExpansion(P, n, Ux, Uy, Om, I, Ir);
            }
        );
        return true;
    });
}


namespace
{

//- The expansion (expansionIntegrals) with the moments of a whole face's
//  plane turned into the axes eu, ev: with x = cu X + su Y and
//  y = -su X + cu Y (X, Y the plane's axes, (cu, su) = eu)
void skinExpansionOfFace
(
    const FacePlane& face,
    const PlaneView& P,
    const Vec3& n,
    double Ux,
    double Uy,
    double Om,
    Vec3& I,
    Vec3& Ir
)
{
    const double s2 = Ux*Ux + Uy*Uy;
    const double s = std::sqrt(s2);
    const double cu = Ux/s, su = Uy/s;
    const double cc = cu*cu, cs = cu*su, ss = su*su;
    const double* M2 = face.moment2;    // XX, XY, YY
    const double* M3 = face.moment3;    // XXX, XXY, XYY, YYY
    const double* M4 = face.moment4;    // XXXX, XXXY, XXYY, XYYY, YYYY
    AxisMoments S;
    S.A = face.area;
    S.Sxx = cc*M2[0] + 2*cs*M2[1] + ss*M2[2];
    S.Syy = ss*M2[0] - 2*cs*M2[1] + cc*M2[2];
    S.Sxy = cs*(M2[2] - M2[0]) + (cc - ss)*M2[1];
    S.Sxxx =
        cu*cc*M3[0] + 3*cc*su*M3[1] + 3*cu*ss*M3[2] + su*ss*M3[3];
    S.Sxxy =
        -cc*su*M3[0] + cu*(cc - 2*ss)*M3[1] + su*(2*cc - ss)*M3[2]
      + cu*ss*M3[3];
    S.Syyy =
        -su*ss*M3[0] + 3*ss*cu*M3[1] - 3*su*cc*M3[2] + cu*cc*M3[3];
    S.Sxxxx =
        cc*cc*M4[0] + 4*cc*cs*M4[1] + 6*cc*ss*M4[2] + 4*cs*ss*M4[3]
      + ss*ss*M4[4];
    expansionIntegrals(P, n, s2, cu, su, Om/s, S, I, Ir);
}

} // anonymous namespace


void skinIntegralOfFace
(
    const FacePlane& plane,
    const Mat3& R,
    const Vec3& n,
    const Vec3& w,
    const Vec3& omega,
    Vec3& I,
    Vec3& Ir
)
{
    I.setZero();
    Ir.setZero();
    // The world's plane: the body's axes and centroid turned, the
    // coordinates as they are
    PlaneView P;
    P.x = plane.x;
    P.y = plane.y;
    P.tx = plane.tx;
    P.ty = plane.ty;
    P.m = plane.m;
    P.ex = R*plane.ex;
    P.ey = R*plane.ey;
    P.centroid = R*plane.centroid;
    P.a2 = plane.a2;
    switchedSkin
    (
        P, n, w, omega, I, Ir,
        [&](double Ux, double Uy, double Om)
        {
            skinExpansionOfFace(plane, P, n, Ux, Uy, Om, I, Ir);
        }
    );
}

} // namespace iceDEM
