/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "FloeDamping.H"
#include "WaterFrame.H"
#include "WaterClip.H"

#include <cmath>
#include <limits>
#include <string>

namespace iceDEM
{

void checkFloeDampingSettings(const FloeDampingSettings& s)
{
    if (!std::isfinite(s.heave) || !(s.heave >= 0))
    {
        throw Error
        (
            "floeDamping: heave " + std::to_string(s.heave)
          + " must be zero or positive (fraction of critical damping)",
            "heave"
        );
    }
    if (!std::isfinite(s.rollPitch) || !(s.rollPitch >= 0))
    {
        throw Error
        (
            "floeDamping: rollPitch " + std::to_string(s.rollPitch)
          + " must be zero or positive (fraction of critical damping)",
            "rollPitch"
        );
    }
}


namespace
{

//- Lid integrals of 1, x, y, x^2, y^2 (coordinates relative to the floe's
//  centre), summed over fan triangles of the wet faces, each as minus its
//  signed horizontal projection; the midpoint rule on the edges of each
//  triangle is exact for quadratics
struct WaterplaneSums
{
    double A = 0, Sx = 0, Sy = 0, Qxx = 0, Qyy = 0;

    void addTriangle(const Vec3& q0, const Vec3& q1, const Vec3& q2)
    {
        const double ap = 0.5*((q1 - q0).cross(q2 - q0)).z();
        if (ap == 0) return;
        const Vec3 m01 = 0.5*(q0 + q1);
        const Vec3 m12 = 0.5*(q1 + q2);
        const Vec3 m20 = 0.5*(q2 + q0);
        A -= ap;
        Sx -= ap*(q0.x() + q1.x() + q2.x())/3;
        Sy -= ap*(q0.y() + q1.y() + q2.y())/3;
        Qxx -= ap*(m01.x()*m01.x() + m12.x()*m12.x() + m20.x()*m20.x())/3;
        Qyy -= ap*(m01.y()*m01.y() + m12.y()*m12.y() + m20.y()*m20.y())/3;
    }

