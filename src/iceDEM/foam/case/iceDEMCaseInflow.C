/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Inflow/outflow of the domain (core/domain/InflowOutflow) from the domain
    sub-dictionary of constant/iceDEMProperties:

        domain
        {
            type        inflowOutflow;
            direction   x;          // drift direction: x | -x | y | -y
            upstream    0;          // [m] coordinate (x or y) of the inflow
            downstream  400;        // [m] floes past it are removed
            stripWidth  20;         // [m] width of an inserted strip
            laneWidth   20;         // [m] width of a lane across the drift
                                    // whose upstream edge is followed on
                                    // its own [default: stripWidth]
            interval    1;          // [s] simulated time between updates
            material    ice;        // material of the new floes
            fieldDict   "system/createIceFieldDict";    // [default]
            window      (20 40);    // [m] (x or y) where the upstream
                                    // concentration is measured [default:
                                    // the strip after the insertion strip]
            windowLateral (100 200); // [m] its bounds across the drift
                                    // [default: the lateral bounds]
            // Generator entries, read from fieldDict unless given here:
            // concentration, meanFloeArea (or nFloes of fieldDict over its
            // region), thickness, radius, seed (default: fieldDict's + 1),
            // lloydIterations, velocity, iceDensity, waterDensity,
            // waterLevel, minCoreEdgeRatio, minCoreWidthRatio; lateral
            // (lo hi) [default: fieldDict's region across the drift]
            sides       open;       // [open] or periodic: the lateral
                                    // bounds are periodic (core/domain/
                                    // Domain: images, wrap), as a periodic
                                    // pack across the drift
        }

    The counts go to the log and to
    postProcessing/inflowOutflow/<startTime>/inflowOutflow.dat.
\*---------------------------------------------------------------------------*/

#include "iceDEMCase.H"
#include "dictionaryChecks.H"
#include "postProcessingFile.H"

#include "domain/InflowOutflow.H"
#include "IFstream.H"
#include "vector2D.H"

#include <cmath>

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

//- The dictionary holding a generator entry: the domain dictionary if it
//  gives it, else the field dictionary
const dictionary& source
(
    const dictionary& d,
    const dictionary& fd,
    const word& key
)
{
    return d.found(key, keyType::LITERAL) ? d : fd;
}

//- A finite scalar entry (required, or with a default)
scalar finite(const dictionary& dict, const word& key)
{
    const scalar v = dict.get<scalar>(key);
    if (!std::isfinite(v))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' must be a finite number; got " << v
            << nl << exit(FatalIOError);
    }
    return v;
}

scalar finite(const dictionary& dict, const word& key, scalar deflt)
{
    return dict.found(key, keyType::LITERAL) ? finite(dict, key) : deflt;
}

