/*---------------------------------------------------------------------------*\
    iceDEM tests: convex polyhedra, dilated mass properties, shapes.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "geometry/ConvexPolyhedron.H"
#include "geometry/DilatedShape.H"
#include "geometry/MassProperties.H"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

using namespace iceDEM;

TEST(geometry, boxTopology)
{
    const ConvexPolyhedron P = ConvexPolyhedron::box(Vec3(1, 2, 3));
    EXPECT_EQ(P.vertices().size(), 8u);
    EXPECT_EQ(P.edges().size(), 12u);
    EXPECT_EQ(P.faces().size(), 6u);
    EXPECT_NEAR(P.volume(), 48.0, 1e-12);
    EXPECT_NEAR(P.area(), 2*(2*4 + 2*6 + 4*6), 1e-12);
    EXPECT_NEAR(P.minWidth(), 2.0, 1e-12);
    for (int e = 0; e < 12; ++e)
    {
        EXPECT_NEAR(P.exteriorAngle(e), M_PI/2, 1e-12);
    }
}

TEST(geometry, steinerVolumeOfDilatedCube)
{
    // V = a^3 + 6 a^2 r + 3 pi a r^2 + 4/3 pi r^3  (method.md 1)
    const double a = 1.3, r = 0.2;
    const ConvexPolyhedron P = ConvexPolyhedron::box(Vec3::Constant(a/2));
    const double exact = a*a*a + 6*a*a*r + 3*M_PI*a*r*r + 4.0/3.0*M_PI*r*r*r;
    EXPECT_NEAR(steinerVolume(P, r), exact, 1e-12*exact);
    // The moment integration tiles the same volume
    EXPECT_NEAR(dilatedMassProperties(P, r).volume, exact, 1e-12*exact);
    // Area: 6 a^2 + 6 pi a r + 4 pi r^2
    const double area = 6*a*a + 6*M_PI*a*r + 4*M_PI*r*r;
    EXPECT_NEAR(steinerArea(P, r), area, 1e-12*area);
}

//- Inertia of a dilated box (half extents h, radius r) about its centre by
//  integration: a fine midpoint grid in x-y, exact in z for each column
static Mat3 dilatedBoxInertiaNumerical(const Vec3& h, double r, int n)
{
    const double X = h.x() + r, Y = h.y() + r;
    const double dx = 2*X/n, dy = 2*Y/n;
    double Ixx = 0, Iyy = 0, Izz = 0, V = 0;
    for (int i = 0; i < n; ++i)
    {
        const double x = -X + (i + 0.5)*dx;
        const double ex = std::max(std::abs(x) - h.x(), 0.0);
        for (int j = 0; j < n; ++j)
        {
            const double y = -Y + (j + 0.5)*dy;
            const double ey = std::max(std::abs(y) - h.y(), 0.0);
            const double s2 = ex*ex + ey*ey;
            if (s2 >= r*r) continue;
            const double zt = h.z() + std::sqrt(r*r - s2);
            const double len = 2*zt;
            const double z2 = 2*zt*zt*zt/3;
            V += len*dx*dy;
            Ixx += (y*y*len + z2)*dx*dy;
            Iyy += (x*x*len + z2)*dx*dy;
            Izz += (x*x + y*y)*len*dx*dy;
        }
    }
    Mat3 I = Mat3::Zero();
    I(0, 0) = Ixx;
    I(1, 1) = Iyy;
    I(2, 2) = Izz;
    return I;
}

TEST(geometry, dilatedBoxInertiaAgainstIntegration)
{
    const Vec3 h(1.0, 0.6, 0.3);
    const double r = 0.15;
    const ConvexPolyhedron P = ConvexPolyhedron::box(h);
    const MassProperties mp = dilatedMassProperties(P, r);
    const Mat3 In = dilatedBoxInertiaNumerical(h, r, 3000);
    EXPECT_NEAR(mp.centroid.norm(), 0, 1e-12);
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_NEAR(mp.inertia(k, k), In(k, k), 1e-3*In(k, k)) << "axis " << k;
    }
    EXPECT_NEAR(mp.inertia(0, 1), 0, 1e-9*In(0, 0));
}

TEST(geometry, polyhedronInertiaExact)
{
    // Box a x b x c: I_xx = V (b^2 + c^2)/12
    const Vec3 h(1.0, 0.6, 0.3);
    const MassProperties mp = polyhedronMassProperties(ConvexPolyhedron::box(h));
    const double V = 8*h.prod();
    EXPECT_NEAR(mp.volume, V, 1e-12*V);
    EXPECT_NEAR(mp.inertia(0, 0), V*(4*h.y()*h.y() + 4*h.z()*h.z())/12, 1e-12);
    EXPECT_NEAR(mp.inertia(2, 2), V*(4*h.x()*h.x() + 4*h.y()*h.y())/12, 1e-12);
}

TEST(geometry, hullMergesCoplanarTriangles)
{
    std::vector<Vec3> pts;
    for (int k = 0; k < 8; ++k)
    {
        pts.emplace_back(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
    }
    pts.emplace_back(0, 0, 0);          // inside
    pts.emplace_back(0, 0, 1);          // on a face
    pts.emplace_back(1, 1, 0);          // on an edge
    const ConvexPolyhedron P = ConvexPolyhedron::hull(pts);
    EXPECT_EQ(P.faces().size(), 6u);
    EXPECT_EQ(P.vertices().size(), 8u);
    EXPECT_EQ(P.edges().size(), 12u);
    EXPECT_NEAR(P.volume(), 8, 1e-12);
}

TEST(geometry, badInputIsAnError)
{
    // Flat points
    std::vector<Vec3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    EXPECT_THROW(ConvexPolyhedron::hull(flat), Error);
    // Non-convex prism outline
    std::vector<Vec2> dart = {{0, 0}, {2, 1}, {0, 2}, {0.5, 1}};
    EXPECT_THROW(ConvexPolyhedron::prism(dart, 0, 1), Error);
    // Dilation radius larger than half the thinnest width
    const ConvexPolyhedron P = ConvexPolyhedron::box(Vec3(1, 1, 0.1));
    try
    {
        DilatedShape S(P, 0.2);
        FAIL() << "no error for a too large radius";
    }
    catch (const Error& e)
    {
        EXPECT_EQ(e.entry(), "radius");
    }
    EXPECT_THROW(DilatedShape(P, 0), Error);
    EXPECT_THROW(DilatedShape(P, -0.1), Error);
}

TEST(geometry, offsetOfBox)
{
    const ConvexPolyhedron P = ConvexPolyhedron::box(Vec3(1, 2, 3)).offset(0.5);
    EXPECT_EQ(P.faces().size(), 6u);
    EXPECT_NEAR(P.volume(), 3*5*7, 1e-9);
}

TEST(geometry, principalFrameOfRotatedBox)
{
    const Vec3 h(2, 1, 0.5);
    const Quat Q(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    const Vec3 c(3, -1, 2);
    const ConvexPolyhedron P = ConvexPolyhedron::box(h).transformed(Q.toRotationMatrix(), c);
    const DilatedShape S(P, 0.1, MassModel::faceted);
    EXPECT_NEAR((S.centroidInput() - c).norm(), 0, 1e-12);
    const Vec3 H = h + Vec3::Constant(0.1);
    const double V = 8*H.prod();
    EXPECT_NEAR(S.volume(), V, 1e-10*V);
    // Principal moments of the outer box, ascending
    std::vector<double> expected =
    {
        V*(4*H.y()*H.y() + 4*H.z()*H.z())/12,
        V*(4*H.x()*H.x() + 4*H.z()*H.z())/12,
        V*(4*H.x()*H.x() + 4*H.y()*H.y())/12
    };
    std::sort(expected.begin(), expected.end());
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_NEAR(S.principalInertia()[k], expected[k], 1e-9*expected[k]);
    }
    // The core in the principal frame is centred
    Vec3 mean = Vec3::Zero();
    for (const Vec3& v : S.core().vertices()) mean += v;
    EXPECT_NEAR(mean.norm()/8, 0, 1e-12);
    EXPECT_NEAR(S.boundingRadius(), (h).norm() + 0.1, 1e-12);
}

// Memory per floe (issue 7): polyhedra with the same combinatorics share one
// topology object; each keeps its own vertices and face planes
TEST(geometry, sharedTopology)
{
    const std::vector<Vec2> hexagonA =
        {{0, 0}, {2, -0.5}, {3.5, 1}, {3, 3}, {1, 3.5}, {-0.5, 2}};
    std::vector<Vec2> hexagonB;
    for (const Vec2& p : hexagonA) hexagonB.push_back(1.3*p + Vec2(10, -4));
    const ConvexPolyhedron A = ConvexPolyhedron::prism(hexagonA, 0, 1);
    const ConvexPolyhedron B = ConvexPolyhedron::prism(hexagonB, -0.3, 0.7);
    const ConvexPolyhedron box = ConvexPolyhedron::box(Vec3(1, 2, 3));

    EXPECT_EQ(&A.topology(), &B.topology());
    EXPECT_NE(&A.topology(), &box.topology());
    EXPECT_EQ(A.topology().nVertices(), 12);
    EXPECT_EQ(A.topology().nEdges(), 18);
    EXPECT_EQ(A.topology().nFaces(), 8);
    EXPECT_NE(A.vertices()[0], B.vertices()[0]);

    // Own geometry: vertices and face planes, nothing else
    EXPECT_EQ(A.heapBytes(), 12*sizeof(Vec3) + 8*sizeof(ConvexPolyhedron::Plane));

    // Copies and moved copies share the topology and hold equal geometry
    const Mat3 R = Eigen::AngleAxisd(0.4, Vec3(0, 0, 1)).toRotationMatrix();
    const ConvexPolyhedron C = A.transformed(R, Vec3(1, 2, 3));
    ConvexPolyhedron D;
    EXPECT_EQ(D.vertices().size(), 0u);
    EXPECT_EQ(D.faces().size(), 0u);
    D = C;
    EXPECT_EQ(&D.topology(), &A.topology());
    for (std::size_t v = 0; v < C.vertices().size(); ++v)
    {
        EXPECT_EQ(D.vertices()[v], C.vertices()[v]);
    }
    for (std::size_t f = 0; f < C.faces().size(); ++f)
    {
        EXPECT_EQ(D.faces()[f].normal, C.faces()[f].normal);
        EXPECT_EQ(D.faces()[f].offset, C.faces()[f].offset);
        // transformed(): each plane through the loop's first vertex
        EXPECT_EQ(C.faces()[f].offset, C.faces()[f].normal.dot(C.vertices()[C.faceVertex(int(f), 0)]));
    }
    const ConvexPolyhedron E(std::move(D));
    EXPECT_EQ(&E.topology(), &A.topology());
    EXPECT_EQ(E.vertices()[3], C.vertices()[3]);
    // A moved-from polyhedron is empty and usable
    EXPECT_EQ(D.vertices().size(), 0u);
    EXPECT_EQ(D.edges().size(), 0u);
    D = E;
    EXPECT_EQ(D.vertices()[3], C.vertices()[3]);

    // Face-loop slot edges: from loop vertex k to k+1
    for (int f = 0; f < A.topology().nFaces(); ++f)
    {
        const int n = A.faces()[f].count;
        for (int k = 0; k < n; ++k)
        {
            const auto& e = A.edges()[A.faceEdge(f, k)];
            const int a = A.faceVertex(f, k);
            const int b = A.faceVertex(f, (k + 1) % n);
            EXPECT_TRUE((e[0] == a && e[1] == b) || (e[0] == b && e[1] == a));
        }
    }
}

// The shape's edge directions, computed from the stored edge lengths, are bit
// for bit what normalized() gives (the contact windows' results must not
// depend on how the shape stores them)
TEST(geometry, edgeDirectionsExact)
{
    const std::vector<Vec2> polygon =
        {{0.1, 0.2}, {2.3, -0.7}, {3.9, 1.1}, {3.1, 3.3}, {0.9, 3.7}, {-0.6, 2.05}, {-0.4, 0.9}};
    const DilatedShape S(ConvexPolyhedron::prism(polygon, -0.45, 0.9), 0.1);
    const ConvexPolyhedron& P = S.core();
    for (int e = 0; e < int(P.edges().size()); ++e)
    {
        const Vec3 d =
            (P.vertices()[P.edges()[e][1]] - P.vertices()[P.edges()[e][0]]).normalized();
        EXPECT_EQ(S.edgeDirection(e), d);
    }
    // A prism's outer polyhedron is derived, not stored
    EXPECT_FALSE(S.outerStored());
    EXPECT_EQ(S.heapBytes(), P.heapBytes() + P.edges().size()*sizeof(double));
}

// The derived outer polyhedron of a prism (three faces at every vertex) is
// the core offset by r as offset() builds it, a half-space intersection
// with its own numbering: the same volume, the same vertices as a set, every
// face plane the core's moved out by r. A pyramid's apex has four faces:
// that outer is stored, and is offset()'s.
TEST(geometry, outerPolyhedronDerivedOrStored)
{
    const double r = 0.1;
    const std::vector<Vec2> polygon =
        {{0.1, 0.2}, {2.3, -0.7}, {3.9, 1.1}, {3.1, 3.3}, {0.9, 3.7}, {-0.6, 2.05}, {-0.4, 0.9}};
    const ConvexPolyhedron prism = ConvexPolyhedron::prism(polygon, -0.45, 0.9);
    const ConvexPolyhedron pyramid = ConvexPolyhedron::hull
    (
        {{-1, -1, 0}, {1.2, -1, 0}, {1, 1.1, 0}, {-1, 1, 0}, {0.1, 0.05, 1.4}}
    );

    for (const ConvexPolyhedron* core : {&prism, &pyramid})
    {
        const DilatedShape S(*core, r);
        EXPECT_EQ(S.outerStored(), core == &pyramid);

        // offset() of the core in the principal frame (the shape's frame)
        const ConvexPolyhedron reference = S.core().offset(r);
        PolyhedronBuffer buffer;
        const PolyhedronView outer = S.outer(buffer);

        EXPECT_NEAR(ConvexPolyhedron::hull
        (
            std::vector<Vec3>(outer.vertices().begin(), outer.vertices().end())
        ).volume(), reference.volume(), 1e-12*reference.volume());
        EXPECT_NEAR(reference.volume(), S.facetedVolume(), 1e-12*reference.volume());

        ASSERT_EQ(outer.vertices().size(), reference.vertices().size());
        for (const Vec3& v : outer.vertices())
        {
            double nearest = 1e300;
            for (const Vec3& w : reference.vertices())
            {
                nearest = std::min(nearest, (v - w).norm());
            }
            EXPECT_LT(nearest, 1e-12);
        }

        // Each face: the plane of its vertices, and the core's face with
        // that normal moved out by r
        ASSERT_EQ(outer.faces().size(), S.core().faces().size());
        for (const auto face : outer.faces())
        {
            for (int k = 0; k < face.count; ++k)
            {
                const Vec3& v = outer.vertices()[outer.faceVertices()[face.begin + k]];
                EXPECT_NEAR(face.normal.dot(v), face.offset, 1e-12);
            }
            bool found = false;
            for (const auto coreFace : S.core().faces())
            {
                if ((coreFace.normal - face.normal).norm() < 1e-12)
                {
                    found = true;
                    EXPECT_NEAR(face.offset, coreFace.offset + r, 1e-12);
                }
            }
            EXPECT_TRUE(found);
        }
    }
}


// A core whose vertices have more than three faces (the hull of random
// points: three to eight faces at a vertex) splits each such vertex into a
// small polygon when its planes move out, with edges down to micrometres
// beside edges of metres. Every one must dilate: offset() gives a closed
// polyhedron whose faces are the core's planes moved out by r, one to one,
// with every vertex on three moved planes at least and inside all of them.
// Before the hull kept its faces consistent by a count of the faces at a
// vertex, 202 of 3,999 such cores (the hand-over tests' pairs of 7- and
// 10-point hulls, seeds 1 to 2,000) failed with "the surface is not
// closed", among them seeds 15, 23 and 38 of the hand-over battery
// (test_handover.C), which that battery skipped; this test failed at
// seed 11
TEST(geometry, everyHullWithVerticesOfManyFacesDilates)
{
    const double r = 0.05;
    int hulls = 0, manyFaced = 0;
    double shortest = 1e300;
    for (unsigned seed = 1; seed <= 120; ++seed)
    {
        std::mt19937_64 rng(seed);
        std::normal_distribution<double> g(0, 1);
        std::vector<Vec3> p;
        for (int k = 0; k < 10; ++k)
        {
            const Vec3 v(g(rng), g(rng), g(rng));
            p.push_back(0.6*v.normalized()*(0.7 + 0.3*std::abs(g(rng))));
        }
        const ConvexPolyhedron core = ConvexPolyhedron::hull(p);
        if (!(r <= 0.5*core.minWidth())) continue;   // too thin for r
        ++hulls;
        for (int v = 0; v < int(core.vertices().size()); ++v)
        {
            if (core.vertexEdgeEnd(v) - core.vertexEdgeBegin(v) > 3) ++manyFaced;
        }

        ConvexPolyhedron outer = core;
        ASSERT_NO_THROW(outer = core.offset(r)) << "seed " << seed;
        ASSERT_NO_THROW(DilatedShape(core, r)) << "seed " << seed;
        ASSERT_EQ(outer.faces().size(), core.faces().size()) << "seed " << seed;
        for (const auto face : outer.faces())
        {
            bool found = false;
            for (const auto coreFace : core.faces())
            {
                if ((coreFace.normal - face.normal).norm() < 1e-9)
                {
                    found = true;
                    EXPECT_NEAR(face.offset, coreFace.offset + r, 1e-9) << "seed " << seed;
                }
            }
            EXPECT_TRUE(found) << "seed " << seed;
        }
        for (const Vec3& v : outer.vertices())
        {
            int on = 0;
            for (const auto coreFace : core.faces())
            {
                const double h = coreFace.normal.dot(v) - coreFace.offset - r;
                EXPECT_LT(h, 1e-9) << "seed " << seed;
                on += std::abs(h) < 1e-9;
            }
            EXPECT_GE(on, 3) << "seed " << seed;
        }
        for (const auto& e : outer.edges())
        {
            shortest = std::min(shortest, (outer.vertices()[e[1]] - outer.vertices()[e[0]]).norm());
        }
    }
    std::printf
    (
        "%d hulls dilated, %d vertices of more than three faces; shortest"
        " edge of an outer polyhedron %.3g m\n", hulls, manyFaced, shortest
    );
    EXPECT_GE(hulls, 100);
    EXPECT_GE(manyFaced, 500);
    EXPECT_LT(shortest, 1e-4) << "no micrometre edge: the case is not reached";
}


// The hull of points as users give them: each point listed up to three
// times with rounding (offsets of 1e-15 to 1e-8 of the size), and boxes
// whose corners carry rounding of 1e-10 of the size, at the origin and a
// kilometre from it. Each gives the polyhedron of its distinct points (the
// same vertices and volume as the clean input) and dilates. Before the hull
// merged points within its faces' tolerance and measured coplanarity from
// a corner of the face instead of by the planes' offsets (of the size of
// the coordinates), 400 of 400 such lists failed ("a face
// is not planar", "a face has zero area"), and so did 916 of 1,000 of
// these boxes a kilometre out (1 of 1,000 now: a face's plane from the
// absolute coordinates of its corners, ConvexPolyhedron's own check, is
// the limit there; 0 of 1,000 at the origin before and after)
TEST(geometry, hullOfRoundedAndRepeatedPointsAnywhere)
{
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> u(-1, 1);
    std::normal_distribution<double> g(0, 1);
    for (int trial = 0; trial < 50; ++trial)
    {
        std::vector<Vec3> clean, repeated;
        for (int k = 0; k < 8; ++k)
        {
            const Vec3 c = Vec3(g(rng), g(rng), g(rng)).normalized();
            clean.push_back(c);
            const int copies = 1 + int(rng() % 3);
            for (int j = 0; j < copies; ++j)
            {
                const double e = std::pow(10.0, -15 + 7*(u(rng) + 1)/2);
                repeated.push_back(c + e*Vec3(u(rng), u(rng), u(rng)));
            }
        }
        const ConvexPolyhedron A = ConvexPolyhedron::hull(clean);
        ConvexPolyhedron B = A;
        ASSERT_NO_THROW(B = ConvexPolyhedron::hull(repeated)) << "trial " << trial;
        EXPECT_EQ(B.vertices().size(), A.vertices().size()) << "trial " << trial;
        EXPECT_EQ(B.faces().size(), A.faces().size()) << "trial " << trial;
        EXPECT_NEAR(B.volume(), A.volume(), 1e-6*A.volume()) << "trial " << trial;
        EXPECT_NO_THROW(DilatedShape(B, 0.05)) << "trial " << trial;
    }
    for (const Vec3 shift : {Vec3(0, 0, 0), Vec3(1000, -2000, 50)})
    {
        for (int trial = 0; trial < 10; ++trial)
        {
            const Quat q(Eigen::AngleAxisd(3*u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
            const Vec3 h(0.5 + 0.4*u(rng), 0.5 + 0.4*u(rng), 0.2 + 0.1*u(rng));
            std::vector<Vec3> corners;
            for (int i = 0; i < 8; ++i)
            {
                const Vec3 c((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
                corners.push_back(q*c + 1e-10*Vec3(u(rng), u(rng), u(rng)) + shift);
            }
            ConvexPolyhedron P = ConvexPolyhedron::box(h);
            ASSERT_NO_THROW(P = ConvexPolyhedron::hull(corners)) << "shift " << shift.transpose();
            EXPECT_EQ(P.vertices().size(), 8u);
            EXPECT_EQ(P.faces().size(), 6u);
            EXPECT_NEAR(P.volume(), 8*h.prod(), 1e-8*h.prod());
            EXPECT_NO_THROW(DilatedShape(P, 0.05));
        }
    }
}


TEST(geometry, keptOuterPolyhedronIsTheDerivedOne)
{
    // keepOuter() (a world with hydrodynamic models) stores what outer()
    // derives: the same numbers, bit for bit, so the clipping gives the
    // same forces whether a shape's outer polyhedron is kept or derived
    const std::vector<Vec2> polygon =
        {{0.1, 0.2}, {2.3, -0.7}, {3.9, 1.1}, {3.1, 3.3}, {0.9, 3.7}, {-0.6, 2.05}};
    const DilatedShape derived(ConvexPolyhedron::prism(polygon, -0.45, 0.9), 0.1);
    DilatedShape kept = derived;
    kept.keepOuter();
    EXPECT_FALSE(derived.outerKept());
    EXPECT_TRUE(kept.outerKept());
    EXPECT_GT(kept.heapBytes(), derived.heapBytes());

    PolyhedronBuffer a, b;
    const PolyhedronView D = derived.outer(a);
    const PolyhedronView K = kept.outer(b);
    EXPECT_TRUE(b.vertices.empty());    // not derived into the caller's buffer
    ASSERT_EQ(D.vertices().size(), K.vertices().size());
    for (std::size_t v = 0; v < D.vertices().size(); ++v)
    {
        EXPECT_EQ(D.vertices()[v], K.vertices()[v]);
    }
    ASSERT_EQ(D.faces().size(), K.faces().size());
    for (std::size_t f = 0; f < D.faces().size(); ++f)
    {
        EXPECT_EQ(D.faces()[f].normal, K.faces()[f].normal);
        EXPECT_EQ(D.faces()[f].offset, K.faces()[f].offset);
    }

    // A pyramid's outer polyhedron is stored; keeping changes nothing
    DilatedShape pyramid
    (
        ConvexPolyhedron::hull({{-1, -1, 0}, {1.2, -1, 0}, {1, 1.1, 0}, {-1, 1, 0}, {0.1, 0.05, 1.4}}),
        0.1
    );
    pyramid.keepOuter();
    EXPECT_TRUE(pyramid.outerStored());
    EXPECT_FALSE(pyramid.outerKept());
}
