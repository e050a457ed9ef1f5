/*---------------------------------------------------------------------------*\
    iceDEM tests: the narrow phase's shortcut predicates (excessPotential.H)
    take the same decisions as the plain comparisons they stand for, bit for
    bit, on random inputs and on inputs placed at the comparisons' edges
    (within a few units in the last place of a tie). The shortcuts skip
    square roots and divisions (tests/benchmark/README.md, thirty-first
    round), and the list walk's first pass takes two edge pairs at a time
    (candidateLists.H, thirty-sixth round); the study's states depend on
    every decision being the same.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "contact/candidateLists.H"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <random>

using namespace iceDEM;
using namespace iceDEM::narrowPhase;

namespace
{

//- The comparisons as they were written before the shortcuts
bool plainInsideSide
(
    const Vec3& a, const Vec3& b, const Vec3& q, const Vec3& n, double R
)
{
    return (b - a).cross(q - a).dot(n) >= -tieTolerance*R*(b - a).norm();
}

bool plainSegmentSegmentInside
(
    const Vec3& p0, const Vec3& p1,
    const Vec3& q0, const Vec3& q1,
    double& s, double& t
)
{
    const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = d1.squaredNorm(), e = d2.squaredNorm();
    const double f = d2.dot(r), c = d1.dot(r), b = d1.dot(d2);
    const double denom = a*e - b*b;
    if (!(denom > 1e-12*a*e)) return false;
    const double sNum = b*f - c*e;
    if (!(sNum > 0 && sNum < denom)) return false;
    s = sNum/denom;
    t = (b*s + f)/e;
    return s > 0 && s < 1 && t > 0 && t < 1;
}

bool sameBits(double x, double y)
{
    return std::memcmp(&x, &y, sizeof(double)) == 0;
}

//- x moved by k units in the last place
double ulps(double x, int k)
{
    const double to = k > 0 ? HUGE_VAL : -HUGE_VAL;
    for (int i = 0; i < std::abs(k); ++i) x = std::nextafter(x, to);
    return x;
}

Vec3 randomUnit(std::mt19937_64& rng)
{
    std::normal_distribution<double> g;
    return Vec3(g(rng), g(rng), g(rng)).normalized();
}

} // anonymous namespace


TEST(predicates, insideSideDecidesAsThePlainComparison)
{
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> u(-1, 1);
    const double R = 0.1;
    long n = 0, nearTie = 0;
    for (int trial = 0; trial < 20000; ++trial)
    {
        // A side of a face at world coordinates of a km-sized pack
        const Vec3 origin(500*u(rng), 500*u(rng), 0.5*u(rng));
        const Vec3 nrm = randomUnit(rng);
        Vec3 along = randomUnit(rng);
        along = (along - along.dot(nrm)*nrm).normalized();
        const Vec3 inward = nrm.cross(along);
        const double len = std::exp(3*u(rng));
        const Vec3 a = origin + 2*u(rng)*along;
        const Vec3 b = a + len*along;
        // Points at signed distances from the side's line: random, at the
        // tie band's edge, and a few units in the last place around it
        const double tie = tieTolerance*R;
        const double offsets[] =
        {
            u(rng), 1e-3*u(rng), 0, -tie, -tie*(1 + 1e-6), -tie*(1 - 1e-6),
            ulps(-tie, 1), ulps(-tie, -1), ulps(-tie, 3), ulps(-tie, -3),
            -1.00005*tie, -0.99995*tie, tie, 1e-300, -1e-300
        };
        for (const double h : offsets)
        {
            const Vec3 q = a + len*u(rng)*along + h*inward;
            const bool plain = plainInsideSide(a, b, q, nrm, R);
            ASSERT_EQ(insideSide(a, b, q, nrm, R), plain)
                << "side a " << a.transpose() << " b " << b.transpose()
                << " q " << q.transpose() << " offset " << h;
            ++n;
            if (std::abs(std::abs(h) - tie) < 1e-3*tie) ++nearTie;
        }
    }
    EXPECT_GT(nearTie, 100000);
    std::cout << n << " sides, " << nearTie << " within 0.1 % of the tie band's edge\n";
}


TEST(predicates, notBelowForCertainOnlyWhereTheRootIsNotBelow)
{
    // Wherever the shortcut rejects, sqrt(dd) < beat fails; and it rejects
    // the clear cases (so that it saves the root at all)
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    long rejected = 0, n = 0;
    for (int trial = 0; trial < 200000; ++trial)
    {
        const double beat = std::exp(-12*u(rng));
        const double d2 = beat*beat;
        const double dds[] =
        {
            d2, ulps(d2, 1), ulps(d2, -1), ulps(d2, 4), ulps(d2, -4),
            d2*(1 + 1e-12), d2*(1 - 1e-12), ulps(d2*(1 + 1e-12), 1),
            ulps(d2*(1 + 1e-12), -1), d2*(1 + 3*u(rng)), d2*u(rng)
        };
        for (const double dd : dds)
        {
            ++n;
            if (notBelowForCertain(dd, beat))
            {
                ++rejected;
                ASSERT_FALSE(std::sqrt(dd) < beat) << "dd " << dd << " beat " << beat;
            }
        }
        // A clear case is taken
        ASSERT_TRUE(notBelowForCertain(4*d2, beat));
        // A negative beat is left to the comparison itself
        ASSERT_FALSE(notBelowForCertain(dds[9], -beat));
    }
    EXPECT_GT(rejected, n/10);
}


TEST(predicates, segmentSegmentInsideGivesThePlainParametersBitForBit)
{
    // Pairs of segments whose common perpendicular meets the second one at
    // t = 0 or 1 (and the first at s = 0, 1 or inside), moved by a few
    // units in the last place and by small amounts, at the coordinates of
    // a km-sized pack; plus random pairs
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> u(-1, 1);
    long n = 0, inside = 0, edge = 0;
    const double targets[] = {0, 1, 0.5};
    for (int trial = 0; trial < 20000; ++trial)
    {
        const Vec3 origin(500*u(rng), 500*u(rng), 0.5*u(rng));
        const Vec3 d2 = std::exp(2*u(rng))*randomUnit(rng);
        const Vec3 q0 = origin, q1 = origin + d2;
        Vec3 perp = randomUnit(rng);
        perp = (perp - perp.dot(d2)/d2.squaredNorm()*d2).normalized();
        Vec3 d1 = randomUnit(rng);
        d1 = (d1 - d1.dot(perp)*perp).normalized()*std::exp(2*u(rng));
        const double h = 0.2*u(rng);
        for (const double tTarget : targets)
        {
            for (const double sTarget : targets)
            {
                const double shifts[] =
                {
                    0, 1e-15, -1e-15, 1e-12, -1e-12, 1e-9, -1e-9, 1e-4*u(rng)
                };
                for (const double dt : shifts)
                {
                    const Vec3 c = q0 + (tTarget + dt)*d2 + h*perp;
                    Vec3 p0 = c - sTarget*d1;
                    Vec3 p1 = p0 + d1;
                    // and a few units in the last place on one coordinate
                    const int k = int(std::floor(7*(u(rng) + 1)/2)) - 3;
                    p1.x() = ulps(p1.x(), k);
                    double s = -1, t = -1, sPlain = -2, tPlain = -2;
                    const bool got = segmentSegmentInside(p0, p1, q0, q1, s, t);
                    const bool plain = plainSegmentSegmentInside(p0, p1, q0, q1, sPlain, tPlain);
                    ASSERT_EQ(got, plain) << "p0 " << p0.transpose() << " p1 " << p1.transpose()
                        << " q0 " << q0.transpose() << " q1 " << q1.transpose();
                    if (got)
                    {
                        ASSERT_TRUE(sameBits(s, sPlain));
                        ASSERT_TRUE(sameBits(t, tPlain));
                        ++inside;
                    }
                    if (tTarget != 0.5 && std::abs(dt) <= 1e-12) ++edge;
                    ++n;
                }
            }
        }
        // A random pair
        const Vec3 a0 = origin + randomUnit(rng), a1 = origin + 2*randomUnit(rng);
        double s = -1, t = -1, sPlain = -2, tPlain = -2;
        const bool got = segmentSegmentInside(a0, a1, q0, q1, s, t);
        ASSERT_EQ(got, plainSegmentSegmentInside(a0, a1, q0, q1, sPlain, tPlain));
        if (got)
        {
            ASSERT_TRUE(sameBits(s, sPlain));
            ASSERT_TRUE(sameBits(t, tPlain));
        }
        ++n;
    }
    EXPECT_GT(inside, n/10);
    std::cout << n << " pairs, " << inside << " inside both, " << edge
              << " within 1e-12 of an end of the second\n";
}


namespace
{

//- The walk's first pass on two pairs of segments at once (as
//  candidateLists.H writes it), lane by lane against SegmentPairTest (the pair (x[0], x[1]; x[2], x[3]) in lane 0,
//  (y[0], ...) in lane 1, and the other way round)
void expectSameInsideDecisions(const Vec3 x[4], const Vec3 y[4])
{
    using twoLanes::lanes;
    const Vec3* in[2] = {x, y};
    for (int swap = 0; swap < 2; ++swap)
    {
        const Vec3* l0 = in[swap];
        const Vec3* l1 = in[1 - swap];
        const twoLanes::Vec3x2 p0 = lanes(l0[0], l1[0]), q0 = lanes(l0[2], l1[2]);
        twoLanes::Double2 b, e, f, denom, sNum;
        const auto got = segmentPairMayBeInside
        (
            lanes(l0[1], l1[1]) - p0, lanes(l0[3], l1[3]) - q0, p0 - q0,
            b, e, f, denom, sNum
        );
        const bool plain0 = SegmentPairTest(l0[0], l0[1], l0[2], l0[3]).mayBeInside;
        const bool plain1 = SegmentPairTest(l1[0], l1[1], l1[2], l1[3]).mayBeInside;
        ASSERT_EQ(got[0] != 0, plain0)
            << "p0 " << l0[0].transpose() << " p1 " << l0[1].transpose()
            << " q0 " << l0[2].transpose() << " q1 " << l0[3].transpose();
        ASSERT_EQ(got[1] != 0, plain1)
            << "p0 " << l1[0].transpose() << " p1 " << l1[1].transpose()
            << " q0 " << l1[2].transpose() << " q1 " << l1[3].transpose();
    }
}

//- Pairs of segments that cross (seen along their common perpendicular, a
//  gap h apart) at parameters s, t of their own, the second turned by
//  angle from the first, at the coordinates of a km-sized pack
void crossingSegments
(
    std::mt19937_64& rng, double s, double t, double angle, Vec3 out[4]
)
{
    std::uniform_real_distribution<double> u(-1, 1);
    const Vec3 c(500*u(rng), 500*u(rng), 0.5*u(rng));
    const Vec3 dirA = randomUnit(rng);
    Vec3 side = randomUnit(rng);
    side = (side - side.dot(dirA)*dirA).normalized();
    const Vec3 dirB = std::cos(angle)*dirA + std::sin(angle)*side;
    const Vec3 gap = 0.05*u(rng)*dirA.cross(side);
    const double lenA = std::exp(2*u(rng)), lenB = std::exp(2*u(rng));
    out[0] = c - s*lenA*dirA;
    out[1] = out[0] + lenA*dirA;
    out[2] = c + gap - t*lenB*dirB;
    out[3] = out[2] + lenB*dirB;
}

} // anonymous namespace


TEST(predicates, walkFirstPassTwoAtATimeDecidesAsSegmentPairTest)
{
    // Each of the test's three conditions (not parallel, s inside, t not
    // outside) taken to the input where its decision flips: a parameter
    // of the family above bisected until the two inputs bracketing the
    // flip are neighbouring doubles, then those inputs and the ones a
    // few units in the last place around them, each beside a random pair
    // in the other lane. Two computations whose rounding differs anywhere
    // (a sum in another order, a product grouped otherwise) flip at
    // different inputs
    std::mt19937_64 rng(36);
    std::uniform_real_distribution<double> u(-1, 1);
    long flips = 0, n = 0;
    for (int trial = 0; trial < 3000; ++trial)
    {
        const int condition = trial % 3;
        // The family: x -> segments; the flip lies in [lo, hi]
        const std::uint64_t seed = rng();
        auto family = [&](double x, Vec3 out[4])
        {
            std::mt19937_64 same(seed);
            if (condition == 0) crossingSegments(same, 0.5, 0.5, x, out);
            else if (condition == 1) crossingSegments(same, x, 0.5, 0.7, out);
            else crossingSegments(same, 0.5, x, 0.7, out);
        };
        // sin^2 of the angle against 1e-12; s across 0; t across 1
        double lo = condition == 0 ? 0.5e-6 : condition == 1 ? -1e-6 : 1 - 1e-6;
        double hi = condition == 0 ? 2e-6 : condition == 1 ? 1e-6 : 1 + 1e-6;
        auto decision = [&](double x)
        {
            Vec3 seg[4];
            family(x, seg);
            return SegmentPairTest(seg[0], seg[1], seg[2], seg[3]).mayBeInside;
        };
        const bool atLo = decision(lo);
        if (atLo == decision(hi)) continue;
        ++flips;
        while (std::nextafter(lo, hi) < hi)
        {
            const double mid = lo + 0.5*(hi - lo);
            if (mid <= lo || mid >= hi) break;
            (decision(mid) == atLo ? lo : hi) = mid;
        }
        for (int k = -3; k <= 3; ++k)
        {
            for (const double x : {ulps(lo, k), ulps(hi, k)})
            {
                Vec3 seg[4], other[4];
                family(x, seg);
                crossingSegments(rng, 0.5 + u(rng), 0.5 + u(rng), u(rng), other);
                expectSameInsideDecisions(seg, other);
                if (HasFatalFailure()) return;
                n += 2;
            }
        }
    }
    // Nearly every family flips inside its bracket
    EXPECT_GT(flips, 2900);
    std::cout << flips << " flips, " << n << " pairs of pairs at them\n";
}
