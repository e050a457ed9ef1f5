/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Reading the top level of constant/iceDEMProperties into the world: the
    DEM settings (time step, skins, contact model and its coefficients),
    the materials, the walls and the interactions (friction and restitution
    of every pair of materials that can meet). See doc/caseFiles.md.
\*---------------------------------------------------------------------------*/

#include "iceDEMCase.H"
#include "dictionaryChecks.H"

#include "HashSet.H"
#include "FixedList.H"

#include <cmath>

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

::iceDEM::WorldSettings Foam::iceDEMCase::readSettings() const
{
    const dictionary& d = properties_;

    ::iceDEM::WorldSettings s;

    s.timeStep = positive(d, "deltaT");
    s.gravity = toVec3(g_);

    if (d.found("neighbourSkin", keyType::LITERAL))
    {
        s.skin = positive(d, "neighbourSkin");
    }
    else
    {
        s.skin = -1;    // the core takes the smallest dilation radius
    }

    // Narrow phase's feature-pair lists; 0: none
    if (d.found("featureSkin", keyType::LITERAL))
    {
        s.featureSkin = nonNegative(d, "featureSkin", 0);
    }
    else
    {
        s.featureSkin = -1;     // the core takes half the smallest radius
    }

    wordList contactModels;
    for (const std::string& n : ::iceDEM::ContactLaw::names())
    {
        contactModels.append(word(n));
    }
    s.contact.model = selectName(d, "contactModel", contactModels, "hertz");
    s.contact.tangentialModel =
        selectName(d, "tangentialModel", wordList({"mindlin", "ratio"}), "mindlin");
    s.contact.tangentialStiffnessRatio =
        positive(d, "tangentialStiffnessRatio", 2.0/3.0);
    s.contact.maxEdgeRadiusRatio =
        inRange(d, "maxEdgeRadiusRatio", 1, 1e6, 10);
    s.contact.dampingPerPair =
        selectName(d, "normalDamping", wordList({"perContact", "perPair"}), "perContact")
     == "perPair";

    s.contactCheckVelocity = positive(d, "contactCheckVelocity", 1);
    s.contactStepsWarn = positive(d, "contactStepsWarn", 10);
    s.contactStepsMin = nonNegative(d, "contactStepsMin", 3);

    // Integer entries in [lo, hi], read as scalars to say so when they are
    // not integers; range: [lo, hi] as the message writes it
    auto integerEntry = [&d]
    (
        const word& name,
        scalar deflt,
        scalar lo,
        scalar hi,
        const char* range,
        const char* meaning
    )
    {
        const scalar v = d.getOrDefault<scalar>(name, deflt);
        if (!(v >= lo && v <= hi && v == std::floor(v)))
        {
            FatalIOErrorInFunction(d)
                << "Entry '" << name << "' of constant/iceDEMProperties is "
                << v << ": it must be an integer in " << range << " ("
                << meaning << ")" << nl
                << exit(FatalIOError);
        }
        return int(v);
    };
    s.bodyForceInterval = integerEntry
    (
        "bodyForceInterval", 1, 1, 1e6, "[1, 1e6]",
        "the body forces are evaluated every bodyForceInterval-th DEM step;"
        " 1: every step"
    );
    s.singleThreadBelow = integerEntry
    (
        "singleThreadBelow", 256, 0, 1e9, "[0, 1e9]",
        "the DEM's loops over fewer bodies or pairs run on one thread;"
        " 0: every loop on all threads"
    );

    // The restart state is read by OpenFOAM's tokenizer, which gives +0 for
    // "-0" and for |value| <= VSMALL: the running state keeps those as +0
    s.storeFloor = VSMALL;

    if (s.contactStepsMin > s.contactStepsWarn)
    {
        FatalIOErrorInFunction(d)
            << "Entry 'contactStepsMin' (" << s.contactStepsMin
            << ") is larger than 'contactStepsWarn' ("
            << s.contactStepsWarn << "): it must not be" << nl
            << exit(FatalIOError);
    }

    return s;
}


