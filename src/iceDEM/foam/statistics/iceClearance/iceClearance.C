/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "iceClearance.H"
#include "iceDEMState.H"
#include "dictionaryChecks.H"
#include "structureSelection.H"

#include "addToRunTimeSelectionTable.H"

#include <algorithm>
#include <cmath>
#include <limits>

// * * * * * * * * * * * * * * * Static Data * * * * * * * * * * * * * * * //

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(iceClearance, 0);
    addToRunTimeSelectionTable(functionObject, iceClearance, dictionary);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::functionObjects::iceClearance::iceClearance
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    timeFunctionObject(name, runTime),
    dict_(dict),
    structureGiven_(false),
    centreGiven_(false),
    centre_(Zero),
    transient_(0),
    connected_(false),
    inactive_(false),
    refId_(-1),
    refIndex_(-1),
    axisInBody_(::iceDEM::Vec3::Zero())
{
    read(dict);
    if (time_.foundObject<iceDEMState>("iceDEMState"))
    {
        connect();
    }
}


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::functionObjects::iceClearance::connect()
{
    connected_ = true;
    if (!time_.foundObject<iceDEMState>("iceDEMState"))
    {
        inactive_ = true;
        WarningInFunction
            << "Function object " << name() << ": no iceDEM case in this"
            << " run (no constant/iceDEMProperties): no ice clearance counts"
            << endl;
        return;
    }
    const iceDEMCase& c =
        time_.lookupObject<iceDEMState>("iceDEMState").demCase();
    const ::iceDEM::World& w = c.world();

    // The structure: selected bodies, or every body that is not free; the
    // first carries the axis
    wordList unused;
    ::iceDEM::Vec3 centroid = ::iceDEM::Vec3::Zero();
    double volume = 0;
    for
    (
        const label i
      : iceDEMStatistics::selectStructure
        (
            c, structureGiven_, structureSel_, dict_, name(), unused
        )
    )
    {
        const ::iceDEM::Body& b = w.bodies()[i];
        if (refIndex_ < 0)
        {
            refIndex_ = i;
            refId_ = b.id;
        }
        const double V = w.shapeOf(i).volume();
        centroid += V*b.x;
        volume += V;
    }
    if (refIndex_ < 0 && !centreGiven_)
    {
        // A case run without its structure (a free-drift reference): as
        // iceLoadStatistics, a warning, not a stop
        inactive_ = true;
        WarningInFunction
            << "Function object " << name() << " in system/controlDict: no"
            << " structure body (every body is free) and no entry 'centre':"
            << " no gate, nothing is counted (give 'centre' for a fixed"
            << " gate)" << endl;
        return;
    }

    const ::iceDEM::Vec3 a =
        centreGiven_ ? iceDEMChecks::toVec3(centre_) : ::iceDEM::Vec3(centroid/volume);
    if (refIndex_ >= 0)
    {
        const ::iceDEM::Body& ref = w.bodies()[refIndex_];
        axisInBody_ = ref.rotation().transpose()*(a - ref.x);
    }
    else
    {
        axisInBody_ = a;
        WarningInFunction
            << "Function object " << name() << ": no structure body (every"
            << " body is free): the gate stays at 'centre' " << centre_
            << endl;
    }

    Info<< type() << ' ' << name() << ": axis (" << a.x() << ' ' << a.y()
        << ") at the start, waterline radius " << settings_.underRadius
        << " m, gate half-width " << settings_.nearRadius << " m, drift ("
        << settings_.dirX << ' ' << settings_.dirY << "), transient "
        << transient_ << " s" << endl;

    // Where the floes are at the start: a crossing in the first sample
    // interval counts (a restart continues where the last run's rows end)
    takeSample(false);
}


