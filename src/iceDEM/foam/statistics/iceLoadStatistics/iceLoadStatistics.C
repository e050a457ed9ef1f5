/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    The function object's settings (read), its samples (execute) and its
    files (series.dat; the headers of statistics.dat and forceBalance.dat).
    What a sample reads from the DEM is in iceLoadStatisticsSampling.C,
    the statistics of the series in iceLoadStatisticsEstimators.C.
\*---------------------------------------------------------------------------*/

#include "iceLoadStatistics.H"
#include "iceDEMState.H"
#include "dictionaryChecks.H"
#include "structureSelection.H"

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


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

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
        << " balanceRatio balanceFloor" << endl;
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
        iceDEMStatistics::selectionNotEmpty
        (
            dict, name(), sel.key, sel.given, sel.size, sel.all
        );
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
    Ex_.push_back(acc_->E.x());
    Ey_.push_back(acc_->E.y());
    steps_.push_back(acc_->steps);
    acc_->reset();

    scalarList T;
    readTensions(T);
    openFiles();

    t_.push_back(time_.value());
    Fx_.push_back(F.x());
    Fy_.push_back(F.y());
    Fh_.push_back(planarNorm(F.x(), F.y()));
    Wx_.push_back(W.x());
    Wy_.push_back(W.y());
    Wh_.push_back(planarNorm(W.x(), W.y()));
    Dx_.push_back(D.x());
    Dy_.push_back(D.y());
    Dh_.push_back(planarNorm(D.x(), D.y()));
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
