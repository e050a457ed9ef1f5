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
    floeImpulse_(Zero),
    fluidImpulse_(Zero),
    lostImpulse_(Zero),
    implicitImpulse_(Zero),
    interval_(0),
    taken_(true),
    flowStep_(0)
{
    Info<< "iceDEM: two-way drag coupling: the floes' drag returns to "
        << UName_ << " (fields iceDragSource,"
        << " iceDragCoefficient)" << nl;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

Foam::scalar Foam::iceDragReaction::sourceScale() const
{
    const scalar dt = mesh_.time().deltaTValue();
    return (interval_ > 0 && dt > 0) ? interval_/dt : 1;
}


Foam::tmp<Foam::fvVectorMatrix> Foam::iceDragReaction::source
(
    const volVectorField& U
) const
{
    // S - k (U - U*):  -k U implicit, the rest explicit
    tmp<fvVectorMatrix> tS(fvm::Sp(-coeff_, U));
    tS.ref() += explicitSource(U)();
    return tS;
}


Foam::tmp<Foam::volVectorField> Foam::iceDragReaction::explicitSource
(
    const volVectorField& U
) const
{
    // The impulse of interval_ over the flow step deltaT
    return tmp<volVectorField>::New
    (
        "iceDragExplicitSource",
        sourceScale()*source_ + coeff_*U.oldTime()
    );
}


void Foam::iceDragReaction::flowTakesSource()
{
    taken_ = true;
    flowStep_ = mesh_.time().deltaTValue();
}


void Foam::iceDragReaction::restartInterval(scalar T)
{
    interval_ = T;
    taken_ = false;
}


void Foam::iceDragReaction::correct()
{
    // What the implicit part gave the flow in the step just solved
    const volVectorField& U = mesh_.lookupObject<volVectorField>(UName_);
    const scalar dt =
        (taken_ && flowStep_ > 0) ? flowStep_ : mesh_.time().deltaTValue();
    implicitImpulse_ =
        -rhoW_*dt
       *gSum
        (
            coeff_.primitiveField()*mesh_.V()
           *(U.primitiveField() - U.oldTime().primitiveField())
        );
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

    // The flow has not taken the previous source (flowSolveInterval > 1):
    // its impulse is added, so the next flow step gets every interval's
    scalar total = T;
    if (!taken_ && interval_ > 0)
    {
        J += source_.primitiveField()*(rhoW_*interval_)*V;
        KT += coeff_.primitiveField()*(rhoW_*interval_)*V;
        total += interval_;
    }
    interval_ = total;
    taken_ = false;

    if (total > 0)
    {
        source_.primitiveFieldRef() = J/(rhoW_*V*total);
        coeff_.primitiveFieldRef() = KT/(rhoW_*V*total);
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
        << ", lost (no cell) " << lostImpulse_ << " N s" << nl
        << "    two-way drag: implicit part's impulse in the last flow step "
        << implicitImpulse_ << " N s" << nl;
    if (total != T)
    {
        Info<< "    two-way drag: the source holds the impulse of the last "
            << total << " s (the flow has not taken it yet), fluid total "
            << gSum(J) << " N s" << nl;
    }
}


// ************************************************************************* //
