/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "FacePlane.H"

#include <algorithm>
#include <cmath>

namespace iceDEM
{

bool planeCoordinates
(
    const Vec3* q,
    int m,
    const Vec3& n,
    double* x,
    double* y,
    Vec3& ex,
    Vec3& ey,
    Vec3& centroid,
    double& a2
)
{
    if (m < 3) return false;
    ex = n.unitOrthogonal();
    ey = n.cross(ex);
    // Coordinates from q[0], then the fan's area and centroid from there
    for (int k = 0; k < m; ++k)
    {
        const Vec3 e = q[k] - q[0];
        x[k] = e.dot(ex);
        y[k] = e.dot(ey);
    }
    double A2 = 0, cx = 0, cy = 0;
    for (int k = 1; k + 1 < m; ++k)
    {
        const double a = x[k]*y[k + 1] - x[k + 1]*y[k];
        A2 += a;
        cx += a*(x[k] + x[k + 1]);
        cy += a*(y[k] + y[k + 1]);
    }
    if (!(A2 > 0)) return false;
    cx /= 3*A2;
    cy /= 3*A2;
    centroid = q[0] + (cx*ex + cy*ey);
    a2 = 0;
    for (int k = 0; k < m; ++k)
    {
        x[k] -= cx;
        y[k] -= cy;
        a2 = std::max(a2, x[k]*x[k] + y[k]*y[k]);
    }
    return true;
}


void edgeTangents
(
    const double* x,
    const double* y,
    int m,
    double* tx,
    double* ty
)
{
    for (int k = 0; k < m; ++k)
    {
        const int k1 = k + 1 == m ? 0 : k + 1;
        const double Ex = x[k1] - x[k], Ey = y[k1] - y[k];
        const double L2 = Ex*Ex + Ey*Ey;
        const double invL = L2 > 0 ? 1/std::sqrt(L2) : 0;
        tx[k] = Ex*invL;
        ty[k] = Ey*invL;
    }
}


namespace
{

//- n! for the moments' weights (n <= 6: moments up to the fourth)
constexpr double factorials[7] = {1, 1, 2, 6, 24, 120, 720};

inline double binomial(int n, int k)
{
    return factorials[n]/(factorials[k]*factorials[n - k]);
}

double power(double v, int k)
{
    double p = 1;
    for (int i = 0; i < k; ++i) p *= v;
    return p;
}

//- int x^i y^j dA over the triangle (0, a, b), D = a x b its twice signed
//  area: the points s a + t b (s, t >= 0, s + t <= 1), dA = D ds dt and
//  int s^k t^l ds dt = k! l!/(k + l + 2)!
double triangleMoment
(
    int i,
    int j,
    double ax,
    double ay,
    double bx,
    double by,
    double D
)
{
    double sum = 0;
    for (int p = 0; p <= i; ++p)
    {
        for (int q = 0; q <= j; ++q)
        {
            // (s ax + t bx)^i (s ay + t by)^j: the term s^(p + q) t^(...)
            const int k = p + q, l = i + j - p - q;
            sum +=
                binomial(i, p)*binomial(j, q)
               *power(ax, p)*power(bx, i - p)*power(ay, q)*power(by, j - q)
               *factorials[k]*factorials[l]/factorials[i + j + 2];
        }
    }
    return D*sum;
}

} // anonymous namespace


bool makeFacePlane(const PolyhedronView& P, int f, FacePlane& plane)
{
    plane.face = -1;
    const auto face = P.faces()[f];
    const int m = face.count;
    if (m > FacePlane::maxVertices) return false;
    // Zeroed past the face's m corners too (never read; a shape's set-up
    // only): the compiler cannot see that planeCoordinates reads m of them
    Vec3 q[FacePlane::maxVertices];
    for (Vec3& v : q) v.setZero();
    for (int k = 0; k < m; ++k)
    {
        q[k] = P.vertices()[P.faceVertex(f, k)];
    }
    if
    (
        !planeCoordinates
        (
            q, m, face.normal, plane.x, plane.y, plane.ex, plane.ey,
            plane.centroid, plane.a2
        )
    )
    {
        return false;
    }
    edgeTangents(plane.x, plane.y, m, plane.tx, plane.ty);
    plane.normal = face.normal;
    plane.m = m;

    // Area and moments about the centroid over the fan of triangles
    // (centroid, vertex k, vertex k + 1)
    double A2 = 0;
    for (double& v : plane.moment2) v = 0;
    for (double& v : plane.moment3) v = 0;
    for (double& v : plane.moment4) v = 0;
    for (int k = 0; k < m; ++k)
    {
        const int k1 = k + 1 == m ? 0 : k + 1;
        const double ax = plane.x[k], ay = plane.y[k];
        const double bx = plane.x[k1], by = plane.y[k1];
        const double D = ax*by - bx*ay;
        A2 += D;
        for (int j = 0; j <= 2; ++j)
        {
            plane.moment2[j] += triangleMoment(2 - j, j, ax, ay, bx, by, D);
        }
        for (int j = 0; j <= 3; ++j)
        {
            plane.moment3[j] += triangleMoment(3 - j, j, ax, ay, bx, by, D);
        }
        for (int j = 0; j <= 4; ++j)
        {
            plane.moment4[j] += triangleMoment(4 - j, j, ax, ay, bx, by, D);
        }
    }
    plane.area = 0.5*A2;
    plane.face = f;
    return true;
}


bool findPrismCaps(const PolyhedronView& P, PrismCaps& caps)
{
    const auto faces = P.faces();
    const int nf = static_cast<int>(faces.size());
    double bestArea = 0;
    bool found = false;
    for (int f0 = 0; f0 < nf; ++f0)
    {
        const Vec3& axis = faces[f0].normal;
        for (int f1 = f0 + 1; f1 < nf; ++f1)
        {
            if (!(faces[f1].normal.dot(axis) < -1 + prismTolerance)) continue;
            bool sides = true;
            for (int f = 0; f < nf && sides; ++f)
            {
                if (f == f0 || f == f1) continue;
                sides = std::abs(faces[f].normal.dot(axis)) <= prismTolerance;
            }
            if (!sides) break;
            FacePlane c0, c1;
            if (!makeFacePlane(P, f0, c0) || !makeFacePlane(P, f1, c1))
            {
                break;
            }
            if (c0.area > bestArea)
            {
                bestArea = c0.area;
                caps.cap[0] = c0;
                caps.cap[1] = c1;
                found = true;
            }
            break;
        }
    }
    return found;
}

} // namespace iceDEM
