/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "iceDragReaction.H"
#include "resolvedFlowVelocity.H"

#include "fvMatrices.H"
#include "fvmSup.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::iceDragReaction::iceDragReaction
(
    const fvMesh& mesh,
    resolvedFlowVelocity& flow,
    scalar waterDensity
)
:
    mesh_(mesh),
    flow_(flow),
    rhoW_(waterDensity),
    UName_(flow.UName()),
    source_
    (
        IOobject
        (
            "iceDragSource",
            mesh.time().timeName(),
            mesh,
            IOobject::READ_IF_PRESENT,
            IOobject::AUTO_WRITE
        ),
        mesh,
        dimensionedVector(dimVelocity/dimTime, Zero),
        calculatedFvPatchField<vector>::typeName
    ),
    coeff_
    (
        IOobject
        (
            "iceDragCoefficient",
            mesh.time().timeName(),
            mesh,
            IOobject::READ_IF_PRESENT,
            IOobject::AUTO_WRITE
        ),
        mesh,
        dimensionedScalar(dimless/dimTime, Zero),
        calculatedFvPatchField<scalar>::typeName
    ),
    correction_
    (
        IOobject
        (
            "iceDragCorrection",
            mesh.time().timeName(),
            mesh,
            IOobject::READ_IF_PRESENT,
            IOobject::AUTO_WRITE
        ),
        mesh,
        dimensionedVector(dimVelocity/dimTime, Zero),
        calculatedFvPatchField<vector>::typeName
    ),
    floeImpulse_(Zero),
    fluidImpulse_(Zero),
    lostImpulse_(Zero)
{
    Info<< "iceDEM: two-way drag coupling: the floes' drag returns to "
        << UName_ << " (fields iceDragSource, iceDragCoefficient,"
        << " iceDragCorrection)" << nl;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

Foam::tmp<Foam::fvVectorMatrix> Foam::iceDragReaction::source
(
    const volVectorField& U
) const
{
    // S - k (U - U*) + C:  -k U implicit, the rest explicit
    tmp<fvVectorMatrix> tS(fvm::Sp(-coeff_, U));
    tS.ref() +=
        source_() + correction_() + coeff_()*U.oldTime()();
    return tS;
}


void Foam::iceDragReaction::correct()
{
    const volVectorField& U = mesh_.lookupObject<volVectorField>(UName_);
    correction_.primitiveFieldRef() =
        coeff_.primitiveField()
       *(U.primitiveField() - U.oldTime().primitiveField());
    correction_.correctBoundaryConditions();
}


void Foam::iceDragReaction::update(scalar T)
{
    vectorField J(mesh_.nCells(), Zero);
    scalarField KT(mesh_.nCells(), Zero);
    ::iceDEM::Vec3 lost;
    const ::iceDEM::Vec3 floe = flow_.deposit(J, KT, lost);

    floeImpulse_ = vector(floe.x(), floe.y(), floe.z());
    lostImpulse_ = vector(lost.x(), lost.y(), lost.z());
    fluidImpulse_ = gSum(J);

    const scalarField& V = mesh_.V();
    if (T > 0)
    {
        source_.primitiveFieldRef() = J/(rhoW_*V*T);
        coeff_.primitiveFieldRef() = KT/(rhoW_*V*T);
    }
    else
    {
        source_.primitiveFieldRef() = Zero;
        coeff_.primitiveFieldRef() = Zero;
    }
    source_.correctBoundaryConditions();
    coeff_.correctBoundaryConditions();

    const scalar scale = max(mag(floeImpulse_), VSMALL);
    Info<< "    two-way drag: floes' drag impulse " << floeImpulse_
        << " N s, fluid source impulse " << fluidImpulse_
        << " N s, relative imbalance "
        << mag(fluidImpulse_ + floeImpulse_ - lostImpulse_)/scale
        << ", lost (no cell) " << lostImpulse_ << " N s" << nl;
}


// ************************************************************************* //
