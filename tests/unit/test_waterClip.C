/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Exact clipping by the water plane (hydro/WaterClip.H) against analytic
    volumes and centroids: a cube half submerged, a cube rolled by 45 deg, a
    cube standing on a corner, an upright prism and a prism lying on its
    side at several water levels; consistency of the clipped faces with the
    clipped volume (divergence theorem) for arbitrary poses; the drag sample
    points; a floe's derived outer polyhedron clips as offset()'s does.
\*---------------------------------------------------------------------------*/

#include "hydro/WaterClip.H"
#include "hydro/WaterFrame.H"
#include "geometry/DilatedShape.H"
#include "hydroFixtures.H"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace iceDEM;

namespace
{

// Relative tolerance of the exact clipping
constexpr double tol = 1e-12;

void expectVolume(const SubmergedVolume& s, double V, const Vec3& c, double L)
{
    EXPECT_NEAR(s.volume, V, tol*V) << "volume";
    // Centroid: relative to the size L of the body
    EXPECT_NEAR((s.centroid - c).norm(), 0, tol*L)
        << "centroid " << s.centroid.transpose()
        << " expected " << c.transpose();
}

Mat3 rotX(double a)
{
    return Eigen::AngleAxisd(a, Vec3::UnitX()).toRotationMatrix();
}

//- Random rotation from a seeded generator
Mat3 randomRotation(std::mt19937& gen)
{
    std::normal_distribution<double> N(0, 1);
    Quat q(N(gen), N(gen), N(gen), N(gen));
    q.normalize();
    return q.toRotationMatrix();
}

} // anonymous namespace


TEST(WaterClip, cubeHalfSubmerged)
{
    const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(0.5, 0.5, 0.5));

    // At the origin and far from it (round-off must not grow with |x|)
    for (const Vec3& x : {Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(1e3, -2e3, 0)})
    {
        const SubmergedVolume s =
            submergedVolume(cube, Mat3::Identity(), x, 0);
        expectVolume(s, 0.5, x + Vec3(0, 0, -0.25), 1);
    }

    // Level moved with the cube
    const Vec3 x(3, -1, 7.25);
    expectVolume
    (
        submergedVolume(cube, Mat3::Identity(), x, 7.25),
        0.5, x - Vec3(0, 0, 0.25), 1
    );
}


TEST(WaterClip, outOfWaterAndFullySubmerged)
{
    const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(1, 2, 3));
    const Mat3 R = rotX(0.3);
    const Vec3 x(1, 1, 10);

    const SubmergedVolume dry = submergedVolume(cube, R, x, 0);
    EXPECT_EQ(dry.volume, 0.0);

    const SubmergedVolume wet = submergedVolume(cube, R, x, 20);
    expectVolume(wet, 48.0, x, 6);
}


TEST(WaterClip, cubeRolled45)
{
    // Cube of side a rolled by 45 deg about x: a diamond cross-section with
    // its lowest vertex sqrt(2) a/2 below the centre. Immersed to depth t
    // below the water: a triangle of area t^2 (t <= sqrt(2) a/2), centroid
    // 2t/3 above the lowest vertex; above that the complement of the dry
    // triangle.
    const double a = 2.0;
    const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(1, 1, 1));
    const Mat3 R = rotX(M_PI/4);
    const Vec3 x(0.3, -0.2, 5.0);
    const double half = std::sqrt(2.0)*a/2;
    const double zLow = x.z() - half;

    for (double t : {0.1, 0.5, 1.0, half, 1.6, 2.0, 2.7})
    {
        double V;
        double zc;
        if (t <= half)
        {
            V = a*t*t;
            zc = zLow + 2*t/3;
        }
        else
        {
            const double s = 2*half - t;       // dry height
            const double Vdry = a*s*s;
            const double zDry = x.z() + half - 2*s/3;
            V = a*a*a - Vdry;
            zc = (a*a*a*x.z() - Vdry*zDry)/V;
        }
        SCOPED_TRACE("depth " + std::to_string(t));
        expectVolume
        (
            submergedVolume(cube, R, x, zLow + t),
            V, Vec3(x.x(), x.y(), zc), a
        );
    }
}


