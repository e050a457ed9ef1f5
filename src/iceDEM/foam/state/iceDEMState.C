/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "iceDEMState.H"
#include "iceDEMCase.H"
#include "dictionaryChecks.H"
#include "completeTime.H"

#include "domain/InflowOutflow.H"

#include "FixedList.H"
#include "vectorList.H"

#include <cmath>

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(iceDEMState, 0);
}


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

using Foam::label;
using Foam::scalar;

//- An integer stored as a scalar (exact below 2^53), checked
long long integerOf
(
    const Foam::dictionary& dict,
    const char* key,
    scalar v,
    long long lo,
    long long hi
)
{
    if (!(v >= scalar(lo) && v <= scalar(hi)) || v != std::floor(v))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "': " << v << " is not an integer in ["
            << scalar(lo) << ", " << scalar(hi) << "]" << Foam::nl
            << Foam::exit(Foam::FatalIOError);
    }
    return static_cast<long long>(v);
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::iceDEMState::iceDEMState
(
    const Time& runTime,
    const iceDEMCase& demCase
)
:
    regIOobject
    (
        IOobject
        (
            "iceDEMState",
            runTime.timeName(),
            "uniform",
            runTime,
            IOobject::READ_IF_PRESENT,
            IOobject::AUTO_WRITE
        )
    ),
    case_(demCase),
    dict_(),
    found_(false)
{
    found_ = readHeaderOk(IOstream::ASCII, typeName);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

bool Foam::iceDEMState::readData(Istream& is)
{
    dict_.clear();
    dict_.read(is);
    dict_.name() = is.name();
    return !is.bad();
}


void Foam::iceDEMState::apply(::iceDEM::World& world) const
{
    if (case_.inflowOutflow())
    {
        applyInflowOutflow(world);
    }

    const dictionary& d = dict_;
    auto& bodies = world.bodies();
    const label n = label(bodies.size());

    const wordList names(d.get<wordList>("bodies"));
    if (names.size() != n)
    {
        FatalIOErrorInFunction(d)
            << "Entry 'bodies': the state has " << names.size()
            << " bodies, the case " << n << ": the state belongs to another"
            << " ice field (remove the time directory or start from 0)" << nl
            << exit(FatalIOError);
    }
    forAll(names, i)
    {
        if (names[i] != case_.name(i))
        {
            FatalIOErrorInFunction(d)
                << "Entry 'bodies': body " << i << " is '" << names[i]
                << "' in the state and '" << case_.name(i) << "' in the case"
                << nl << exit(FatalIOError);
        }
    }

    auto vectors = [&](const char* key)
    {
        vectorList v(d.get<vectorList>(key));
        if (v.size() != n)
        {
            FatalIOErrorInFunction(d)
                << "Entry '" << key << "' has " << v.size()
                << " values for " << n << " bodies" << nl
                << exit(FatalIOError);
        }
        return v;
    };

    const vectorList x(vectors("position"));
    const vectorList v(vectors("velocity"));
    const vectorList L(vectors("angularMomentum"));
    const vectorList F(vectors("force"));
    const vectorList T(vectors("torque"));

    const List<FixedList<scalar, 4>> q
    (
        d.get<List<FixedList<scalar, 4>>>("orientation")
    );
    if (q.size() != n)
    {
        FatalIOErrorInFunction(d)
            << "Entry 'orientation' has " << q.size()
            << " values for " << n << " bodies" << nl
            << exit(FatalIOError);
    }

    for (label i = 0; i < n; ++i)
    {
        ::iceDEM::Body& b = bodies[i];
        b.x = toVec3(x[i]);
        b.q = ::iceDEM::Quat(q[i][0], q[i][1], q[i][2], q[i][3]);
        b.v = toVec3(v[i]);
        b.L = toVec3(L[i]);
        b.force = toVec3(F[i]);
        b.torque = toVec3(T[i]);

        const scalar qn = b.q.norm();
        if (!(std::abs(qn - 1) < 1e-9) || !b.x.allFinite() || !b.v.allFinite())
        {
            FatalIOErrorInFunction(d)
                << "Body " << i << " (" << names[i] << "): position, velocity"
                << " or orientation is not finite (|q| = " << qn << ")"
                << nl << exit(FatalIOError);
        }
    }

    const List<FixedList<scalar, 4>> c
    (
        d.get<List<FixedList<scalar, 4>>>("contacts")
    );
    const vectorList xi(d.get<vectorList>("contactSprings"));
    if (xi.size() != c.size())
    {
        FatalIOErrorInFunction(d)
            << "Entry 'contactSprings' has " << xi.size() << " values for "
            << c.size() << " contacts" << nl
            << exit(FatalIOError);
    }

    const long long nWalls = world.walls().size();
    std::vector<::iceDEM::ContactRecord> records(c.size());
    forAll(c, k)
    {
        ::iceDEM::ContactRecord& r = records[k];
        r.i = int(integerOf(d, "contacts", c[k][0], 0, n - 1));
        r.j = int(integerOf(d, "contacts", c[k][1], -nWalls, n - 1));
        r.featureI =
            std::uint32_t(integerOf(d, "contacts", c[k][2], 0, 4294967295LL));
        r.featureJ =
            std::uint32_t(integerOf(d, "contacts", c[k][3], 0, 4294967295LL));
        r.xi = toVec3(xi[k]);
    }

    coreCall
    (
        d, "contacts",
        [&]{ world.setContactRecords(records); }
    );

    world.setTime(d.get<scalar>("time"));

    // The multi-rate step's schedule (written with bodyForceInterval > 1;
    // absent: a single-rate state, at a boundary)
    world.setRestartSchedule
    (
        int(integerOf(d, "bodyForceInterval", d.getOrDefault<scalar>("bodyForceInterval", 1), 1, 1000000)),
        int(integerOf(d, "bodyForcePhase", d.getOrDefault<scalar>("bodyForcePhase", 0), 0, 1000000))
    );
}


void Foam::iceDEMState::applyInflowOutflow(::iceDEM::World& world) const
{
    if (!dict_.isDict("inflowOutflow"))
    {
        FatalIOErrorInFunction(dict_)
            << "No entry 'inflowOutflow' in the DEM state, but constant/"
            << "iceDEMProperties has domain type inflowOutflow: the state was"
            << " written without inflow (start from time 0, or remove the"
            << " domain entry)" << nl << exit(FatalIOError);
    }
    const dictionary& d = dict_.subDict("inflowOutflow");
    ::iceDEM::InflowOutflow& io = *case_.inflow();

    ::iceDEM::InflowOutflowState s;
    s.floesIn = integerOf(d, "floesIn", d.get<scalar>("floesIn"), 0, 1LL << 52);
    s.floesOut = integerOf(d, "floesOut", d.get<scalar>("floesOut"), 0, 1LL << 52);
    s.strips = integerOf(d, "strips", d.get<scalar>("strips"), 0, 1LL << 52);
    s.nextId = integerOf(d, "nextId", d.get<scalar>("nextId"), -1, 1LL << 31);
    s.lastUpdate = d.get<scalar>("lastUpdate");
    s.floesDropped = integerOf
    (
        d, "floesDropped", d.getOrDefault<scalar>("floesDropped", 0), 0, 1LL << 52
    );
    // The lanes' last strips; a state written before the lanes has none
    // (every lane then starts against its floes)
    {
        const scalarList bounds(d.getOrDefault<scalarList>("laneBounds", scalarList()));
        const labelList ids(d.getOrDefault<labelList>("stripIds", labelList()));
        const labelList lanes(d.getOrDefault<labelList>("stripLanes", labelList()));
        const scalarList along(d.getOrDefault<scalarList>("stripAlong", scalarList()));
        if (lanes.size() != ids.size() || along.size() != ids.size())
        {
            FatalIOErrorInFunction(d)
                << "Entries 'stripIds' (" << ids.size() << "), 'stripLanes' ("
                << lanes.size() << ") and 'stripAlong' (" << along.size()
                << ") must have the same length" << nl << exit(FatalIOError);
        }
        s.laneBounds.assign(bounds.begin(), bounds.end());
        s.stripIds.assign(ids.begin(), ids.end());
        s.stripLanes.assign(lanes.begin(), lanes.end());
        s.stripAlong.assign(along.begin(), along.end());
    }

    // The inserted floes: (id zBottom thickness radius x0 y0 x1 y1 ...)
    const List<scalarList> rows(d.get<List<scalarList>>("floes"));
    std::map<int, ::iceDEM::Floe> floes;
    for (const scalarList& r : rows)
    {
        if (r.size() < 10 || r.size() % 2 != 0)
        {
            FatalIOErrorInFunction(d)
                << "Entry 'floes': a floe is (id zBottom thickness radius"
                << " x0 y0 x1 y1 x2 y2 ...); got " << r.size() << " numbers"
                << nl << exit(FatalIOError);
        }
        ::iceDEM::Floe f;
        const int id = int(integerOf(d, "floes", r[0], 0, 1LL << 31));
        f.zBottom = r[1];
        f.thickness = r[2];
        f.radius = r[3];
        for (label k = 4; k < r.size(); k += 2)
        {
            f.outline.push_back(::iceDEM::Vec2(r[k], r[k + 1]));
        }
        floes[id] = f;
    }

    // The world's bodies: those of the state (by id, in its order): the
    // initial bodies still there, then the inserted floes
    const labelList ids(d.get<labelList>("ids"));
    std::map<label, label> order;
    forAll(ids, k)
    {
        order[ids[k]] = k;
    }
    const auto& bodies = world.bodies();
    std::vector<bool> remove(bodies.size(), false);
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        remove[i] = order.count(bodies[i].id) == 0;
    }
    coreCall(d, "ids", [&]{ world.removeBodies(remove); });
    for (label k = label(world.bodies().size()); k < ids.size(); ++k)
    {
        const auto f = floes.find(int(ids[k]));
        if (f == floes.end())
        {
            FatalIOErrorInFunction(d)
                << "Entry 'ids': body id " << ids[k] << " is neither in the"
                << " case nor among the inserted 'floes'" << nl
                << exit(FatalIOError);
        }
        coreCall
        (
            d, "floes",
            [&]{ io.addInsertedBody(world, int(ids[k]), f->second); }
        );
    }
    forAll(ids, k)
    {
        if (k >= label(world.bodies().size()) || world.bodies()[k].id != ids[k])
        {
            FatalIOErrorInFunction(d)
                << "Entry 'ids': body " << k << " has id " << ids[k]
                << " in the state, not in the rebuilt world" << nl
                << exit(FatalIOError);
        }
    }
    coreCall(d, "inflowOutflow", [&]{ io.restore(s, std::move(floes)); });
}


