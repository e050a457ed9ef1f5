/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    The multi-rate step (WorldSettings::bodyForceInterval k, WorldStep.C):
    body forces every k-th step as impulses, contacts every step. Against
    what it cannot fake:
      - heave of a wall-sided floe at the DEM step of the study (0.01 s):
        the period's error is that of velocity Verlet with the outer step
        H = k dt, -(omega H)^2/24 (it scales as (k dt/T)^2), the draft exact;
      - roll period, drag decay, spin-down and the heave decay of floe
        damping within the tolerances of their single-rate tests at k = 4
        and 8;
      - contacts every step: a dry elastic impact in a world with a
        (zero) body-force model is the single-rate one bit for bit;
      - restart in the middle of an outer step = uninterrupted (the phase
        is part of the state; without it the run differs);
      - 1 thread = 2 threads;
      - the drive reported for a force balance (modelForceOnFreeBodies) is
        the impulse the kicks applied: the floes' momentum change equals
        its trapezoidal sum to rounding.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "hydro/Buoyancy.H"
#include "hydro/Drag.H"
#include "hydro/FloeDamping.H"
#include "hydro/FlowVelocity.H"
#include "hydro/Wind.H"
#include "hydroFixtures.H"
#include "testWorlds.H"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

using namespace iceDEM;

namespace
{

using namespace test::hydro;

const WaterSettings water{rhoWater, 0};

//- A world of box floes (hydroFixtures' boxFloe, soft ice) with the
//  multi-rate interval k
std::unique_ptr<World> boxWorld
(
    double dt,
    int k,
    const Vec3& gravity = Vec3(0, 0, -g)
)
{
    WorldSettings ws;
    ws.timeStep = dt;
    ws.gravity = gravity;
    ws.bodyForceInterval = k;
    auto w = std::make_unique<World>(ws);
    w->addMaterial(Material{"ice", rhoIce, 1e9, 0.33});
    return w;
}

int addBox
(
    World& w,
    double Lx, double Ly, double h, double zb,
    const Quat& q = Quat::Identity(),
    const Vec3& v = Vec3::Zero(),
    const Vec3& omega = Vec3::Zero()
)
{
    const int shape = w.addShape(boxFloe(Lx, Ly, h, zb));
    return w.addBody(shape, 0, Vec3::Zero(), q, v, omega);
}


//- Heave of a 4 x 4 x h floe released at rest at 90 % of its draft, over
//  about n periods: measured period and the draft from the mean position
void heave(int k, double dt, double h, int n, double& period, double& draft)
{
    const double d = rhoIce/rhoWater*h;
    auto w = boxWorld(dt, k);
    addBox(*w, 4, 4, h, -0.9*d);
    w->addForceModel(std::make_shared<Buoyancy>(water));
    const double zEq = 0.5*h - d;
    const double T = 2*M_PI*std::sqrt(d/g);
    std::vector<double> t, z;
    double zMin = 1e9, zMax = -1e9;
    while (w->time() < (n + 0.5)*T)
    {
        w->step();
        t.push_back(w->time());
        z.push_back(w->bodies()[0].x.z() - zEq);
        zMin = std::min(zMin, w->bodies()[0].x.z());
        zMax = std::max(zMax, w->bodies()[0].x.z());
    }
    const std::vector<double> c = upCrossings(t, z);
    period = c.size() >= 2 ? meanPeriod(c) : 0;
    draft = 0.5*h - 0.5*(zMin + zMax);
}


//- A model that adds nothing (a world with models, and no body force)
class NoForce
:
    public BodyForceModel
{
public:
    const char* name() const override { return "noForce"; }
    void addForces(const World&, int, int, Vec3*, Vec3*) const override {}
};

} // anonymous namespace


TEST(MultiRate, intervalBelowOneIsAnError)
{
    WorldSettings ws;
    ws.bodyForceInterval = 0;
    expectError([&]{ World w(ws); }, "bodyForceInterval");
}


