/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Floe damping (hydro/FloeDamping.H) against the linear model:
      - the waterplane of a box and of a heeled box (exact integrals);
      - heave free decay of a wall-sided floe: m z'' + c z' + k z = 0 with
        k = rho_w g A_wp, c = 2 zeta sqrt(m k): the displacement follows
        z0 e^(-zeta w t) (cos w_d t + zeta/sqrt(1 - zeta^2) sin w_d t)
        within 5 % of z0;
      - a floe at rest at its draft stays at rest (no drift from damping);
      - horizontal motion and yaw get no force from it;
      - roll decays with damping and does not without;
      - settings errors name the entry.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "hydro/Buoyancy.H"
#include "hydro/FloeDamping.H"
#include "hydro/WaterFrame.H"
#include "hydroFixtures.H"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <vector>

using namespace iceDEM;

namespace
{

using namespace test::hydro;

struct DampWorld
:
    test::hydro::BoxWorld
{
    explicit DampWorld(double dt) : BoxWorld(dt) {}

    int addBox
    (
        double Lx, double Ly, double h, double zb,
        const Quat& q = Quat::Identity(),
        const Vec3& v = Vec3::Zero(),
        const Vec3& omega = Vec3::Zero()
    )
    {
        return BoxWorld::addBox(Lx, Ly, h, zb, Vec3::Zero(), q, v, omega);
    }

    void addWater(const FloeDampingSettings* damping)
    {
        const WaterSettings water{rhoWater, 0};
        world->addForceModel(std::make_shared<Buoyancy>(water));
        if (damping)
        {
            world->addForceModel
            (
                std::make_shared<FloeDamping>(water, *damping)
            );
        }
    }
};

} // anonymous namespace


TEST(FloeDamping, settingsErrorsNameTheEntry)
{
    FloeDampingSettings s;
    s.heave = -0.1;
    try
    {
        FloeDamping d(WaterSettings{}, s);
        FAIL() << "negative heave accepted";
    }
    catch (const Error& e) { EXPECT_EQ(e.entry(), "heave"); }
    s = FloeDampingSettings();
    s.rollPitch = std::nan("");
    try
    {
        FloeDamping d(WaterSettings{}, s);
        FAIL() << "NaN rollPitch accepted";
    }
    catch (const Error& e) { EXPECT_EQ(e.entry(), "rollPitch"); }
    EXPECT_EQ(FloeDampingSettings().heave, 0.1);
    EXPECT_EQ(FloeDampingSettings().rollPitch, 0.1);
}


TEST(FloeDamping, waterplaneOfABox)
{
    // 3 (x) by 2 (y) box cut at mid height: A = 6, Ixx = int x^2 = 2*27/12,
    // Iyy = 3*8/12; heeled by theta about x: the cut is 3 by 2/cos(theta)
    const double Lx = 3, Ly = 2;
    for (double theta : {0.0, 0.1})
    {
        DampWorld dw(1e-3);
        dw.addBox(Lx, Ly, 1, -0.5, Quat(Eigen::AngleAxisd(theta, Vec3::UnitX())));
        PolyhedronBuffer buf;
        const Body& b = dw.body(0);
        const Waterplane wp = waterplane
        (
            dw.world->shapeOf(0).outer(buf), b.rotation(), b.x, 0
        );
        const double B = Ly/std::cos(theta);
        EXPECT_NEAR(wp.area, Lx*B, 1e-12*Lx*B);
        EXPECT_NEAR(wp.Ixx, B*Lx*Lx*Lx/12, 1e-12);
        EXPECT_NEAR(wp.Iyy, Lx*B*B*B/12, 1e-12);
        EXPECT_NEAR(wp.centroid.head<2>().norm(), 0, 1e-12);
    }
}


