/*---------------------------------------------------------------------------*\
    iceDEM tests: a feature-pair list stays valid under the pair's relative
    motion only (NarrowPhase.H): a pair moved and turned together by a large
    rigid motion keeps its list and gets the contacts of a full search.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "testWorlds.H"
#include "contact/NarrowPhase.H"

#include <gtest/gtest.h>

#include <limits>
#include <random>

using namespace iceDEM;
using namespace iceDEM::test;

namespace
{

//- A floe-like prism (irregular hexagon, 0.8 m thick), dilated by 0.1 m
DilatedShape floe(double scale, double phase)
{
    std::vector<Vec2> poly;
    const double radii[6] = {1.0, 1.25, 1.1, 0.95, 1.3, 1.05};
    for (int k = 0; k < 6; ++k)
    {
        const double a = phase + 2*M_PI*k/6;
        poly.emplace_back(scale*radii[k]*std::cos(a), scale*radii[k]*std::sin(a));
    }
    return DilatedShape(ConvexPolyhedron::prism(poly, -0.4, 0.8), 0.1);
}

//- A body at pose (x, q): its world core vertices and its view
struct Placed
{
    const DilatedShape* shape;
    Vec3 x;
    Quat q;
    std::vector<Vec3> w;

    Placed(const DilatedShape& S, const Vec3& x0, const Quat& q0)
    :
        shape(&S), x(x0), q(q0.normalized())
    {
        const Mat3 R = q.toRotationMatrix();
        for (const Vec3& s : S.core().vertices()) w.push_back(x + R*s);
    }

    BodyView view() const
    {
        return BodyView{shape, w.data(), q.toRotationMatrix(), x, q};
    }

    //- The same body after the rigid motion y -> G y + g of the world
    Placed moved(const Quat& G, const Vec3& g) const
    {
        return Placed(*shape, G*x + g, G*q);
    }
};

Quat rotation(double angle, const Vec3& axis)
{
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

//- The contacts of a and b agree bit for bit (same order)
void expectSameContacts(const FoundContact* a, int na, const FoundContact* b, int nb)
{
    ASSERT_EQ(na, nb);
    for (int k = 0; k < na; ++k)
    {
        EXPECT_EQ(a[k].featureA, b[k].featureA) << "contact " << k;
        EXPECT_EQ(a[k].featureB, b[k].featureB) << "contact " << k;
        EXPECT_EQ(a[k].g.overlap, b[k].g.overlap) << "contact " << k;
        EXPECT_EQ(a[k].g.weight, b[k].g.weight) << "contact " << k;
        for (int c = 0; c < 3; ++c)
        {
            EXPECT_EQ(a[k].g.point[c], b[k].g.point[c]) << "contact " << k;
            EXPECT_EQ(a[k].g.normal[c], b[k].g.normal[c]) << "contact " << k;
        }
    }
}

constexpr int maxOut = 64;

} // anonymous namespace


TEST(featurePairLists, relativeMotionBoundHoldsForEveryCorePoint)
{
    // The bound of the list's validity: every core point of B moves in A's
    // frame by at most m_B|A, every core point of A in B's frame by at most
    // m_A|B; relativeMotionBound is the smaller. Checked on the vertices
    // (the cores' extreme points) for random poses and random motions.
    const DilatedShape SA = floe(1.0, 0.2), SB = floe(1.4, 1.1);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    auto randomQuat = [&]() { return Quat(u(rng), u(rng), u(rng), u(rng)).normalized(); };
    auto randomVec = [&](double a) { return Vec3(a*u(rng), a*u(rng), a*u(rng)); };
    const double RA = SA.boundingRadius(), RB = SB.boundingRadius();
    int tight = 0;
    for (int trial = 0; trial < 2000; ++trial)
    {
        const Placed A0(SA, randomVec(500), randomQuat());
        const Placed B0(SB, A0.x + randomVec(3), randomQuat());
        // The pair moved by a large common rigid motion, then B a little
        // relative to A (or A relative to B)
        const Quat G = randomQuat();
        const Vec3 g = randomVec(1000);
        const double size = trial % 2 ? 0.05 : 0.5;
        Placed A1 = A0.moved(G, g);
        Placed B1 = B0.moved(G, g);
        const Quat dq = rotation(size*u(rng), randomVec(1));
        if (trial % 3 == 0) A1 = Placed(SA, A1.x + randomVec(size), dq*A1.q);
        else B1 = Placed(SB, B1.x + randomVec(size), dq*B1.q);

        const RelativePose r0 = relativePose(A0.view(), B0.view());
        const RelativePose r1 = relativePose(A1.view(), B1.view());
        const double bound = relativeMotionBound(r0.t, r0.Q, r1.t, r1.Q, RA, RB);

        // Displacements in A's frame (of B's vertices) and in B's frame
        // (of A's vertices)
        double moveBInA = 0, moveAInB = 0;
        for (std::size_t k = 0; k < B0.w.size(); ++k)
        {
            const Vec3 y0 = A0.q.conjugate()*(B0.w[k] - A0.x);
            const Vec3 y1 = A1.q.conjugate()*(B1.w[k] - A1.x);
            moveBInA = std::max(moveBInA, (y1 - y0).norm());
        }
        for (std::size_t k = 0; k < A0.w.size(); ++k)
        {
            const Vec3 y0 = B0.q.conjugate()*(A0.w[k] - B0.x);
            const Vec3 y1 = B1.q.conjugate()*(A1.w[k] - B1.x);
            moveAInB = std::max(moveAInB, (y1 - y0).norm());
        }
        // Each frame's bound alone (the other one made infinite), then the
        // smaller; rounding of the world coordinates (up to 1,500 m): 1e-9 m
        const double inf = std::numeric_limits<double>::infinity();
        const double boundBInA = relativeMotionBound(r0.t, r0.Q, r1.t, r1.Q, inf, RB);
        const double boundAInB = relativeMotionBound(r0.t, r0.Q, r1.t, r1.Q, RA, inf);
        EXPECT_LE(moveBInA, boundBInA + 1e-9) << "trial " << trial;
        EXPECT_LE(moveAInB, boundAInB + 1e-9) << "trial " << trial;
        EXPECT_EQ(bound, std::min(boundBInA, boundAInB));
        EXPECT_LE(std::min(moveBInA, moveAInB), bound + 1e-9) << "trial " << trial;
        tight += std::min(moveBInA, moveAInB) > 0.5*bound;
    }
    // Not vacuous: the bound is close to the real motion in most trials
    EXPECT_GT(tight, 1000);
}


TEST(featurePairLists, keptUnderACommonRigidMotionWithTheContactsOfAFullSearch)
{
    // Two floes pressed side to side (the cores 0.05 m apart, r_A + r_B =
    // 0.2 m), a list built by a full search; then both moved 400 m and
    // turned by up to a radian together, with B moved relative to A by
    // less or more than the skin. The list is kept exactly when the
    // relative motion is below the skin (the world motion of each body
    // being hundreds of metres), and the contacts are those of a full
    // search bit for bit, kept list or not. A kept list skips the entries
    // whose certificate exceeds the relative motion (NarrowPhase.H, entry
    // certificates): its contacts and its next axis (the closest pair when
    // nothing touches) are those of the same list walked without
    // certificates, bit for bit.
    const DilatedShape SA = floe(1.0, 0.2), SB = floe(1.1, 0.9);
    NarrowPhaseSettings nps;
    nps.featureSkin = 0.05;

    // B beside A along x, its core 0.05 m from A's, a little turned
    const Quat qB = rotation(0.02, Vec3(0.2, 0.1, 1.0));
    double xB = 0;
    {
        // Smallest x at which the cores are 0.05 m apart along x: the gap
        // of the two cores' extents along x
        double maxA = -1e9, minB = 1e9;
        for (const Vec3& s : SA.core().vertices()) maxA = std::max(maxA, s.x());
        const Mat3 R = qB.toRotationMatrix();
        for (const Vec3& s : SB.core().vertices()) minB = std::min(minB, (R*s).x());
        xB = maxA - minB + 0.05;
    }
    const Placed A0(SA, Vec3::Zero(), Quat::Identity());
    const Placed B0(SB, Vec3(xB, 0.1, 0.0), qB);

    FeaturePairEntry buffer0[FeaturePairList::capacity];
    FeaturePairEntry buffer1[FeaturePairList::capacity];
    FeaturePairEntry buffer2[FeaturePairList::capacity];
    FeaturePairEntry bare[FeaturePairList::capacity];
    FeaturePairList list0;
    list0.buffer = buffer0;
    FoundContact found[maxOut];
    Vec3 axis = Vec3::Zero();
    const int n0 = findContacts(A0.view(), B0.view(), nps, axis, found, maxOut, &list0);
    ASSERT_GT(n0, 0);
    ASSERT_GT(list0.count, 0);
    ASSERT_EQ(list0.entries, buffer0);
    // The same entries without certificates
    int certified = 0;
    for (int k = 0; k < list0.count; ++k)
    {
        bare[k] = FeaturePairEntry{list0.entries[k].key, 0};
        certified += list0.entries[k].margin > 0;
    }
    EXPECT_GT(certified, list0.count/4);

    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    int kept = 0, rebuilt = 0, withContacts = 0, walksSkipping = 0, keptWithout = 0;
    long skipped = 0;
    for (int trial = 0; trial < 400; ++trial)
    {
        // A large common rigid motion
        const Quat G = rotation(u(rng), Vec3(u(rng), u(rng), 1 + u(rng)));
        const Vec3 g(400*u(rng), 400*u(rng), u(rng));
        const Placed A1 = A0.moved(G, g);
        Placed B1 = B0.moved(G, g);
        // B relative to A, in A's frame: up to twice the skin
        const double size = 0.1*std::abs(u(rng));
        const Vec3 shift = size*Vec3(u(rng), u(rng), 0.3*u(rng)).normalized();
        const Quat turn = rotation(0.3*size/SB.boundingRadius(), Vec3(u(rng), u(rng), u(rng)));
        B1 = Placed(SB, B1.x + A1.q*shift, A1.q*turn*A1.q.conjugate()*B1.q);

        // The world-frame bound of each body's motion would lapse the list
        const double worldMotion =
            motionBound(A0.x, A0.q, A1.x, A1.q, SA.boundingRadius())
          + motionBound(B0.x, B0.q, B1.x, B1.q, SB.boundingRadius());
        EXPECT_GT(worldMotion, 10*nps.featureSkin);

        FeaturePairList list = list0;
        list.buffer = buffer1;
        list.touched = true;
        Vec3 axisList = axis;
        FoundContact withList[maxOut];
        const int nList = findContacts(A1.view(), B1.view(), nps, axisList, withList, maxOut, &list);

        Vec3 axisFull = Vec3::Zero();
        FoundContact full[maxOut];
        const int nFull = findContacts(A1.view(), B1.view(), nps, axisFull, full, maxOut, nullptr);
        expectSameContacts(withList, nList, full, nFull);
        withContacts += nFull > 0;

        // Kept (entries and relative pose of the search untouched) exactly
        // when the relative motion is below the skin less the rounding
        // allowance
        const RelativePose r = relativePose(A1.view(), B1.view());
        const double relative = relativeMotionBound
        (
            list0.t, list0.Q, r.t, r.Q, SA.boundingRadius(), SB.boundingRadius()
        );
        const double eta = 1e-6*(SA.boundingRadius() + SB.boundingRadius());
        // Its entries in the buffer (rebuilt, or certificates renewed) or
        // where they were
        EXPECT_TRUE(list.entries == buffer1 || list.entries == buffer0);
        if (list.t == list0.t && list.Q.coeffs() == list0.Q.coeffs())
        {
            ++kept;
            EXPECT_LT(relative, nps.featureSkin - eta) << "trial " << trial;
            ASSERT_EQ(list.count, list0.count);
            // The same feature pairs (kind | a | b; bit 28, the flag of a
            // certificate by distance, may change with the certificate)
            const std::uint32_t pairBits = ~(std::uint32_t(1) << 28);
            int skips = 0;
            for (int k = 0; k < list0.count; ++k)
            {
                EXPECT_EQ(list.entries[k].key & pairBits, list0.entries[k].key & pairBits);
                skips += relative < list0.entries[k].margin;
            }
            skipped += skips;
            walksSkipping += skips > 0;

            // The same list without certificates: the same contacts and
            // the same next axis
            FeaturePairList without = list0;
            without.entries = bare;
            without.buffer = buffer2;
            without.touched = true;
            Vec3 axisWithout = axis;
            FoundContact withoutFound[maxOut];
            const int nWithout = findContacts
            (
                A1.view(), B1.view(), nps, axisWithout, withoutFound, maxOut, &without
            );
            expectSameContacts(withList, nList, withoutFound, nWithout);
            keptWithout += nWithout == 0;
            for (int c = 0; c < 3; ++c)
            {
                EXPECT_EQ(axisList[c], axisWithout[c]) << "trial " << trial;
            }
        }
        else
        {
            ++rebuilt;
            EXPECT_GE(relative, nps.featureSkin - eta) << "trial " << trial;
        }
        // The relative pose is what the list sees: B's centroid moved in
        // A's frame by the shift applied there
        EXPECT_NEAR((r.t - list0.t).norm(), size, 1e-9);
    }
    // Both branches exercised, and mostly with contacts
    EXPECT_GT(kept, 100);
    EXPECT_GT(rebuilt, 100);
    EXPECT_GT(withContacts, 200);
    // Certificates skipped entries in most kept walks
    EXPECT_GT(walksSkipping, kept/2);
    EXPECT_GT(skipped, 2*kept);
    std::printf
    (
        "kept %d, rebuilt %d; in the kept walks %ld entries skipped of %d x %d;"
        " %d kept walks without contact\n",
        kept, rebuilt, skipped, kept, list0.count, keptWithout
    );
}
