/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Water (buoyancy) and drag of constant/iceDEMProperties: the water
    sub-dictionary adds the core's Buoyancy model and, unless switched off,
    its FloeDamping (floeDamping: heave, roll and pitch, on by default), the
    wind sub-dictionary the core's Wind model, the drag sub-dictionary the
    core's Drag model with a uniform current (type empirical) or with the
    flow velocity made by the solver's factory (type resolved).
\*---------------------------------------------------------------------------*/

#include "iceDEMCase.H"
#include "dictionaryChecks.H"

#include "hydro/Buoyancy.H"
#include "hydro/Drag.H"
#include "hydro/FlowVelocity.H"
#include "hydro/FloeDamping.H"
#include "hydro/Wind.H"
#include "windDict.H"

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

//- floeDamping: on by default wherever there is water
void addFloeDamping
(
    const dictionary& props,
    ::iceDEM::World& world,
    const ::iceDEM::WaterSettings& water
)
{
    ::iceDEM::FloeDampingSettings s;
    const dictionary* dptr = props.findDict("floeDamping", keyType::LITERAL);
    if (dptr)
    {
        const dictionary& d = *dptr;
        checkEntries
        (
            d, "constant/iceDEMProperties", {"floeDamping"}, "floeDamping"
        );
        s.heave = nonNegative(d, "heave", s.heave);
        s.rollPitch = nonNegative(d, "rollPitch", s.rollPitch);
        coreCall(d, "floeDamping", [&]{ ::iceDEM::checkFloeDampingSettings(s); });
    }
    if (s.heave == 0 && s.rollPitch == 0)
    {
        Info<< "iceDEM: floe damping off" << endl;
        return;
    }
    Info<< "iceDEM: floe damping, fraction of critical: heave " << s.heave
        << ", roll and pitch " << s.rollPitch << endl;
    world.addForceModel(std::make_shared<::iceDEM::FloeDamping>(water, s));
}


