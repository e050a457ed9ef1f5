/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

\*---------------------------------------------------------------------------*/

#include "hullMotionLog.H"
#include "sixDoFRigidBodyMotion.H"
#include "quaternion.H"
#include "OSspecific.H"
#include "mathematicalConstants.H"
#include "postProcessingFile.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

const Foam::FixedList<Foam::direction, 2> Foam::hullMotionLog::components_
({
    vector::X,
    vector::Z
});

const Foam::FixedList<Foam::word, 2> Foam::hullMotionLog::names_
({
    "surge",
    "heave"
});


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::hullMotionLog::hullMotionLog(const Time& runTime)
:
    runTime_(runTime),
    file_(),
    v0_(Zero),
    t0_(0),
    first_(true),
    lastMax_(-1),
    vPeak_(Zero)
{
    if (Pstream::master())
    {
        const fileName dir
        (
            runTime.globalPath()/"postProcessing"/"hullMotion"
           /runTime.timeName(runTime.startTime().value())
        );
        mkDir(dir);
        file_.reset(new OFstream(newOutputFile(runTime, dir, "motion.dat")));
        file_().precision(10);
        file_()
            << "# Structure motion (sixDoFRigidBodyMotion)" << nl
            << "# time x y z roll pitch yaw[deg] vx vy vz wx wy wz" << endl;
    }
}


// * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * * //

void Foam::hullMotionLog::write(const sixDoFRigidBodyMotion& motion)
{
    const scalar t = runTime_.value();
    const point x = motion.centreOfMass();
    const vector v = motion.v();
    const vector w = motion.omega();

    // Orientation (rotation from the reference frame, Q = I), roll-pitch-yaw
    const quaternion q(motion.orientation());
    const vector rpy = (180.0/constant::mathematical::pi)*q.eulerAngles(quaternion::XYZ);

    if (file_.valid())
    {
        file_()
            << t << ' '
            << x.x() << ' ' << x.y() << ' ' << x.z() << ' '
            << rpy.x() << ' ' << rpy.y() << ' ' << rpy.z() << ' '
            << v.x() << ' ' << v.y() << ' ' << v.z() << ' '
            << w.x() << ' ' << w.y() << ' ' << w.z() << endl;
    }

    forAll(components_, ci)
    {
        const scalar vc = v[components_[ci]];
        vPeak_[ci] = max(vPeak_[ci], mag(vc));
        if (!first_ && v0_[ci] > 0 && vc <= 0 && vPeak_[ci] > vSmall_)
        {
            // Velocity crosses zero from above: a maximum
            const scalar tMax = t0_ + (t - t0_)*v0_[ci]/(v0_[ci] - vc);
            Info<< "hullMotion: " << names_[ci] << " maximum at t = " << tMax;
            if (lastMax_[ci] >= 0)
            {
                Info<< ", " << names_[ci] << " period "
                    << tMax - lastMax_[ci] << " s";
            }
            Info<< endl;
            lastMax_[ci] = tMax;
            vPeak_[ci] = 0;
        }
        v0_[ci] = vc;
    }
    t0_ = t;
    first_ = false;
}


// ************************************************************************* //