TEST(WaterClip, cubeOnCorner)
{
    // Cube with its main diagonal vertical: the part within height t of the
    // lowest corner is a tetrahedron with three orthogonal legs s = sqrt(3) t
    // (s <= a): V = s^3/6, centroid 3t/4 above the corner.
    const double a = 1.5;
    const ConvexPolyhedron cube =
        ConvexPolyhedron::box(Vec3(a/2, a/2, a/2));
    const Mat3 R =
        Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3::UnitZ())
       .toRotationMatrix();
    const Vec3 x(-4, 2, 1);
    const double zLow = x.z() - std::sqrt(3.0)*a/2;
    const double zHigh = x.z() + std::sqrt(3.0)*a/2;

    for (double t : {0.05, 0.3, 0.6, a/std::sqrt(3.0)})
    {
        const double s = std::sqrt(3.0)*t;
        SCOPED_TRACE("height " + std::to_string(t));

        // Corner down
        expectVolume
        (
            submergedVolume(cube, R, x, zLow + t),
            s*s*s/6, Vec3(x.x(), x.y(), zLow + 0.75*t), a
        );

        // Everything but the top corner
        const double Vc = s*s*s/6;
        const double V = a*a*a - Vc;
        const double zc = (a*a*a*x.z() - Vc*(zHigh - 0.75*t))/V;
        expectVolume
        (
            submergedVolume(cube, R, x, zHigh - t),
            V, Vec3(x.x(), x.y(), zc), a
        );
    }
}


TEST(WaterClip, uprightPrismAtSeveralLevels)
{
    // Irregular convex hexagon, extruded from zb to zb + h
    const std::vector<Vec2> poly =
    {
        {0, 0}, {4, -0.5}, {6, 1.5}, {5.5, 4}, {2, 5}, {-0.5, 2.5}
    };
    const double zb = -0.7;
    const double h = 1.3;
    const ConvexPolyhedron P = ConvexPolyhedron::prism(poly, zb, h);

    // Shoelace area and centroid
    double A = 0;
    Vec2 c = Vec2::Zero();
    for (std::size_t k = 0; k < poly.size(); ++k)
    {
        const Vec2& p = poly[k];
        const Vec2& q = poly[(k + 1) % poly.size()];
        const double w = p.x()*q.y() - q.x()*p.y();
        A += 0.5*w;
        c += (w/6)*(p + q);
    }
    c /= A;

    const Vec3 x(10, 20, 0);
    for (double level : {-0.6, -0.2, 0.0, 0.35, 0.59})
    {
        SCOPED_TRACE("level " + std::to_string(level));
        const double d = level - zb;
        expectVolume
        (
            submergedVolume(P, Mat3::Identity(), x, level),
            A*d, Vec3(x.x() + c.x(), x.y() + c.y(), 0.5*(zb + level)), 6
        );
    }

    // Dry and fully submerged
    EXPECT_EQ(submergedVolume(P, Mat3::Identity(), x, zb).volume, 0.0);
    expectVolume
    (
        submergedVolume(P, Mat3::Identity(), x, 3),
        A*h, Vec3(x.x() + c.x(), x.y() + c.y(), zb + 0.5*h), 6
    );
}


TEST(WaterClip, prismOnItsSide)
{
    // Triangle (-1, 0), (1, 0), (0, -1.5) extruded along z over [0, L],
    // then rolled by +90 deg about x: (x, y, z) -> (x, -z, y). The
    // triangle stands in the xz-plane with its apex down; immersed to depth
    // t <= 1.5 the wet section is the similar triangle scaled by t/1.5.
    const double L = 3.0;
    const ConvexPolyhedron P = ConvexPolyhedron::prism
    (
        {{-1, 0}, {1, 0}, {0, -1.5}}, 0, L
    );
    const Mat3 R = rotX(M_PI/2);
    const Vec3 x(2, 0, 1);
    const double zApex = x.z() - 1.5;
    const double Atri = 1.5;

    for (double t : {0.2, 0.75, 1.2, 1.5})
    {
        SCOPED_TRACE("depth " + std::to_string(t));
        const double k = t/1.5;
        expectVolume
        (
            submergedVolume(P, R, x, zApex + t),
            k*k*Atri*L, Vec3(x.x(), x.y() - L/2, zApex + 2*t/3), L
        );
    }
}