TEST(FloeDamping, waterFrameAgreesWithThePerFacePaths)
{
    // The shared frame (hydro/WaterFrame.H) against the per-face clipping:
    // the submerged volume bit for bit (same arithmetic), the waterplane
    // to round-off (vertices relative to the centroid, not world points
    // minus the centroid), on random poses: level, heeled, overwashed, dry
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> U(-1, 1);
    DampWorld dw(1e-3);
    dw.addBox(3, 2, 1, -0.5, Quat::Identity());
    Body& b = dw.world->bodies()[0];
    PolyhedronBuffer buf;
    int cut = 0;
    for (int trial = 0; trial < 400; ++trial)
    {
        const double tilt = trial % 2 ? 0.2 : M_PI;
        b.q = Quat(Eigen::AngleAxisd
        (
            tilt*U(gen), Vec3(U(gen), U(gen), U(gen)).normalized()
        ));
        b.x = Vec3(20*U(gen), 20*U(gen), 1.5*U(gen));
        const PolyhedronView P = dw.world->shapeOf(0).outer(buf);
        const Mat3 R = b.rotation();
        const WaterFrame& frame = waterFrame(*dw.world, 0, 0.1);
        ASSERT_TRUE(frame.valid());
        const SubmergedVolume& sv = frameVolume(P, frame);
        const SubmergedVolume ref = submergedVolume(P, R, b.x, 0.1);
        EXPECT_EQ(sv.volume, ref.volume);
        EXPECT_EQ(sv.centroid, ref.centroid);
        const Waterplane wf = waterplane(frame);
        const Waterplane wr = waterplane(P, R, b.x, 0.1);
        EXPECT_NEAR(wf.area, wr.area, 1e-12*6);
        // (an overwashed box has a waterplane of round-off area, whose
        // centroid is round-off over round-off in both)
        if (wr.area > 1e-6)
        {
            EXPECT_NEAR((wf.centroid - wr.centroid).norm(), 0, 1e-12*20);
        }
        EXPECT_NEAR(wf.Ixx, wr.Ixx, 1e-11);
        EXPECT_NEAR(wf.Iyy, wr.Iyy, 1e-11);
        cut += wr.area > 0;
        // Asked again: the same frame (cached), not recomputed
        EXPECT_EQ(&waterFrame(*dw.world, 0, 0.1), &frame);
        EXPECT_TRUE(frame.hasVolume);
    }
    EXPECT_GT(cut, 100);
}