//- A floe inserted in a run (inflow) that breaks a bound the floes the run
//  started with keep stops the run at the step it joins, naming
//  bodyForceInterval: one bound at a time (the other kept), and a floe like
//  the first joins. Without the check the run goes on past either.
TEST(MultiRate, anInsertedFloeBeyondTheBoundsStopsTheRunWhereItJoins)
{
    const SingleThread oneThread;
    const int k = 8;     // so that the smaller floe keeps deltaT's own bound

    // A 4 x 4 x 1 floe at rest, of ice soft enough (E = 1 MPa) that its
    // contact bound is near its heave bound: its bounds set the step, H
    // just inside them
    const auto world = [&](double dt)
    {
        WorldSettings ws;
        ws.timeStep = dt;
        ws.gravity = Vec3(0, 0, -g);
        ws.bodyForceInterval = k;
        auto w = std::make_unique<World>(ws);
        w->addMaterial(Material{"ice", rhoIce, 1e6, 0.33});
        addBox(*w, 4, 4, 1, -rhoIce/rhoWater);
        w->addForceModel(std::make_shared<Buoyancy>(water));
        return w;
    };
    const auto startWith = [&](double& dt)
    {
        const BodyForceLimits b = world(1.0)->bodyForceLimits(0, 1);
        dt = 0.98*std::min(b.contactLimit(), b.periodLimit())/k;
        return world(dt);
    };
    // The inserted floe's bounds, at its insertion pose, at the step dt
    const auto insert = [&](World& w, double L, double h)
    {
        const int shape = w.addShape(boxFloe(L, L, h, -rhoIce/rhoWater*h));
        const int i = w.insertBodyInRun(shape, 0, Vec3(100, 0, 0), Quat::Identity(), Vec3::Zero());
        return w.bodyForceLimits(i, i + 1);
    };

    // Like the first: joins
    {
        double dt;
        auto w = startWith(dt);
        for (int n = 0; n < 5; ++n) w->step();
        insert(*w, 4, 1);
        EXPECT_NO_THROW(for (int n = 0; n < 5; ++n) w->step());
    }
    // Smaller (a shorter contact time; the same thickness, so the same
    // heave period, and a longer roll period): the contact bound
    {
        double dt;
        auto w = startWith(dt);
        for (int n = 0; n < 5; ++n) w->step();
        const BodyForceLimits b = insert(*w, 1, 1);
        ASSERT_GT(k*dt, b.contactLimit());
        ASSERT_LT(k*dt, b.periodLimit());
        expectError([&]{ w->step(); }, "bodyForceInterval");
    }
    // Wider and thinner (heavier: a longer contact time; a shorter heave
    // period): the period bound
    {
        double dt;
        auto w = startWith(dt);
        for (int n = 0; n < 5; ++n) w->step();
        const BodyForceLimits b = insert(*w, 20, 0.2);
        ASSERT_LT(k*dt, b.contactLimit());
        ASSERT_GT(k*dt, b.periodLimit());
        expectError([&]{ w->step(); }, "bodyForceInterval");
    }
}


TEST(MultiRate, heavePeriodErrorScalesAsTheOuterStepSquared)
{
    const SingleThread oneThread;

    // 4 x 4 x 1.2 floe (the study's thickness) at the study's DEM step:
    // the slow part of the scheme is velocity Verlet with H = k dt on the
    // heave oscillator (the contacts, absent here, take the inner steps),
    // whose period is 2 pi H/acos(1 - (omega H)^2/2): relative error
    // -(omega H)^2/24 to leading order
    const double dt = 0.01, h = 1.2;
    const double d = rhoIce/rhoWater*h;
    const double omega = std::sqrt(g/d);
    const double T = 2*M_PI/omega;

    const int ks[] = {1, 2, 4, 8, 16};
    std::vector<double> err;
    for (const int k : ks)
    {
        double period, draft;
        heave(k, dt, h, 12, period, draft);
        const double H = k*dt;
        const double discrete = 2*M_PI*H/std::acos(1 - 0.5*omega*omega*H*H);
        const double e = period/T - 1;
        const double leading = -std::pow(omega*H, 2)/24;
        err.push_back(e);
        std::cout << "heave k = " << k << " (H/T = " << H/T << "): period "
                  << period << " s, analytic " << T << " s, error " << e
                  << " (Verlet with H: " << discrete/T - 1 << ", leading "
                  << leading << "); draft " << draft << " m (analytic " << d
                  << ")" << std::endl;
        // The discrete oscillator's period, to the crossings' resolution
        // (the crossings of the sampled path: a few 1e-4 T at k = 16)
        EXPECT_NEAR(period, discrete, 2e-5*T + 0.05*std::abs(discrete - T)) << "k = " << k;
        // The draft (mean position) is exact at any k
        EXPECT_NEAR(draft, d, 1e-3*d) << "k = " << k;
    }
    // (k dt/T)^2: 16 times the error at four times the interval
    EXPECT_NEAR(err[4]/err[2], 16, 0.5);
    EXPECT_NEAR(err[3]/err[1], 16, 0.8);
    // At k = 8 (H = T/26) within 0.3 % of the continuous period
    EXPECT_LT(std::abs(err[3]), 3e-3);
}