TEST(WaterClip, belowPlusAboveIsWhole)
{
    // Arbitrary poses: the part below the plane plus the part above (the
    // part below -level of the pose turned upside down) gives back the
    // whole volume and centroid.
    const ConvexPolyhedron P = ConvexPolyhedron::prism
    (
        {{0, 0}, {3, 0.2}, {3.5, 2}, {1, 3}}, -0.4, 0.9
    );
    const double V = P.volume();
    // Volume centroid (body frame): everything submerged
    const Vec3 c =
        submergedVolume(P, Mat3::Identity(), Vec3::Zero(), 10).centroid;

    std::mt19937 gen(12345);
    std::uniform_real_distribution<double> U(-1, 1);
    const Mat3 flip = Eigen::AngleAxisd(M_PI, Vec3::UnitX()).toRotationMatrix();
    for (int trial = 0; trial < 50; ++trial)
    {
        const Mat3 R = randomRotation(gen);
        const Vec3 x(5*U(gen), 5*U(gen), 0.5*U(gen));
        const double level = 0.3*U(gen);

        const SubmergedVolume below = submergedVolume(P, R, x, level);
        SubmergedVolume above = submergedVolume(P, flip*R, flip*x, -level);
        above.centroid = flip.transpose()*above.centroid;

        EXPECT_NEAR(below.volume + above.volume, V, tol*V);
        const Vec3 whole =
            (below.volume*below.centroid + above.volume*above.centroid)/V;
        EXPECT_NEAR((whole - (R*c + x)).norm(), 0, tol*4);
    }
}


// submergedVolume (divergence theorem over the wet faces) against the
// general path (clipped tetrahedra) at random poses: level, tilted, on a
// corner, overwashed, a sliver wet, nearly and entirely submerged, near the
// origin and far from it, the truncated prisms among them; equal to
// round-off
TEST(WaterClip, divergenceEqualsTetrahedraOnRandomPoses)
{
    const DilatedShape floe
    (
        ConvexPolyhedron::prism
        (
            {{0, 0}, {3, 0.2}, {3.5, 2}, {1.2, 3.1}, {-0.3, 1.4}}, -0.4, 0.9
        ),
        0.1
    );
    PolyhedronBuffer buffer;
    const PolyhedronView outer = floe.outer(buffer);
    const ConvexPolyhedron box = ConvexPolyhedron::box(Vec3(2, 1, 0.5));
    const double L = 4;

    std::mt19937 gen(2026);
    std::uniform_real_distribution<double> U(-1, 1);
    int partly = 0;
    int prismPoses = 0;
    for (int trial = 0; trial < 2000; ++trial)
    {
        const PolyhedronView P = trial % 2 ? PolyhedronView(box) : outer;
        // Half the poses nearly level (a floating floe), half any rotation
        const Mat3 R = trial % 4 < 2
            ? Mat3(Eigen::AngleAxisd
              (
                  0.2*U(gen), Vec3(U(gen), U(gen), U(gen)).normalized()
              ).toRotationMatrix())
            : randomRotation(gen);
        const double far = trial % 3 == 0 ? 1e3 : 1;
        const Vec3 x(far*U(gen), far*U(gen), 1.5*U(gen));
        const double level = 0.5*U(gen);

        const SubmergedVolume a = submergedVolume(P, R, x, level);
        const SubmergedVolume b = submergedVolumeByTetrahedra(P, R, x, level);
        const double whole =
            submergedVolumeByTetrahedra(P, R, x, level + 100).volume;
        EXPECT_NEAR(a.volume, b.volume, tol*whole) << "trial " << trial;
        EXPECT_NEAR((a.centroid - b.centroid).norm(), 0, tol*L + 1e-14*far)
            << "trial " << trial;
        partly += b.volume > 0 && b.volume < whole;
        // Poses that take the truncated-prism path
        std::vector<double> h;
        for (const Vec3& v : P.vertices()) h.push_back((R*v + x).z() - level);
        prismPoses += truncatedPrismBottom(P, R, h.data()) >= 0;
    }
    // Most poses cut the body; many cut the sides only
    EXPECT_GT(partly, 1000);
    EXPECT_GT(prismPoses, 150);
    std::cout << partly << " of 2000 poses cut, " << prismPoses
              << " of them across the sides only" << std::endl;
}


