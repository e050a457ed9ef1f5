/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

\*---------------------------------------------------------------------------*/

#include "spreadMooring.H"
#include "motionConstraints.H"
#include "verticalModes.H"
#include "timeRegistry.H"
#include "addToRunTimeSelectionTable.H"
#include "caseEntries.H"
#include "sixDoFRigidBodyMotion.H"
#include "mathematicalConstants.H"
#include "OSspecific.H"
#include "unitConversion.H"
#include "postProcessingFile.H"

#include <cmath>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace sixDoFRigidBodyMotionRestraints
{
    defineTypeNameAndDebug(spreadMooring, 0);

    addToRunTimeSelectionTable
    (
        sixDoFRigidBodyMotionRestraint,
        spreadMooring,
        dictionary
    );
}
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::readLine
(
    const dictionary& dict,
    const label i,
    const point& anchor,
    const point& fairlead
)
{
    const scalar L = mag(fairlead - anchor);
    if (!(L > 0))
    {
        FatalIOErrorInFunction(dict)
            << "Mooring line " << i << " of restraint " << name_ << " in "
            << dict.name() << ": anchor and fairlead coincide (" << anchor
            << ")." << nl << exit(FatalIOError);
    }

    const scalar k = dict.get<scalar>("stiffness");
    if (!(k > 0))
    {
        FatalIOErrorInFunction(dict)
            << "Mooring line " << i << " of restraint " << name_ << " in "
            << dict.name() << ": 'stiffness " << k << "' must be positive."
            << nl << exit(FatalIOError);
    }

    const scalar c = dict.lookupOrDefault<scalar>("damping", 0);
    if (c < 0)
    {
        FatalIOErrorInFunction(dict)
            << "Mooring line " << i << " of restraint " << name_ << " in "
            << dict.name() << ": 'damping " << c << "' must not be negative."
            << nl << exit(FatalIOError);
    }

    const bool hasRest = dict.found("restLength");
    const bool hasPre = dict.found("pretension");
    if (hasRest && hasPre)
    {
        FatalIOErrorInFunction(dict)
            << "Mooring line " << i << " of restraint " << name_ << " in "
            << dict.name() << " has both 'restLength' and 'pretension':"
            << " give exactly one." << nl << exit(FatalIOError);
    }
    if (!hasRest && !hasPre)
    {
        FatalIOErrorInFunction(dict)
            << "Mooring line " << i << " of restraint " << name_ << " in "
            << dict.name() << " has no length: give 'restLength' [m] or"
            << " 'pretension' [N]." << nl << exit(FatalIOError);
    }

    scalar L0 = 0;
    if (hasRest)
    {
        L0 = dict.get<scalar>("restLength");
        if (!(L0 > 0))
        {
            FatalIOErrorInFunction(dict)
                << "Mooring line " << i << " of restraint " << name_ << " in "
                << dict.name() << ": 'restLength " << L0
                << "' must be positive." << nl << exit(FatalIOError);
        }
    }
    else
    {
        const scalar T0 = dict.get<scalar>("pretension");
        L0 = L - T0/k;
        if (T0 < 0 || !(L0 > 0))
        {
            FatalIOErrorInFunction(dict)
                << "Mooring line " << i << " of restraint " << name_ << " in "
                << dict.name() << ": 'pretension " << T0 << "' must be >= 0"
                << " and less than stiffness x length (" << k*L << ")."
                << nl << exit(FatalIOError);
        }
    }

    anchors_[i] = anchor;
    fairleads_[i] = fairlead;
    stiffness_[i] = k;
    restLength_[i] = L0;
    damping_[i] = c;
}


void Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::open
(
    const Time& runTime
) const
{
    const fileName dir
    (
        runTime.globalPath()/"postProcessing"/name_
       /runTime.timeName(runTime.startTime().value())
    );
    mkDir(dir);

    // A restraint re-read during the run must not truncate the file
    fileName file(dir/"tensions.dat");
    if (isFile(file))
    {
        file = dir/("tensions_" + runTime.timeName() + ".dat");
    }
    else
    {
        warnRowsBeyondStart(runTime, dir, "tensions.dat");
    }

    file_.reset(new OFstream(file));
    OFstream& os = file_();
    os.precision(10);
    os  << "# Mooring line tensions [N] of restraint " << name_ << nl
        << "# line: anchor fairlead(initial pose) stiffness restLength" << nl;
    forAll(anchors_, i)
    {
        os  << "#   " << i << ' ' << anchors_[i] << ' ' << fairleads_[i] << ' '
            << stiffness_[i] << ' ' << restLength_[i] << nl;
    }
    os  << "# time";
    forAll(anchors_, i)
    {
        os  << " T" << i;
    }
    os  << endl;
}


void Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::flush() const
{
    if (pendingIndex_ < 0 || !file_.valid())
    {
        return;
    }
    OFstream& os = file_();
    os  << pendingTime_;
    forAll(pending_, i)
    {
        os  << ' ' << pending_[i];
    }
    os  << endl;
    pendingIndex_ = -1;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::spreadMooring
(
    const word& name,
    const dictionary& sDoFRBMRDict
)
:
    sixDoFRigidBodyMotionRestraint(name, sDoFRBMRDict),
    anchors_(),
    fairleads_(),
    stiffness_(),
    restLength_(),
    damping_(),
    file_(),
    pending_(),
    pendingTime_(0),
    pendingIndex_(-1),
    reported_(false)
{
    read(sDoFRBMRDict);
}


Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::spreadMooring
(
    const spreadMooring& sm
)
:
    sixDoFRigidBodyMotionRestraint(sm),
    anchors_(sm.anchors_),
    fairleads_(sm.fairleads_),
    stiffness_(sm.stiffness_),
    restLength_(sm.restLength_),
    damping_(sm.damping_),
    file_(),
    pending_(),
    pendingTime_(0),
    pendingIndex_(-1),
    reported_(sm.reported_)
{}


Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::~spreadMooring()
{
    flush();
}


// * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * * //

Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::lineState
Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::line
(
    const sixDoFRigidBodyMotion& motion,
    const label i
) const
{
    lineState s;
    s.fairlead = motion.transform(fairleads_[i]);
    s.r = s.fairlead - anchors_[i];
    s.length = mag(s.r);
    s.direction = s.r/(s.length + VSMALL);
    s.elasticTension = stiffness_[i]*(s.length - restLength_[i]);
    return s;
}


Foam::tmp<Foam::scalarField>
Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::tensions
(
    const sixDoFRigidBodyMotion& motion
) const
{
    tmp<scalarField> tT(new scalarField(size(), Zero));
    scalarField& T = tT.ref();

    forAll(anchors_, i)
    {
        const lineState s = line(motion, i);
        T[i] = max
        (
            scalar(0),
            s.elasticTension
          + damping_[i]*(s.direction & motion.velocity(s.fairlead))
        );
    }
    return tT;
}


Foam::tensor
Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::lineStiffness
(
    const lineState& s,
    const label i,
    const bool everyLineTaut
) const
{
    if (!(s.elasticTension > 0 || everyLineTaut))
    {
        return Zero;
    }
    const vector& e = s.direction;
    return
        stiffness_[i]*sqr(e)
      + (max(s.elasticTension, scalar(0))/s.length)*(tensor::I - sqr(e));
}


Foam::tensor
Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::stiffnessMatrix
(
    const sixDoFRigidBodyMotion& motion,
    const bool everyLineTaut
) const
{
    tensor K(Zero);
    forAll(anchors_, i)
    {
        K += lineStiffness(line(motion, i), i, everyLineTaut);
    }
    return K;
}


Foam::tensor
Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::dampingMatrix
(
    const sixDoFRigidBodyMotion& motion
) const
{
    tensor D(Zero);
    forAll(anchors_, i)
    {
        D += damping_[i]*tensor(sqr(line(motion, i).direction));
    }
    return D;
}


void Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::verticalModes
(
    const sixDoFRigidBodyMotion& motion,
    vector& stiffness,
    vector& damping
) const
{
    const point G = motion.centreOfMass();
    const vector ez(0, 0, 1);
    const FixedList<vector, 2> axes({vector(1, 0, 0), vector(0, 1, 0)});
    stiffness = Zero;
    damping = Zero;
    forAll(anchors_, i)
    {
        const lineState s = line(motion, i);
        const tensor K = lineStiffness(s, i, true);
        const vector& e = s.direction;
        const vector F = -max(s.elasticTension, scalar(0))*e;
        const vector arm = s.fairlead - G;
        stiffness.x() += ez & K & ez;
        damping.x() += damping_[i]*sqr(e & ez);
        for (label k = 0; k < 2; ++k)
        {
            // The fairlead's displacement by a unit rotation about a, and
            // the moment of the tension turning with the hull
            const vector& a = axes[k];
            const vector df = a ^ arm;
            stiffness[k + 1] += (df & K & df) + (arm & F) - (a & arm)*(a & F);
            damping[k + 1] += damping_[i]*sqr(e & df);
        }
    }
}


void Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::checkPeriodResolved
(
    const sixDoFRigidBodyMotion& motion,
    bool report
) const
{
    // The stiffness with every line taut (a line slack now, on the side the
    // structure moved towards, pulls again when it swings back: the motion
    // meets this stiffness), in the free horizontal directions (the
    // constraints' projection; heave is left out: it has its own added
    // mass and hydrostatics); its largest eigenvalue over the mass without
    // added mass (the fluid's would lower the frequency): a bound from above.
    // The same for the lines' damping, explicit at the half-step velocity
    const tensor C(translationConstraints(motion));
    const auto largestHorizontal = [&C](const tensor& T)
    {
        const tensor Tf(C & T & C);
        const scalar a = Tf.xx(), b = 0.5*(Tf.xy() + Tf.yx()), d = Tf.yy();
        return 0.5*(a + d) + Foam::sqrt(sqr(0.5*(a - d)) + sqr(b));
    };
    const scalar kMax = largestHorizontal(stiffnessMatrix(motion, true));
    const scalar dMax = largestHorizontal(dampingMatrix(motion));
    if (!(kMax > 0) && !(dMax > 0))
    {
        return;
    }
    const scalar M = motion.mass();
    const scalar omega = Foam::sqrt(max(kMax, scalar(0))/M);
    const scalar b = max(dMax, scalar(0))/M;
    const scalar dt = motion.time().deltaTValue();
    const scalar period =
        omega > 0 ? constant::mathematical::twoPi/omega : GREAT;
    if (report)
    {
        Info<< "    shortest horizontal period 2 pi sqrt(M/K) = " << period
            << " s: " << period/dt << " structure steps (deltaT " << dt
            << " s); the lines' damping rate D/M " << b << " 1/s" << endl;
    }

    // The structure's integrators (OpenFOAM's symplectic, rigidLidSymplectic)
    // are stable for (omega deltaT)^2 + 2 b deltaT < 4 only (omega deltaT < 2
    // without damping; verticalModes.H): beyond, the motion grows without
    // bound (a floating point exception after some steps)
    const scalar bound = sqr(omega*dt) + 2*b*dt;
    if (bound >= 4)
    {
        const scalar dtMax = 4/(b + std::hypot(b, 2*omega));
        FatalIOErrorInFunction(coeffDict())
            << "Entry 'stiffness' of restraint " << name_ << " in "
            << coeffDict().name() << ": the lines' horizontal stiffness "
            << kMax << " N/m (period 2 pi sqrt(M/K) = " << period << " s),"
            << " their damping " << dMax << " N s/m (entry 'damping') and"
            << " the structure's mass " << M << " kg give (omega deltaT)^2"
            << " + 2 (D/M) deltaT = " << bound << " at the structure's step"
            << " deltaT = " << dt << " s (system/controlDict) and its pose"
            << " at time " << motion.time().timeName() << ": the motion is"
            << " stable below 4 only (deltaT < period/pi without damping)."
            << " Reduce deltaT below " << dtMax << " s, or the stiffness"
            << " or the damping." << nl
            << exit(FatalIOError);
    }
}


void Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::restrain
(
    const sixDoFRigidBodyMotion& motion,
    vector& restraintPosition,
    vector& restraintForce,
    vector& restraintMoment
) const
{
    const Time& runTime = motion.time();

    const bool first = !reported_;
    if (first)
    {
        reported_ = true;
        const tensor K = stiffnessMatrix(motion);
        Info<< "Restraint " << name_ << " (spreadMooring): " << size()
            << " lines, linearised stiffness [N/m] Kxx " << K.xx()
            << " Kyy " << K.yy() << " Kzz " << K.zz() << nl
            << "    surge period without added mass 2 pi sqrt(M/Kxx) = "
            << constant::mathematical::twoPi
              *Foam::sqrt(motion.mass()/max(K.xx(), VSMALL))
            << " s" << endl;
    }
    // At every evaluation, at the pose it is made at: the lines stiffen as
    // the structure drifts, and a check at the start only let a run go on
    // that its own restart from a drifted pose refused
    checkPeriodResolved(motion, first);
    {
        vector stiffness, damping;
        verticalModes(motion, stiffness, damping);
        addVerticalModes(runTime, name_, stiffness, damping);
    }

    const scalarField T(tensions(motion));

    const point& CofR = motion.centreOfRotation();
    restraintPosition = CofR;
    restraintForce = Zero;
    restraintMoment = Zero;

    forAll(anchors_, i)
    {
        const lineState s = line(motion, i);
        const vector F = -T[i]*s.r/(s.length + VSMALL);
        restraintForce += F;
        restraintMoment += (s.fairlead - CofR) ^ F;
    }

    // The tensions on the Time database for function objects
    // (iceLoadStatistics): an unwritten scalar field '<restraint>:tensions'
    storeOnTime(runTime, name_ + ":tensions", T);

    // Output: one row per time step, the last evaluation of the step
    if (!file_.valid())
    {
        open(runTime);
    }
    if (pendingIndex_ >= 0 && pendingIndex_ != runTime.timeIndex())
    {
        flush();
    }
    pending_ = T;
    pendingTime_ = runTime.value();
    pendingIndex_ = runTime.timeIndex();

    if (motion.report())
    {
        Info<< " mooring force " << restraintForce
            << " moment " << restraintMoment
            << " max tension " << max(T) << endl;
    }
}


bool Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::read
(
    const dictionary& sDoFRBMRDict
)
{
    sixDoFRigidBodyMotionRestraint::read(sDoFRBMRDict);
    iceDEMChecks::checkEntries
    (
        sDoFRBMRCoeffs_, "constant/dynamicMeshDict",
        {"sixDoFRigidBodyMotionCoeffs/restraints/*(sixDoFRigidBodyMotionRestraint spreadMooring)"},
        "restraint " + name_
    );

    const bool hasLines = sDoFRBMRDict.found("lines");
    const bool hasSpread = sDoFRBMRDict.found("spread");
    if (hasLines == hasSpread)
    {
        FatalIOErrorInFunction(sDoFRBMRDict)
            << "Restraint " << name_ << " (spreadMooring) in "
            << sDoFRBMRDict.name() << " needs exactly one of 'lines'"
            << " (a list of line dictionaries) or 'spread' (equally spaced"
            << " lines)." << nl << exit(FatalIOError);
    }

    if (hasLines)
    {
        const PtrList<dictionary> lines
        (
            sDoFRBMRDict.lookup("lines")
        );
        if (lines.empty())
        {
            FatalIOErrorInFunction(sDoFRBMRDict)
                << "Restraint " << name_ << " in " << sDoFRBMRDict.name()
                << ": 'lines' is empty." << nl << exit(FatalIOError);
        }
        const label n = lines.size();
        anchors_.setSize(n);
        fairleads_.setSize(n);
        stiffness_.setSize(n);
        restLength_.setSize(n);
        damping_.setSize(n);
        forAll(lines, i)
        {
            dictionary lineDict(lines[i]);
            lineDict.name() = sDoFRBMRDict.name() + ".lines." + Foam::name(i);
            iceDEMChecks::checkEntries
            (
                lineDict, "constant/dynamicMeshDict",
                {"spreadMooring line"},
                "line " + Foam::name(i) + " of restraint " + name_
            );
            readLine
            (
                lineDict,
                i,
                lineDict.get<point>("anchor"),
                lineDict.get<point>("fairlead")
            );
        }
    }
    else
    {
        const dictionary& dict = sDoFRBMRDict.subDict("spread");
        iceDEMChecks::checkEntries
        (
            dict, "constant/dynamicMeshDict",
            {"sixDoFRigidBodyMotionCoeffs/restraints/*(sixDoFRigidBodyMotionRestraint spreadMooring)/spread"},
            "spread of restraint " + name_
        );
        const label n = dict.get<label>("nLines");
        if (n < 1)
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'nLines " << n << "' in " << dict.name()
                << " must be at least 1." << nl << exit(FatalIOError);
        }
        const point centre(dict.lookupOrDefault<point>("centre", Zero));
        const scalar phi0 =
            degToRad(dict.lookupOrDefault<scalar>("startAngle", 0));
        const scalar Ra = dict.get<scalar>("anchorRadius");
        const scalar za = dict.get<scalar>("anchorZ");
        const scalar Rf = dict.get<scalar>("fairleadRadius");
        const scalar zf = dict.get<scalar>("fairleadZ");
        if (!(Ra > 0) || Rf < 0)
        {
            FatalIOErrorInFunction(dict)
                << "In " << dict.name() << ": 'anchorRadius' must be"
                << " positive and 'fairleadRadius' not negative." << nl
                << exit(FatalIOError);
        }

        anchors_.setSize(n);
        fairleads_.setSize(n);
        stiffness_.setSize(n);
        restLength_.setSize(n);
        damping_.setSize(n);
        for (label i = 0; i < n; ++i)
        {
            const scalar phi =
                phi0 + constant::mathematical::twoPi*scalar(i)/scalar(n);
            const vector er(Foam::cos(phi), Foam::sin(phi), 0);
            readLine
            (
                dict,
                i,
                point(centre.x(), centre.y(), za) + Ra*er,
                point(centre.x(), centre.y(), zf) + Rf*er
            );
        }
    }

    pending_.setSize(anchors_.size(), Zero);
    return true;
}


void Foam::sixDoFRigidBodyMotionRestraints::spreadMooring::write
(
    Ostream& os
) const
{
    os.writeKeyword("lines") << nl
        << indent << token::BEGIN_LIST << incrIndent << nl;
    forAll(anchors_, i)
    {
        os  << indent << token::BEGIN_BLOCK << incrIndent << nl;
        os.writeEntry("anchor", anchors_[i]);
        os.writeEntry("fairlead", fairleads_[i]);
        os.writeEntry("stiffness", stiffness_[i]);
        os.writeEntry("restLength", restLength_[i]);
        os.writeEntry("damping", damping_[i]);
        os  << decrIndent << indent << token::END_BLOCK << nl;
    }
    os  << decrIndent << indent << token::END_LIST << token::END_STATEMENT
        << nl;
}


// ************************************************************************* //
