/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "MassProperties.H"

#include <algorithm>
#include <cmath>

namespace iceDEM
{

void MomentSums::addTetrahedron
(
    const Vec3& a,
    const Vec3& b,
    const Vec3& c,
    const Vec3& d
)
{
    // V = |det|/6, int x = V s/4, int x x^T = V/20 (sum v v^T + s s^T)
    const double V = std::abs((b - a).dot((c - a).cross(d - a)))/6.0;
    const Vec3 s = a + b + c + d;
    volume += V;
    first += V*s/4.0;
    second += V/20.0
        *(a*a.transpose() + b*b.transpose() + c*c.transpose()
        + d*d.transpose() + s*s.transpose());
}


MomentSums& MomentSums::operator+=(const MomentSums& o)
{
    volume += o.volume;
    first += o.first;
    second += o.second;
    return *this;
}


MassProperties MomentSums::massProperties() const
{
    MassProperties m;
    m.volume = volume;
    m.centroid = first/volume;
    // Second moment about the centroid, then the inertia tensor
    const Mat3 C = second - volume*m.centroid*m.centroid.transpose();
    m.inertia = C.trace()*Mat3::Identity() - C;
    return m;
}


namespace
{

MomentSums polyhedronSums(const ConvexPolyhedron& P)
{
    // Fan of tetrahedra from the vertex mean (inside a convex polyhedron)
    Vec3 o = Vec3::Zero();
    for (const Vec3& v : P.vertices()) o += v;
    o /= double(P.vertices().size());

    MomentSums s;
    const auto& V = P.vertices();
    for (int f = 0; f < int(P.faces().size()); ++f)
    {
        const int n = P.faces()[f].count;
        const Vec3& a = V[P.faceVertex(f, 0)];
        for (int k = 1; k + 1 < n; ++k)
        {
            s.addTetrahedron(o, a, V[P.faceVertex(f, k)], V[P.faceVertex(f, k + 1)]);
        }
    }
    return s;
}


//- Slab on face f: the face polygon swept along its normal by r
void addFaceSlab(MomentSums& s, const ConvexPolyhedron& P, int f, double r)
{
    const auto& V = P.vertices();
    const auto& face = P.faces()[f];
    const Vec3 h = r*face.normal;
    const Vec3& a = V[P.faceVertex(f, 0)];
    for (int k = 1; k + 1 < face.count; ++k)
    {
        const Vec3& b = V[P.faceVertex(f, k)];
        const Vec3& c = V[P.faceVertex(f, k + 1)];
        // Triangular prism abc-a'b'c' as three tetrahedra
        s.addTetrahedron(a, b, c, a + h);
        s.addTetrahedron(b, c, a + h, b + h);
        s.addTetrahedron(c, a + h, b + h, c + h);
    }
}


//- Wedge on edge e: cylinder sector of radius r over the exterior angle
void addEdgeWedge(MomentSums& s, const ConvexPolyhedron& P, int e, double r)
{
    const Vec3& a = P.vertices()[P.edges()[e][0]];
    const Vec3& b = P.vertices()[P.edges()[e][1]];
    const double L = (b - a).norm();
    const Vec3 t = (b - a)/L;
    const Vec3& n0 = P.faces()[P.edgeFaces()[e][0]].normal;
    const Vec3& n1 = P.faces()[P.edgeFaces()[e][1]].normal;
    const double theta = P.exteriorAngle(e);
    if (theta <= 0)
    {
        return;
    }
    Vec3 m = n1 - n1.dot(n0)*n0;
    m.normalize();

    // Points a + s t + rho u(phi), u = cos(phi) n0 + sin(phi) m, element rho
    const double area = 0.5*theta*r*r;                  // int rho drho dphi
    const double rho2 = r*r*r/3.0;                      // int rho^2 drho
    const double rho3 = r*r*r*r/4.0;                    // int rho^3 drho
    const Vec3 U1 = std::sin(theta)*n0 + (1 - std::cos(theta))*m;
    const Mat3 U2 =
        (0.5*theta + 0.25*std::sin(2*theta))*n0*n0.transpose()
      + (0.5*theta - 0.25*std::sin(2*theta))*m*m.transpose()
      + 0.5*std::sin(theta)*std::sin(theta)*(n0*m.transpose() + m*n0.transpose());

    const Vec3 P1 = L*a + 0.5*L*L*t;                    // int p ds
    const Mat3 P2 = L*a*a.transpose()
        + 0.5*L*L*(a*t.transpose() + t*a.transpose())
        + L*L*L/3.0*t*t.transpose();                    // int p p^T ds

    s.volume += L*area;
    s.first += area*P1 + L*rho2*U1;
    s.second += area*P2 + rho2*(P1*U1.transpose() + U1*P1.transpose()) + L*rho3*U2;
}


//- Integrals of 1, u and u u^T over a spherical triangle abc
void sphericalTriangle
(
    const Vec3& a,
    const Vec3& b,
    const Vec3& c,
    int level,
    double& omega,
    Mat3& uu
)
{
    if (level == 0)
    {
        // Solid angle (Van Oosterom & Strackee), integrand at the centroid
        const double num = std::abs(a.dot(b.cross(c)));
        const double den = 1 + a.dot(b) + b.dot(c) + c.dot(a);
        const double w = 2*std::atan2(num, den);
        const Vec3 u = (a + b + c).normalized();
        omega += w;
        uu += w*u*u.transpose();
        return;
    }
    const Vec3 ab = (a + b).normalized();
    const Vec3 bc = (b + c).normalized();
    const Vec3 ca = (c + a).normalized();
    sphericalTriangle(a, ab, ca, level - 1, omega, uu);
    sphericalTriangle(ab, b, bc, level - 1, omega, uu);
    sphericalTriangle(ca, bc, c, level - 1, omega, uu);
    sphericalTriangle(ab, bc, ca, level - 1, omega, uu);
}


//- Exact int u dOmega over a spherical triangle (the vector solid angle):
//  half the sum over its arcs of the arc angle times the arc plane's normal
Vec3 sphericalTriangleFirstMoment(const Vec3& a, const Vec3& b, const Vec3& c)
{
    Vec3 sum = Vec3::Zero();
    const Vec3* v[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k)
    {
        const Vec3& p = *v[k];
        const Vec3& q = *v[(k + 1) % 3];
        const Vec3 x = p.cross(q);
        const double s = x.norm();
        if (s > 0)
        {
            sum += std::atan2(s, p.dot(q))*x/s;
        }
    }
    // Orientation: the result points into the triangle
    if (sum.dot(a + b + c) < 0) sum = -sum;
    return 0.5*sum;
}


//- Sector of the ball of radius r at vertex v over its normal cone
void addVertexSector
(
    MomentSums& s,
    const ConvexPolyhedron& P,
    int v,
    double r,
    int levels
)
{
    // Normals of the faces around v, ordered around their mean
    std::vector<Vec3> normals;
    for (int f = 0; f < int(P.faces().size()); ++f)
    {
        for (int k = 0; k < P.faces()[f].count; ++k)
        {
            if (P.faceVertex(f, k) == v)
            {
                normals.push_back(P.faces()[f].normal);
                break;
            }
        }
    }
    Vec3 axis = Vec3::Zero();
    for (const Vec3& n : normals) axis += n;
    axis.normalize();
    Vec3 e1 = normals[0] - normals[0].dot(axis)*axis;
    e1.normalize();
    const Vec3 e2 = axis.cross(e1);
    std::sort
    (
        normals.begin(), normals.end(),
        [&](const Vec3& p, const Vec3& q)
        {
            return std::atan2(p.dot(e2), p.dot(e1)) < std::atan2(q.dot(e2), q.dot(e1));
        }
    );

    double omega = 0;
    Vec3 u1 = Vec3::Zero();
    Mat3 u2 = Mat3::Zero();
    for (std::size_t k = 1; k + 1 < normals.size(); ++k)
    {
        sphericalTriangle(normals[0], normals[k], normals[k + 1], levels, omega, u2);
        u1 += sphericalTriangleFirstMoment(normals[0], normals[k], normals[k + 1]);
    }

    const Vec3& x = P.vertices()[v];
    const double Vs = r*r*r/3.0*omega;
    const Vec3 F1 = r*r*r*r/4.0*u1;
    s.volume += Vs;
    s.first += Vs*x + F1;
    s.second += Vs*x*x.transpose() + (x*F1.transpose() + F1*x.transpose())
              + r*r*r*r*r/5.0*u2;
}

} // anonymous namespace


MassProperties polyhedronMassProperties(const ConvexPolyhedron& P)
{
    return polyhedronSums(P).massProperties();
}


double steinerVolume(const ConvexPolyhedron& P, double r)
{
    double edgeSum = 0;
    for (int e = 0; e < int(P.edges().size()); ++e)
    {
        const double L =
            (P.vertices()[P.edges()[e][1]] - P.vertices()[P.edges()[e][0]]).norm();
        edgeSum += L*P.exteriorAngle(e);
    }
    return P.volume() + P.area()*r + 0.5*r*r*edgeSum + 4.0/3.0*M_PI*r*r*r;
}


double steinerArea(const ConvexPolyhedron& P, double r)
{
    double edgeSum = 0;
    for (int e = 0; e < int(P.edges().size()); ++e)
    {
        const double L =
            (P.vertices()[P.edges()[e][1]] - P.vertices()[P.edges()[e][0]]).norm();
        edgeSum += L*P.exteriorAngle(e);
    }
    return P.area() + r*edgeSum + 4*M_PI*r*r;
}


MassProperties dilatedMassProperties
(
    const ConvexPolyhedron& P,
    double r,
    int levels
)
{
    MomentSums s = polyhedronSums(P);
    for (int f = 0; f < int(P.faces().size()); ++f)
    {
        addFaceSlab(s, P, f, r);
    }
    for (int e = 0; e < int(P.edges().size()); ++e)
    {
        addEdgeWedge(s, P, e, r);
    }
    for (int v = 0; v < int(P.vertices().size()); ++v)
    {
        addVertexSector(s, P, v, r, levels);
    }
    // The solid angles of the sub-triangles tile each cone exactly, so the
    // volume equals Steiner's to round-off (the tests check it)
    return s.massProperties();
}

} // namespace iceDEM
