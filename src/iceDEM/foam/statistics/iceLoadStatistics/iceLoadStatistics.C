/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "iceLoadStatistics.H"
#include "iceDEMState.H"
#include "dictionaryChecks.H"
#include "statistics/SeriesStatistics.H"

#include "IOField.H"
#include "addToRunTimeSelectionTable.H"

#include <algorithm>
#include <cmath>

// * * * * * * * * * * * * * * * Static Data * * * * * * * * * * * * * * * //

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(iceLoadStatistics, 0);
    addToRunTimeSelectionTable(functionObject, iceLoadStatistics, dictionary);
}
}

namespace
{
    // MSER batch size (MSER-5, White et al. 2000)
    constexpr int mserBatch = 5;

    double hypot2(double x, double y) { return std::sqrt(x*x + y*y); }
}


// * * * * * * * * * * * * * * * Accumulator * * * * * * * * * * * * * * * //

void Foam::functionObjects::iceLoadStatistics::accumulator::demStep
(
    const iceDEMCase& demCase,
    scalar h
)
{
    const ::iceDEM::World& w = demCase.world();
    ::iceDEM::Vec3 f = ::iceDEM::Vec3::Zero();
    for (std::size_t k = 0; k < bodies.size(); ++k)
    {
        label& b = bodies[k];
        if (b >= label(w.bodies().size()) || w.bodies()[b].id != ids[k])
        {
            b = w.indexOfId(int(ids[k]), int(b));
            if (b < 0)
            {
                FatalErrorInFunction
                    << "Structure body id " << ids[k] << " is no longer in"
                    << " the DEM" << exit(FatalError);
            }
        }
        // A structure body's force is its contact load (no model acts on
        // it, no gravity); unlike contactLoad it survives the neighbour
        // list's rebuild when inflow/outflow removes floes
        f += w.bodies()[b].force;
    }
    ::iceDEM::Vec3 wl = ::iceDEM::Vec3::Zero();
    if (!walls.empty())
    {
        w.wallContactForces(wallForce);
        for (const label k : walls)
        {
            wl += wallForce[k];
        }
    }
    F += h*f;
    W += h*wl;
    D += h*w.modelForceOnFreeBodies();
    duration += h;
}


void Foam::functionObjects::iceLoadStatistics::accumulator::reset()
{
    F.setZero();
    W.setZero();
    D.setZero();
    duration = 0;
}


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::functionObjects::iceLoadStatistics::connect()
{
    connected_ = true;

    if (!time_.foundObject<iceDEMState>("iceDEMState"))
    {
        noCase_ = true;
        WarningInFunction
            << "Function object " << name() << ": no iceDEM case in this"
            << " run (no constant/iceDEMProperties): no ice load statistics"
            << endl;
        return;
    }
    const iceDEMCase& c =
        time_.lookupObject<iceDEMState>("iceDEMState").demCase();
    const ::iceDEM::World& w = c.world();

    // The structure: selected bodies, or every body that is not free
    const label nBodies = label(w.bodies().size());
    wordList unused;
    for (label i = 0; i < nBodies; ++i)
    {
        const word n = c.name(i);
        const bool isFree = w.bodies()[i].isFree();
        if (structureGiven_ ? structureSel_.match(n) : !isFree)
        {
            if (isFree)
            {
                FatalIOErrorInFunction(dict_)
                    << "Entry 'structure' of function object " << name()
                    << " selects body " << n << ", which is free: the"
                    << " structure must be fixed or prescribed bodies"
                    << nl << exit(FatalIOError);
            }
            acc_->bodies.push_back(i);
            acc_->ids.push_back(w.bodies()[i].id);
        }
        else if (!isFree)
        {
            unused.append(n);
        }
    }
    if (structureGiven_)
    {
        for (const wordRe& r : structureSel_)
        {
            bool any = false;
            for (label i = 0; i < nBodies; ++i) { any = any || r.match(c.name(i)); }
            if (!any)
            {
                FatalIOErrorInFunction(dict_)
                    << "Entry 'structure' of function object " << name()
                    << ": '" << r << "' matches no body. Bodies that are"
                    << " not free: " << unused << nl << exit(FatalIOError);
            }
        }
    }

    // Walls: selected, or all
    wordList unusedWalls;
    const wordList& wn = c.wallNames();
    forAll(wn, k)
    {
        if (!wallsGiven_ || wallSel_.match(wn[k]))
        {
            acc_->walls.push_back(k);
        }
        else
        {
            unusedWalls.append(wn[k]);
        }
    }
    if (wallsGiven_)
    {
        for (const wordRe& r : wallSel_)
        {
            bool any = false;
            forAll(wn, k) { any = any || r.match(wn[k]); }
            if (!any)
            {
                FatalIOErrorInFunction(dict_)
                    << "Entry 'walls' of function object " << name()
                    << ": '" << r << "' matches no wall. Walls: " << wn
                    << nl << exit(FatalIOError);
            }
        }
    }
    acc_->wallForce.resize(w.walls().size());

    if (unused.size() || unusedWalls.size())
    {
        WarningInFunction
            << "Function object " << name() << ": bodies " << unused
            << " and walls " << unusedWalls << " are neither in"
            << " 'structure' nor in 'walls': the load they take is missing"
            << " from the force balance" << endl;
    }
    if (acc_->bodies.empty())
    {
        WarningInFunction
            << "Function object " << name() << ": no structure body (every"
            << " body is free): the structure load is zero" << endl;
    }

    c.addStepObserver(acc_);
    P0_ = floeMomentum();

    Info<< type() << ' ' << name() << ": structure bodies "
        << acc_->bodies.size() << ", walls " << acc_->walls.size()
        << ", transient ";
    if (autoTransient_) Info<< "auto (MSER-5)";
    else Info<< transient_ << " s";
    Info<< ", " << batches_ << " batches" << endl;
}


