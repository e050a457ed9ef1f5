/*---------------------------------------------------------------------------*\
    iceDEM tests: the half-angle sine and cosine of the free rotation's
    splitting (series for small angles) agree with the library to rounding;
    the saved state holds no value a text store would give back otherwise.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "worldDetail.H"
#include "testWorlds.H"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace iceDEM;
using namespace iceDEM::worldDetail;

TEST(integration, halfAngleSinCosAgreesWithTheLibraryToRounding)
{
    // Over the series' range (and a little beyond, where the library
    // takes over), log-uniform angles of both signs: within 2 ulp of
    // std::sin and std::cos, and s^2 + c^2 = 1 to 4 eps (the splitting's
    // sub-rotations stay rotations)
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> logx(std::log(1e-12), std::log(0.05));
    const double eps = std::numeric_limits<double>::epsilon();
    int inSeries = 0;
    for (int k = 0; k < 200000; ++k)
    {
        const double x = (k % 2 ? -1 : 1)*std::exp(logx(rng));
        double s, c;
        halfAngleSinCos(x, s, c);
        EXPECT_LE(std::abs(s - std::sin(x)), 2*eps*std::abs(std::sin(x))) << x;
        EXPECT_LE(std::abs(c - std::cos(x)), 2*eps) << x;
        EXPECT_LE(std::abs(s*s + c*c - 1), 4*eps) << x;
        inSeries += std::abs(x) <= sinCosSeriesLimit;
    }
    EXPECT_GT(inSeries, 150000);
    double s, c;
    halfAngleSinCos(0.0, s, c);
    EXPECT_EQ(s, 0.0);
    EXPECT_EQ(c, 1.0);
}


TEST(integration, theSavedStateKeepsNoNegativeZeroNorValueBelowTheStoreFloor)
{
    // A text store that reads "-0" and |x| <= 1e-300 back as +0 (OpenFOAM's
    // reader) gives back the running state only if the state holds neither
    // (a restart then continues the uninterrupted run to the bit:
    // tests/cases/iceDEMFoam_restartExactState). A box at rest in a world
    // without gravity, turned half a turn about a horizontal axis (w = -0),
    // drifting at (-0, 1e-310, 2) m/s with angular momentum (-0, 0, 0):
    // after one step every such value is +0 and the others are untouched
    const auto stepped = [](double floor)
    {
        WorldSettings s;
        s.timeStep = 1e-3;
        s.gravity = Vec3::Zero();
        s.storeFloor = floor;
        World w(s);
        const int mat = w.addMaterial(test::ice());
        const int box = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3(1, 1, 0.5)), 0.05));
        w.addBody(box, mat, Vec3(3, -0.0, 0));
        w.initialise();
        Body& b = w.bodies()[0];
        b.q = Quat(-0.0, 0.6, 0.8, 0.0);
        b.v = Vec3(-0.0, 1e-310, 2.0);
        b.L = Vec3(-0.0, 0.0, 0.0);
        w.step();
        return b;
    };
    const auto positiveZero = [](double x) { return x == 0 && !std::signbit(x); };

    const Body b = stepped(1e-300);
    EXPECT_TRUE(positiveZero(b.q.w()));
    EXPECT_EQ(b.q.x(), 0.6);
    EXPECT_EQ(b.q.y(), 0.8);
    EXPECT_TRUE(positiveZero(b.q.z()));
    EXPECT_TRUE(positiveZero(b.v.x()));
    EXPECT_TRUE(positiveZero(b.v.y()));
    EXPECT_EQ(b.v.z(), 2.0);
    EXPECT_TRUE(positiveZero(b.x.y()));
    EXPECT_EQ(b.x.z(), 2e-3);
    for (int d = 0; d < 3; ++d)
    {
        EXPECT_TRUE(positiveZero(b.L[d])) << d;
        EXPECT_TRUE(positiveZero(b.force[d])) << d;
        EXPECT_TRUE(positiveZero(b.torque[d])) << d;
    }

    // The default floor 0: negative zeros only, the tiny velocity stays
    const Body b0 = stepped(0);
    EXPECT_TRUE(positiveZero(b0.q.w()));
    EXPECT_TRUE(positiveZero(b0.v.x()));
    EXPECT_EQ(b0.v.y(), 1e-310);
}