TEST(MultiRate, rollPeriodAtIntervalsFourAndEight)
{
    const SingleThread oneThread;

    // test_buoyancy's roll test at the study's step: 4 x 4 x 1 floe heeled
    // by 3 deg, period 2 pi sqrt(I/(m g GM)); tolerance 3 % as there
    const double B = 4, h = 1;
    const double d = rhoIce/rhoWater*h;
    const double GM = d/2 + B*B/(12*d) - h/2;
    const double theta0 = 3*M_PI/180;
    const double T = 2*M_PI*std::sqrt((B*B + h*h)/12/(g*GM));

    for (const int k : {1, 4, 8})
    {
        auto w = boxWorld(0.01, k);
        addBox(*w, B, B, h, -d, Quat(Eigen::AngleAxisd(theta0, Vec3::UnitX())));
        w->addForceModel(std::make_shared<Buoyancy>(water));
        const Quat toInput = w->shapeOf(0).principalToInput().inverse();
        std::vector<double> t, heel;
        double heelMax = 0;
        while (w->time() < 6.5*T)
        {
            w->step();
            const Vec3 up = (w->bodies()[0].q*toInput)*Vec3::UnitZ();
            t.push_back(w->time());
            heel.push_back(-std::asin(up.y()));
            heelMax = std::max(heelMax, std::abs(heel.back()));
        }
        const std::vector<double> c = upCrossings(t, heel);
        ASSERT_GE(c.size(), 4u);
        const double period = meanPeriod(c);
        std::cout << "roll k = " << k << ": period " << period
                  << " s, analytic " << T << " s, error " << period/T - 1
                  << ", largest heel / start " << heelMax/theta0 << std::endl;
        EXPECT_NEAR(period, T, 0.03*T);
        // Symplectic: no growth of the amplitude
        EXPECT_LT(heelMax, theta0*1.01);
    }
}


TEST(MultiRate, dragDecayAndSpinDownAtIntervalsFourAndEight)
{
    const SingleThread oneThread;
    const DragSettings ds;
    const double h = 1;
    const double d = rhoIce/rhoWater*h;

    for (const int k : {4, 8})
    {
        // test_drag's decayInStillWater: u0/(1 + k_d u0 t), 2 %
        {
            const double L = 10, u0 = 1;
            auto w = boxWorld(0.01, k);
            addBox(*w, L, L, h, -d, Quat::Identity(), Vec3(u0, 0, 0));
            w->addForceModel(std::make_shared<Buoyancy>(water));
            w->addForceModel(std::make_shared<Drag>(water, ds, std::make_shared<UniformCurrent>(Vec3::Zero())));
            const double m = w->bodies()[0].mass;
            const double kd =
                0.5*rhoWater*(ds.formCoefficient*L*d + ds.skinCoefficient*L*L)/m;
            double worst = 0;
            for (int s = 1; s <= 80; ++s)
            {
                w->advanceTo(s*1.0);
                const double expected = u0/(1 + kd*u0*w->time());
                worst = std::max(worst, std::abs(w->bodies()[0].v.x()/expected - 1));
            }
            std::cout << "drag decay k = " << k << ": largest relative "
                      << "deviation " << worst << std::endl;
            EXPECT_LT(worst, 0.02);
        }
        // test_drag's spinDown: w0/(1 + (c/I) w0 t), 2 %, c from the exact
        // integration's moment at the start
        {
            const double L = 4, w0 = 0.5;
            auto w = boxWorld(0.01, k);
            addBox(*w, L, L, h, -d, Quat::Identity(), Vec3::Zero(), Vec3(0, 0, w0));
            auto drag = std::make_shared<Drag>(water, ds, std::make_shared<UniformCurrent>(Vec3::Zero()));
            Vec3 F, M;
            drag->bodyDrag(*w, 0, F, M);
            const double c = -M.z()/(w0*w0);
            w->addForceModel(std::make_shared<Buoyancy>(water));
            w->addForceModel(drag);
            const double I = w->bodies()[0].mass*L*L/6;
            double worst = 0;
            for (int s = 1; s <= 60; ++s)
            {
                w->advanceTo(s*1.0);
                const double expected = w0/(1 + c/I*w0*w->time());
                worst = std::max(worst, std::abs(w->bodies()[0].omega().z()/expected - 1));
            }
            std::cout << "spin-down k = " << k << ": largest relative "
                      << "deviation " << worst << std::endl;
            EXPECT_LT(worst, 0.02);
        }
    }
}


