/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "iceDEMState.H"
#include "iceDEMCase.H"
#include "dictionaryChecks.H"
#include "completeTime.H"

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