TEST(WaterClip, truncatedPrismFromItsKeptCap)
{
    // A floe's kept caps (findPrismCaps, DilatedShape::prismCaps): random
    // prisms of 3 to 12 sides are found with their two caps (a box with
    // its largest pair, a pyramid not at all); on nearly level and heeled
    // poses at any height lowerCapBelow takes the cap truncatedPrismBottom
    // finds, and the truncated prism's volume and centre from the cap's
    // area and second moments equal those from its vertices and from the
    // tetrahedra (the same integrals, other round-off)
    std::mt19937 gen(4242);
    std::uniform_real_distribution<double> U(-1, 1);
    int cut = 0;
    double worstVolume = 0, worstCentre = 0;
    for (int trial = 0; trial < 40; ++trial)
    {
        const std::vector<Vec2> polygon =
            test::hydro::randomOutline(gen, 3 + trial % 10);
        const double z0 = -0.2 - std::abs(U(gen)), z1 = 0.3 + std::abs(U(gen));
        const ConvexPolyhedron prism = ConvexPolyhedron::prism(polygon, z0, z1);
        const PolyhedronView P = prism.view();
        PrismCaps caps;
        ASSERT_TRUE(findPrismCaps(P, caps)) << "trial " << trial;
        for (const FacePlane& cap : caps.cap)
        {
            ASSERT_GE(cap.face, 0);
            EXPECT_EQ(std::abs(P.faces()[cap.face].normal.z()), 1);
            EXPECT_EQ(caps.of(cap.face), &cap);
        }
        double radius = 0;
        for (const Vec2& v : polygon) radius = std::max(radius, v.norm());
        const double size = radius + z1 - z0;
        for (int pose = 0; pose < 50; ++pose)
        {
            const Mat3 R = Eigen::AngleAxisd
            (
                (pose % 2 ? 0.05 : 0.4)*U(gen),
                Vec3(U(gen), U(gen), U(gen)).normalized()
            ).toRotationMatrix();
            const double far = pose % 3 == 0 ? 1e3 : 1;
            const Vec3 x(far*U(gen), far*U(gen), 0.5*U(gen));
            const double level = 0.3*U(gen);
            std::vector<Vec3> r;
            std::vector<double> h;
            for (const Vec3& v : P.vertices())
            {
                r.push_back(R*v);
                h.push_back(r.back().z() + x.z() - level);
            }
            const int k = lowerCapBelow(caps, P, R, h.data());
            const int bottom = truncatedPrismBottom(P, R, h.data());
            ASSERT_EQ(k >= 0 ? caps.cap[k].face : -1, bottom)
                << "trial " << trial << " pose " << pose;
            if (k < 0) continue;
            ++cut;
            const SubmergedVolume fromCap =
                truncatedPrismVolume(caps.cap[k], R, x, level);
            const SubmergedVolume fromVertices = truncatedPrismVolume
            (
                P, R, r.data(), h.data(), bottom, x
            );
            const SubmergedVolume byTetrahedra =
                submergedVolumeByTetrahedra(P, R, x, level);
            const double V = byTetrahedra.volume;
            worstVolume = std::max
            (
                worstVolume, std::abs(fromCap.volume - fromVertices.volume)/V
            );
            worstCentre = std::max
            (
                worstCentre,
                (fromCap.centroid - fromVertices.centroid).norm()/size
            );
            EXPECT_NEAR(fromCap.volume, fromVertices.volume, tol*V);
            EXPECT_NEAR(fromCap.volume, V, tol*V);
            EXPECT_NEAR
            (
                (fromCap.centroid - fromVertices.centroid).norm(), 0,
                tol*size + 1e-14*far
            );
            EXPECT_NEAR
            (
                (fromCap.centroid - byTetrahedra.centroid).norm(), 0,
                tol*size + 1e-14*far
            );
        }
    }
    std::cout << cut << " of 2000 poses cut across the sides only; from the"
              << " kept cap against its vertices: volume " << worstVolume
              << ", centre " << worstCentre << " of the size" << std::endl;
    EXPECT_GT(cut, 400);

    // A box: the pair of the largest faces (any pair is a prism's caps)
    {
        const ConvexPolyhedron box = ConvexPolyhedron::box(Vec3(3, 2, 1));
        PrismCaps caps;
        ASSERT_TRUE(findPrismCaps(box.view(), caps));
        for (const FacePlane& cap : caps.cap)
        {
            EXPECT_EQ(std::abs(box.faces()[cap.face].normal.z()), 1);
            EXPECT_NEAR(cap.area, 6*4, 1e-12);
        }
    }
    // A pyramid is no prism
    {
        const ConvexPolyhedron pyramid = ConvexPolyhedron::hull
        (
            {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0),
             Vec3(0, 0, 1)}
        );
        PrismCaps caps;
        EXPECT_FALSE(findPrismCaps(pyramid.view(), caps));
    }
}


