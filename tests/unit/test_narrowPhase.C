/*---------------------------------------------------------------------------*\
    iceDEM tests: the narrow phase finds the closest point of two cores in
    configurations its windows once missed.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "testWorlds.H"
#include "contact/NarrowPhase.H"
#include "contact/NeighbourList.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

using namespace iceDEM;
using namespace iceDEM::test;

namespace
{

//- Squared distance between the segments [p1, q1] and [p2, q2] (clamped
//  closest points)
double segmentSegmentDistance2(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2)
{
    const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const double a = d1.squaredNorm(), e = d2.squaredNorm();
    const double b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
    const double den = a*e - b*b;
    double s = den > 0 ? std::clamp((b*f - c*e)/den, 0.0, 1.0) : 0.0;
    double t = (b*s + f)/e;
    if (t < 0) { t = 0; s = std::clamp(-c/a, 0.0, 1.0); }
    else if (t > 1) { t = 1; s = std::clamp((b - c)/a, 0.0, 1.0); }
    return (p1 + s*d1 - p2 - t*d2).squaredNorm();
}

//- Core vertices of body i of w at its present pose, world frame
std::vector<Vec3> worldCore(const World& w, int i)
{
    const Body& b = w.bodies()[i];
    const Mat3 R = b.rotation();
    std::vector<Vec3> v;
    for (const Vec3& s : w.shapeOf(i).core().vertices()) v.push_back(R*s + b.x);
    return v;
}

//- Distance between the cores of bodies i and j of w (separated cores), by
//  brute force: every edge pair and every vertex over a face's interior
double coreDistance(const World& w, int i, int j)
{
    const ConvexPolyhedron& PA = w.shapeOf(i).core();
    const ConvexPolyhedron& PB = w.shapeOf(j).core();
    const std::vector<Vec3> worldA = worldCore(w, i), worldB = worldCore(w, j);
    const Vec3* vA = worldA.data();
    const Vec3* vB = worldB.data();
    double d2 = std::numeric_limits<double>::infinity();
    for (const auto& ea : PA.edges())
    {
        for (const auto& eb : PB.edges())
        {
            d2 = std::min(d2, segmentSegmentDistance2(vA[ea[0]], vA[ea[1]], vB[eb[0]], vB[eb[1]]));
        }
    }
    double d = std::sqrt(d2);
    auto overFaces = [&d](const ConvexPolyhedron& P, const Body& body, const Vec3* others, int n)
    {
        const Mat3 R = body.rotation();
        for (int f = 0; f < int(P.faces().size()); ++f)
        {
            const auto& face = P.faces()[f];
            for (int k = 0; k < n; ++k)
            {
                const Vec3 p = R.transpose()*(others[k] - body.x);
                const double h = face.normal.dot(p) - face.offset;
                bool inside = h >= 0;
                for (int m = 0; inside && m < face.count; ++m)
                {
                    const Vec3& v0 = P.vertices()[P.faceVertex(f, m)];
                    const Vec3& v1 = P.vertices()[P.faceVertex(f, (m + 1) % face.count)];
                    inside = (v1 - v0).cross(p - v0).dot(face.normal) >= 0;
                }
                if (inside) d = std::min(d, h);
            }
        }
    };
    overFaces(PB, w.bodies()[j], vA, int(PA.vertices().size()));
    overFaces(PA, w.bodies()[i], vB, int(PB.vertices().size()));
    return d;
}

//- A world without gravity (step 1 ms) with one ice material (index 0):
//  E = 1 GPa, 920 kg/m3, friction 0.2, restitution 0.3
std::unique_ptr<World> iceWorldWithoutGravity()
{
    WorldSettings s;
    s.timeStep = 1e-3;
    s.gravity = Vec3::Zero();
    auto w = std::make_unique<World>(s);
    const int mat = w->addMaterial(ice(1e9, 920));
    w->setPairProperties(mat, mat, PairProperties{0.2, 0.3});
    return w;
}

//- Body i of w as the narrow phase sees it; vertices: its world core
BodyView viewOf(const World& w, int i, const std::vector<Vec3>& vertices)
{
    const Body& b = w.bodies()[i];
    return BodyView{&w.shapeOf(i), vertices.data(), b.rotation(), b.x, b.q};
}

} // anonymous namespace


TEST(narrowPhase, twistedNearlyParallelEdgesCrossingKeepTheCoresApart)
{
    // The configuration of two floes of the compacting benchmark whose
    // cores went through each other without a contact (tests/benchmark,
    // -compactN 500, t = 10-12 s). Two prisms (cores 0.8 m thick, r = 0.1 m)
    // face each other with their sides x = 0. Each is tilted about y
    // (beta: the two sides are closer at the top, dihedral 2 beta = 0.06,
    // more than main's former parallelEdgeSin 0.05) and twisted about x the
    // other way (alpha: the top edges, sin 2 alpha = 0.0126, below it,
    // cross near y = 0).
    // Their lateral extents are staggered, so the top corner of each lies
    // above the other's top edge. The closest point of the cores is the
    // crossing of the two top edges, strictly inside both. Before: that
    // nearly parallel edge pair was not a contact, and the pairs around it
    // (vertex-face at the corners, vertex-edge at the edges' ends,
    // edge-edge with the side edges) were all outside their windows: no
    // contact at all, and the cores went through each other. (The excess
    // potential has the crossing as an edge-edge term, NarrowPhase.H.)
    const double alpha = 0.0063, beta = 0.03, r = 0.1;
    const auto world = iceWorldWithoutGravity();
    World& w = *world;
    const int mat = 0;
    const int sA = w.addShape(DilatedShape(ConvexPolyhedron::prism
    (
        {{-4, -2.65}, {0, -2.65}, {0, 2.65}, {-4, 2.65}}, -0.4, 0.8
    ), r));
    const int sB = w.addShape(DilatedShape(ConvexPolyhedron::prism
    (
        {{0, -2.45}, {4, -2.45}, {4, 2.85}, {0, 2.85}}, -0.4, 0.8
    ), r));
    const Quat qA =
        Quat(Eigen::AngleAxisd(alpha, Vec3::UnitX()))*Quat(Eigen::AngleAxisd(beta, Vec3::UnitY()));
    const Quat qB =
        Quat(Eigen::AngleAxisd(-alpha, Vec3::UnitX()))*Quat(Eigen::AngleAxisd(-beta, Vec3::UnitY()));
    w.addBody(sA, mat, Vec3::Zero(), qA);
    w.addBody(sB, mat, Vec3(0.3, 0, 0), qB, Vec3(-0.5, 0, 0));
    w.initialise();

    const double rs = 2*r;
    int touching = 0;
    double closest = 1;
    for (int step = 0; step < 1000; ++step)
    {
        w.step();
        const std::vector<Vec3> core0 = worldCore(w, 0), core1 = worldCore(w, 1);
        ASSERT_FALSE(coresIntersect(viewOf(w, 0, core0), viewOf(w, 1, core1))) << "step " << step;
        const double d = coreDistance(w, 0, 1);
        closest = std::min(closest, d);
        if (d < rs)
        {
            // The closest point of the cores is a contact, with its overlap
            ++touching;
            double deepest = 0;
            for (const auto& c : w.contacts()) deepest = std::max(deepest, c.overlap);
            ASSERT_NEAR(deepest, rs - d, 1e-9) << "step " << step;
        }
    }
    // One impact: about 40 steps of contact, an overlap of about 7 mm
    // (edge-edge, R = 10 r), as the Hertz estimate gives
    EXPECT_GT(touching, 10);
    EXPECT_LT(closest, rs - 0.003);
    // Stopped and pushed back (equal masses, e = 0.3)
    EXPECT_GT(w.bodies()[1].v.x() - w.bodies()[0].v.x(), 0);
}


TEST(narrowPhase, pairsWithASeparationCertificateCannotTouch)
{
    // The pair loop skips a pair while one of its certificates holds: the
    // separation found by a separating axis, less both bodies' motion
    // bounds since the neighbour list's build, is positive; or the
    // separation at the pair's own last check exceeds the relative motion
    // since (World::certifiedApart). Check against the brute-force
    // distance of the cores at every step of a colliding field: such a
    // pair is farther apart than r_i + r_j, so it has no contact and
    // skipping it is exact. Also across rebuilds of the neighbour list,
    // which carry the certificates over.
    auto w = makeField(100, 13);
    w->initialise();
    long skipped = 0, skippedAfterBuild = 0, touching = 0, bySinceCheck = 0;
    long builds = w->neighbourListBuilds();
    for (int step = 0; step < 1200; ++step)
    {
        w->step();
        const bool rebuilt = w->neighbourListBuilds() > builds;
        builds = w->neighbourListBuilds();
        const NeighbourList& nl = w->neighbourList();
        for (const ContactPair& p : nl.pairs())
        {
            touching += p.nContacts > 0;
            if (!w->certifiedApart(p)) continue;
            ++skipped;
            bySinceCheck += !nl.separated(p);
            skippedAfterBuild += rebuilt;
            EXPECT_EQ(p.nContacts, 0);
            const double ri = w->shapeOf(p.i).radius();
            if (p.isWall())
            {
                const Wall& wall = w->walls()[p.wall()];
                for (const Vec3& v : worldCore(*w, p.i))
                {
                    EXPECT_GT(wall.normal.dot(v - wall.point), ri)
                        << "step " << step << " body " << p.i << " wall " << p.wall();
                }
            }
            else
            {
                EXPECT_GT(coreDistance(*w, p.i, p.j), ri + w->shapeOf(p.j).radius())
                    << "step " << step << " bodies " << p.i << ", " << p.j;
            }
        }
    }
    EXPECT_GT(touching, 1000);
    EXPECT_GT(skipped, 10000);
    EXPECT_GT(skippedAfterBuild, 100);
    // The certificate from the pair's own check skips pairs the other
    // cannot
    EXPECT_GT(bySinceCheck, 10000);
}


TEST(narrowPhase, faceNormalsCertifyAPairThatNeitherAxisSeparates)
{
    // Two long boxes side by side, staggered along their length: the line
    // of their centres is not a separating axis (their projections on it
    // overlap by metres) and there is no hint yet, but the side normal y
    // separates them by 0.3 m, more than r_i + r_j = 0.2 m. Nothing
    // touches; the search certifies the pair apart by the widest face
    // normal's gap less the radii (so World skips it until it has moved
    // that much) and hands that normal on as the next hint. Without the
    // face normals such a pair had no certificate and was searched in full
    // at every step (the drifting benchmark: 994 pairs per step, now 325).
    const double r = 0.1;
    const auto world = iceWorldWithoutGravity();
    World& w = *world;
    const int mat = 0;
    const int box = w.addShape(DilatedShape(ConvexPolyhedron::prism
    (
        {{-10, -0.5}, {10, -0.5}, {10, 0.5}, {-10, 0.5}}, -0.4, 0.8
    ), r));
    w.addBody(box, mat, Vec3::Zero());
    w.addBody(box, mat, Vec3(15, 1.3, 0));
    w.initialise();

    const std::vector<Vec3> core0 = worldCore(w, 0), core1 = worldCore(w, 1);
    const BodyView A = viewOf(w, 0, core0), B = viewOf(w, 1, core1);

    // The line of centres does not separate
    const Vec3 c = (B.x - A.x).normalized();
    double maxA = -1e300, minB = 1e300;
    for (const Vec3& v : core0) maxA = std::max(maxA, c.dot(v));
    for (const Vec3& v : core1) minB = std::min(minB, c.dot(v));
    ASSERT_LT(minB - maxA, 2*r);

    FoundContact found[World::maxContactsPerPair];
    Vec3 axis = Vec3::Zero();
    double separation = std::numeric_limits<double>::lowest();
    const int n = findContacts
    (
        A, B, NarrowPhaseSettings(), axis, found, World::maxContactsPerPair, nullptr, &separation
    );
    EXPECT_EQ(n, 0);
    const double distance = coreDistance(w, 0, 1);
    EXPECT_NEAR(distance, 0.3, 1e-12);
    // A certificate, and never more than the true clearance
    EXPECT_GT(separation, 0.0999);
    EXPECT_LE(separation, distance - 2*r);
    EXPECT_NEAR(axis.y(), 1, 1e-12);

    // Moved 0.15 m closer the boxes touch along the whole overlap: terms,
    // no certificate
    const std::vector<Vec3> closer = [&]
    {
        std::vector<Vec3> v = core1;
        for (Vec3& p : v) p.y() -= 0.15;
        return v;
    }();
    BodyView Bc = B;
    Bc.vertices = closer.data();
    Bc.x.y() -= 0.15;
    axis = Vec3::Zero();
    separation = std::numeric_limits<double>::lowest();
    EXPECT_GT
    (
        findContacts(A, Bc, NarrowPhaseSettings(), axis, found, World::maxContactsPerPair, nullptr, &separation),
        0
    );
    EXPECT_EQ(separation, std::numeric_limits<double>::lowest());
}