void Foam::iceDEMCase::readMaterials()
{
    if (!properties_.isDict("materials"))
    {
        FatalIOErrorInFunction(properties_)
            << "Missing sub-dictionary 'materials', e.g." << nl
            << "    materials { ice { density 900; youngsModulus 1e9;"
            << " poissonsRatio 0.33; } }" << nl
            << exit(FatalIOError);
    }
    const dictionary& mats = properties_.subDict("materials");

    for (const entry& e : mats)
    {
        const word& name = e.keyword();
        if (name.empty() || name[0] == '_')
        {
            continue;
        }
        if (!e.isDict())
        {
            FatalIOErrorInFunction(mats)
                << "Entry '" << name << "' of 'materials' must be a"
                << " dictionary { density ..; youngsModulus ..;"
                << " poissonsRatio ..; }" << nl
                << exit(FatalIOError);
        }
        const dictionary& d = e.dict();
        checkEntries
        (
            d, "constant/iceDEMProperties", {"materials/*"},
            "material " + name
        );

        ::iceDEM::Material m;
        m.name = name;
        m.density = positive(d, "density");
        m.youngsModulus = positive(d, "youngsModulus");
        m.poissonsRatio = inRange(d, "poissonsRatio", -0.99, 0.5);

        coreCall
        (
            d, "material " + name,
            [&]{ ::iceDEM::checkMaterial(m); }
        );

        const label index =
            coreCall(d, "material " + name, [&]{ return world_->addMaterial(m); });
        materialIndex_.insert(name, index);
    }

    if (materialIndex_.empty())
    {
        FatalIOErrorInFunction(mats)
            << "No material in 'materials'" << nl
            << exit(FatalIOError);
    }
}


Foam::label Foam::iceDEMCase::materialOf(const dictionary& dict) const
{
    const word name = dict.get<word>("material");
    const auto iter = materialIndex_.cfind(name);
    if (!iter.found())
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'material': unknown material '" << name << "'" << nl
            << "    Materials of " << "constant/iceDEMProperties" << ": "
            << flatOutput(materialIndex_.sortedToc()) << nl
            << exit(FatalIOError);
    }
    return iter.val();
}