void readThickness(const dictionary& dict, ::iceDEM::ThicknessSettings& t)
{
    using D = ::iceDEM::ThicknessSettings::Distribution;
    if (const dictionary* td = dict.findDict("thickness", keyType::LITERAL))
    {
        const word dist = selectName
        (
            *td, "distribution", wordList{"constant", "uniform", "normal"}
        );
        t.distribution = ::iceDEM::thicknessDistributionFromName(dist);
        switch (t.distribution)
        {
            case D::constant:
                checkKeywords(*td, {"distribution", "value"}, "thickness");
                t.value = positive(*td, "value");
                break;
            case D::uniform:
                checkKeywords(*td, {"distribution", "min", "max"}, "thickness");
                t.min = positive(*td, "min");
                t.max = positive(*td, "max");
                break;
            case D::normal:
                checkKeywords
                (
                    *td,
                    {"distribution", "mean", "standardDeviation", "min", "max",
                     "maxDraws"},
                    "thickness"
                );
                t.mean = positive(*td, "mean");
                t.standardDeviation = positive(*td, "standardDeviation");
                t.min = positive(*td, "min");
                t.max = positive(*td, "max");
                t.maxDraws = labelInRange(*td, "maxDraws", 1, 1000000, t.maxDraws);
                break;
        }
    }
    else
    {
        t.distribution = D::constant;
        t.value = positive(dict, "thickness");
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::iceDEMCase::readInflowOutflow(const dictionary& d)
{
    checkEntries
    (
        d, "constant/iceDEMProperties",
        {"domain", "domain(type inflowOutflow)"}, "domain"
    );

    ::iceDEM::InflowOutflowSettings s;

    const word dir =
        selectName(d, "direction", wordList{"x", "-x", "y", "-y"});
    s.axis = (dir == "x" || dir == "-x") ? 0 : 1;
    s.sign = dir[0] == '-' ? -1 : 1;

    const scalar up = finite(d, "upstream");
    const scalar down = finite(d, "downstream");
    s.upstream = s.sign*up;
    s.downstream = s.sign*down;
    if (!(s.downstream > s.upstream))
    {
        FatalIOErrorInFunction(d)
            << "Entries 'upstream' (" << up << ") and 'downstream' (" << down
            << ") of 'domain': the downstream bound must lie beyond the"
            << " upstream one along direction " << dir << nl
            << exit(FatalIOError);
    }
    s.stripWidth = positive(d, "stripWidth");
    if (s.stripWidth > s.downstream - s.upstream)
    {
        FatalIOErrorInFunction(d)
            << "Entry 'stripWidth' of 'domain': " << s.stripWidth
            << " m is longer than the domain (" << s.downstream - s.upstream
            << " m between upstream and downstream)" << nl
            << exit(FatalIOError);
    }
    s.laneWidth = positive(d, "laneWidth", s.stripWidth);
    s.interval = positive(d, "interval");
    s.material = materialOf(d);
    if (d.found("window", keyType::LITERAL))
    {
        const vector2D w = d.get<vector2D>("window");
        const scalar a = s.sign*w.x(), b = s.sign*w.y();
        s.windowLo = min(a, b);
        s.windowHi = max(a, b);
        if (!std::isfinite(a) || !std::isfinite(b) || !(s.windowHi > s.windowLo))
        {
            FatalIOErrorInFunction(d)
                << "Entry 'window' of 'domain': two finite, different"
                << " coordinates along the drift; got " << w << nl
                << exit(FatalIOError);
        }
    }

    if (d.found("windowLateral", keyType::LITERAL))
    {
        const vector2D w = d.get<vector2D>("windowLateral");
        s.windowLateralLo = min(w.x(), w.y());
        s.windowLateralHi = max(w.x(), w.y());
        if (!std::isfinite(w.x()) || !std::isfinite(w.y()) || !(w.x() != w.y()))
        {
            FatalIOErrorInFunction(d)
                << "Entry 'windowLateral' of 'domain': two finite, different"
                << " coordinates across the drift; got " << w << nl
                << exit(FatalIOError);
        }
    }

    // The generator's dictionary (createIceField's)
    // (relative to the case, not to a processor directory in parallel)
    const fileName fdName =
        d.getOrDefault<fileName>("fieldDict", "system/createIceFieldDict");
    fileName fdPath(fdName);
    fdPath.expand();
    if (!fdPath.isAbsolute())
    {
        fdPath = runTime_.globalPath()/fdPath;
    }
    IFstream fdStream(fdPath);
    if (!fdStream.good())
    {
        FatalIOErrorInFunction(d)
            << "Entry 'fieldDict' of 'domain': cannot read " << fdPath
            << " (the createIceField dictionary whose generator entries the"
            << " inflow uses)" << nl << exit(FatalIOError);
    }
    const dictionary fd(fdStream);

    ::iceDEM::VoronoiFieldSettings& f = s.field;

    // Concentration in (0, 1), below 1 by the gaps the floes keep
    // (VoronoiField.H: maxFieldConcentration)
    {
        const dictionary& src = source(d, fd, "concentration");
        const scalar c = finite(src, "concentration");
        if (!::iceDEM::fieldConcentrationAllowed(c, f.tolerance))
        {
            FatalIOErrorInFunction(src)
                << "Entry 'concentration' (inflow of 'domain'): "
                << ::iceDEM::concentrationRangeText(c, f.tolerance).c_str()
                << nl << exit(FatalIOError);
        }
        f.concentration = c;
    }

    // Mean floe area: given, or nFloes of the field dictionary over its
    // region at its concentration
    if (d.found("meanFloeArea", keyType::LITERAL))
    {
        f.meanFloeArea = positive(d, "meanFloeArea");
    }
    else if (fd.found("meanFloeArea", keyType::LITERAL))
    {
        f.meanFloeArea = positive(fd, "meanFloeArea");
    }
    else
    {
        const label n = fd.get<label>("nFloes");
        const dictionary& region = fd.subDict("region");
        const vector2D lo = region.get<vector2D>("min");
        const vector2D hi = region.get<vector2D>("max");
        const scalar c = finite(fd, "concentration");
        const scalar a = c*(hi.x() - lo.x())*(hi.y() - lo.y())/scalar(n);
        if (!(n >= 1) || !(a > 0) || !std::isfinite(a))
        {
            FatalIOErrorInFunction(fd)
                << "Entries 'nFloes', 'region', 'concentration': no mean floe"
                << " area for the inflow follows from them (nFloes " << n
                << ")" << nl << exit(FatalIOError);
        }
        f.meanFloeArea = a;
    }
    f.nFloes = 0;

    readThickness(source(d, fd, "thickness"), f.thickness);
    f.radius = positive(source(d, fd, "radius"), "radius");

    if (d.found("seed", keyType::LITERAL))
    {
        f.seed = std::uint64_t(labelInRange(d, "seed", 0, labelMax, 0));
    }
    else
    {
        f.seed = std::uint64_t(labelInRange(fd, "seed", 0, labelMax - 1, 1)) + 1;
    }
    f.lloydIterations = labelInRange
    (
        source(d, fd, "lloydIterations"), "lloydIterations", 0, 1000,
        f.lloydIterations
    );
    {
        const dictionary& src = source(d, fd, "velocity");
        const vector U = src.getOrDefault<vector>("velocity", vector::zero);
        if (!std::isfinite(U.x()) || !std::isfinite(U.y()) || !std::isfinite(U.z()))
        {
            FatalIOErrorInFunction(src)
                << "Entry 'velocity' (inflow of 'domain'): must be finite;"
                << " got " << U << nl << exit(FatalIOError);
        }
        f.velocity = toVec3(U);
    }
    f.iceDensity =
        positive(source(d, fd, "iceDensity"), "iceDensity", f.iceDensity);
    f.waterDensity =
        positive(source(d, fd, "waterDensity"), "waterDensity", f.waterDensity);
    f.waterLevel =
        finite(source(d, fd, "waterLevel"), "waterLevel", f.waterLevel);
    f.minCoreEdgeRatio = positive
    (
        source(d, fd, "minCoreEdgeRatio"), "minCoreEdgeRatio",
        f.minCoreEdgeRatio
    );
    f.minCoreWidthRatio = positive
    (
        source(d, fd, "minCoreWidthRatio"), "minCoreWidthRatio",
        f.minCoreWidthRatio
    );

    // Lateral bounds: given, or the field's region across the drift
    scalar latLo, latHi;
    if (d.found("lateral", keyType::LITERAL))
    {
        const vector2D b = d.get<vector2D>("lateral");
        latLo = b.x();
        latHi = b.y();
    }
    else
    {
        const dictionary& region = fd.subDict("region");
        const vector2D lo = region.get<vector2D>("min");
        const vector2D hi = region.get<vector2D>("max");
        latLo = s.axis == 0 ? lo.y() : lo.x();
        latHi = s.axis == 0 ? hi.y() : hi.x();
    }
    if (!std::isfinite(latLo) || !std::isfinite(latHi) || !(latHi > latLo))
    {
        FatalIOErrorInFunction(d)
            << "Entry 'lateral' of 'domain' (or the region of " << fdName
            << "): the bounds across the drift must be finite with lo < hi;"
            << " got (" << latLo << " " << latHi << ")" << nl
            << exit(FatalIOError);
    }
    if (s.axis == 0)
    {
        f.ymin = latLo;
        f.ymax = latHi;
    }
    else
    {
        f.xmin = latLo;
        f.xmax = latHi;
    }
    // A lane's strip, for the generator's own checks (the settings keep
    // the whole lateral extent)
    {
        const label nLanes =
            max(label(1), label(std::lround((latHi - latLo)/s.laneWidth)));
        ::iceDEM::VoronoiFieldSettings g = f;
        const scalar laneHi = latLo + (latHi - latLo)/nLanes;
        g.xmin = s.axis == 0 ? s.upstream : latLo;
        g.xmax = s.axis == 0 ? s.upstream + s.stripWidth : laneHi;
        g.ymin = s.axis == 1 ? s.upstream : latLo;
        g.ymax = s.axis == 1 ? s.upstream + s.stripWidth : laneHi;
        coreCall
        (
            d, "domain (inflow generator from " + fdName + " and domain,"
            " on a lane's strip)",
            [&]{ ::iceDEM::checkVoronoiFieldSettings(g); }
        );
    }

    // Across the drift: open, or periodic over the lateral bounds (the
    // same Domain as type periodic, in the lateral direction only)
    const bool periodicSides =
        selectName(d, "sides", wordList{"open", "periodic"}, "open")
     == "periodic";

    coreCall
    (
        d, "domain",
        [&]
        {
            inflow_ = std::make_shared<::iceDEM::InflowOutflow>(s);
            world_->setInflowOutflow(inflow_);
            if (periodicSides)
            {
                ::iceDEM::DomainSettings ds;
                ds.periodic[1 - s.axis] = true;
                ds.lo[1 - s.axis] = latLo;
                ds.hi[1 - s.axis] = latHi;
                world_->setDomain(ds);
            }
        }
    );

    Info<< "iceDEM: inflow/outflow along " << dir << ": upstream " << up
        << ", downstream " << down << " m, strips of " << s.stripWidth
        << " m in " << inflow_->lanes() << " lanes of "
        << inflow_->settings().laneWidth << " m every " << s.interval << " s, concentration "
        << f.concentration << ", mean floe area " << f.meanFloeArea
        << " m2, seed " << label(f.seed) << " (generator from " << fdName
        << "), sides " << (periodicSides ? "periodic (" : "open (") << latLo
        << " " << latHi << ")" << nl;
}


void Foam::iceDEMCase::startInflowOutflow()
{
    if (!inflow_)
    {
        return;
    }
    const ::iceDEM::InflowOutflowState st = inflow_->state();
    inflowLoggedIn_ = st.floesIn;
    inflowLoggedOut_ = st.floesOut;
    if (Pstream::master())
    {
        const fileName dir =
            runTime_.globalPath()/"postProcessing"/"inflowOutflow"
           /runTime_.timeName();
        mkDir(dir);
        inflowFile_.reset
        (
            new OFstream(newOutputFile(runTime_, dir, "inflowOutflow.dat"))
        );
        OFstream& os = inflowFile_();
        os.precision(12);
        os  << "# inflow/outflow: floes in (inserted upstream), out (removed"
            << " downstream), free floes in the domain, plan-area"
            << " concentration in the window, new floes dropped (their room"
            << " was taken)" << nl
            << "# time in out floes upstreamConcentration dropped" << nl;
    }
    writeInflowOutflow();
}


void Foam::iceDEMCase::writeInflowOutflow()
{
    if (!inflow_)
    {
        return;
    }
    reportWarnings();
    const ::iceDEM::World& w = *world_;
    label floes = 0;
    for (const ::iceDEM::Body& b : w.bodies())
    {
        if (b.isFree()) ++floes;
    }
    const scalar c = inflow_->upstreamConcentration(w);
    const long nIn = inflow_->floesIn();
    const long nOut = inflow_->floesOut();
    if (nIn != inflowLoggedIn_ || nOut != inflowLoggedOut_)
    {
        Info<< "iceDEM inflowOutflow: " << nIn - inflowLoggedIn_ << " in, "
            << nOut - inflowLoggedOut_ << " out (total " << nIn << " in, "
            << nOut << " out, " << inflow_->floesDropped() << " dropped), "
            << floes << " floes, upstream concentration " << c << nl;
        inflowLoggedIn_ = nIn;
        inflowLoggedOut_ = nOut;
    }
    if (inflowFile_.valid())
    {
        inflowFile_()
            << w.time() << ' ' << nIn << ' ' << nOut << ' ' << floes << ' '
            << c << ' ' << inflow_->floesDropped() << endl;
    }
}


// ************************************************************************* //