TEST(MultiRate, heaveDecayOfFloeDampingAtTheRecommendedInterval)
{
    const SingleThread oneThread;

    // test_floeDamping's heaveDecayFollowsTheLinearModel at dt = 0.01:
    // the damped oscillator z0 e^(-zeta w t)(cos wd t + ...), 5 % of z0
    // over 4 periods. The recommended k = 4 (H = T/47) passes; k = 8 (H =
    // T/23) gives 5.9 % (the period's error, (omega H)^2/24 = 0.3 %,
    // accumulates as a phase lag): measured and printed, not asserted
    const double L = 6, h = 1;
    const double d = rhoIce/rhoWater*h;
    const double z0 = -0.05;
    const FloeDampingSettings s;
    for (const int k : {1, 4, 8})
    {
        auto w = boxWorld(0.01, k);
        addBox(*w, L, L, h, -d + z0);
        w->addForceModel(std::make_shared<Buoyancy>(water));
        w->addForceModel(std::make_shared<FloeDamping>(water, s));
        const double m = w->bodies()[0].mass;
        const double om = std::sqrt(rhoWater*g*L*L/m);
        const double zeta = s.heave;
        const double wd = om*std::sqrt(1 - zeta*zeta);
        const double zEq = w->bodies()[0].x.z() - z0;
        const double T = 2*M_PI/wd;
        double worst = 0;
        for (int n = 1; n <= 400; ++n)
        {
            w->advanceTo(n*4*T/400);
            const double t = w->time();
            const double expected = z0*std::exp(-zeta*om*t)
               *(std::cos(wd*t) + zeta/std::sqrt(1 - zeta*zeta)*std::sin(wd*t));
            worst = std::max(worst, std::abs(w->bodies()[0].x.z() - zEq - expected)/std::abs(z0));
        }
        std::cout << "heave decay k = " << k << ": largest deviation "
                  << worst << " of z0" << std::endl;
        if (k <= 4) EXPECT_LT(worst, 0.05) << "k = " << k;
    }
}