::iceDEM::Vec3 Foam::functionObjects::iceClearance::axis()
{
    if (refId_ < 0)
    {
        return axisInBody_;     // no structure: the fixed centre
    }
    const ::iceDEM::World& w =
        time_.lookupObject<iceDEMState>("iceDEMState").demCase().world();
    if
    (
        refIndex_ >= label(w.bodies().size())
     || w.bodies()[refIndex_].id != refId_
    )
    {
        refIndex_ = w.indexOfId(int(refId_), int(refIndex_));
        if (refIndex_ < 0)
        {
            FatalErrorInFunction
                << "Structure body id " << refId_ << " is no longer in the"
                << " DEM" << exit(FatalError);
        }
    }
    const ::iceDEM::Body& ref = w.bodies()[refIndex_];
    return ref.x + ref.rotation()*axisInBody_;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

bool Foam::functionObjects::iceClearance::read(const dictionary& dict)
{
    using namespace iceDEMChecks;

    dict_ = dict;
    checkEntries
    (
        dict, "system/controlDict", {"functions/*(type iceClearance)"},
        "function object " + name()
    );

    structureGiven_ = dict.found("structure", keyType::LITERAL);
    if (structureGiven_)
    {
        structureSel_ = dict.get<wordRes>("structure");
    }
    iceDEMStatistics::selectionNotEmpty
    (
        dict, name(), "structure", structureGiven_, structureSel_.size(),
        "every body that is not free"
    );

    settings_.underRadius = positive(dict, "underRadius");
    settings_.nearRadius = dict.found("nearRadius", keyType::LITERAL)
        ? positive(dict, "nearRadius") : 2*settings_.underRadius;
    settings_.maxStep = positive(dict, "maxStep", settings_.underRadius);

    vector d(1, 0, 0);
    if (dict.found("direction", keyType::LITERAL))
    {
        d = dict.get<vector>("direction");
    }
    settings_.dirX = d.x();
    settings_.dirY = d.y();
    if (!std::isfinite(d.z()))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'direction' of function object " << name()
            << " in system/controlDict: " << d << " is not finite" << nl
            << exit(FatalIOError);
    }

    centreGiven_ = dict.found("centre", keyType::LITERAL);
    if (centreGiven_)
    {
        centre_ = dict.get<vector>("centre");
        for (direction k = 0; k < vector::nComponents; ++k)
        {
            if (!std::isfinite(centre_[k]))
            {
                FatalIOErrorInFunction(dict)
                    << "Entry 'centre' of function object " << name()
                    << " in system/controlDict: " << centre_ << " is not"
                    << " finite" << nl << exit(FatalIOError);
            }
        }
    }

    transient_ = nonNegative(dict, "transient", 0);
    const scalar endTime = time_.endTime().value();
    if (!std::isfinite(transient_) || transient_ >= endTime)
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'transient " << transient_ << "' of function object "
            << name() << " in system/controlDict: the transient [s] must be"
            << " >= 0 and before endTime " << endTime << " (nothing would be"
            << " counted)" << nl << exit(FatalIOError);
    }

    counter_.reset
    (
        coreCall
        (
            dict, "function object " + name() + " in system/controlDict",
            [this]()
            {
                return new ::iceDEM::statistics::IceClearance(settings_);
            }
        )
    );
    settings_ = counter_->settings();
    return true;
}


void Foam::functionObjects::iceClearance::takeSample(bool count)
{
    const iceDEMCase& c =
        time_.lookupObject<iceDEMState>("iceDEMState").demCase();
    const ::iceDEM::World& w = c.world();
    const double waterLevel = c.waterLevel();

    // The floes: every free body, its centre, the height of its highest
    // point above the water and its volume
    floes_.clear();
    const label nBodies = label(w.bodies().size());
    for (label i = 0; i < nBodies; ++i)
    {
        const ::iceDEM::Body& b = w.bodies()[i];
        if (!b.isFree())
        {
            continue;
        }
        const ::iceDEM::DilatedShape& s = w.shapeOf(i);
        const ::iceDEM::Mat3 R = b.rotation();
        double top = -std::numeric_limits<double>::max();
        for (const ::iceDEM::Vec3& v : s.core().vertices())
        {
            top = std::max(top, R.row(2).dot(v));
        }
        top += b.x.z() + s.radius() - waterLevel;
        floes_.push_back({b.id, b.x.x(), b.x.y(), top, s.volume()});
    }

    const ::iceDEM::Vec3 a = axis();
    counter_->sample(a.x(), a.y(), floes_, count);
}


bool Foam::functionObjects::iceClearance::execute()
{
    if (!connected_)
    {
        connect();
    }
    if (inactive_)
    {
        return true;
    }
    takeSample(time_.value() > transient_);

    if (Pstream::master())
    {
        if (!file_.valid())
        {
            const fileName dir
            (
                time_.globalPath()/"postProcessing"/name()
               /time_.timeName(time_.startTime().value())
            );
            mkDir(dir);
            file_.reset(new OFstream(dir/"clearance.dat"));
            file_().precision(10);
            file_()
                << "# ice past the structure: net floes (and ice volume [m3])"
                << " whose centre crossed the gate through the axis normal to"
                << " the drift, under the structure (|lateral| < underRadius "
                << settings_.underRadius << " m) or around it (< nearRadius "
                << settings_.nearRadius << " m), counted after the transient "
                << transient_ << " s; passedSubmerged: of those, floes whose"
                << " top was below the water near the axis; near, under,"
                << " submergedNear: floes now within nearRadius, inside"
                << " underRadius, within nearRadius with the top below the"
                << " water" << nl
                << "# time passedUnder passedAround passedSubmerged"
                << " volumeUnder volumeAround near under submergedNear"
                << endl;
        }
        const auto& n = counter_->counts();
        const auto& now = counter_->now();
        file_()
            << time_.value() << ' ' << n.passedUnder << ' ' << n.passedAround
            << ' ' << n.passedSubmerged << ' ' << n.volumeUnder << ' '
            << n.volumeAround << ' ' << now.near << ' ' << now.under << ' '
            << now.submergedNear << endl;
    }
    return true;
}


bool Foam::functionObjects::iceClearance::write()
{
    return true;
}


bool Foam::functionObjects::iceClearance::end()
{
    if (counter_ && !inactive_)
    {
        const auto& n = counter_->counts();
        Info<< type() << ' ' << name() << ": after " << transient_ << " s,"
            << " floes passed under the structure " << n.passedUnder << " ("
            << n.volumeUnder << " m3), around it " << n.passedAround << " ("
            << n.volumeAround << " m3), pushed under the water near it "
            << n.passedSubmerged << endl;
    }
    return true;
}


// ************************************************************************* //
