/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    The statistics of iceLoadStatistics' series and their rows: the steady
    window (fixed transient or MSER-5), mean, standard deviation, maximum,
    P99 and the batch-means interval per quantity (statistics.dat), the
    force balance (forceBalance.dat), the summary in the log, and the stop
    at a narrow enough interval (stopAtHalfWidth).
\*---------------------------------------------------------------------------*/

#include "iceLoadStatistics.H"
#include "statistics/SeriesStatistics.H"

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{
    // MSER batch size (MSER-5, White et al. 2000)
    constexpr int mserBatch = 5;
}


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

size_t Foam::functionObjects::iceLoadStatistics::steadyStart
(
    bool& steady
) const
{
    const size_t n = t_.size();
    steady = true;
    if (!autoTransient_)
    {
        size_t k = 0;
        while (k < n && t_[k] <= transient_) ++k;
        return k;
    }
    const ::iceDEM::statistics::Truncation a =
        ::iceDEM::statistics::mserTruncation(Fh_.data(), n, mserBatch);
    const ::iceDEM::statistics::Truncation b =
        ::iceDEM::statistics::mserTruncation(Dh_.data(), n, mserBatch);
    steady = a.steady && b.steady;
    return std::max(a.samples, b.samples);
}


void Foam::functionObjects::iceLoadStatistics::writeRow
(
    const word& quantity,
    const std::vector<double>& x,
    size_t start
)
{
    using namespace ::iceDEM::statistics;
    const size_t n = x.size() - start;
    const double tEnd = start > 0 ? t_[start - 1] : time_.startTime().value();
    OFstream& os = statsFile_();
    if (n == 0)
    {
        // Nothing is defined: a comment line, never 'nan'
        os  << "# " << time_.timeName() << ' ' << quantity << ' ' << n << ' '
            << tEnd << " no steady samples" << endl;
        return;
    }
    double mean, sd, mx;
    moments(x.data() + start, n, mean, sd, mx);
    const double p99 = quantile(x.data() + start, n, 0.99, scratch_);
    const BatchMeansResult bm =
        batchMeans(x.data() + start, n, batches_, confidence_);
    if (!bm.batches)
    {
        // Too few samples for the batch means: the interval is left out;
        // the row is a comment, so that every data row has every column
        os  << "# " << time_.timeName() << ' ' << quantity << ' ' << n << ' '
            << tEnd << ' ' << mean << ' ' << sd << ' ' << mx << ' ' << p99
            << " not enough samples for the interval: " << n << " of the "
            << batches_ << " needed" << endl;
        return;
    }
    os  << time_.timeName() << ' ' << quantity << ' ' << n << ' ' << tEnd
        << ' ' << mean << ' ' << sd << ' ' << mx << ' ' << p99 << ' '
        << bm.halfWidth << ' ' << bm.batchSize << ' ' << bm.lag1 << ' '
        << bm.correlated << endl;
}