TEST(FloeDamping, waterlinePolygonAgreesWithTheWetFaces)
{
    // A floating floe's waterplane from its waterline polygon (the lower
    // cap moved along the axis to the water: waterplane(P, frame), what
    // the damping uses) against the lid of all wet polygons
    // (waterplane(frame)) on random poses of an irregular hexagonal prism:
    // level to heeled by 0.3 rad, at any height (cut across the sides, or
    // across a cap: there both take the wet polygons). Equal to round-off;
    // the heeled box's closed form is checked above. With the floe's caps
    // (findPrismCaps, kept by a world with water: DilatedShape::prismCaps)
    // the waterline polygon comes from the lower cap's moments, equal to
    // round-off to the one from the cap's vertices
    std::mt19937 gen(23);
    std::uniform_real_distribution<double> U(-1, 1);
    DampWorld dw(1e-3);
    const int shape = dw.world->addShape
    (
        DilatedShape
        (
            ConvexPolyhedron::prism
            (
                {{-2.1, -1.0}, {0.3, -1.9}, {2.4, -0.6}, {2.0, 1.3},
                 {-0.2, 2.2}, {-2.3, 0.9}},
                -0.45, 0.8
            ),
            radius
        )
    );
    dw.world->addBody(shape, dw.ice, Vec3::Zero(), Quat::Identity());
    Body& b = dw.world->bodies()[0];
    PolyhedronBuffer buf;
    int lid = 0;
    double worst = 0, capWorst = 0;
    PrismCaps caps;
    ASSERT_TRUE(findPrismCaps(dw.world->shapeOf(0).outer(buf), caps));
    const auto withCaps = std::make_unique<WaterFrame>();
    for (int trial = 0; trial < 400; ++trial)
    {
        b.q = Quat(Eigen::AngleAxisd
        (
            0.3*U(gen), Vec3(U(gen), U(gen), U(gen)).normalized()
        ));
        b.x = Vec3(30*U(gen), 30*U(gen), 0.1 + 0.4*U(gen));
        const PolyhedronView P = dw.world->shapeOf(0).outer(buf);
        const WaterFrame& frame = waterFrame(*dw.world, 0, 0.1);
        ASSERT_TRUE(frame.valid());
        const Waterplane wl = waterplane(P, frame);
        const Waterplane wf = waterplane(frame);
        lid += frame.prismBottom >= 0;
        computeWaterFrame(P, frame.R, b.x, 0.1, *withCaps, false, &caps);
        const Waterplane wc = waterplane(P, *withCaps);
        EXPECT_EQ(withCaps->prismBottom, frame.prismBottom);
        EXPECT_EQ(withCaps->prismBottomPlane != nullptr, frame.prismBottom >= 0);
        const double a2 = std::max(wl.area*wl.area, 1.0);
        capWorst = std::max
        (
            capWorst,
            std::max
            (
                std::abs(wc.area - wl.area)/std::max(wl.area, 1.0),
                std::abs(wc.Ixx - wl.Ixx)/a2
            )
        );
        EXPECT_NEAR(wc.area, wl.area, 1e-14*std::max(wl.area, 1.0));
        if (wl.area > 1e-6)
        {
            EXPECT_NEAR((wc.centroid - wl.centroid).norm(), 0, 1e-13*3);
        }
        EXPECT_NEAR(wc.Ixx, wl.Ixx, 1e-13*a2);
        EXPECT_NEAR(wc.Iyy, wl.Iyy, 1e-13*a2);
        const double A = std::max(wf.area, 1.0);
        worst = std::max
        (
            worst,
            std::max(std::abs(wl.area - wf.area)/A, std::abs(wl.Ixx - wf.Ixx)/(A*A))
        );
        EXPECT_NEAR(wl.area, wf.area, 1e-13*A) << "trial " << trial;
        if (wf.area > 1e-6)
        {
            EXPECT_NEAR((wl.centroid - wf.centroid).norm(), 0, 1e-13*3)
                << "trial " << trial;
        }
        EXPECT_NEAR(wl.Ixx, wf.Ixx, 1e-12*A*A) << "trial " << trial;
        EXPECT_NEAR(wl.Iyy, wf.Iyy, 1e-12*A*A) << "trial " << trial;
    }
    std::cout << "waterline polygon against the wet faces' lid: " << lid
              << " of 400 poses by the polygon, largest relative difference "
              << worst << "; from the kept cap against its vertices "
              << capWorst << std::endl;
    // Most poses are cut across the sides only (the waterline polygon)
    EXPECT_GT(lid, 150);
    EXPECT_LT(lid, 400);
}


TEST(FloeDamping, heaveDecayFollowsTheLinearModel)
{
    const SingleThread oneThread;
    const double L = 6, h = 1;
    const double d = rhoIce/rhoWater*h;
    const double z0 = -0.05;            // pushed down, released at rest
    const FloeDampingSettings s;        // the default fraction

    DampWorld dw(1e-3);
    dw.addBox(L, L, h, -d + z0);
    dw.addWater(&s);

    const double m = dw.body(0).mass;
    const double k = rhoWater*g*L*L;
    const double w = std::sqrt(k/m);
    const double zeta = s.heave;
    const double wd = w*std::sqrt(1 - zeta*zeta);
    const double zEq = dw.body(0).x.z() - z0;

    double worst = 0;
    const double T = 2*M_PI/wd;
    for (int n = 1; n <= 400; ++n)
    {
        const double t = n*4*T/400;
        dw.world->advanceTo(t);
        const double tt = dw.world->time();
        const double expected = z0*std::exp(-zeta*w*tt)
           *(std::cos(wd*tt) + zeta/std::sqrt(1 - zeta*zeta)*std::sin(wd*tt));
        const double z = dw.body(0).x.z() - zEq;
        worst = std::max(worst, std::abs(z - expected)/std::abs(z0));
    }
    const double zEnd = dw.body(0).x.z() - zEq;
    std::cout << "heave decay: zeta " << zeta << ", period " << T
              << " s, amplitude after 4 periods " << std::abs(zEnd/z0)
              << " (model " << std::exp(-zeta*w*4*T) << "), largest "
              << "deviation from the model " << worst << " of z0"
              << std::endl;
    EXPECT_LT(worst, 0.05);
}


