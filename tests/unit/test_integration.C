/*---------------------------------------------------------------------------*\
    iceDEM tests: the half-angle sine and cosine of the free rotation's
    splitting (series for small angles) agree with the library to rounding.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "worldDetail.H"

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
