/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Load statistics (statistics/SeriesStatistics.H) against what they
    cannot fake:
      - mean, standard deviation, maximum and P99 of a known sample against
        their exact values;
      - coverage of the 95 % batch-means interval on an AR(1) series with a
        known mean and correlation time: 400 independent repetitions (fixed
        seed) must cover the true mean in [0.92, 0.98] of them (binomial
        standard error 0.011 at 0.95); the naive i.i.d. interval must fail
        the same check (it ignores the correlation), so the check can fail;
      - MSER-5 finds a known transient (exponential decay onto a noisy
        steady level) within a few correlation times of its end, and
        keeps a stationary series whole.
\*---------------------------------------------------------------------------*/

#include "statistics/SeriesStatistics.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <vector>

using namespace iceDEM::statistics;

namespace
{

//- AR(1): x_t = mu + phi (x_{t-1} - mu) + sigma e_t, started in its
//  stationary distribution (no transient)
void ar1(std::mt19937_64& rng, double mu, double phi, double sigma,
         std::vector<double>& x)
{
    std::normal_distribution<double> e(0.0, 1.0);
    double y = sigma/std::sqrt(1 - phi*phi)*e(rng);
    for (double& xi : x)
    {
        y = phi*y + sigma*e(rng);
        xi = mu + y;
    }
}

} // namespace


TEST(Statistics, momentsAndQuantileOfKnownSample)
{
    // 1, 2, ..., 101 shuffled: mean 51, sample variance n(n+1)/12 = 858.5
    // (n = 101), max 101; type 7: P99 = x_(100*0.99) = 1 + 99 = 100,
    // P50 = 51, P99.5 = 100.5
    std::vector<double> x(101);
    for (int i = 0; i < 101; ++i) x[i] = i + 1;
    std::mt19937_64 rng(7);
    std::shuffle(x.begin(), x.end(), rng);

    double mean, sd, mx;
    moments(x.data(), x.size(), mean, sd, mx);
    EXPECT_DOUBLE_EQ(mean, 51.0);
    EXPECT_NEAR(sd, std::sqrt(101.0*102.0/12.0), 1e-12);
    EXPECT_DOUBLE_EQ(mx, 101.0);

    std::vector<double> scratch;
    EXPECT_DOUBLE_EQ(quantile(x.data(), x.size(), 0.99, scratch), 100.0);
    EXPECT_DOUBLE_EQ(quantile(x.data(), x.size(), 0.50, scratch), 51.0);
    EXPECT_DOUBLE_EQ(quantile(x.data(), x.size(), 0.995, scratch), 100.5);
    EXPECT_DOUBLE_EQ(quantile(x.data(), x.size(), 1.0, scratch), 101.0);
    EXPECT_DOUBLE_EQ(quantile(x.data(), x.size(), 0.0, scratch), 1.0);

    // Two values: linear between them
    const double two[2] = {3.0, 1.0};
    EXPECT_DOUBLE_EQ(quantile(two, 2, 0.99, scratch), 1.0 + 0.99*2.0);

    EXPECT_THROW(quantile(x.data(), 0, 0.5, scratch), std::invalid_argument);
    EXPECT_THROW(quantile(x.data(), x.size(), 1.5, scratch),
                 std::invalid_argument);
}


TEST(Statistics, studentT)
{
    EXPECT_DOUBLE_EQ(studentT(19, 0.95), 2.093);
    // Beyond the table: the expansion meets the tabulated value at 30
    // and the normal quantile at infinity
    EXPECT_NEAR(studentT(31, 0.95), 2.040, 1e-3);
    EXPECT_NEAR(studentT(120, 0.95), 1.980, 1e-3);
    EXPECT_NEAR(studentT(60, 0.99), 2.660, 1e-3);
    EXPECT_NEAR(studentT(1000000, 0.95), 1.959964, 1e-5);
    EXPECT_THROW(studentT(10, 0.8), std::invalid_argument);
}