    //- The waterplane of a floe centred at x, the water at level
    Waterplane waterplane(const Vec3& x, double level) const
    {
        Waterplane w;
        if (!(A > 0)) return w;
        w.area = A;
        const double xF = Sx/A;
        const double yF = Sy/A;
        w.centroid = x + Vec3(xF, yF, level - x.z());
        w.Ixx = std::max(0.0, Qxx - A*xF*xF);
        w.Iyy = std::max(0.0, Qyy - A*yF*yF);
        return w;
    }
};

//- The waterplane of a truncated prism from its lower cap's plane (kept:
//  PrismCaps), as waterplane(P, frame) makes it from the cap's vertices:
//  the cap moved along the axis a to the water plane, l = r - h/a_z a, is
//  an affine image of the cap, l = lc + X u + Y v (X, Y the cap's
//  coordinates about its centroid, whose first moments vanish), so the
//  lid's area and its second moments about its centroid lc are the cap's
//  times minus the map's Jacobian (u x v)_z (negative: the cap runs
//  clockwise seen from above); equal up to round-off
//  (FloeDamping.waterlinePolygonAgreesWithTheWetFaces)
Waterplane capWaterplane(const FacePlane& bottom, const WaterFrame& frame)
{
    const Mat3& R = frame.R;
    const Vec3 ex = R*bottom.ex;
    const Vec3 ey = R*bottom.ey;
    const Vec3 c = R*bottom.centroid;
    const Vec3 a = -(R*bottom.normal);
    const double invAz = 1/a.z();
    const double hc = c.z() + (frame.x.z() - frame.level);
    const Vec3 lc = c - (hc*invAz)*a;
    const Vec3 u = ex - (ex.z()*invAz)*a;
    const Vec3 v = ey - (ey.z()*invAz)*a;
    const double J = -(u.x()*v.y() - u.y()*v.x());
    Waterplane w;
    const double A = J*bottom.area;
    if (!(A > 0)) return w;
    const double Mxx = bottom.moment2[0];
    const double Mxy = bottom.moment2[1];
    const double Myy = bottom.moment2[2];
    w.area = A;
    w.centroid =
        frame.x + Vec3(lc.x(), lc.y(), frame.level - frame.x.z());
    // About the lid's centroid lc: the cap's moments about its own
    w.Ixx = std::max
    (
        0.0, J*(u.x()*u.x()*Mxx + 2*u.x()*v.x()*Mxy + v.x()*v.x()*Myy)
    );
    w.Iyy = std::max
    (
        0.0, J*(u.y()*u.y()*Mxx + 2*u.y()*v.y()*Mxy + v.y()*v.y()*Myy)
    );
    return w;
}

} // anonymous namespace


Waterplane waterplane
(
    const PolyhedronView& P,
    const Mat3& R,
    const Vec3& x,
    double level
)
{
    // The wet faces' fan triangles, relative to x (WaterplaneSums)
    WaterplaneSums sums;
    SubmergedFace face;
    const int nf = static_cast<int>(P.faces().size());
    for (int f = 0; f < nf; ++f)
    {
        if (!submergedFace(P, f, R, x, level, face)) continue;
        const Vec3 q0 = face.vertices[0] - x;
        for (int k = 1; k + 1 < face.nVertices; ++k)
        {
            const Vec3 q1 = face.vertices[k] - x;
            const Vec3 q2 = face.vertices[k + 1] - x;
            sums.addTriangle(q0, q1, q2);
        }
    }

    return sums.waterplane(x, level);
}


Waterplane waterplane(const WaterFrame& frame)
{
    // As above, from the frame's wet polygons (already relative to x)
    WaterplaneSums sums;
    for (int wf = 0; wf < frame.nWet; ++wf)
    {
        const Vec3* q = frame.wetVertex + frame.wetBegin[wf];
        const int m = frame.wetBegin[wf + 1] - frame.wetBegin[wf];
        const Vec3& q0 = q[0];
        for (int k = 1; k + 1 < m; ++k)
        {
            const Vec3& q1 = q[k];
            const Vec3& q2 = q[k + 1];
            sums.addTriangle(q0, q1, q2);
        }
    }

    return sums.waterplane(frame.x, frame.level);
}


Waterplane waterplane(const PolyhedronView& P, const WaterFrame& frame)
{
    if (!frame.valid())
    {
        return waterplane(P, frame.R, frame.x, frame.level);
    }
    frameVolume(P, frame);
    const int bottom = frame.prismBottom;
    if (bottom < 0)
    {
        return waterplane(frame);
    }
    if (frame.prismBottomPlane)
    {
        return capWaterplane(*frame.prismBottomPlane, frame);
    }

    // The lower cap's vertices r (heights h < 0) moved along the prism's
    // axis a (up, world) to the plane: l = r - h/a_z a. The cap's order
    // (counter-clockwise from below) is the lid's as the wet faces close
    // it, so WaterplaneSums takes the polygon as it is.
    constexpr int cap = SubmergedFace::maxVertices;
    const Vec3 a = -(frame.R*P.faces()[bottom].normal);
    const double invAz = 1/a.z();
    const int n = P.faces()[bottom].count;
    Vec3 l[cap];
    for (int k = 0; k < n; ++k)
    {
        const int v = P.faceVertex(bottom, k);
        l[k] = frame.r[v] - (frame.h[v]*invAz)*a;
    }
    WaterplaneSums sums;
    for (int k = 1; k + 1 < n; ++k)
    {
        sums.addTriangle(l[0], l[k], l[k + 1]);
    }
    return sums.waterplane(frame.x, frame.level);
}


double shortestHydrostaticPeriod
(
    const World& world,
    const WaterSettings& water,
    int begin,
    int end
)
{
    const double rhoG = water.density*world.settings().gravity.norm();
    double T = std::numeric_limits<double>::infinity();
    if (!(rhoG > 0)) return T;
    PolyhedronBuffer buffer;
    const double twoPi = 2*M_PI;
    const std::vector<Body>& bodies = world.bodies();
    for (int i = begin; i < end; ++i)
    {
        const Body& b = bodies[i];
        if (!b.isFree()) continue;
        const PolyhedronView P = world.shapeOf(i).outer(buffer);
        const Mat3 R = b.rotation();
        const Waterplane wp = waterplane(P, R, b.x, water.level);
        if (!(wp.area > 0)) continue;
        T = std::min(T, twoPi*std::sqrt(b.mass/(rhoG*wp.area)));

        const SubmergedVolume sub = submergedVolume(P, R, b.x, water.level);
        const double VBG = sub.volume*(sub.centroid.z() - b.x.z());
        const Vec3 I = b.invInertia.cwiseInverse();
        const Mat3 Iw = R*I.asDiagonal()*R.transpose();
        const double k4 = rhoG*(wp.Iyy + VBG);
        const double k5 = rhoG*(wp.Ixx + VBG);
        if (k4 > 0) T = std::min(T, twoPi*std::sqrt(Iw(0, 0)/k4));
        if (k5 > 0) T = std::min(T, twoPi*std::sqrt(Iw(1, 1)/k5));
    }
    return T;
}


FloeDamping::FloeDamping
(
    const WaterSettings& water,
    const FloeDampingSettings& settings
)
:
    water_(water),
    settings_(settings)
{
    checkWaterSettings(water_);
    checkFloeDampingSettings(settings_);
}


const char* FloeDamping::name() const
{
    return "floeDamping";
}


Vec3 FloeDamping::coefficients(const World& world, int i) const
{
    Vec3 c = Vec3::Zero();
    const Body& b = world.bodies()[i];
    const double rhoG = water_.density*world.settings().gravity.norm();
    if (!b.isFree() || rhoG == 0) return c;

    const PolyhedronView P = outerForModels(world.shapeOf(i));
    // The floe's frame, shared with buoyancy and drag
    const WaterFrame& frame = waterFrame(world, i, water_.level);
    const Mat3& R = frame.R;

    const Waterplane wp = waterplane(P, frame);
    if (wp.area == 0) return c;

    const double k3 = rhoG*wp.area;
    c.x() = 2*settings_.heave*std::sqrt(b.mass*k3);

    if (settings_.rollPitch > 0)
    {
        const SubmergedVolume& sub = frameVolume(P, frame);
        const double VBG = sub.volume*(sub.centroid.z() - b.x.z());
        const double k4 = rhoG*(wp.Iyy + VBG);
        const double k5 = rhoG*(wp.Ixx + VBG);
        // World inertia about G: R diag(I) R^T
        const Vec3 I = b.invInertia.cwiseInverse();
        const Mat3 Iw = R*I.asDiagonal()*R.transpose();
        if (k4 > 0) c.y() = 2*settings_.rollPitch*std::sqrt(Iw(0, 0)*k4);
        if (k5 > 0) c.z() = 2*settings_.rollPitch*std::sqrt(Iw(1, 1)*k5);
    }
    return c;
}


void FloeDamping::addForces
(
    const World& world,
    int begin,
    int end,
    Vec3* force,
    Vec3* torque
) const
{
    if (settings_.heave == 0 && settings_.rollPitch == 0) return;

    const std::vector<Body>& bodies = world.bodies();
    for (int i = begin; i < end; ++i)
    {
        const Body& b = bodies[i];
        if (!b.isFree()) continue;
        const Vec3 c = coefficients(world, i);
        if (c.isZero(0)) continue;
        const Vec3 omega = b.omega();
        force[i].z() -= c.x()*b.v.z();
        torque[i].x() -= c.y()*omega.x();
        torque[i].y() -= c.z()*omega.y();
    }
}

} // namespace iceDEM