void Foam::iceDEMState::writeInflowOutflow(Ostream& os) const
{
    const ::iceDEM::World& w = case_.world();
    const ::iceDEM::InflowOutflow& io = *case_.inflow();
    const ::iceDEM::InflowOutflowState s = io.state();

    os.beginBlock("inflowOutflow");
    os.writeEntry("floesIn", scalar(s.floesIn));
    os.writeEntry("floesOut", scalar(s.floesOut));
    os.writeEntry("strips", scalar(s.strips));
    os.writeEntry("nextId", scalar(s.nextId));
    os.writeEntry("lastUpdate", s.lastUpdate);
    os.writeEntry("floesDropped", scalar(s.floesDropped));
    {
        scalarList bounds(label(s.laneBounds.size()));
        forAll(bounds, k) bounds[k] = s.laneBounds[k];
        labelList ids(label(s.stripIds.size())), lanes(ids.size());
        scalarList along(ids.size());
        forAll(ids, k)
        {
            ids[k] = s.stripIds[k];
            lanes[k] = s.stripLanes[k];
            along[k] = s.stripAlong[k];
        }
        os.writeEntry("laneBounds", bounds);
        os.writeEntry("stripIds", ids);
        os.writeEntry("stripLanes", lanes);
        os.writeEntry("stripAlong", along);
    }

    labelList ids(w.bodies().size());
    forAll(ids, i)
    {
        ids[i] = w.bodies()[i].id;
    }
    os.writeEntry("ids", ids);

    List<scalarList> rows(io.insertedFloes().size());
    label k = 0;
    for (const auto& idFloe : io.insertedFloes())
    {
        const ::iceDEM::Floe& f = idFloe.second;
        scalarList& r = rows[k++];
        r.setSize(4 + 2*f.outline.size());
        r[0] = idFloe.first;
        r[1] = f.zBottom;
        r[2] = f.thickness;
        r[3] = f.radius;
        for (std::size_t j = 0; j < f.outline.size(); ++j)
        {
            r[4 + 2*j] = f.outline[j].x();
            r[5 + 2*j] = f.outline[j].y();
        }
    }
    os.writeEntry("floes", rows);
    os.endBlock();
}