TEST(MultiRate, dryElasticImpactIsTheSingleRateOne)
{
    // Two floes collide head-on (no gravity, a model that adds nothing):
    // the contacts are integrated at every step whatever k, so the run is
    // the single-rate one bit for bit, and the impact elastic
    auto run = [](int k)
    {
        WorldSettings ws;
        ws.timeStep = 1e-4;
        ws.gravity = Vec3::Zero();
        ws.bodyForceInterval = k;
        auto w = std::make_unique<World>(ws);
        const int mat = w->addMaterial(test::ice(1e9));
        w->setPairProperties(mat, mat, PairProperties{0.0, 1.0});
        const int shape = w->addShape
        (
            DilatedShape(ConvexPolyhedron::prism({{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}, -0.4, 0.8), 0.1)
        );
        w->addBody(shape, mat, Vec3(-1.2, 0, 0), Quat::Identity(), Vec3(1, 0, 0));
        w->addBody(shape, mat, Vec3(1.2, 0, 0), Quat::Identity(), Vec3(-1, 0, 0));
        w->addForceModel(std::make_shared<NoForce>());
        w->advanceTo(0.4);
        return w;
    };
    auto a = run(1);
    auto b = run(7);
    test::expectSameBodies(a->bodies(), b->bodies());
    const double ke0 = 2*0.5*a->bodies()[0].mass*1.0;
    const double ke = b->energies().kinetic;
    std::cout << "dry impact: kinetic energy after / before " << ke/ke0
              << ", velocities " << b->bodies()[0].v.x() << ' '
              << b->bodies()[1].v.x() << std::endl;
    EXPECT_LT(b->bodies()[0].v.x(), 0);     // it rebounded
    EXPECT_NEAR(ke/ke0, 1, 1e-6);
}


TEST(MultiRate, restartInTheMiddleOfAnOuterStepEqualsUninterruptedRun)
{
    // k = 4; the restart is written after 303 steps (3 into an outer step)
    const int k = 4;
    const double cut = 0.303;
    auto a = windyFloeField(100, 11, k);
    a->advanceTo(cut);
    ASSERT_EQ(a->bodyForcePhase(), 3);
    a->advanceTo(0.8);

    auto b = windyFloeField(100, 11, k);
    b->advanceTo(cut);
    auto c = windyFloeField(100, 11, k);
    test::restartFrom(*c, *b);
    ASSERT_EQ(c->bodyForcePhase(), 3);
    c->advanceTo(0.8);
    EXPECT_GT(b->contactCount(), 0);
    test::expectSameBodies(a->bodies(), c->bodies());

    // Without the phase the restarted run starts a new outer step: it
    // differs (the test above sees the schedule)
    auto e = windyFloeField(100, 11, k);
    test::restartFrom(*e, *b);
    e->setBodyForcePhase(0);
    e->advanceTo(0.8);
    EXPECT_NE(a->bodies()[0].x, e->bodies()[0].x);
}


TEST(MultiRate, independentOfThreadCount)
{
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    auto a = windyFloeField(1200, 5, 4);
    a->advanceTo(0.1);
    omp_set_num_threads(std::max(2, threads));
    auto b = windyFloeField(1200, 5, 4);
    b->advanceTo(0.1);
    omp_set_num_threads(threads);
    EXPECT_GT(a->contactCount(), 0);
    test::expectSameBodies(a->bodies(), b->bodies());
}


TEST(MultiRate, reportedDriveIsTheImpulseApplied)
{
    const SingleThread oneThread;

    // Floes far apart (no contacts) under current, wind, buoyancy and
    // damping, k = 5: the floes' horizontal momentum changes by exactly
    // sum h/2 (D_{n-1} + D_n) of the reported drive (the sum a force
    // balance takes, iceLoadStatistics), which is k times the models'
    // force at the outer steps' ends and zero in between
    const int k = 5;
    auto w = windyFloeField(16, 3, k, 12.0);
    w->initialise();
    auto momentum = [&]
    {
        Vec3 P = Vec3::Zero();
        for (const Body& b : w->bodies()) P += b.mass*b.v;
        return P;
    };
    const Vec3 P0 = momentum();
    Vec3 Dprev = w->modelForceOnFreeBodies();
    Vec3 impulse = Vec3::Zero();
    double scale = 0;
    int zeros = 0;
    const double dt = w->settings().timeStep;
    for (int s = 0; s < 1000; ++s)
    {
        w->step();
        const Vec3 D = w->modelForceOnFreeBodies();
        if (D.isZero(0)) ++zeros;
        impulse += 0.5*dt*(Dprev + D);
        scale += 0.5*dt*(Dprev.head<2>().norm() + D.head<2>().norm());
        Dprev = D;
    }
    EXPECT_EQ(w->contactCount(), 0);
    EXPECT_EQ(zeros, 1000 - 1000/k);
    const Vec3 dP = momentum() - P0;
    std::cout << "drive: momentum change " << dP.head<2>().transpose()
              << ", reported impulse " << impulse.head<2>().transpose()
              << std::endl;
    EXPECT_GT(dP.head<2>().norm(), 1e-3*scale);
    EXPECT_NEAR((dP - impulse).head<2>().norm(), 0, 1e-10*scale);
}