// clipNegative: the part of a polygon where a linear function is negative
TEST(WaterClip, clipNegativeOfASquare)
{
    const Vec3 p[4] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
    Vec3 q[5];
    double sq[5];
    // s = x - 0.5: the strip 0 <= x < 0.5, a rectangle
    const double s[4] = {-0.5, 1.5, 1.5, -0.5};
    ASSERT_EQ(clipNegative(p, s, 4, q, sq), 4);
    double area = 0;
    for (int k = 1; k + 1 < 4; ++k)
    {
        area += 0.5*((q[k] - q[0]).cross(q[k + 1] - q[0])).z();
    }
    EXPECT_NEAR(area, 1, 1e-15);
    // s = x + y - 1: the corner triangle below the diagonal, s = 0 on its
    // cut vertices
    const double t[4] = {-1, 1, 3, 1};
    ASSERT_EQ(clipNegative(p, t, 4, q, sq), 3);
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_NEAR(sq[k], q[k].x() + q[k].y() - 1, 1e-15);
    }
    // Nothing negative, only a vertex on zero: nothing
    const double u[4] = {0, 1, 2, 1};
    EXPECT_EQ(clipNegative(p, u, 4, q, sq), 0);
}


// splitPolygon: both sides of a polygon in one pass, bit for bit the two
// clipNegative calls (s and -s) it replaces in the water frame; and the
// frame's dry polygons made in the wet pass (a wind reads them) equal
// frameDry's on random poses, vertices on the plane included
TEST(WaterClip, splitPolygonEqualsBothClips)
{
    std::mt19937 gen(1618);
    std::uniform_real_distribution<double> U(-1, 1);
    int cut = 0;
    for (int trial = 0; trial < 2000; ++trial)
    {
        const int n = 3 + trial % 8;
        Vec3 p[16];
        double s[16], sMinus[16];
        for (int k = 0; k < n; ++k)
        {
            const double th = 2*M_PI*(k + 0.4*std::abs(U(gen)))/n;
            p[k] = Vec3(3*std::cos(th), 2*std::sin(th), U(gen));
            // Linear s, with vertices exactly on zero now and then
            s[k] = trial % 5 == 0 && k % 3 == 0
                ? 0 : p[k].x()*U(gen) + 0.5*p[k].y() + 0.3;
            sMinus[k] = -s[k];
        }
        Vec3 a[17], b[17], c[17], d[17];
        double sa[17], sb[17], sc[17];
        const int ma = clipNegative(p, s, n, a, sa);
        const int mb = clipNegative(p, sMinus, n, b, sb);
        int mc = -1, md = -1;
        splitPolygon(p, s, n, c, sc, mc, d, md);
        ASSERT_EQ(mc, ma) << "trial " << trial;
        ASSERT_EQ(md, mb) << "trial " << trial;
        for (int k = 0; k < ma; ++k)
        {
            EXPECT_EQ(c[k], a[k]);
            EXPECT_EQ(sc[k], sa[k]);
        }
        for (int k = 0; k < mb; ++k)
        {
            EXPECT_EQ(d[k], b[k]);
        }
        cut += ma > 0 && mb > 0;
    }
    EXPECT_GT(cut, 500);

    const DilatedShape floe
    (
        ConvexPolyhedron::prism
        (
            {{0, 0}, {3, 0.2}, {3.5, 2}, {1.2, 3.1}, {-0.3, 1.4}}, -0.4, 0.9
        ),
        0.1
    );
    PolyhedronBuffer buffer;
    const PolyhedronView P = floe.outer(buffer);
    WaterFrame lazy, both;
    int bothPoses = 0;
    for (int trial = 0; trial < 1000; ++trial)
    {
        const Mat3 R = trial % 2
            ? Mat3(Eigen::AngleAxisd
              (
                  0.2*U(gen), Vec3(U(gen), U(gen), U(gen)).normalized()
              ).toRotationMatrix())
            : randomRotation(gen);
        const Vec3 x(U(gen), U(gen), 1.5*U(gen));
        // Now and then the level through a vertex
        const double level = trial % 7 == 0
            ? (R*P.vertices()[trial % P.vertices().size()] + x).z()
            : 0.5*U(gen);
        computeWaterFrame(P, R, x, level, lazy);
        computeWaterFrame(P, R, x, level, both, true);
        ASSERT_EQ(lazy.nWet, both.nWet);
        for (int k = 0; k <= lazy.nWet; ++k)
        {
            ASSERT_EQ(lazy.wetBegin[k], both.wetBegin[k]);
        }
        for (int k = 0; k < lazy.wetBegin[lazy.nWet]; ++k)
        {
            EXPECT_EQ(lazy.wetVertex[k], both.wetVertex[k]);
            EXPECT_EQ(lazy.wetHeight[k], both.wetHeight[k]);
        }
        bothPoses += both.hasDry;
        ASSERT_TRUE(frameDry(P, lazy));
        ASSERT_TRUE(frameDry(P, both));
        ASSERT_EQ(lazy.nDry, both.nDry) << "trial " << trial;
        for (int k = 0; k < lazy.nDry; ++k)
        {
            ASSERT_EQ(lazy.dryFace[k], both.dryFace[k]);
            ASSERT_EQ(lazy.dryBegin[k + 1], both.dryBegin[k + 1]);
        }
        for (int k = 0; k < lazy.dryBegin[lazy.nDry]; ++k)
        {
            EXPECT_EQ(lazy.dryVertex[k], both.dryVertex[k]);
        }
    }
    // Most poses cut the floe: their dry side came from the wet pass
    EXPECT_GT(bothPoses, 500);
}