void Foam::functionObjects::iceLoadStatistics::writeStatistics()
{
    if (noCase_ || !connected_)
    {
        return;
    }
    if (lastWriteIndex_ == time_.timeIndex())
    {
        return;
    }
    lastWriteIndex_ = time_.timeIndex();

    using namespace ::iceDEM::statistics;
    bool steady = true;
    const size_t start = std::min(steadyStart(steady), t_.size());
    const size_t n = t_.size() - start;

    // Force balance along the mean driving direction
    double lx = 0, ly = 0, dx = 0, dy = 0;
    for (size_t k = start; k < t_.size(); ++k)
    {
        lx += Fx_[k] + Wx_[k];
        ly += Fy_[k] + Wy_[k];
        dx += Dx_[k];
        dy += Dy_[k];
    }
    if (n)
    {
        lx /= n; ly /= n; dx /= n; dy /= n;
    }
    const double dMag = planarNorm(dx, dy);
    const double ex = dMag > 0 ? dx/dMag : 1;
    const double ey = dMag > 0 ? dy/dMag : 0;
    std::vector<double> diff(n);
    for (size_t k = 0; k < n; ++k)
    {
        const size_t j = start + k;
        diff[k] = (Fx_[j] + Wx_[j] - Dx_[j])*ex + (Fy_[j] + Wy_[j] - Dy_[j])*ey;
    }
    const BatchMeansResult bd = batchMeans(diff.data(), n, batches_, confidence_);
    const double load = lx*ex + ly*ey;
    const double ratio = dMag > 0 ? load/dMag : NAN;

    // The floes' momentum change over the window: load + dP/dt = drive
    double duration = 0;
    for (size_t k = start; k < t_.size(); ++k) duration += h_[k];
    double momentumRate = 0;
    if (n && duration > 0)
    {
        const double p0x = start > 0 ? Px_[start - 1] : P0_.x();
        const double p0y = start > 0 ? Py_[start - 1] : P0_.y();
        momentumRate = ((Px_.back() - p0x)*ex + (Py_.back() - p0y)*ey)/duration;
    }
    const double balance = dMag > 0 ? (load + momentumRate)/dMag : NAN;
    // What balance - 1 can resolve: the leapfrog's end-point term over the
    // window and the rounding of N steps' sums (iceLoadStatistics.H)
    double Ewx = 0, Ewy = 0, steps = 0;
    for (size_t k = start; k < t_.size(); ++k)
    {
        Ewx += Ex_[k];
        Ewy += Ey_[k];
        steps += steps_[k];
    }
    const double floor = dMag > 0 && duration > 0
      ? std::abs(Ewx*ex + Ewy*ey)/(duration*dMag)
      + steps*std::numeric_limits<double>::epsilon()
      : NAN;
    const double ratioHW = dMag > 0 && bd.batches ? bd.halfWidth/dMag : NAN;

    double meanF = 0, sdF = 0, maxF = 0, p99F = 0;
    BatchMeansResult bF;
    if (n)
    {
        moments(Fh_.data() + start, n, meanF, sdF, maxF);
        p99F = quantile(Fh_.data() + start, n, 0.99, scratch_);
        bF = batchMeans(Fh_.data() + start, n, batches_, confidence_);
    }

    if (Pstream::master())
    {
        writeRow("iceLoad", Fh_, start);
        if (acc_->walls.size())
        {
            writeRow("wallLoad", Wh_, start);
        }
        forAll(tensionNames_, i)
        {
            writeRow(tensionNames_[i], T_[i], start);
        }
        if (tensionNames_.size())
        {
            writeRow("maxTension", Tmax_, start);
        }

        // A row only where the ratio and its interval are defined; else a
        // comment that says why (never 'nan')
        OFstream& os = balanceFile_();
        const bool defined = dMag > 0 && bd.batches;
        os  << (defined ? "" : "# ") << time_.timeName() << ' ' << n << ' '
            << (start > 0 ? t_[start - 1] : time_.startTime().value()) << ' '
            << lx << ' ' << ly << ' ' << dx << ' ' << dy << ' '
            << load << ' ' << dMag << ' ';
        if (defined)
        {
            os  << ratio << ' ' << ratioHW << ' ' << bd.lag1 << ' '
                << bd.correlated << ' ' << steady << ' ' << momentumRate
                << ' ' << balance << ' ' << floor;
        }
        else if (!(dMag > 0))
        {
            os  << "no driving force on the floes: the ratio is undefined";
        }
        else
        {
            os  << "not enough samples for the interval: " << n
                << " of the " << batches_ << " needed";
        }
        os  << endl;
    }

    Info<< type() << ' ' << name() << " at " << time_.timeName() << ": "
        << n << " steady samples";
    if (n)
    {
        Info<< " (after " << (start > 0 ? t_[start - 1] : 0) << " s)" << nl
            << "    horizontal ice load [N]: mean " << meanF;
        if (bF.batches)
        {
            Info<< " +- " << bF.halfWidth
                << (bF.correlated ? " (batches correlated: run longer)" : "");
        }
        else
        {
            Info<< " (not enough samples for the interval: " << n
                << " of the " << batches_ << " needed)";
        }
        Info<< ", std " << sdF << ", max " << maxF << ", P99 " << p99F << nl
            << "    force balance: load on structure + walls " << load
            << " N, floes' momentum change dP/dt " << momentumRate
            << " N, driving force on the floes " << dMag << " N";
        if (dMag > 0)
        {
            Info<< ", load/drive " << ratio;
            if (bd.batches)
            {
                Info<< " +- " << ratioHW;
            }
            Info<< ", (load + dP/dt)/drive " << balance
                << " (resolves " << floor << ')';
        }
        if (!steady)
        {
            Info<< nl << "    no steady state detected (MSER-5: the best"
                << " truncation is at half the series): run longer";
        }
    }
    Info<< endl;
}


void Foam::functionObjects::iceLoadStatistics::checkStop()
{
    if (stopFraction_ <= 0 || noCase_)
    {
        return;
    }
    using namespace ::iceDEM::statistics;
    bool steady = true;
    const size_t start = std::min(steadyStart(steady), t_.size());
    const size_t n = t_.size() - start;
    const BatchMeansResult b =
        batchMeans(Fh_.data() + start, n, batches_, confidence_);

    // Correlated batch means understate the interval: for an AR(1)
    // sequence of batch means with lag-1 correlation rho the variance of
    // their mean grows by (1 + rho)/(1 - rho). The stop compares the
    // half-width widened by its square root (a pack that has come to rest
    // has correlated batch means of a vanishing spread, and stops)
    scalar widened = b.halfWidth;
    if (b.correlated)
    {
        widened =
            b.lag1 < 1
          ? b.halfWidth*std::sqrt((1 + b.lag1)/(1 - b.lag1))
          : GREAT;
    }
    if
    (
        steady
     && b.batches
     && label(b.batchSize) >= minBatchSize_
     && b.mean > 0
     && widened <= stopFraction_*b.mean
    )
    {
        Info<< type() << ' ' << name() << ": half-width " << b.halfWidth
            << " N";
        if (b.correlated)
        {
            Info<< " (batch means correlated, lag-1 " << b.lag1
                << ": widened to " << widened << " N)";
        }
        Info<< " <= " << stopFraction_ << " x mean " << b.mean
            << " N: writing and stopping at time " << time_.timeName()
            << endl;
        writeStatistics();
        stopped_ = true;
        const_cast<Time&>(time_).writeAndEnd();
    }
}


// ************************************************************************* //