bool Foam::iceDEMState::writeObject
(
    IOstream::streamFormat,
    IOstream::versionNumber ver,
    IOstream::compressionType cmp,
    const bool
) const
{
    // Into the current time directory (as regIOobject::writeObject does)
    const_cast<iceDEMState&>(*this).instance() = time().timeName();

    // Beside, then renamed into place: a kill never leaves half a state
    return completeTime::atomicWrite(*this, IOstream::ASCII, ver, cmp);
}


bool Foam::iceDEMState::writeData(Ostream& os) const
{
    const ::iceDEM::World& w = case_.world();
    const auto& bodies = w.bodies();
    const label n = label(bodies.size());

    // Bit-exact doubles in ascii
    os.precision(17);

    os.writeEntry("time", w.time());
    os.writeEntry("step", scalar(w.stepIndex()));
    if (w.bodyForceInterval() > 1)
    {
        os.writeEntry("bodyForceInterval", scalar(w.bodyForceInterval()));
        os.writeEntry("bodyForcePhase", scalar(w.bodyForcePhase()));
    }

    wordList names(n);
    vectorList x(n), v(n), L(n), F(n), T(n);
    List<FixedList<scalar, 4>> q(n);
    for (label i = 0; i < n; ++i)
    {
        const ::iceDEM::Body& b = bodies[i];
        names[i] = case_.name(i);
        x[i] = toVector(b.x);
        v[i] = toVector(b.v);
        L[i] = toVector(b.L);
        F[i] = toVector(b.force);
        T[i] = toVector(b.torque);
        q[i] = FixedList<scalar, 4>({b.q.w(), b.q.x(), b.q.y(), b.q.z()});
    }

    os.writeEntry("bodies", names);
    os.writeEntry("position", x);
    os.writeEntry("orientation", q);
    os.writeEntry("velocity", v);
    os.writeEntry("angularMomentum", L);
    os.writeEntry("force", F);
    os.writeEntry("torque", T);

    const std::vector<::iceDEM::ContactRecord> records = w.contactRecords();
    List<FixedList<scalar, 4>> c(records.size());
    vectorList xi(records.size());
    forAll(c, k)
    {
        const ::iceDEM::ContactRecord& r = records[k];
        c[k] = FixedList<scalar, 4>
        ({
            scalar(r.i), scalar(r.j), scalar(r.featureI), scalar(r.featureJ)
        });
        xi[k] = toVector(r.xi);
    }
    os.writeEntry("contacts", c);
    os.writeEntry("contactSprings", xi);

    if (case_.inflowOutflow())
    {
        writeInflowOutflow(os);
    }

    if (!case_.couplingState().empty())
    {
        os.beginBlock("coupling");
        for (const entry& e : case_.couplingState())
        {
            os << e;
        }
        os.endBlock();
    }

    return os.good();
}


// ************************************************************************* //
