/*---------------------------------------------------------------------------*\
    iceDEM tests: a feature-pair list stays valid under the pair's relative
    motion only (NarrowPhase.H): a pair moved and turned together by a large
    rigid motion keeps its list and gets the contacts of a full search.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "testWorlds.H"
#include "contact/NarrowPhase.H"

#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <memory>
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

//- Where B (shape SB, orientation qB) placed at A's centroid + d dir first
//  touches A, coming from far away: a scan in steps of 5 mm from the sum
//  of the bounding radii, then bisection to the rounding of the
//  coordinates; -1 if B touches at no d above 0. out: room for maxOut
//  terms (the full search's, overwritten)
double firstContactDistance
(
    const Placed& A,
    const DilatedShape& SB,
    const Quat& qB,
    const Vec3& dir,
    FoundContact* out
)
{
    const NarrowPhaseSettings none;
    auto touchesAt = [&](double d)
    {
        const Placed B(SB, A.x + d*dir, qB);
        Vec3 axis = Vec3::Zero();
        return findContacts(A.view(), B.view(), none, axis, out, maxOut) > 0;
    };
    double touching = A.shape->boundingRadius() + SB.boundingRadius();
    while (touching > 0 && !touchesAt(touching)) touching -= 0.005;
    if (!(touching > 0)) return -1;
    double apart = touching + 0.005;
    for (int k = 0; k < 80; ++k)
    {
        const double mid = 0.5*(touching + apart);
        (touchesAt(mid) ? touching : apart) = mid;
    }
    return touching;
}

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


namespace
{

//- Follows two floes through a random walk of small relative motions that
//  keeps them touching (or nearly), and compares at every step the terms
//  of findContacts with the pair's candidate list (skin) against those of
//  the full search (no list), bit for bit; counts the steps that walked a
//  kept list, and the terms of each type
struct ListRun
{
    int steps = 0;
    int reused = 0;
    int touching = 0;
    int types[5] = {0, 0, 0, 0, 0};
};

void walkPair
(
    const DilatedShape& SA,
    const DilatedShape& SB,
    bool upright,
    double skin,
    double stepSize,
    std::uint64_t seed,
    ListRun& run
)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    auto randomVec = [&](double a) { return Vec3(a*u(rng), a*u(rng), a*u(rng)); };
    auto randomQuat = [&]()
    {
        return upright
          ? rotation(M_PI*u(rng), Vec3::UnitZ())
          : Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
    };

    const Quat qA = randomQuat(), qB = randomQuat();
    const Vec3 xA = randomVec(50);
    Vec3 dir = upright ? Vec3(u(rng), u(rng), 0) : randomVec(1);
    dir.normalize();
    // From far away towards A until the full search finds a term
    double dist = SA.boundingRadius() + SB.boundingRadius();
    NarrowPhaseSettings none, lists;
    lists.featureSkin = skin;
    FoundContact full[maxOut], fromList[maxOut];
    Vec3 axisFull = Vec3::Zero(), axisList = Vec3::Zero();
    Placed A(SA, xA, qA);
    Placed B(SB, xA + dist*dir, qB);
    while (dist > 0)
    {
        B = Placed(SB, xA + dist*dir, qB);
        Vec3 axis = Vec3::Zero();
        if (findContacts(A.view(), B.view(), none, axis, full, maxOut) > 0) break;
        dist -= 0.005;
    }

    FeaturePairEntry buffer[FeaturePairList::capacity];
    FeaturePairList list;
    list.buffer = buffer;
    // A random walk of B (and sometimes A): steps of stepSize, drawn back
    // towards contact when the pair drifts apart, pushed out when deep
    Vec3 drift = Vec3::Zero();
    for (int step = 0; step < 400; ++step)
    {
        const int before = list.count;
        const Vec3 t0 = list.t;
        const int nFull = findContacts(A.view(), B.view(), none, axisFull, full, maxOut);
        const int nList = findContacts(A.view(), B.view(), lists, axisList, fromList, maxOut, &list);
        // As World::pairForces: a pair that touches walks its held list
        // before the separating axes at its next search
        list.touched = nList > 0;
        expectSameContacts(full, nFull, fromList, nList);
        ASSERT_FALSE(::testing::Test::HasFailure()) << "seed " << seed << " step " << step;
        EXPECT_EQ(axisFull, axisList);
        ++run.steps;
        run.reused += before >= 0 && list.count == before && list.t == t0;
        run.touching += nFull > 0;
        for (int k = 0; k < nFull; ++k) ++run.types[int(full[k].g.type)];

        double deepest = 0;
        for (int k = 0; k < nFull; ++k) deepest = std::max(deepest, full[k].g.overlap);
        const Vec3 toA = (A.x - B.x).normalized();
        const double pull = nFull == 0 ? 1 : (deepest > 0.05 ? -1 : 0);
        drift = 0.7*drift + randomVec(stepSize) + 0.5*stepSize*pull*toA;
        const Quat turn = rotation(0.5*stepSize*u(rng), upright ? Vec3::UnitZ() : randomVec(1));
        if (step % 5 == 0)
        {
            A = Placed(SA, A.x - 0.3*drift, turn.conjugate()*A.q);
        }
        B = Placed(SB, B.x + drift, turn*B.q);
    }
}

} // anonymous namespace


TEST(candidateLists, sameTermsAsTheFullSearchBitForBit)
{
    // The candidate lists of the excess potential (candidateLists.H) give
    // the full search's terms, in its order, to the bit, at every step of
    // random walks of touching floes (upright ones: faces, edges and
    // vertices level with each other; tilted ones), with the default skin
    // (r/2) and a larger one, small steps and large; not vacuous: most
    // steps walk a kept list, but not all (the lists are rebuilt), most
    // touch, and every type of term occurs
    const DilatedShape SA = floe(1.0, 0.2), SB = floe(1.4, 1.1);
    ListRun run;
    int seed = 0;
    for (const bool upright : {true, false})
    {
        for (const double skin : {0.05, 0.15})
        {
            for (const double stepSize : {0.004, 0.02})
            {
                for (int k = 0; k < 10; ++k)
                {
                    walkPair(SA, SB, upright, skin, stepSize, 100 + seed++, run);
                    if (::testing::Test::HasFailure()) return;
                }
            }
        }
    }
    EXPECT_EQ(run.steps, 80*400);
    EXPECT_GT(run.reused, run.steps/2);
    EXPECT_GT(run.steps - run.reused, run.steps/20);
    EXPECT_GT(run.touching, run.steps/2);
    for (int t = 0; t < 4; ++t)
    {
        EXPECT_GT(run.types[t], 100) << featurePairName(FeaturePair(t));
    }
    std::cout << "steps " << run.steps << ", list kept " << run.reused
              << ", touching " << run.touching << "; terms: vertexVertex "
              << run.types[0] << ", vertexEdge " << run.types[1]
              << ", vertexFace " << run.types[2] << ", edgeEdge "
              << run.types[3] << std::endl;
}


TEST(candidateLists, skinBeyondTheContactsHoldsForTheNearestVertex)
{
    // A skin larger than the dilation radii's sum (0.3 m against R =
    // 0.2 m; kullukPack: 0.1 m against 0.1 m): every vertex of a contact
    // is within the skin of the other core, so a list may hold only until
    // the nearest listed vertex could reach the other core's inside (its
    // limit, candidateLists.H). The same terms as the full search to the
    // bit, and the lists are kept (before the limit, a touching pair was
    // searched in full at every step: no list kept while touching)
    const DilatedShape SA = floe(1.0, 0.2), SB = floe(1.4, 1.1);
    ListRun run;
    int seed = 500;
    for (const bool upright : {true, false})
    {
        for (const double stepSize : {0.004, 0.02})
        {
            for (int k = 0; k < 5; ++k)
            {
                walkPair(SA, SB, upright, 0.3, stepSize, seed++, run);
                if (::testing::Test::HasFailure()) return;
            }
        }
    }
    EXPECT_EQ(run.steps, 20*400);
    EXPECT_GT(run.touching, run.steps/2);
    EXPECT_GT(run.reused, run.steps/2);
    // Rebuilt (at each walk's start and when a list lapses) often enough
    // that the builds are compared too
    EXPECT_GT(run.steps - run.reused, 200);
    std::cout << "steps " << run.steps << ", list kept " << run.reused
              << ", touching " << run.touching << std::endl;
}


TEST(candidateLists, noSkinMeansNoList)
{
    // featureSkin 0: the full search on every call, no list kept
    const DilatedShape SA = floe(1.0, 0.2), SB = floe(1.4, 1.1);
    const Placed A(SA, Vec3::Zero(), Quat::Identity());
    const Placed B(SB, Vec3(2.5, 0, 0), rotation(0.3, Vec3::UnitZ()));
    NarrowPhaseSettings none;
    FoundContact found[maxOut];
    FeaturePairEntry buffer[FeaturePairList::capacity];
    FeaturePairList list;
    list.buffer = buffer;
    list.count = 3;
    Vec3 axis = Vec3::Zero();
    findContacts(A.view(), B.view(), none, axis, found, maxOut, &list);
    EXPECT_EQ(list.count, -1);
}


TEST(candidateLists, fieldWithListsFollowsTheFullSearchBitForBit)
{
    // A walled field of colliding prisms with the lists (the default skin)
    // and without (featureSkin 0): the same trajectory to the bit. Not
    // vacuous: the pool of lists, which keeps a list where it is until its
    // pair replaces or drops it, is compacted more than once (garbage of
    // replaced lists and of pairs the neighbour list dropped)
    auto full = makeField(300, 17, 0);
    auto listed = makeField(300, 17);
    int touching = 0;
    while (listed->time() < 3.0)
    {
        listed->step();
        touching = std::max(touching, listed->contactPairCount());
    }
    full->advanceTo(listed->time());
    std::cout << "touching pairs up to " << touching << ", list pool compactions "
        << listed->featureListCompactions() << ", neighbour-list builds "
        << listed->neighbourListBuilds() << std::endl;
    EXPECT_GT(touching, 20);
    EXPECT_GT(listed->featureListCompactions(), 1);
    EXPECT_EQ(full->featureListCompactions(), 0);
    expectSameState(*full, *listed);
}


namespace
{

//- A pile of n^3 random convex hulls (clouds of 4 to 20 points, flattened
//  at random, dilated by 2-6 cm) dropped from a lattice of spacing 0.8 m
//  into a walled box under gravity, with friction and damping, and the
//  given candidate-list skin (World.H: < 0 the default, 0 none)
std::unique_ptr<World> pileOfHulls(int n, double featureSkin)
{
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    std::normal_distribution<double> g(0, 1);
    std::uniform_int_distribution<int> nPoints(4, 20);
    auto in = [&](double a, double b) { return a + (b - a)*0.5*(1 + u(rng)); };
    WorldSettings s;
    s.timeStep = 2e-5;
    s.featureSkin = featureSkin;
    auto w = std::make_unique<World>(s);
    const int mat = w->addMaterial(ice(1e9, 900));
    w->setPairProperties(mat, mat, PairProperties{0.5, 0.3});
    const double spacing = 0.8, half = 0.5*n*spacing, reach = 0.4;
    const Vec3 dirs[6] =
    {
        Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()
    };
    for (int k = 0; k < 6; ++k)
    {
        Wall wall;
        wall.name = "wall" + std::to_string(k);
        wall.point = -(half + 0.25)*dirs[k];
        wall.normal = dirs[k];
        wall.material = mat;
        w->addWall(wall);
    }
    for (int i = 0; i < n*n*n; ++i)
    {
        const double r = in(0.02, 0.06);
        const Vec3 axes(in(0.5, 1), in(0.5, 1), in(0.5, 1));
        const double scale = in(0.25, 0.5);
        int shape = -1;
        while (shape < 0)
        {
            std::vector<Vec3> p;
            const int np = nPoints(rng);
            double far = 0;
            for (int k = 0; k < np; ++k)
            {
                p.push_back(scale*Vec3(axes.x()*g(rng), axes.y()*g(rng), axes.z()*g(rng)));
                far = std::max(far, p.back().norm());
            }
            // Within reach of its lattice site, so that no two start in touch
            if (far + r > reach) for (Vec3& v : p) v *= (reach - r)/far;
            try
            {
                shape = w->addShape(DilatedShape(ConvexPolyhedron::hull(p), r));
            }
            catch (const Error&) {}     // a flat draw: drawn again
        }
        const Vec3 x
        (
            -half + (i % n + 0.5)*spacing,
            -half + (i/n % n + 0.5)*spacing,
            -half + (i/(n*n) + 0.5)*spacing
        );
        const Quat q(Eigen::AngleAxisd(3*u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
        w->addBody(shape, mat, x, q, Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)));
    }
    w->initialise();
    return w;
}

} // anonymous namespace


TEST(candidateLists, pileOfRandomHullsFollowsTheFullSearchBitForBit)
{
    // The field above is of prisms; general hulls have vertices of up to
    // seven faces and edges in every direction, the lists' vertex groups
    // and edge pairs of every kind. 64 of them fall into a pile that rests
    // on the floor and the walls, with persistent contacts: with the lists
    // (the default skin) and without, the same trajectory to the bit
    auto full = pileOfHulls(4, 0);
    auto listed = pileOfHulls(4, -1);
    while (listed->time() < 1.2) listed->step();
    full->advanceTo(listed->time());
    std::cout << "contacts " << listed->contactCount() << " in "
        << listed->contactPairCount() << " touching pairs, list pool compactions "
        << listed->featureListCompactions() << std::endl;
    EXPECT_GT(listed->contactPairCount(), 40);
    EXPECT_GT(listed->featureListCompactions(), 1);
    EXPECT_EQ(full->featureListCompactions(), 0);
    expectSameState(*full, *listed);
}


TEST(candidateLists, touchingWalkSkipsTheAxesOnlyWhereNoneCanSeparate)
{
    // A pair whose held list is walked and still touches skips the
    // separating axes when its deepest term overlaps by more than the
    // rounding of a gap (NarrowPhase.C). Floes about 700 m from the origin
    // (the study's periodic pack reaches that far), upright and tilted,
    // their deepest overlap set from about 1e-13 m to 1e-6 m, within and
    // beyond that rounding (2e-11 m here): the terms and the next axis of
    // the walk are those of the full search, bit for bit
    const DilatedShape SA = floe(1.0, 0.2), SB = floe(1.4, 1.1);
    std::mt19937_64 rng(71);
    std::uniform_real_distribution<double> u(-1, 1);
    NarrowPhaseSettings none, lists;
    lists.featureSkin = 0.05;
    int compared = 0, deep = 0, shallow = 0;
    for (int trial = 0; trial < 200; ++trial)
    {
        const bool upright = trial % 2 == 0;
        auto randomQuat = [&]()
        {
            return upright
              ? rotation(M_PI*u(rng), Vec3::UnitZ())
              : Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
        };
        const Quat qA = randomQuat(), qB = randomQuat();
        const Vec3 xA(700*u(rng), 700*u(rng), 0.1*u(rng));
        Vec3 dir = upright ? Vec3(u(rng), u(rng), 0) : Vec3(u(rng), u(rng), u(rng));
        dir.normalize();
        const Placed A(SA, xA, qA);
        FoundContact full[maxOut], fromList[maxOut];
        // The first contact from far away, to within the rounding of the
        // coordinates
        const double touching = firstContactDistance(A, SB, qB, dir, full);
        if (!(touching > 0)) continue;
        for (const double depth : {1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6})
        {
            const Placed B(SB, xA + (touching - depth)*dir, qB);
            FeaturePairEntry buffer[FeaturePairList::capacity];
            FeaturePairList list;
            list.buffer = buffer;
            Vec3 axisFull = Vec3::Zero(), axisList = Vec3::Zero();
            // The list's build, then its walk at the same poses (a pair
            // that touched walks its held list first, as World does)
            for (int call = 0; call < 2; ++call)
            {
                const int nFull = findContacts(A.view(), B.view(), none, axisFull, full, maxOut);
                const int nList =
                    findContacts(A.view(), B.view(), lists, axisList, fromList, maxOut, &list);
                list.touched = nList > 0;
                expectSameContacts(full, nFull, fromList, nList);
                ASSERT_FALSE(::testing::Test::HasFailure())
                    << "trial " << trial << " depth " << depth << " call " << call;
                EXPECT_EQ(axisFull, axisList);
                if (call == 1 && nFull > 0)
                {
                    ++compared;
                    double deepest = 0;
                    for (int k = 0; k < nFull; ++k) deepest = std::max(deepest, full[k].g.overlap);
                    ++(deepest > 2e-10 ? deep : shallow);
                }
            }
        }
    }
    // Not vacuous: walks that skip the axes and walks that try them
    EXPECT_GT(deep, 500);
    EXPECT_GT(shallow, 100);
    std::cout << compared << " walks of touching pairs: " << deep
              << " deeper than 2e-10 m, " << shallow << " shallower\n";
}


TEST(candidateLists, edgePairsComingIntoReachAreWalkedInTime)
{
    // An edge pair listed beyond reach (its margin, the segments' distance
    // at the build less R and the slack) must be evaluated as soon as the
    // relative motion bound passes that margin: tilted floes whose first
    // contact is an edge crossing an edge, the list built while they are
    // a few millimetres apart, then B moved straight at A in steps of
    // 0.25 mm. The terms of every step, the first edge-edge term among
    // them, are those of the full search, bit for bit, from the held list
    // (an entry evaluated 1 mm late, or its first tests dropping a pair
    // that can touch, fails here)
    const DilatedShape SA = floe(1.0, 0.2), SB = floe(1.4, 1.1);
    std::mt19937_64 rng(97);
    std::uniform_real_distribution<double> u(-1, 1);
    NarrowPhaseSettings none, lists;
    lists.featureSkin = 0.05;
    int edgeFirst = 0;
    for (int trial = 0; trial < 400 && edgeFirst < 40; ++trial)
    {
        const Quat qA = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
        const Quat qB = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
        const Vec3 xA(50*u(rng), 50*u(rng), 0.1*u(rng));
        const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
        const Placed A(SA, xA, qA);
        FoundContact full[maxOut], fromList[maxOut];
        // The first contact, and its one term an edge-edge one
        const double touching = firstContactDistance(A, SB, qB, dir, full);
        if (!(touching > 0)) continue;
        const Placed atContact(SB, xA + touching*dir, qB);
        Vec3 axisFirst = Vec3::Zero();
        const int nFirst =
            findContacts(A.view(), atContact.view(), none, axisFirst, full, maxOut);
        if (!(nFirst == 1 && full[0].g.type == FeaturePair::edgeEdge)) continue;

        // The list built 2-5 mm before that contact, then the approach
        const double gap = 0.002 + 0.003*0.5*(1 + u(rng));
        FeaturePairEntry buffer[FeaturePairList::capacity];
        FeaturePairList list;
        list.buffer = buffer;
        Vec3 axisFull = Vec3::Zero(), axisList = Vec3::Zero();
        bool builtApart = false, heldAtContact = false;
        for (double d = touching + gap; d > touching - 0.002; d -= 2.5e-4)
        {
            const Placed B(SB, xA + d*dir, qB);
            const int before = list.count;
            const Vec3 t0 = list.t;
            const int nFull = findContacts(A.view(), B.view(), none, axisFull, full, maxOut);
            const int nList =
                findContacts(A.view(), B.view(), lists, axisList, fromList, maxOut, &list);
            list.touched = nList > 0;
            expectSameContacts(full, nFull, fromList, nList);
            ASSERT_FALSE(::testing::Test::HasFailure()) << "trial " << trial << " d " << d;
            EXPECT_EQ(axisFull, axisList);
            const bool held = before >= 0 && list.count == before && list.t == t0;
            if (d > touching + 1e-3 && nFull == 0 && list.count >= 0) builtApart = true;
            if (nFull > 0)
            {
                heldAtContact = builtApart && held;
                break;
            }
        }
        edgeFirst += heldAtContact;
    }
    // Not vacuous: approaches whose first term, an edge-edge one, came from
    // a list held since the floes were apart
    EXPECT_GE(edgeFirst, 20);
    std::cout << edgeFirst << " approaches met at an edge-edge term by a held list\n";
}
