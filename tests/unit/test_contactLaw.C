/*---------------------------------------------------------------------------*\
    iceDEM tests: the contact law's two contacts at a time (evaluateTwo, the
    pair loop's path) give what evaluate gives on each, to the bit, in every
    regime: sticking and sliding springs, separating contacts, subtracted
    and fractional terms, a spring with no length, no tangential stiffness.
    Both are one template (ContactLaw.C, hertzLaw); what differs is what it
    is built from, per type: the lanes' products, roots and dot products
    (twoLanes.H) and the selections where one contact branches.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "testWorlds.H"
#include "contact/ContactLaw.H"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

using namespace iceDEM;
using namespace iceDEM::test;

namespace
{

bool sameBits(double a, double b)
{
    return std::memcmp(&a, &b, sizeof(double)) == 0;
}

bool sameBits(const Vec3& a, const Vec3& b)
{
    return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

Vec3 unitVector(std::mt19937_64& rng)
{
    std::normal_distribution<double> N(0, 1);
    Vec3 v(N(rng), N(rng), N(rng));
    return v.normalized();
}

//- A random contact: every feature pair, weights of either sign, springs
//  from none to well past the friction cap, approaching and separating
struct RandomContact
{
    ContactGeometry g;
    Vec3 vRel;
    Vec3 xi;
};

RandomContact randomContact(std::mt19937_64& rng)
{
    std::uniform_real_distribution<double> U(0, 1);
    RandomContact c;
    const FeaturePair types[] =
    {
        FeaturePair::vertexVertex, FeaturePair::vertexEdge, FeaturePair::vertexFace,
        FeaturePair::edgeEdge, FeaturePair::vertexWall
    };
    c.g.type = types[static_cast<int>(U(rng)*5) % 5];
    c.g.normal = unitVector(rng);
    c.g.point = Vec3(U(rng), U(rng), U(rng))*10.0;
    c.g.overlap = 1e-5 + 1e-2*U(rng);
    c.g.radiusI = 0.05 + 0.3*U(rng);
    c.g.radiusJ = c.g.type == FeaturePair::vertexWall ? 0 : 0.05 + 0.3*U(rng);
    c.g.sinAngle = 1e-3 + U(rng);
    const double kind = U(rng);
    c.g.weight = kind < 0.2 ? -1.0 : kind < 0.5 ? U(rng) : 1.0;
    if (kind >= 0.2 && kind < 0.5)
    {
        c.g.weightGradient = unitVector(rng)*U(rng);
        c.g.weightGradientX = unitVector(rng)*U(rng);
    }
    c.vRel = unitVector(rng)*(3*U(rng));
    const double spring = U(rng);
    c.xi = spring < 0.15 ? Vec3::Zero()
         : spring < 0.25 ? Vec3(c.g.normal*1e-3)     // along the normal: no tangential part
         : Vec3(unitVector(rng)*(1e-2*U(rng)*U(rng)));
    return c;
}

//- evaluate on a and b, then evaluateTwo on both: every result to the bit;
//  returns evaluate's result for a
ContactResult expectSameBits
(
    const ContactLaw& law,
    const PairCoefficients& pc,
    const RandomContact& a,
    const RandomContact& b,
    double mEff,
    double dt
)
{
    // Each lane its own damping mass (a pair's damping shared by its
    // terms' stiffness, ContactLawSettings::dampingPerPair)
    const double mEffs[2] = {mEff, 0.37*mEff};
    Vec3 xiA = a.xi, xiB = b.xi;
    const ContactResult rA = law.evaluate(pc, a.g, mEffs[0], a.vRel, xiA, dt);
    const ContactResult rB = law.evaluate(pc, b.g, mEffs[1], b.vRel, xiB, dt);

    const ContactGeometry* const g[2] = {&a.g, &b.g};
    const Vec3 vRel[2] = {a.vRel, b.vRel};
    Vec3 xi2[2] = {a.xi, b.xi};
    Vec3* const xi[2] = {&xi2[0], &xi2[1]};
    ContactResult r[2];
    law.evaluateTwo(pc, g, mEffs, vRel, xi, dt, r);

    const ContactResult* one[2] = {&rA, &rB};
    const Vec3* xiOne[2] = {&xiA, &xiB};
    for (int k = 0; k < 2; ++k)
    {
        EXPECT_TRUE(sameBits(r[k].forceOnJ, one[k]->forceOnJ)) << "lane " << k;
        EXPECT_TRUE(sameBits(r[k].normalForce, one[k]->normalForce)) << "lane " << k;
        EXPECT_TRUE(sameBits(r[k].elasticEnergy, one[k]->elasticEnergy)) << "lane " << k;
        EXPECT_TRUE(sameBits(r[k].coupleOnJ, one[k]->coupleOnJ)) << "lane " << k;
        EXPECT_TRUE(sameBits(xi2[k], *xiOne[k])) << "lane " << k;
    }
    return rA;
}

void expectTwoAsOne(const ContactLaw& law, const PairCoefficients& pc, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0, 1);
    int sliding = 0, sticking = 0, separating = 0;
    for (int n = 0; n < 4000; ++n)
    {
        const RandomContact a = randomContact(rng), b = randomContact(rng);
        const double mEff = 1e3 + 1e5*U(rng);
        const double dt = U(rng) < 0.1 ? 0.0 : 1e-2*U(rng);
        const ContactResult rA = expectSameBits(law, pc, a, b, mEff, dt);
        ASSERT_FALSE(::testing::Test::HasFailure()) << "pair of contacts " << n;
        // Which regimes the random contacts reached (lane 0, whole terms:
        // their tangential force is what is left of the force on j)
        if (rA.normalForce == 0)
        {
            ++separating;
        }
        else if (a.g.weight == 1)
        {
            const double Ft = (rA.forceOnJ - rA.normalForce*a.g.normal).norm();
            if (Ft >= (1 - 1e-9)*pc.friction*rA.normalForce) ++sliding;
            else ++sticking;
        }
    }
    // The comparison covered each regime many times
    EXPECT_GT(separating, 100);
    EXPECT_GT(sliding, 100);
    EXPECT_GT(sticking, 100);
}

PairCoefficients iceOnIce(double friction, double restitution)
{
    return PairCoefficients::make(ice(), ice(), PairProperties{friction, restitution});
}

} // anonymous namespace


TEST(ContactLaw, twoAtATimeIsEachAloneToTheBitHertzMindlin)
{
    ContactLawSettings s;
    const auto law = ContactLaw::New(s);
    expectTwoAsOne(*law, iceOnIce(0.2, 0.3), 1);
}

TEST(ContactLaw, twoAtATimeIsEachAloneToTheBitSimplifiedRatio)
{
    ContactLawSettings s;
    s.model = "hertzSimplified";
    s.tangentialModel = "ratio";
    const auto law = ContactLaw::New(s);
    expectTwoAsOne(*law, iceOnIce(0.5, 0.9), 2);
}

TEST(ContactLaw, twoAtATimeWithoutTangentialStiffness)
{
    // k_t = 0: the spring is dropped where it slides, and stores nothing
    ContactLawSettings s;
    s.tangentialModel = "ratio";
    s.tangentialStiffnessRatio = 0;
    const auto law = ContactLaw::New(s);
    std::mt19937_64 rng(3);
    const PairCoefficients pc = iceOnIce(0.2, 0.3);
    for (int n = 0; n < 500; ++n)
    {
        const RandomContact a = randomContact(rng), b = randomContact(rng);
        expectSameBits(*law, pc, a, b, 1e4, 1e-2);
        ASSERT_FALSE(::testing::Test::HasFailure()) << "pair of contacts " << n;
    }
}