void Foam::iceDEMCase::readInteractions()
{
    if (!properties_.isDict("interactions"))
    {
        FatalIOErrorInFunction(properties_)
            << "Missing sub-dictionary 'interactions' (friction and"
            << " restitution of every pair of materials in contact), e.g."
            << nl
            << "    interactions { iceIce { materials (ice ice);"
            << " friction 0.2; restitution 0.3; } }" << nl
            << exit(FatalIOError);
    }
    const dictionary& inter = properties_.subDict("interactions");

    // Pairs (min, max) of material indices with an entry
    HashSet<labelPair, labelPair::Hash<>> defined;

    for (const entry& e : inter)
    {
        const word& name = e.keyword();
        if (name.empty() || name[0] == '_')
        {
            continue;
        }
        if (!e.isDict())
        {
            FatalIOErrorInFunction(inter)
                << "Entry '" << name << "' of 'interactions' must be a"
                << " dictionary { materials (a b); friction ..;"
                << " restitution ..; }" << nl
                << exit(FatalIOError);
        }
        const dictionary& d = e.dict();
        checkEntries
        (
            d, "constant/iceDEMProperties", {"interactions/*"},
            "interaction " + name
        );

        const FixedList<word, 2> names(d.get<FixedList<word, 2>>("materials"));
        label ab[2];
        for (label k = 0; k < 2; ++k)
        {
            const auto iter = materialIndex_.cfind(names[k]);
            if (!iter.found())
            {
                FatalIOErrorInFunction(d)
                    << "Entry 'materials': unknown material '" << names[k]
                    << "'" << nl
                    << "    Materials: "
                    << flatOutput(materialIndex_.sortedToc()) << nl
                    << exit(FatalIOError);
            }
            ab[k] = iter.val();
        }

        ::iceDEM::PairProperties p;
        p.friction = nonNegative(d, "friction", 0);
        p.restitution = d.getOrDefault<scalar>("restitution", 1);
        if (!(p.restitution > 0 && p.restitution <= 1))
        {
            FatalIOErrorInFunction(d)
                << "Entry 'restitution' is " << p.restitution
                << ": it must lie in (0, 1]" << nl
                << exit(FatalIOError);
        }
        coreCall
        (
            d, "interaction " + name,
            [&]{ ::iceDEM::checkPairProperties(p); }
        );

        const labelPair key(min(ab[0], ab[1]), max(ab[0], ab[1]));
        if (!defined.insert(key))
        {
            FatalIOErrorInFunction(d)
                << "Entry 'materials': the pair (" << names[0] << ' '
                << names[1] << ") has more than one entry in 'interactions'"
                << nl << exit(FatalIOError);
        }

        coreCall
        (
            d, "interaction " + name,
            [&]{ world_->setPairProperties(ab[0], ab[1], p); }
        );
    }

    // Which pairs can meet: bodies with bodies (same material only when
    // two bodies have it), bodies with walls
    const label nMat = materialIndex_.size();
    labelList bodyCount(nMat, 0);
    labelList wallCount(nMat, 0);
    for (const ::iceDEM::Body& b : world_->bodies())
    {
        ++bodyCount[b.material];
    }
    for (const ::iceDEM::Wall& w : world_->walls())
    {
        ++wallCount[w.material];
    }
    // The structure of a coupled solver (added later) meets the bodies like
    // a wall does
    if (properties_.isDict("structure"))
    {
        const dictionary& sd = properties_.subDict("structure");
        if (sd.found("material", keyType::LITERAL))
        {
            ++wallCount[materialOf(sd)];
        }
    }
    wordList matNames(nMat);
    forAllConstIters(materialIndex_, iter)
    {
        matNames[iter.val()] = iter.key();
    }

    for (label a = 0; a < nMat; ++a)
    {
        for (label b = a; b < nMat; ++b)
        {
            const bool meet =
                (a == b ? bodyCount[a] >= 2 : bodyCount[a] && bodyCount[b])
             || (bodyCount[a] && wallCount[b])
             || (bodyCount[b] && wallCount[a]);

            if (meet && !defined.found(labelPair(a, b)))
            {
                FatalIOErrorInFunction(inter)
                    << "No entry in 'interactions' for the material pair ("
                    << matNames[a] << ' ' << matNames[b] << "): every pair"
                    << " of materials whose bodies or walls can touch needs"
                    << " one, e.g." << nl
                    << "    " << matNames[a] << '_' << matNames[b]
                    << " { materials (" << matNames[a] << ' ' << matNames[b]
                    << "); friction 0.2; restitution 0.3; }" << nl
                    << exit(FatalIOError);
            }
        }
    }
}


void Foam::iceDEMCase::readWalls()
{
    if (!properties_.found("walls", keyType::LITERAL))
    {
        return;
    }
    const dictionary& walls = properties_.subDict("walls");

    for (const entry& e : walls)
    {
        const word& name = e.keyword();
        if (name.empty() || name[0] == '_')
        {
            continue;
        }
        if (!e.isDict())
        {
            FatalIOErrorInFunction(walls)
                << "Entry '" << name << "' of 'walls' must be a dictionary"
                << " { point (x y z); normal (nx ny nz); material m; }" << nl
                << exit(FatalIOError);
        }
        const dictionary& d = e.dict();
        checkEntries
        (
            d, "constant/iceDEMProperties", {"walls/*"}, "wall " + name
        );

        ::iceDEM::Wall w;
        w.name = name;
        w.point = toVec3(d.get<vector>("point"));
        w.normal = toVec3(unitVector(d, "normal"));
        w.material = materialOf(d);

        coreCall(d, "wall " + name, [&]{ world_->addWall(w); });
        wallNames_.append(name);
    }
}


// ************************************************************************* //