::iceDEM::Vec3
Foam::functionObjects::iceLoadStatistics::floeMomentum() const
{
    const ::iceDEM::World& w =
        time_.lookupObject<iceDEMState>("iceDEMState").demCase().world();
    ::iceDEM::Vec3 P = ::iceDEM::Vec3::Zero();
    for (const ::iceDEM::Body& b : w.bodies())
    {
        if (b.isFree()) P += b.mass*b.v;
    }
    return P;
}


bool Foam::functionObjects::iceLoadStatistics::readTensions(scalarList& T)
{
    T.clear();
    if (!Pstream::master())
    {
        return false;
    }
    if (!tensionsFound_)
    {
        tensionsFound_ = true;
        wordList restraints(mooring_);
        if (!mooringGiven_)
        {
            wordList names(time_.sortedNames<IOField<scalar>>());
            for (const word& n : names)
            {
                if (n.size() > 9 && n.substr(n.size() - 9) == ":tensions")
                {
                    restraints.append(n.substr(0, n.size() - 9));
                }
            }
        }
        for (const word& r : restraints)
        {
            const word key(r + ":tensions");
            if (!time_.foundObject<IOField<scalar>>(key))
            {
                FatalIOErrorInFunction(dict_)
                    << "Entry 'mooring' of function object " << name()
                    << ": '" << r << "' is not a spreadMooring restraint"
                    << " of this run (constant/dynamicMeshDict)" << nl
                    << exit(FatalIOError);
            }
            const label n = time_.lookupObject<IOField<scalar>>(key).size();
            for (label i = 0; i < n; ++i)
            {
                tensionNames_.append(r + ".T" + Foam::name(i));
            }
        }
        mooring_ = restraints;
        T_.resize(tensionNames_.size());
    }

    for (const word& r : mooring_)
    {
        T.append(time_.lookupObject<IOField<scalar>>(r + ":tensions"));
    }
    return T.size() > 0;
}


