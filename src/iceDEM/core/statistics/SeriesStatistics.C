/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "statistics/SeriesStatistics.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace iceDEM
{
namespace statistics
{

void RunningMoments::add(double x)
{
    ++n_;
    if (n_ == 1)
    {
        min_ = max_ = x;
    }
    else
    {
        min_ = std::min(min_, x);
        max_ = std::max(max_, x);
    }
    const double d = x - mean_;
    mean_ += d/n_;
    m2_ += d*(x - mean_);
}


double RunningMoments::variance() const
{
    return n_ > 1 ? m2_/(n_ - 1) : 0.0;
}


double RunningMoments::stdDev() const
{
    return std::sqrt(variance());
}


void moments(const double* x, std::size_t n, double& mean, double& stdDev,
             double& max)
{
    RunningMoments m;
    for (std::size_t i = 0; i < n; ++i) m.add(x[i]);
    mean = m.mean();
    stdDev = m.stdDev();
    max = m.max();
}


double quantile(const double* x, std::size_t n, double p,
                std::vector<double>& scratch)
{
    if (n == 0)
    {
        throw std::invalid_argument("quantile of an empty series");
    }
    if (!(p >= 0 && p <= 1))
    {
        throw std::invalid_argument("quantile: p must be in [0, 1]");
    }
    scratch.assign(x, x + n);
    const double h = (n - 1)*p;
    const std::size_t k = static_cast<std::size_t>(std::floor(h));
    std::nth_element(scratch.begin(), scratch.begin() + k, scratch.end());
    const double lo = scratch[k];
    if (k + 1 >= n)
    {
        return lo;
    }
    // The next order statistic: the smallest of the upper part
    const double hi =
        *std::min_element(scratch.begin() + k + 1, scratch.end());
    return lo + (h - k)*(hi - lo);
}


double studentT(int dof, double confidence)
{
    // Two-sided quantiles t_{dof, (1 + c)/2}, dof = 1..30 (standard tables)
    static const double t90[30] =
    {
        6.314, 2.920, 2.353, 2.132, 2.015, 1.943, 1.895, 1.860, 1.833,
        1.812, 1.796, 1.782, 1.771, 1.761, 1.753, 1.746, 1.740, 1.734,
        1.729, 1.725, 1.721, 1.717, 1.714, 1.711, 1.708, 1.706, 1.703,
        1.701, 1.699, 1.697
    };
    static const double t95[30] =
    {
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262,
        2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101,
        2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052,
        2.048, 2.045, 2.042
    };
    static const double t99[30] =
    {
        63.657, 9.925, 5.841, 4.604, 4.032, 3.707, 3.499, 3.355, 3.250,
        3.169, 3.106, 3.055, 3.012, 2.977, 2.947, 2.921, 2.898, 2.878,
        2.861, 2.845, 2.831, 2.819, 2.807, 2.797, 2.787, 2.779, 2.771,
        2.763, 2.756, 2.750
    };

    const double* table = nullptr;
    double z = 0;
    if (std::abs(confidence - 0.90) < 1e-12) { table = t90; z = 1.6448536; }
    else if (std::abs(confidence - 0.95) < 1e-12) { table = t95; z = 1.9599640; }
    else if (std::abs(confidence - 0.99) < 1e-12) { table = t99; z = 2.5758293; }
    else
    {
        throw std::invalid_argument
        (
            "confidence must be 0.90, 0.95 or 0.99"
        );
    }
    if (dof < 1)
    {
        throw std::invalid_argument("Student t: dof must be >= 1");
    }
    if (dof <= 30)
    {
        return table[dof - 1];
    }
    // Cornish-Fisher expansion in 1/dof (Abramowitz & Stegun 26.7.5)
    const double v = dof;
    const double z2 = z*z;
    return z
        + z*(z2 + 1)/(4*v)
        + z*((5*z2 + 16)*z2 + 3)/(96*v*v)
        + z*(((3*z2 + 19)*z2 + 17)*z2 - 15)/(384*v*v*v);
}


double lag1Autocorrelation(const double* x, std::size_t n)
{
    if (n < 3) return 0;
    double mean = 0;
    for (std::size_t i = 0; i < n; ++i) mean += x[i];
    mean /= n;
    double num = 0, den = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const double d = x[i] - mean;
        den += d*d;
        if (i + 1 < n) num += d*(x[i + 1] - mean);
    }
    return den > 0 ? num/den : 0.0;
}


BatchMeansResult batchMeans(const double* x, std::size_t n, int k,
                            double confidence)
{
    if (k < 2)
    {
        throw std::invalid_argument("batch means: at least 2 batches");
    }
    BatchMeansResult r;
    const std::size_t b = n/k;
    if (b == 0)
    {
        return r;
    }
    r.batches = k;
    r.batchSize = b;
    r.used = b*k;

    // The newest k b samples: the oldest remainder is nearest the transient
    const double* y = x + (n - r.used);
    std::vector<double> means(k);
    RunningMoments m;
    for (int j = 0; j < k; ++j)
    {
        double s = 0;
        for (std::size_t i = 0; i < b; ++i) s += y[j*b + i];
        means[j] = s/b;
        m.add(means[j]);
    }
    r.mean = m.mean();
    r.halfWidth = studentT(k - 1, confidence)*m.stdDev()/std::sqrt(double(k));
    r.lag1 = lag1Autocorrelation(means.data(), k);
    // One-sided 5 % test of independence of the batch means
    r.correlated = r.lag1 > 1.6448536/std::sqrt(double(k));
    return r;
}


BatchMeansResult iidInterval(const double* x, std::size_t n,
                             double confidence)
{
    BatchMeansResult r;
    if (n < 2) return r;
    RunningMoments m;
    for (std::size_t i = 0; i < n; ++i) m.add(x[i]);
    r.batches = static_cast<int>(std::min<std::size_t>(n, 1u << 30));
    r.batchSize = 1;
    r.used = n;
    r.mean = m.mean();
    r.halfWidth =
        studentT(static_cast<int>(std::min<std::size_t>(n - 1, 1u << 30)),
                 confidence)
       *m.stdDev()/std::sqrt(double(n));
    r.lag1 = lag1Autocorrelation(x, n);
    return r;
}


Truncation mserTruncation(const double* x, std::size_t n, int m)
{
    if (m < 1)
    {
        throw std::invalid_argument("MSER: batch size must be >= 1");
    }
    Truncation t;
    const std::size_t nb = n/m;
    if (nb < 4)
    {
        return t;
    }

    // Batch averages of the first nb m samples
    std::vector<double> y(nb);
    for (std::size_t j = 0; j < nb; ++j)
    {
        double s = 0;
        for (int i = 0; i < m; ++i) s += x[j*m + i];
        y[j] = s/m;
    }

    // Suffix sums give every MSER(d) in O(nb)
    std::vector<double> s1(nb + 1, 0.0), s2(nb + 1, 0.0);
    for (std::size_t j = nb; j-- > 0;)
    {
        s1[j] = s1[j + 1] + y[j];
        s2[j] = s2[j + 1] + y[j]*y[j];
    }

    const std::size_t dMax = nb/2;
    double best = std::numeric_limits<double>::infinity();
    std::size_t dBest = 0;
    for (std::size_t d = 0; d <= dMax; ++d)
    {
        const double c = double(nb - d);
        const double mean = s1[d]/c;
        // sum (y - mean)^2 = s2 - c mean^2, clipped at round-off
        const double ss = std::max(0.0, s2[d] - c*mean*mean);
        const double v = ss/(c*c);
        if (v < best)
        {
            best = v;
            dBest = d;
        }
    }
    t.samples = dBest*m;
    t.steady = dBest < dMax;
    return t;
}

} // namespace statistics
} // namespace iceDEM
