/*---------------------------------------------------------------------------*\
    iceDEM tests: the load a floe pressed down by a fixed inclined plate puts
    on the plate (issue 15): the plate's contact force and its moment about a
    reference point are minus the floe's at every step (moment balance, to
    round-off) and equal the resultant of the individual contact forces and
    their moments at their points (to the damping of the residual velocity,
    1e-5), with the signs the geometry demands: the floe pushed down, the
    plate pushed up and downstream, bow-up pitch.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "testWorlds.H"
#include "hydro/Buoyancy.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace iceDEM;
using namespace iceDEM::test;

namespace
{

//- The push of a steady current on every free body, linearised: a
//  horizontal force k (U - v) towards the current's velocity U, and linear
//  damping of the vertical velocity and of the rotation (the water's
//  radiation damping). The floe drifts at U and, stopped, presses with k U.
//  The test is about the contact load, not about these forces.
class LinearCurrent
:
    public BodyForceModel
{
    Vec3 U_;
    double k_, cz_, cr_;

public:

    LinearCurrent(const Vec3& U, double k, double cz, double cr)
    :
        U_(U), k_(k), cz_(cz), cr_(cr)
    {}

    const char* name() const override { return "linearCurrent"; }

    void addForces
    (
        const World& world,
        int begin,
        int end,
        Vec3* force,
        Vec3* torque
    ) const override
    {
        for (int i = begin; i < end; ++i)
        {
            const Body& b = world.bodies()[i];
            if (b.motion == BodyMotion::free)
            {
                const Vec3 dv = U_ - b.v;
                force[i] += Vec3(k_*dv.x(), k_*dv.y(), -cz_*b.v.z());
                torque[i] -= cr_*b.omega();
            }
        }
    }
};

//- Moment about ref of the contact forces on body b, summed from the list of
//  contacts (each force at its contact point); F: their resultant
void contactResultant
(
    const World& w,
    int b,
    const Vec3& ref,
    Vec3& F,
    Vec3& M
)
{
    F.setZero();
    M.setZero();
    for (const World::ContactInfo& c : w.contacts())
    {
        Vec3 f;
        if (c.j == b)
        {
            f = c.forceOnJ;
        }
        else if (c.i == b)
        {
            f = -c.forceOnJ;
        }
        else
        {
            continue;
        }
        F += f;
        M += (c.point - ref).cross(f);
    }
}

} // anonymous namespace


// The plate slopes like the waterline of a downward-breaking cone (the
// Kulluk: its hull widens upwards): it leans upstream, so a floe drifting
// along +x meets a surface whose outward normal points upstream and down,
// n = (-sin a, 0, -cos a), and is pushed down under it. The reference point
// is the structure's centre, 5 m downstream of the plate at the waterline.
TEST(StructureLoad, floePressedDownByInclinedPlate)
{
    const double g = 9.81;
    const double rhoIce = 900, rhoWater = 1025;
    const double a = M_PI/4;                    // plate 45 deg from vertical
    const Vec3 n(-std::sin(a), 0, -std::cos(a));

    WorldSettings s;
    s.timeStep = 2e-4;
    s.gravity = Vec3(0, 0, -g);
    World w(s);
    const int ice = w.addMaterial(test::ice(1e9, rhoIce));
    const int steel = w.addMaterial(test::steel());
    w.setPairProperties(ice, steel, PairProperties{0.1, 0.3});
    w.setPairProperties(ice, ice, PairProperties{0.2, 0.3});

    // Floe 2 m x 2 m x 0.5 m at its floating draft, 0.3 m upstream of the
    // plate, drifting onto it with the current at 0.2 m/s; stopped, the
    // current presses it with a twentieth of its weight
    const double r = 0.05;
    const double h = 0.5;
    const std::vector<Vec2> square{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    const int floeShape =
        w.addShape(DilatedShape(ConvexPolyhedron::prism(square, -h/2, h), r));
    const double draft = rhoIce/rhoWater*h;
    const int floe = w.addBody
    (
        floeShape, ice, Vec3(-1.4, 0, h/2 - draft), Quat::Identity(),
        Vec3(0.2, 0, 0)
    );

    // Plate 4 m x 4 m x 0.2 m, its outer (dilated) face on the plane through
    // the origin with normal n
    const double t = 0.1;
    const int plateShape =
        w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3(2, 2, t)), r));
    const Vec3 plateCentre = -(t + r)*n;
    const int plate = w.addBody
    (
        plateShape, steel, plateCentre,
        rotationFromTo(Vec3::UnitZ(), -n), Vec3::Zero(), Vec3::Zero(),
        BodyMotion::fixed
    );
    const Vec3 ref(5, 0, 0);

    const double floeWeight = w.bodies()[floe].mass*g;
    w.addForceModel(std::make_shared<Buoyancy>(WaterSettings{rhoWater, 0}));
    // Heave: stiffness rho_w g A = 4.0e4 N/m, mass 1.8e3 kg: damped at half
    // critical (8.5e3 N s/m); rotation damped in a few seconds
    const double push = 0.05*floeWeight;
    const double U = 0.2;
    w.addForceModel
    (
        std::make_shared<LinearCurrent>(Vec3(U, 0, 0), push/U, 8.5e3, 3e3)
    );
    w.initialise();

    // 8 s: contact after about 1.5 s, then the floe pressed down the plate,
    // settled after about 5 s
    double maxForce = 0;
    double maxErrF = 0, maxErrM = 0, maxErrNewton = 0;
    int contactSteps = 0;
    Vec3 sumF = Vec3::Zero(), sumM = Vec3::Zero(), sumFloeF = Vec3::Zero();
    double sumDepth = 0;
    int averaged = 0;
    const int steps = int(std::lround(8.0/s.timeStep));
    for (int k = 0; k < steps; ++k)
    {
        w.step();
        const ContactLoad Lp = w.contactLoad(plate);
        const ContactLoad Lf = w.contactLoad(floe);

        // The structure's load about the reference point (as the coupling
        // sums it: force, torque about the centroid moved to ref)
        const Vec3 Fp = Lp.force;
        const Vec3 Mp = Lp.torque + (w.bodies()[plate].x - ref).cross(Fp);

        // ... equals the resultant of the contact forces and their moments
        Vec3 Fc, Mc;
        contactResultant(w, plate, ref, Fc, Mc);

        // ... and is equal and opposite to the floe's (moment balance about
        // the same point)
        const Vec3 Mf = Lf.torque + (w.bodies()[floe].x - ref).cross(Lf.force);

        const double scale = std::max(Fp.norm(), 1.0);
        maxForce = std::max(maxForce, Fp.norm());
        if (w.time() > 5.0)
        {
            maxErrF = std::max(maxErrF, (Fp - Fc).norm()/scale);
            maxErrM = std::max(maxErrM, (Mp - Mc).norm()/(scale*ref.norm()));
        }
        maxErrNewton = std::max
        (
            maxErrNewton,
            std::max((Fp + Lf.force).norm()/scale, (Mp + Mf).norm()/(scale*ref.norm()))
        );

        if (w.contactCount() > 0)
        {
            ++contactSteps;
        }
        if (w.time() > 5.0)
        {
            sumF += Fp;
            sumM += Mp;
            sumFloeF += Lf.force;
            sumDepth += w.bodies()[floe].x.z() - (h/2 - draft);
            ++averaged;
        }
    }
    ASSERT_GT(contactSteps, 1000) << "the floe never reached the plate";
    ASSERT_GT(averaged, 0);
    ASSERT_GT(w.contactCount(), 0) << "the floe is not pressed on the plate at the end";

    // Moment balance at every step, to round-off: the plate's force and
    // moment about the reference point are minus the floe's (each contact
    // force acts on both at the same point)
    EXPECT_LT(maxErrNewton, 1e-12) << "plate load vs minus the floe's load";

    // The plate's load equals the resultant of the individual contact
    // forces, each at its contact point (World::contacts), once the floe is
    // settled: contacts() recomputes every force from the stored contact
    // state with the velocities at the end of the step, the step applied
    // them with those of its force evaluation, so the two differ by the
    // contact damping of the floe's residual velocity (measured 1.4e-6 of
    // the force)
    EXPECT_LT(maxErrF, 1e-5) << "plate force vs resultant of the contacts";
    EXPECT_LT(maxErrM, 1e-5) << "plate moment vs moments of the contacts";

    const Vec3 F = sumF/averaged;
    const Vec3 M = sumM/averaged;
    const Vec3 Ff = sumFloeF/averaged;
    const double depth = sumDepth/averaged;

    // The floe is pressed down: the plate pushes it downwards and upstream,
    // and it floats deeper than its free draft
    EXPECT_LT(Ff.z(), 0.0);
    EXPECT_LT(Ff.x(), 0.0);
    EXPECT_LT(depth, 0.0);

    // The plate takes the reaction: downstream and upwards (the buoyancy of
    // the floe pushed under it), about equal parts at 45 deg plus friction
    // (mu 0.1, sliding down the plate: tilts the force towards the plate's
    // normal by at most atan(0.1))
    EXPECT_GT(F.x(), 0.0);
    EXPECT_GT(F.z(), 0.0);
    const double angle = std::atan2(F.z(), F.x());
    EXPECT_NEAR(angle, a, std::atan(0.1) + 1e-3);

    // Quasi-static force balance of the floe on the time average: the
    // horizontal push is carried by the plate
    EXPECT_NEAR(F.x(), push, 0.05*push);

    // Pitch: the upward force acts 5 m upstream of the reference point and
    // lifts that side: a positive moment about +y (the bow up), larger than
    // the horizontal force's moment from its point below the waterline
    EXPECT_GT(M.y(), 0.0);
    EXPECT_NEAR(M.x(), 0.0, 1e-6*F.norm());
    EXPECT_NEAR(M.z(), 0.0, 1e-6*F.norm()*ref.norm());

    std::printf
    (
        "plate load (mean, t > 5 s): F = (%.1f, %.1f, %.1f) N, M about "
        "(5, 0, 0) = (%.1f, %.1f, %.1f) N m; floe %.3f m below its draft;"
        " max |F| %.1f N; vs the contacts: force %.1e, moment %.1e; vs minus the floe's %.1e\n",
        F.x(), F.y(), F.z(), M.x(), M.y(), M.z(), depth, maxForce, maxErrF,
        maxErrM, maxErrNewton
    );
}


// ************************************************************************* //