void Foam::functionObjects::iceLoadStatistics::openFiles()
{
    if (!Pstream::master() || seriesFile_.valid())
    {
        return;
    }
    const fileName dir
    (
        time_.globalPath()/"postProcessing"/name()
       /time_.timeName(time_.startTime().value())
    );
    mkDir(dir);

    seriesFile_.reset(new OFstream(dir/"series.dat"));
    seriesFile_().precision(10);
    seriesFile_()
        << "# ice load statistics samples: structure load F, wall load W,"
        << " driving force D on the free floes [N], averaged over the DEM"
        << " sub-steps of the interval ending at time; line tensions [N]"
        << nl << "# time Fx Fy Fh Wx Wy Dx Dy";
    for (const word& n : tensionNames_)
    {
        seriesFile_() << ' ' << n;
    }
    seriesFile_() << endl;

    statsFile_.reset(new OFstream(dir/"statistics.dat"));
    statsFile_().precision(8);
    statsFile_()
        << "# steady part (time > transientEnd): halfWidth of the "
        << confidence_*100 << " % interval of the mean by " << batches_
        << " batch means; correlated = 1: lag-1 correlation of the batch"
        << " means > 1.645/sqrt(batches); a row commented out (#) has too"
        << " few samples for the interval (it says how many are needed)" << nl
        << "# time quantity samples transientEnd mean std max P99"
        << " halfWidth batchSize lag1 correlated" << endl;

    balanceFile_.reset(new OFstream(dir/"forceBalance.dat"));
    balanceFile_().precision(12);
    balanceFile_()
        << "# mean horizontal load on structure + walls (load) against the"
        << " mean horizontal driving force on the free floes (drive), along"
        << " the direction of the mean driving force [N]" << nl
        << "# balance: load + momentumRate = drive, momentumRate = (P_end -"
        << " P_start)/T the change of the floes' momentum over the window"
        << " [N]; balanceRatio = (load + momentumRate)/drive" << nl
        << "# time samples transientEnd loadX loadY driveX driveY load drive"
        << " ratio ratioHalfWidth lag1 correlated steady momentumRate"
        << " balanceRatio" << endl;
}


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
    const double dMag = hypot2(dx, dy);
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
                << ' ' << balance;
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
            Info<< ", (load + dP/dt)/drive " << balance;
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


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::functionObjects::iceLoadStatistics::iceLoadStatistics
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    timeFunctionObject(name, runTime),
    dict_(dict),
    structureGiven_(false),
    wallsGiven_(false),
    mooringGiven_(false),
    autoTransient_(true),
    transient_(0),
    batches_(20),
    confidence_(0.95),
    minBatchSize_(10),
    stopFraction_(-1),
    acc_(std::make_shared<accumulator>()),
    connected_(false),
    noCase_(false),
    tensionsFound_(false),
    P0_(::iceDEM::Vec3::Zero()),
    lastWriteIndex_(-1),
    stopped_(false)
{
    read(dict);
    if (time_.foundObject<iceDEMState>("iceDEMState"))
    {
        connect();
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

bool Foam::functionObjects::iceLoadStatistics::read(const dictionary& dict)
{
    using namespace iceDEMChecks;

    dict_ = dict;
    checkEntries
    (
        dict, "system/controlDict", {"functions/*(type iceLoadStatistics)"},
        "function object " + name()
    );

    structureGiven_ = dict.found("structure", keyType::LITERAL);
    if (structureGiven_)
    {
        structureSel_ = dict.get<wordRes>("structure");
    }
    wallsGiven_ = dict.found("walls", keyType::LITERAL);
    if (wallsGiven_)
    {
        wallSel_ = dict.get<wordRes>("walls");
    }
    mooringGiven_ = dict.found("mooring", keyType::LITERAL);
    if (mooringGiven_)
    {
        mooring_ = dict.get<wordList>("mooring");
    }

    // An empty list would select nothing and leave that load out of the
    // statistics and the force balance without a word; omitting the entry
    // selects every one (or none where there is none), which covers each
    // meaningful case
    const struct { const char* key; bool given; label size; const char* all; }
    selections[] =
    {
        {"structure", structureGiven_, structureSel_.size(),
         "every body that is not free"},
        {"walls", wallsGiven_, wallSel_.size(), "every wall"},
        {"mooring", mooringGiven_, mooring_.size(),
         "every spreadMooring restraint"}
    };
    for (const auto& sel : selections)
    {
        if (sel.given && sel.size == 0)
        {
            FatalIOErrorInFunction(dict)
                << "Entry '" << sel.key << "' of function object " << name()
                << " in system/controlDict is an empty list: it would select"
                << " nothing. Give names (or regular expressions), or omit"
                << " the entry to select " << sel.all << nl
                << exit(FatalIOError);
        }
    }

    // transient: a time [s] or 'auto'
    autoTransient_ = true;
    if (dict.found("transient", keyType::LITERAL))
    {
        ITstream& is = dict.lookup("transient", keyType::LITERAL);
        token tok(is);
        if (tok.isWord() && tok.wordToken() == "auto")
        {
            autoTransient_ = true;
        }
        else if (tok.isNumber() && std::isfinite(tok.number()))
        {
            autoTransient_ = false;
            transient_ = tok.number();
            const scalar endTime = time_.endTime().value();
            if (transient_ < 0 || transient_ >= endTime)
            {
                FatalIOErrorInFunction(dict)
                    << "Entry 'transient " << transient_ << "' of function"
                    << " object " << name() << ": the transient [s] must be"
                    << " >= 0 and before endTime " << endTime << " of"
                    << " system/controlDict (no sample would be left), or"
                    << " 'auto' (MSER-5)" << nl << exit(FatalIOError);
            }
        }
        else
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'transient' of function object " << name()
                << ": expected a time [s] or 'auto', found " << tok << nl
                << exit(FatalIOError);
        }
    }

    batches_ = labelInRange(dict, "batches", 2, 1000, 20);
    confidence_ = dict.getOrDefault<scalar>("confidence", 0.95);
    if
    (
        std::abs(confidence_ - 0.90) > 1e-12
     && std::abs(confidence_ - 0.95) > 1e-12
     && std::abs(confidence_ - 0.99) > 1e-12
    )
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'confidence " << confidence_ << "' of function object "
            << name() << ": allowed values are 0.90, 0.95 and 0.99" << nl
            << exit(FatalIOError);
    }
    minBatchSize_ = labelInRange(dict, "minBatchSize", 1, labelMax, 10);
    stopFraction_ = -1;
    if (dict.found("stopAtHalfWidth", keyType::LITERAL))
    {
        const scalar f = dict.get<scalar>("stopAtHalfWidth");
        if (!(f > 0) || !std::isfinite(f))
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'stopAtHalfWidth " << f << "' of function object "
                << name() << ": the tolerance (half-width of the interval"
                << " over the mean load) must be a finite number > 0" << nl
                << exit(FatalIOError);
        }
        stopFraction_ = f;
    }
    return true;
}