// Buoyancy and drag clip a floe's outer polyhedron, derived from the core
// for a prism (DilatedShape::outer): at arbitrary poses it gives the
// submerged volume, centroid and wet face areas of the half-space
// intersection offset() builds (another vertex numbering, the same solid)
TEST(WaterClip, derivedOuterClipsAsOffset)
{
    const double r = 0.15;
    const DilatedShape S
    (
        ConvexPolyhedron::prism({{0, 0}, {3, 0.2}, {3.5, 2}, {1.2, 3.1}, {-0.3, 1.4}}, -0.4, 0.9),
        r
    );
    ASSERT_FALSE(S.outerStored());
    PolyhedronBuffer buffer;
    const PolyhedronView outer = S.outer(buffer);
    const ConvexPolyhedron reference = S.core().offset(r);
    const double L = 4;

    std::mt19937 gen(2026);
    std::uniform_real_distribution<double> U(-1, 1);
    for (int trial = 0; trial < 50; ++trial)
    {
        const Mat3 R = randomRotation(gen);
        const Vec3 x(5*U(gen), 5*U(gen), 0.5*U(gen));
        const double level = 0.5*U(gen);

        const SubmergedVolume a = submergedVolume(outer, R, x, level);
        const SubmergedVolume b = submergedVolume(reference, R, x, level);
        EXPECT_NEAR(a.volume, b.volume, tol*reference.volume());
        EXPECT_NEAR((a.centroid - b.centroid).norm(), 0, tol*L);

        // Wet area of the faces with the same outward normal
        for (int f = 0; f < int(outer.faces().size()); ++f)
        {
            SubmergedFace fa;
            const double areaA = submergedFace(outer, f, R, x, level, fa) ? fa.area : 0;
            double areaB = -1;
            for (int g = 0; g < int(reference.faces().size()); ++g)
            {
                if ((reference.faces()[g].normal - outer.faces()[f].normal).norm() < 1e-12)
                {
                    SubmergedFace fb;
                    areaB = submergedFace(reference, g, R, x, level, fb) ? fb.area : 0;
                }
            }
            ASSERT_GE(areaB, 0) << "no face of offset() with the normal of face " << f;
            EXPECT_NEAR(areaA, areaB, tol*L*L);
        }
    }
}