TEST(FloeDamping, floeAtRestStaysAtRest)
{
    const SingleThread oneThread;
    const double L = 5, h = 1;
    const double d = rhoIce/rhoWater*h;
    const FloeDampingSettings s;
    DampWorld dw(0.01);
    dw.addBox(L, L, h, -d);
    dw.addWater(&s);
    const Vec3 x0 = dw.body(0).x;
    dw.world->advanceTo(100);
    std::cout << "floe at rest: displacement after 100 s "
              << (dw.body(0).x - x0).norm() << " m, speed "
              << dw.body(0).v.norm() << " m/s" << std::endl;
    EXPECT_LT((dw.body(0).x - x0).norm(), 1e-9);
    EXPECT_LT(dw.body(0).v.norm(), 1e-10);
    EXPECT_LT(dw.body(0).omega().norm(), 1e-10);
}


TEST(FloeDamping, horizontalMotionAndYawAreNotDamped)
{
    const double L = 5, h = 1;
    const double d = rhoIce/rhoWater*h;
    DampWorld dw(1e-3);
    dw.addBox(L, L, h, -d, Quat::Identity(), Vec3(1, -0.5, 0), Vec3(0, 0, 0.3));
    const FloeDamping damping(WaterSettings{rhoWater, 0}, FloeDampingSettings());
    std::vector<Vec3> F(1, Vec3::Zero()), M(1, Vec3::Zero());
    damping.addForces(*dw.world, 0, 1, F.data(), M.data());
    // The coefficients themselves are there
    const Vec3 c = damping.coefficients(*dw.world, 0);
    EXPECT_GT(c.minCoeff(), 0);
    // No heave velocity: no force; roll and pitch rates are zero up to the
    // round-off of omega = I^-1 L in the world frame (1e-33 rad/s here)
    EXPECT_EQ(F[0].norm(), 0.0);
    EXPECT_LT(M[0].norm(), 1e-25*c.maxCoeff());
}


TEST(FloeDamping, rollDecays)
{
    const SingleThread oneThread;
    // 4 x 4 x 1 floe heeled by 0.03 rad about x at its draft: with damping
    // the roll after 6 s is a small fraction of the start, without it the
    // roll keeps its amplitude
    const double L = 4, h = 1;
    const double d = rhoIce/rhoWater*h;
    const double theta0 = 0.03;
    auto rollAmplitude = [&](const FloeDampingSettings* s)
    {
        DampWorld dw(1e-3);
        dw.addBox(L, L, h, -d, Quat(Eigen::AngleAxisd(theta0, Vec3::UnitX())));
        dw.addWater(s);
        double amp = 0;
        for (int n = 1; n <= 600; ++n)
        {
            dw.world->advanceTo(n*0.01);
            if (dw.world->time() > 4)
            {
                const Mat3 R = dw.body(0).rotation();
                amp = std::max(amp, std::abs(std::asin(R(2, 1))));
            }
        }
        return amp;
    };
    const FloeDampingSettings s;
    const double damped = rollAmplitude(&s);
    const double undamped = rollAmplitude(nullptr);
    std::cout << "roll: amplitude after 4 s with damping " << damped
              << ", without " << undamped << " (start " << theta0 << ")"
              << std::endl;
    EXPECT_GT(undamped, 0.9*theta0);
    EXPECT_LT(damped, 0.5*theta0);
}