bool Foam::functionObjects::iceLoadStatistics::execute()
{
    if (stopped_)
    {
        return true;
    }
    if (!connected_)
    {
        connect();
    }
    if (noCase_ || !(acc_->duration > 0))
    {
        return true;
    }

    const scalar h = acc_->duration;
    const ::iceDEM::Vec3 F = acc_->F/h;
    const ::iceDEM::Vec3 W = acc_->W/h;
    const ::iceDEM::Vec3 D = acc_->D/h;
    acc_->reset();

    scalarList T;
    readTensions(T);
    openFiles();

    t_.push_back(time_.value());
    Fx_.push_back(F.x());
    Fy_.push_back(F.y());
    Fh_.push_back(hypot2(F.x(), F.y()));
    Wx_.push_back(W.x());
    Wy_.push_back(W.y());
    Wh_.push_back(hypot2(W.x(), W.y()));
    Dx_.push_back(D.x());
    Dy_.push_back(D.y());
    Dh_.push_back(hypot2(D.x(), D.y()));
    h_.push_back(h);
    const ::iceDEM::Vec3 P = floeMomentum();
    Px_.push_back(P.x());
    Py_.push_back(P.y());
    if (T.size())
    {
        double tmax = T[0];
        forAll(T, i)
        {
            if (i < label(T_.size())) T_[i].push_back(T[i]);
            tmax = std::max(tmax, double(T[i]));
        }
        Tmax_.push_back(tmax);
    }

    if (Pstream::master())
    {
        OFstream& os = seriesFile_();
        os  << time_.value() << ' ' << F.x() << ' ' << F.y() << ' '
            << Fh_.back() << ' ' << W.x() << ' ' << W.y() << ' ' << D.x()
            << ' ' << D.y();
        forAll(T, i)
        {
            os  << ' ' << T[i];
        }
        os  << endl;
    }

    checkStop();
    return true;
}


bool Foam::functionObjects::iceLoadStatistics::write()
{
    if (time_.writeTime() && !stopped_)
    {
        writeStatistics();
    }
    return true;
}


bool Foam::functionObjects::iceLoadStatistics::end()
{
    if (!stopped_)
    {
        writeStatistics();
    }
    return true;
}


// ************************************************************************* //