TEST(WaterClip, facesHalfSubmergedCube)
{
    const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(0.5, 0.5, 0.5));
    const Vec3 x(1, 2, 0);
    SubmergedFace s;
    int wet = 0;
    for (int f = 0; f < static_cast<int>(cube.faces().size()); ++f)
    {
        const Vec3 n = cube.faces()[f].normal;
        const bool ok = submergedFace(cube, f, Mat3::Identity(), x, 0, s);
        if (n.z() > 0.5)
        {
            EXPECT_FALSE(ok) << "top face";
            continue;
        }
        ASSERT_TRUE(ok);
        ++wet;
        EXPECT_NEAR((s.normal - n).norm(), 0, tol);
        if (n.z() < -0.5)
        {
            EXPECT_NEAR(s.area, 1.0, tol);
            EXPECT_NEAR((s.centroid - (x - Vec3(0, 0, 0.5))).norm(), 0, tol);
        }
        else
        {
            EXPECT_NEAR(s.area, 0.5, tol);
            const Vec3 expected = x + 0.5*n - Vec3(0, 0, 0.25);
            EXPECT_NEAR((s.centroid - expected).norm(), 0, tol);
        }
    }
    EXPECT_EQ(wet, 5);
}


TEST(WaterClip, facesAgreeWithVolume)
{
    // Divergence theorem over the submerged region (wet faces plus the
    // water-plane section with normal +z):
    //   sum_f A_f n_f = -A_wp e_z   (so the horizontal parts vanish)
    //   sum_f A_f n_z,f (z_f - level) = V_sub
    //   sum_f A_f n_x,f (x_f - x_ref) = V_sub   (any x_ref, here x)
    const ConvexPolyhedron P = ConvexPolyhedron::prism
    (
        {{0, 0}, {2, -0.3}, {3, 1}, {2.2, 2.5}, {0.3, 2}}, -0.5, 1.1
    );
    std::mt19937 gen(777);
    std::uniform_real_distribution<double> U(-1, 1);
    SubmergedFace s;
    for (int trial = 0; trial < 50; ++trial)
    {
        const Mat3 R = randomRotation(gen);
        const Vec3 x(3*U(gen), 3*U(gen), 0.6*U(gen));
        const double level = 0.2*U(gen);
        const SubmergedVolume sub = submergedVolume(P, R, x, level);

        Vec3 vectorArea = Vec3::Zero();
        double fluxZ = 0;
        double fluxX = 0;
        for (int f = 0; f < static_cast<int>(P.faces().size()); ++f)
        {
            if (!submergedFace(P, f, R, x, level, s))
            {
                continue;
            }
            vectorArea += s.area*s.normal;
            fluxZ += s.area*s.normal.z()*(s.centroid.z() - level);
            fluxX += s.area*s.normal.x()*(s.centroid.x() - x.x());
        }
        const double scale = std::max(sub.volume, 1e-3);
        EXPECT_NEAR(vectorArea.x(), 0, tol*10);
        EXPECT_NEAR(vectorArea.y(), 0, tol*10);
        EXPECT_NEAR(fluxZ, sub.volume, tol*scale);
        EXPECT_NEAR(fluxX, sub.volume, tol*scale);
    }
}