TEST(Statistics, batchMeansCoverageOnAR1)
{
    // AR(1) with phi = 0.9: integrated correlation time
    // (1 + phi)/(1 - phi) = 19 samples; 10,000 samples, 20 batches of 500
    const double mu = 3.0, phi = 0.9, sigma = 1.0;
    const int reps = 400;
    const std::size_t n = 10000;

    std::mt19937_64 rng(20261125);
    std::vector<double> x(n);
    int coveredBM = 0, coveredIID = 0, flagged = 0;
    for (int r = 0; r < reps; ++r)
    {
        ar1(rng, mu, phi, sigma, x);
        const BatchMeansResult bm = batchMeans(x.data(), n, 20, 0.95);
        const BatchMeansResult iid = iidInterval(x.data(), n, 0.95);
        ASSERT_EQ(bm.batches, 20);
        ASSERT_EQ(bm.batchSize, 500u);
        coveredBM += std::abs(bm.mean - mu) <= bm.halfWidth;
        coveredIID += std::abs(iid.mean - mu) <= iid.halfWidth;
        flagged += bm.correlated;
    }
    const double cBM = double(coveredBM)/reps;
    const double cIID = double(coveredIID)/reps;
    std::cout << "    coverage of the 95 % interval over " << reps
              << " AR(1) series: batch means " << cBM
              << ", naive i.i.d. " << cIID
              << "; batch means flagged correlated in " << flagged << std::endl;
    EXPECT_GE(cBM, 0.92);
    EXPECT_LE(cBM, 0.98);
    // The same check fails for the interval that ignores the correlation
    EXPECT_FALSE(cIID >= 0.92 && cIID <= 0.98);
    // Independent batch means: the one-sided 5 % test flags about 5 %
    EXPECT_LE(flagged, 0.12*reps);
}


TEST(Statistics, batchMeansFlagsShortBatches)
{
    // phi = 0.999: correlation time ~2000 samples against batches of 100
    std::mt19937_64 rng(3);
    std::vector<double> x(2000);
    int flagged = 0;
    for (int r = 0; r < 50; ++r)
    {
        ar1(rng, 0.0, 0.999, 1.0, x);
        flagged += batchMeans(x.data(), x.size(), 20).correlated;
    }
    EXPECT_GE(flagged, 40);
}


TEST(Statistics, mserFindsKnownTransient)
{
    // Exponential approach from 10 to 1 with time constant 200 samples
    // (within 1e-3 of the level, below the noise, after ~1400 samples),
    // then AR(1) noise (phi 0.5, std ~0.58) about 1: 8000 samples
    std::mt19937_64 rng(11);
    const std::size_t n = 8000;
    const double tau = 200;
    int found = 0;
    for (int r = 0; r < 20; ++r)
    {
        std::vector<double> x(n);
        ar1(rng, 1.0, 0.5, 0.5, x);
        for (std::size_t i = 0; i < n; ++i) x[i] += 9.0*std::exp(-(i/tau));
        const Truncation t = mserTruncation(x.data(), n, 5);
        EXPECT_TRUE(t.steady);
        // Cut where the bias 9 exp(-i/tau) is about the noise's standard
        // error over the rest: between 2 and 8 time constants
        EXPECT_GE(t.samples, std::size_t(2*tau));
        EXPECT_LE(t.samples, std::size_t(8*tau));
        found += t.steady;
    }
    EXPECT_EQ(found, 20);

    // A stationary series loses little
    std::vector<double> y(n);
    ar1(rng, 1.0, 0.5, 0.5, y);
    const Truncation t = mserTruncation(y.data(), n, 5);
    EXPECT_TRUE(t.steady);
    EXPECT_LE(t.samples, n/10);

    // A series still drifting at the end is not steady
    for (std::size_t i = 0; i < n; ++i) y[i] = double(i);
    EXPECT_FALSE(mserTruncation(y.data(), n, 5).steady);
}