//- wind: optional
void addWind
(
    const dictionary& props,
    ::iceDEM::World& world,
    const ::iceDEM::WaterSettings& water
)
{
    const dictionary* dptr = props.findDict("wind", keyType::LITERAL);
    if (!dptr) return;
    const dictionary& d = *dptr;
    // The entries of the other type may stay when the type is switched
    checkEntries
    (
        d, "constant/iceDEMProperties",
        {"wind", "wind(type uniform)", "wind(type table)"}, "wind"
    );
    const ::iceDEM::WindHistory history = readWindHistory(d);
    ::iceDEM::WindSettings s;
    s.rhoAir = nonNegative(d, "rhoAir", s.rhoAir);
    s.skinCoefficient = nonNegative(d, "Cs", s.skinCoefficient);
    s.formCoefficient = nonNegative(d, "Cf", s.formCoefficient);
    s.subdivision = labelInRange
    (
        d, "subdivision", 0, ::iceDEM::DragSettings::maxSubdivision,
        s.subdivision
    );
    s.topCosine = d.getOrDefault<scalar>("topCosine", s.topCosine);
    if (!std::isfinite(s.topCosine) || !(s.topCosine > 0 && s.topCosine <= 1))
    {
        FatalIOErrorInFunction(d)
            << "Entry 'topCosine' is " << s.topCosine
            << ": it must lie in (0, 1]" << nl << exit(FatalIOError);
    }
    if (d.found("integration"))
    {
        s.integration = ::iceDEM::dragIntegrationFromName
        (
            selectName(d, "integration", wordList({"exact", "sampled"}))
        );
    }
    if
    (
        s.integration == ::iceDEM::DragIntegration::exact
     && d.found("subdivision", keyType::LITERAL)
    )
    {
        // A wind has no type to switch to that would use it (unlike the
        // drag's empirical/resolved): say that it does nothing
        IOWarningInFunction(d)
            << "Entry 'subdivision' has no effect with 'integration exact'"
            << " (the default): it sets the sample points of"
            << " 'integration sampled'" << endl;
    }
    world.addForceModel
    (
        coreCall
        (
            d, "wind",
            [&]{ return std::make_shared<::iceDEM::Wind>(water, s, history); }
        )
    );
    Info<< "iceDEM: wind on the floes, " << history.table().size()
        << " row(s), rhoAir " << s.rhoAir << ", Cs " << s.skinCoefficient
        << ", Cf " << s.formCoefficient << endl;
}

} // anonymous namespace

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::iceDEMCase::readWater(const flowVelocityFactory& resolvedFlow)
{
    const bool hasWater = properties_.found("water", keyType::LITERAL);
    const bool hasDrag = properties_.found("drag", keyType::LITERAL);

    if (!hasWater)
    {
        for (const word key : {"wind", "floeDamping"})
        {
            if (properties_.found(key, keyType::LITERAL))
            {
                FatalIOErrorInFunction(properties_)
                    << "Entry '" << key << "' needs the sub-dictionary"
                    << " 'water' (density, level) in"
                    << " constant/iceDEMProperties" << nl
                    << exit(FatalIOError);
            }
        }
        if (hasDrag)
        {
            FatalIOErrorInFunction(properties_.subDict("drag"))
                << "Entry 'drag' needs the sub-dictionary 'water' (density,"
                << " level) in " << "constant/iceDEMProperties" << nl
                << exit(FatalIOError);
        }
        return;
    }

    const dictionary& wd = properties_.subDict("water");
    checkEntries(wd, "constant/iceDEMProperties", {"water"}, "water");

    ::iceDEM::WaterSettings water;
    water.density = positive(wd, "density", 1025);
    water.level = wd.getOrDefault<scalar>("level", 0);

    coreCall(wd, "water", [&]{ ::iceDEM::checkWaterSettings(water); });

    // Free bodies denser than the water sink: legitimate for a block on a
    // floor, a mistake for ice (e.g. densities swapped), so say it
    {
        std::vector<label> sinking(world_->materials().size(), 0);
        for (const ::iceDEM::Body& b : world_->bodies())
        {
            if
            (
                b.isFree()
             && world_->materials()[b.material].density >= water.density
            )
            {
                ++sinking[b.material];
            }
        }
        for (size_t m = 0; m < sinking.size(); ++m)
        {
            if (sinking[m])
            {
                IOWarningInFunction(wd)
                    << "Entry 'density' (" << water.density << " kg/m3):"
                    << " the water is not denser than " << sinking[m]
                    << " free bodies of material "
                    << world_->materials()[m].name.c_str() << " (density "
                    << world_->materials()[m].density << " kg/m3 in"
                    << " constant/iceDEMProperties): they do not float" << nl
                    << endl;
            }
        }
    }
    world_->addForceModel(std::make_shared<::iceDEM::Buoyancy>(water));
    water_ = true;
    waterLevel_ = water.level;

    addFloeDamping(properties_, *world_, water);
    addWind(properties_, *world_, water);

    if (!hasDrag)
    {
        return;
    }

    const dictionary& dd = properties_.subDict("drag");
    // The entries of type resolved may stay when the type is switched
    checkEntries
    (
        dd, "constant/iceDEMProperties", {"drag", "drag(type resolved)"},
        "drag"
    );

    dragType_ =
        selectName(dd, "type", wordList({"empirical", "resolved"}));

    ::iceDEM::DragSettings drag;
    drag.formCoefficient = nonNegative(dd, "formCoefficient", 1.0);
    drag.skinCoefficient = nonNegative(dd, "skinCoefficient", 0.004);
    drag.subdivision = labelInRange
    (
        dd, "subdivision", 0, ::iceDEM::DragSettings::maxSubdivision, 2
    );
    drag.bottomCosine =
        dd.getOrDefault<scalar>("bottomCosine", 0.70710678118654752);
    if (!(drag.bottomCosine > 0 && drag.bottomCosine <= 1))
    {
        FatalIOErrorInFunction(dd)
            << "Entry 'bottomCosine' is " << drag.bottomCosine
            << ": it must lie in (0, 1]" << nl
            << exit(FatalIOError);
    }
    if (dd.found("integration"))
    {
        drag.integration = ::iceDEM::dragIntegrationFromName
        (
            selectName(dd, "integration", wordList({"exact", "sampled"}))
        );
    }
    coreCall(dd, "drag", [&]{ ::iceDEM::checkDragSettings(drag); });

    std::shared_ptr<const ::iceDEM::FlowVelocity> flow;

    if (dragType_ == "empirical")
    {
        // 'U' (the field of type resolved) may stay in the dictionary and is
        // not used: switching the type is the only change between the two
        const vector current = dd.getOrDefault<vector>("current", Zero);
        flow = std::make_shared<::iceDEM::UniformCurrent>(toVec3(current));

        // A uniform current has no flow to return the drag to
        if (dd.found("twoWay", keyType::LITERAL))
        {
            ITstream& is = dd.lookup("twoWay", keyType::LITERAL);
            const token t(is);
            const bool isFalse =
                is.nRemainingTokens() == 0
             && (
                    (t.isBool() && !t.boolToken())
                 || (t.isWord() && Switch(t.wordToken(), true).valid()
                  && !Switch(t.wordToken(), true))
                );
            if (!isFalse)
            {
                FatalIOErrorInFunction(dd)
                    << "Entry 'twoWay': two-way coupling returns the drag to"
                    << " the resolved flow; it needs drag type resolved"
                    << " (iceFloatingFoam), not empirical (a uniform"
                    << " current). Allowed here: twoWay false, or no entry"
                    << nl << exit(FatalIOError);
            }
        }
    }
    else
    {
        if (!resolvedFlow)
        {
            FatalIOErrorInFunction(dd)
                << "Entry 'type': drag type resolved needs the velocity"
                << " field of a flow solver (iceFloatingFoam); this"
                << " application (iceDEMFoam, iceFloatingFoam -noFlow) has"
                << " none: use type empirical (uniform 'current')"
                << nl << exit(FatalIOError);
        }
        flow = resolvedFlow(dd);
        if (!flow)
        {
            FatalIOErrorInFunction(dd)
                << "drag type resolved: the solver made no velocity field"
                << nl << exit(FatalIOError);
        }
    }

    world_->addForceModel
    (
        coreCall
        (
            dd, "drag",
            [&]{ return std::make_shared<::iceDEM::Drag>(water, drag, flow); }
        )
    );
}


// ************************************************************************* //