TEST(WaterClip, samplePoints)
{
    // Rolled cube: the wet side faces are clipped quadrilaterals or
    // triangles. The equal-area sub-triangle centroids integrate linear
    // functions exactly: sum a = A, sum a p = A c.
    const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(1, 1.5, 0.5));
    const Mat3 R = rotX(0.4)*Eigen::AngleAxisd(0.3, Vec3::UnitZ())
       .toRotationMatrix();
    const Vec3 x(0, 0, 0.2);

    constexpr int capacity = 2048;
    std::vector<Vec3> points(capacity);
    std::vector<double> areas(capacity);
    SubmergedFace s;
    for (int sub = 0; sub <= 3; ++sub)
    {
        for (int f = 0; f < 6; ++f)
        {
            if (!submergedFace(cube, f, R, x, 0, s))
            {
                continue;
            }
            const int n = faceSamples
            (
                s, sub, points.data(), areas.data(), capacity
            );
            EXPECT_EQ(n, s.nVertices*(1 << (2*sub)));
            double A = 0;
            Vec3 first = Vec3::Zero();
            for (int k = 0; k < n; ++k)
            {
                A += areas[k];
                first += areas[k]*points[k];
                // On the face plane and below the water
                EXPECT_NEAR((points[k] - s.centroid).dot(s.normal), 0, tol*4);
                EXPECT_LT(points[k].z(), 0);
            }
            EXPECT_NEAR(A, s.area, tol*s.area);
            EXPECT_NEAR((first/A - s.centroid).norm(), 0, tol*4);
        }
    }

    // Too small a buffer: Error naming the subdivision entry
    for (int f = 0; f < 6; ++f)
    {
        if (submergedFace(cube, f, R, x, 0, s))
        {
            try
            {
                faceSamples(s, 3, points.data(), areas.data(), 10);
                FAIL() << "no Error for a too small buffer";
            }
            catch (const Error& e)
            {
                EXPECT_EQ(e.entry(), "subdivision");
            }
            break;
        }
    }
}


TEST(WaterClip, triangleSamplesSubdivision)
{
    const Vec3 a(0, 0, 0), b(3, 0, 0), c(0, 3, 0);
    Vec3 p[64];
    double w[64];
    EXPECT_EQ(triangleSamples(a, b, c, 0, p, w), 1);
    EXPECT_NEAR((p[0] - Vec3(1, 1, 0)).norm(), 0, tol);
    EXPECT_NEAR(w[0], 4.5, tol);

    // Level 1: the four midpoint triangles
    EXPECT_EQ(triangleSamples(a, b, c, 1, p, w), 4);
    std::vector<Vec3> expected =
    {
        Vec3(0.5, 0.5, 0), Vec3(1, 1, 0), Vec3(0.5, 2, 0), Vec3(2, 0.5, 0)
    };
    for (const Vec3& e : expected)
    {
        bool found = false;
        for (int k = 0; k < 4; ++k)
        {
            found = found || (p[k] - e).norm() < tol;
            EXPECT_NEAR(w[k], 4.5/4, tol);
        }
        EXPECT_TRUE(found) << e.transpose();
    }
    EXPECT_EQ(triangleSamples(a, b, c, 3, p, w), 64);
}


TEST(WaterClip, tooManyFaceVertices)
{
    std::vector<Vec2> circle;
    const int n = SubmergedFace::maxVertices + 10;
    for (int k = 0; k < n; ++k)
    {
        const double t = 2*M_PI*k/n;
        circle.emplace_back(10*std::cos(t), 10*std::sin(t));
    }
    const ConvexPolyhedron P = ConvexPolyhedron::prism(circle, -1, 2);
    SubmergedFace s;
    bool thrown = false;
    for (int f = 0; f < static_cast<int>(P.faces().size()); ++f)
    {
        try
        {
            submergedFace(P, f, Mat3::Identity(), Vec3::Zero(), 0, s);
        }
        catch (const Error&)
        {
            thrown = true;
        }
    }
    EXPECT_TRUE(thrown);
}
