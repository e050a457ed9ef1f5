/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Drag (hydro/Drag.H) on box-shaped floes built as in the case files,
    against analytic results (method.md 4 and 7.6):
      - the force and moment of a uniform relative flow (exact: the sample
        points integrate a uniform load exactly);
      - a floe moving through still water slows down as u0/(1 + k u0 t),
        k = 1/2 rho_w (C_f A_side + C_s A_bottom)/m;
      - a floe released at rest in a uniform current reaches the current:
        U - u = U/(1 + k U t);
      - a spinning floe spins down as w0/(1 + (c/I) w0 t), c the moment
        coefficient of the facet model, compared with the continuous law
        c = rho_w C_f d L^4/32 + 1/2 rho_w C_s K (L/2)^5,
        K = int over [-1,1]^2 of (x^2 + y^2)^(3/2);
      - settings errors name the entry; results do not depend on the
        number of threads.
    The floes float (gravity and buoyancy on) unless said otherwise.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "hydro/Buoyancy.H"
#include "hydro/Drag.H"
#include "hydro/FlowVelocity.H"
#include "hydroFixtures.H"
#include "testWorlds.H"

#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <vector>

using namespace iceDEM;

namespace
{

using namespace test::hydro;

//- A random convex polygon in any plane, as the skin-integral tests draw
//  it: m vertices on an ellipse of semi-axes a, b in [1, 5] (in-plane axes
//  t1, t2 of the normal n) about a random origin, at jittered angles
struct PlanePolygon
{
    Vec3 n, t1, t2, origin;
    double a, b;
    std::vector<Vec3> q;
};

PlanePolygon randomEllipsePolygon(std::mt19937& gen, int m)
{
    std::uniform_real_distribution<double> U(-1, 1);
    PlanePolygon P;
    P.n = Vec3(U(gen), U(gen), U(gen)).normalized();
    P.t1 = P.n.unitOrthogonal();
    P.t2 = P.n.cross(P.t1);
    P.a = 1 + 4*std::abs(U(gen));
    P.b = 1 + 4*std::abs(U(gen));
    P.origin = Vec3(5*U(gen), 5*U(gen), 5*U(gen));
    const double phase = M_PI*U(gen);
    for (int k = 0; k < m; ++k)
    {
        const double th = phase + 2*M_PI*(k + 0.3*std::abs(U(gen)))/m;
        P.q.push_back(P.origin + P.a*std::cos(th)*P.t1 + P.b*std::sin(th)*P.t2);
    }
    return P;
}

//- World with square-ish box floes Lx x Ly x h (true size) with their
//  bottom at zb (test::hydro::BoxWorld: soft ice, no contacts happen)
struct DragWorld
:
    test::hydro::BoxWorld
{
    using BoxWorld::BoxWorld;

    int addFloe
    (
        double Lx,
        double Ly,
        double h,
        double zb,
        const Vec3& centre = Vec3::Zero(),
        const Vec3& v = Vec3::Zero(),
        const Vec3& omega = Vec3::Zero()
    )
    {
        return addBox(Lx, Ly, h, zb, centre, Quat::Identity(), v, omega);
    }

    void addWater(const DragSettings& ds, const Vec3& current)
    {
        const WaterSettings water{rhoWater, 0};
        world->addForceModel(std::make_shared<Buoyancy>(water));
        world->addForceModel
        (
            std::make_shared<Drag>
            (
                water, ds, std::make_shared<UniformCurrent>(current)
            )
        );
    }
};

} // anonymous namespace


TEST(Drag, settingsErrorsNameTheEntry)
{
    const WaterSettings w;
    const auto flow = std::make_shared<UniformCurrent>(Vec3(0.3, 0, 0));

    DragSettings s;
    s.formCoefficient = -1;
    expectError([&]{ Drag d(w, s, flow); }, "formCoefficient");

    s = DragSettings();
    s.skinCoefficient = -0.004;
    expectError([&]{ Drag d(w, s, flow); }, "skinCoefficient");

    s = DragSettings();
    s.subdivision = -1;
    expectError([&]{ Drag d(w, s, flow); }, "subdivision");
    s.subdivision = DragSettings::maxSubdivision + 1;
    expectError([&]{ Drag d(w, s, flow); }, "subdivision");

    s = DragSettings();
    s.bottomCosine = 0;
    expectError([&]{ Drag d(w, s, flow); }, "bottomCosine");

    expectError
    (
        [&]{ Drag d(WaterSettings{-1, 0}, DragSettings(), flow); },
        "density"
    );
    expectError([&]{ Drag d(w, DragSettings(), nullptr); }, "type");
    expectError
    (
        [&]{ UniformCurrent u(Vec3(std::nan(""), 0, 0)); },
        "current"
    );

    // Documented defaults
    EXPECT_EQ(DragSettings().formCoefficient, 1.0);
    EXPECT_EQ(DragSettings().skinCoefficient, 0.004);
    EXPECT_EQ(DragSettings().subdivision, 2);
    EXPECT_NO_THROW(Drag(w, DragSettings(), flow));
}


TEST(Drag, uniformFlowForceAndMoment)
{
    // 3 (x) by 2 (y) by 1 floe, bottom at z = -0.6, held in a current:
    // every sample point sees the same relative velocity, so the sums are
    // exact: the form drag on each leading side acts at the centroid of
    // its wet part, the skin drag at the centre of the bottom.
    const double Lx = 3, Ly = 2, zb = -0.6;
    const double zG = zb + 0.5;
    const Vec3 U(0.3, -0.2, 0);
    DragSettings ds;
    ds.formCoefficient = 0.8;
    ds.skinCoefficient = 0.01;

    for (int sub : {0, 2, 4})
    {
        ds.subdivision = sub;
        for (bool moving : {false, true})
        {
            // The same relative velocity: a floe at rest in the current U,
            // or a floe moving at -U through still water
            DragWorld dw(1e-3, Vec3::Zero());
            dw.addFloe(Lx, Ly, 1, zb, Vec3::Zero(), moving ? Vec3(-U) : Vec3::Zero());
            Drag drag
            (
                WaterSettings{rhoWater, 0}, ds,
                std::make_shared<UniformCurrent>(moving ? Vec3::Zero() : U)
            );
            Vec3 F, M;
            drag.bodyDrag(*dw.world, 0, F, M);

            const double h2 = 0.5*rhoWater;
            const double depth = -zb;
            // Leading sides: -x (area Ly depth) and +y (area Lx depth)
            const Vec3 Fx(h2*ds.formCoefficient*Ly*depth*U.x()*U.x(), 0, 0);
            const Vec3 Fy(0, -h2*ds.formCoefficient*Lx*depth*U.y()*U.y(), 0);
            const Vec3 Fs = h2*ds.skinCoefficient*Lx*Ly*U.norm()*U;
            const Vec3 rx(-0.5*Lx, 0, 0.5*zb - zG);
            const Vec3 ry(0, 0.5*Ly, 0.5*zb - zG);
            const Vec3 rs(0, 0, zb - zG);
            const Vec3 Fe = Fx + Fy + Fs;
            const Vec3 Me = rx.cross(Fx) + ry.cross(Fy) + rs.cross(Fs);

            SCOPED_TRACE("subdivision " + std::to_string(sub)
                + (moving ? ", moving floe" : ", current"));
            EXPECT_NEAR((F - Fe).norm(), 0, 1e-12*Fe.norm());
            EXPECT_NEAR((M - Me).norm(), 0, 1e-12*Me.norm());
        }
    }
}


TEST(Drag, pureHeaveHasNoDrag)
{
    // Side normals are horizontal and the bottom only feels tangential
    // (skin) drag: drag does not damp heave
    DragWorld dw(1e-3, Vec3::Zero());
    dw.addFloe(3, 2, 1, -0.6, Vec3::Zero(), Vec3(0, 0, -0.5));
    Drag drag
    (
        WaterSettings{}, DragSettings(),
        std::make_shared<UniformCurrent>(Vec3::Zero())
    );
    Vec3 F, M;
    drag.bodyDrag(*dw.world, 0, F, M);
    EXPECT_EQ(F.norm(), 0.0);
    EXPECT_EQ(M.norm(), 0.0);
}


TEST(Drag, decayInStillWater)
{
    const SingleThread oneThread;

    // 10 x 10 x 1 floe at its draft d moving at u0 through still water:
    //   du/dt = -k u^2,  k = 1/2 rho_w (C_f L d + C_s L^2)/m
    const double L = 10, h = 1;
    const double d = rhoIce/rhoWater*h;
    const double u0 = 1.0;
    const DragSettings ds;
    DragWorld dw(5e-3);
    dw.addFloe(L, L, h, -d, Vec3::Zero(), Vec3(u0, 0, 0));
    dw.addWater(ds, Vec3::Zero());

    const double m = dw.body(0).mass;
    ASSERT_NEAR(m, rhoIce*L*L*h, 1e-9*m);
    const double k =
        0.5*rhoWater*(ds.formCoefficient*L*d + ds.skinCoefficient*L*L)/m;

    double worst = 0;
    for (int s = 1; s <= 80; ++s)
    {
        dw.world->advanceTo(s*1.0);
        const double t = dw.world->time();
        const double expected = u0/(1 + k*u0*t);
        worst = std::max(worst, std::abs(dw.body(0).v.x()/expected - 1));
    }
    std::cout << "decay: k u0 t_end = " << k*u0*dw.world->time()
              << ", largest relative deviation from u0/(1 + k u0 t): "
              << worst << std::endl;
    EXPECT_LT(worst, 0.02);
    EXPECT_LT(std::abs(dw.body(0).v.y()), 1e-9);
}


TEST(Drag, reachesTheCurrent)
{
    const SingleThread oneThread;

    // 4 x 4 x 1 floe released at rest in a current U along x:
    //   U - u = U/(1 + k U t),  k = 1/2 rho_w (C_f L d + C_s L^2)/m
    const double L = 4, h = 1;
    const double d = rhoIce/rhoWater*h;
    const Vec3 U(0.3, 0, 0);
    const DragSettings ds;
    DragWorld dw(0.02);
    dw.addFloe(L, L, h, -d);
    dw.addWater(ds, U);

    const double m = dw.body(0).mass;
    const double k =
        0.5*rhoWater*(ds.formCoefficient*L*d + ds.skinCoefficient*L*L)/m;
    const double Un = U.norm();

    double worst = 0;
    const double tEnd = 200/(k*Un);     // U - u = U/201 analytically
    const int nOut = 100;
    for (int s = 1; s <= nOut; ++s)
    {
        dw.world->advanceTo(s*tEnd/nOut);
        const double t = dw.world->time();
        const double expected = Un - Un/(1 + k*Un*t);
        worst = std::max(worst, std::abs(dw.body(0).v.x() - expected)/expected);
    }
    const double lag = (dw.body(0).v - U).norm()/Un;
    std::cout << "current: t_end " << tEnd << " s, relative lag at the end "
              << lag << " (analytic " << 1.0/201 << "), largest relative "
              << "deviation from U kUt/(1 + kUt): " << worst << std::endl;
    EXPECT_LT(worst, 0.02);
    EXPECT_LT(lag, 0.01);
}


TEST(Drag, obliqueCurrent)
{
    const SingleThread oneThread;

    // Current at an angle to the sides of a 4 x 4 x 1 floe. With w = U - u
    // the lag, the form drag acts on the -x and +y sides separately and
    // the skin drag along w:
    //   dw/dt = -k_f (w_x |w_x|, w_y |w_y|) - k_s |w| w,
    //   k_f = 1/2 rho_w C_f L d/m,  k_s = 1/2 rho_w C_s L^2/m
    // (no yaw moment: each force acts on the floe's centre line). The lag
    // is compared with this law integrated by RK4.
    const double L = 4, h = 1;
    const double d = rhoIce/rhoWater*h;
    const Vec3 U(0.2, -0.25, 0);
    const DragSettings ds;
    DragWorld dw(0.02);
    dw.addFloe(L, L, h, -d);
    dw.addWater(ds, U);

    const double m = dw.body(0).mass;
    const double kf = 0.5*rhoWater*ds.formCoefficient*L*d/m;
    const double ks = 0.5*rhoWater*ds.skinCoefficient*L*L/m;
    auto rate = [&](const Vec2& w) -> Vec2
    {
        return -kf*Vec2(w.x()*std::abs(w.x()), w.y()*std::abs(w.y()))
              - ks*w.norm()*w;
    };

    Vec2 w = U.head<2>();
    double tRef = 0;
    const double dtRef = 0.1;
    double worst = 0;
    double lag = 1;
    for (int s = 1; s <= 30; ++s)
    {
        const double t = s*50.0;
        while (tRef < t - 1e-9)
        {
            const Vec2 k1 = rate(w);
            const Vec2 k2 = rate(w + 0.5*dtRef*k1);
            const Vec2 k3 = rate(w + 0.5*dtRef*k2);
            const Vec2 k4 = rate(w + dtRef*k3);
            w += dtRef/6*(k1 + 2*k2 + 2*k3 + k4);
            tRef += dtRef;
        }
        dw.world->advanceTo(t);
        const Vec3 lagVec = U - dw.body(0).v;
        worst = std::max
        (
            worst, (lagVec.head<2>() - w).norm()/w.norm()
        );
        const double newLag = lagVec.norm()/U.norm();
        EXPECT_LT(newLag, lag);
        lag = newLag;
    }
    std::cout << "oblique current: relative lag after "
              << dw.world->time() << " s: " << lag << " (law "
              << w.norm()/U.norm() << "), largest relative deviation of "
              << "the lag from the law: " << worst << std::endl;
    EXPECT_LT(worst, 0.02);
    EXPECT_LT(std::abs(dw.body(0).omega().z()), 1e-6);
}


TEST(Drag, spinDown)
{
    const SingleThread oneThread;

    // 4 x 4 x 1 floe at its draft spinning at w0 about z in still water.
    // Continuous law: form drag on the leading half of each side and skin
    // drag on the bottom give M_z = -c w|w| with
    //   c = rho_w C_f d L^4/32 + 1/2 rho_w C_s K (L/2)^5,
    //   K = 8/5 [ sec^3 tan/4 + 3/8 (sec tan + ln(sec + tan)) ] at pi/4.
    // The facet model has the same form M_z = -c_m w|w| (the sampled
    // velocities scale with w), so w = w0/(1 + (c_m/I) w0 t), I = m L^2/6;
    // c_m tends to c as the sampling is refined.
    const double L = 4, h = 1;
    const double d = rhoIce/rhoWater*h;
    const double w0 = 0.5;
    DragSettings ds;

    const double s2 = std::sqrt(2.0);
    const double K =
        1.6*(2*s2/4 + 0.375*(s2 + std::log(1 + s2)));
    const double c =
        rhoWater*ds.formCoefficient*d*std::pow(L, 4)/32
      + 0.5*rhoWater*ds.skinCoefficient*K*std::pow(0.5*L, 5);

    // Moment coefficient of the facet model: sampled per subdivision, then
    // the exact integration (last)
    std::vector<double> cm;
    for (int sub = 0; sub <= DragSettings::maxSubdivision + 1; ++sub)
    {
        const bool exact = sub > DragSettings::maxSubdivision;
        ds.integration =
            exact ? DragIntegration::exact : DragIntegration::sampled;
        ds.subdivision = exact ? 2 : sub;
        DragWorld dw(1e-3, Vec3::Zero());
        dw.addFloe(L, L, h, -d, Vec3::Zero(), Vec3::Zero(), Vec3(0, 0, w0));
        Drag drag
        (
            WaterSettings{rhoWater, 0}, ds,
            std::make_shared<UniformCurrent>(Vec3::Zero())
        );
        Vec3 F, M;
        drag.bodyDrag(*dw.world, 0, F, M);
        EXPECT_NEAR(F.norm(), 0, 1e-12*c*w0*w0/L);
        EXPECT_NEAR(M.head<2>().norm(), 0, 1e-12*c*w0*w0);
        cm.push_back(-M.z()/(w0*w0));
        std::cout << "spin-down: "
                  << (exact ? std::string("exact")
                      : "subdivision " + std::to_string(sub))
                  << ": c_m/c = " << cm.back()/c << std::endl;
    }
    const double cExact = cm.back();
    cm.pop_back();
    // Sampled: converges to the continuous law, the error falls with
    // refinement
    for (std::size_t s = 1; s < cm.size(); ++s)
    {
        EXPECT_LT(std::abs(cm[s]/c - 1), std::abs(cm[s - 1]/c - 1));
    }
    EXPECT_NEAR(cm.back()/c, 1, 0.01);
    // Exact: the form drag is exact, and the skin drag too (the closed
    // form: a spin about the centroid is a rotation about it; the 6-point
    // rule used before erred by 5.5e-4 of the skin part, 2.2 % of c here)
    EXPECT_NEAR(cExact, c, 1e-12*c);
    EXPECT_LT(std::abs(cExact/c - 1), std::abs(cm.back()/c - 1));

    // Time history at the default settings (exact integration)
    ds = DragSettings();
    ASSERT_TRUE(ds.integration == DragIntegration::exact);
    DragWorld dw(5e-3);
    dw.addFloe(L, L, h, -d, Vec3::Zero(), Vec3::Zero(), Vec3(0, 0, w0));
    dw.addWater(ds, Vec3::Zero());
    const double I = dw.body(0).mass*L*L/6;
    const double cDefault = cExact;

    double worst = 0;
    for (int s = 1; s <= 60; ++s)
    {
        dw.world->advanceTo(s*1.0);
        const double t = dw.world->time();
        const double expected = w0/(1 + cDefault/I*w0*t);
        worst = std::max
        (
            worst, std::abs(dw.body(0).omega().z()/expected - 1)
        );
    }
    std::cout << "spin-down: (c_m/I) w0 t_end = "
              << cDefault/I*w0*dw.world->time()
              << ", largest relative deviation from w0/(1 + (c_m/I) w0 t): "
              << worst << std::endl;
    EXPECT_LT(worst, 0.02);
    EXPECT_LT(dw.body(0).v.norm(), 1e-6);
}


TEST(Drag, independentOfThreadCount)
{
    // Several floes drifting and spinning in a current: the same states
    // with one thread and with two (five floes: on the threads only with
    // singleThreadBelow 0)
    auto run = [](int threads)
    {
        omp_set_num_threads(threads);
        DragWorld dw(5e-3, Vec3(0, 0, -test::hydro::g), 1e7, 0);
        for (int k = 0; k < 5; ++k)
        {
            dw.addFloe
            (
                3 + 0.5*k, 2 + 0.3*k, 1, -0.8,
                Vec3(20.0*k, 0, 0), Vec3(0.1*k, 0, 0), Vec3(0, 0, 0.1)
            );
        }
        dw.addWater(DragSettings(), Vec3(0.3, 0.1, 0));
        dw.world->advanceTo(2);
        std::vector<Body> bodies = dw.world->bodies();
        return bodies;
    };
    const int saved = omp_get_max_threads();
    const std::vector<Body> a = run(1);
    const std::vector<Body> b = run(2);
    omp_set_num_threads(saved);
    test::expectSameBodies(a, b);
}


// The exact integration (uniform current) against the sampled path on many
// random poses, velocities and currents: level, tilted, overwashed, a
// sliver wet. Form drag (C_s = 0): the closed form is the limit the sampled
// sums converge to, at the midpoint rule's rate h^2 (a factor ~4 per
// subdivision). Skin drag (C_f = 0): the 6-point conical rule against the
// Richardson limit of the sampled sums (4 F_4 - F_3)/3. The errors are
// printed (the accuracy table of tests/benchmark/README.md).
TEST(Drag, exactAgreesWithSampledOnRandomPoses)
{
    const SingleThread oneThread;
    std::mt19937 gen(16);
    std::uniform_real_distribution<double> U(-1, 1);

    ExactVsSampled stats;
    constexpr int nSub = ExactVsSampled::nSub;

    for (int trial = 0; trial < 200; ++trial)
    {
        DragWorld dw(1e-3, Vec3::Zero());
        const double Lx = 2 + 3*std::abs(U(gen));
        const double Ly = 2 + 3*std::abs(U(gen));
        dw.addFloe(Lx, Ly, 1, -0.5);
        // Nearly level (floating) or any attitude (overwashed, on edge)
        randomHydroPose(dw.world->bodies()[0], gen, trial % 2, 0.3);
        const Vec3 current(0.3*U(gen), 0.3*U(gen), 0);
        const double size = std::max(Lx, Ly);

        auto drag = [&](bool form, DragIntegration integration, int sub,
                        Vec3& F, Vec3& M)
        {
            DragSettings ds;
            ds.formCoefficient = form ? 1.0 : 0.0;
            ds.skinCoefficient = form ? 0.0 : 0.004;
            ds.integration = integration;
            ds.subdivision = sub;
            Drag d
            (
                WaterSettings{rhoWater, 0}, ds,
                std::make_shared<UniformCurrent>(current)
            );
            d.bodyDrag(*dw.world, 0, F, M);
        };
        stats.add(drag, size);   // skipped: dry, or nothing leading
    }

    ASSERT_GT(stats.nPoses, 100);
    stats.print("drag", "form exact, skin (closed form)");

    // The sampled form drag converges to the closed form at the rate h^2
    for (int sub = 1; sub < nSub; ++sub)
    {
        EXPECT_GT(stats.formRms(sub - 1)/stats.formRms(sub), 3.0)
            << "subdivision " << sub;
    }
    EXPECT_LT(stats.formRms(nSub - 1), 1e-3);
    // The skin rule: no less accurate than the sampling it replaces as the
    // default (subdivision 2), in the mean and at its worst
    EXPECT_LT(stats.exactRms(), stats.skinRms(2));
    EXPECT_LT(stats.exactMax, stats.skinMax[2]);
}


// Reference skin integrals of a convex polygon: each fan triangle from the
// centroid split into 4^level congruent triangles, each by the conical rule
void skinReference
(
    const std::vector<Vec3>& q, const Vec3& n, const Vec3& w,
    const Vec3& omega, int level, Vec3& I, Vec3& Ir
)
{
    I.setZero();
    Ir.setZero();
    Vec3 c = Vec3::Zero();
    for (const Vec3& p : q) c += p;
    c /= q.size();
    std::vector<std::array<Vec3, 3>> tris, next;
    for (std::size_t k = 0; k < q.size(); ++k)
    {
        tris.push_back({c, q[k], q[(k + 1) % q.size()]});
    }
    for (int l = 0; l < level; ++l)
    {
        next.clear();
        for (const auto& t : tris)
        {
            const Vec3 ab = 0.5*(t[0] + t[1]), bc = 0.5*(t[1] + t[2]),
                ca = 0.5*(t[2] + t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({ab, t[1], bc});
            next.push_back({ca, bc, t[2]});
            next.push_back({ab, bc, ca});
        }
        tris.swap(next);
    }
    for (const auto& t : tris)
    {
        Vec3 dI, dIr;
        if (skinIntegralConical(t.data(), 3, n, w, omega, dI, dIr))
        {
            I += dI;
            Ir += dIr;
        }
    }
}


TEST(Drag, skinClosedFormAgreesWithFineQuadrature)
{
    // Random convex polygons (3 to 8 vertices on an ellipse, any plane)
    // under random rigid-body velocities: the closed form of the skin
    // integrals against the conical rule on 4^6 sub-triangles per fan
    // triangle (its error: the kink of |u| at the centre of rotation); and
    // skinIntegral's switch to the expansion far from the centre of
    // rotation against the closed form
    std::mt19937 gen(1616);
    std::uniform_real_distribution<double> U(-1, 1);
    double worst = 0, worstRule = 0, worstFar = 0;
    for (int trial = 0; trial < 60; ++trial)
    {
        const int m = 3 + trial % 6;
        const PlanePolygon P = randomEllipsePolygon(gen, m);
        const Vec3& n = P.n;
        const Vec3& t1 = P.t1;
        const Vec3& origin = P.origin;
        const std::vector<Vec3>& q = P.q;
        const Vec3 w(0.5*U(gen), 0.5*U(gen), 0.5*U(gen));
        const Vec3 omega(0.3*U(gen), 0.3*U(gen), 0.3*U(gen));
        const double size = std::max(P.a, P.b);
        auto error = [&](const Vec3& I, const Vec3& Ir,
                         const Vec3& J, const Vec3& Jr)
        {
            const double scale = J.norm() + (Jr - origin.cross(J)).norm()/size;
            return ((I - J).norm() + (Ir - Jr).norm()/size)/scale;
        };

        Vec3 I, Ir, Ic, Icr, Iref, Irref;
        ASSERT_TRUE(skinIntegralClosedForm(q.data(), m, n, w, omega, I, Ir));
        ASSERT_TRUE(skinIntegralConical(q.data(), m, n, w, omega, Ic, Icr));
        skinReference(q, n, w, omega, 6, Iref, Irref);
        worst = std::max(worst, error(I, Ir, Iref, Irref));
        worstRule = std::max(worstRule, error(Ic, Icr, Iref, Irref));

        // Nearly uniform: the centre of rotation 50 to 500 radii away
        for (double D : {50.0, 99.0, 101.0, 500.0})
        {
            const Vec3 wf =
                D*size*std::abs(omega.dot(n))*t1 - omega.cross(origin);
            Vec3 Iw, Iwr, Ie, Ier;
            ASSERT_TRUE(skinIntegral(q.data(), m, n, wf, omega, Iw, Iwr));
            ASSERT_TRUE
            (
                skinIntegralClosedForm(q.data(), m, n, wf, omega, Ie, Ier)
            );
            worstFar = std::max(worstFar, error(Iw, Iwr, Ie, Ier));
        }
    }
    std::cout << "skin integrals, relative error of I + Ir/size, worst of 60"
              << " polygons: closed form " << worst << ", 6-point rule "
              << worstRule << " (vs 4^6 sub-triangles); the expansion"
              << " beyond " << skinUniformRatio << " radii vs closed form "
              << worstFar << std::endl;
    EXPECT_LT(worst, 1e-6);
    EXPECT_LT(worst, 0.01*worstRule);
    EXPECT_LT(worstFar, 1e-7);

    // A pure translation: |w_t| w_t A, no moment about the centroid
    {
        const std::vector<Vec3> sq
            {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 3, 0), Vec3(0, 3, 0)};
        const Vec3 w(0.3, -0.4, 0.7);
        Vec3 I, Ir;
        ASSERT_TRUE(skinIntegral(sq.data(), 4, Vec3::UnitZ(), w,
            Vec3::Zero(), I, Ir));
        const Vec3 wt(0.3, -0.4, 0);
        EXPECT_NEAR((I - 6*0.5*wt).norm(), 0, 1e-15);
        EXPECT_NEAR((Ir - Vec3(1, 1.5, 0).cross(I)).norm(), 0, 1e-15);
    }
}

TEST(Drag, skinClosedFormAboutAVertex)
{
    // A floe turning about one of its polygon's vertices: that edge's end
    // lies on the centre of rotation (r = 0, p round-off), where the edge
    // term's logarithm took log(0) (a floating-point trap in the solvers,
    // an infinite drag without). Under the unit tests' traps (fpeTraps.C)
    // the closed form must be finite and agree with the fine quadrature as
    // anywhere else (an end exactly on the centre, not only within
    // round-off, comes in some of these rotations: the code before this
    // test trapped here)
    std::mt19937 gen(2727);
    std::uniform_real_distribution<double> U(-1, 1);
    double worst = 0;
    int rotations = 0;
    for (int trial = 0; trial < 1000; ++trial)
    {
        const int m = 3 + trial % 6;
        const PlanePolygon P = randomEllipsePolygon(gen, m);
        const Vec3 omega(0.3*U(gen), 0.3*U(gen), 0.3*U(gen));
        for (int k = 0; k < m; ++k)
        {
            // u = omega x (r - q_k): the rotation about vertex k
            const Vec3 w = -omega.cross(P.q[k]);
            Vec3 I, Ir, Iref, Irref;
            ASSERT_TRUE
            (
                skinIntegralClosedForm(P.q.data(), m, P.n, w, omega, I, Ir)
            );
            ASSERT_TRUE(I.allFinite() && Ir.allFinite()) << "trial " << trial;
            if (k == 0 && trial < 60)
            {
                const double size = std::max(P.a, P.b);
                skinReference(P.q, P.n, w, omega, 6, Iref, Irref);
                const double scale =
                    Iref.norm() + (Irref - P.origin.cross(Iref)).norm()/size;
                worst = std::max
                (
                    worst, ((I - Iref).norm() + (Ir - Irref).norm()/size)/scale
                );
            }
            ++rotations;
        }
    }
    std::cout << "skin closed form about a vertex: " << rotations
              << " rotations finite; worst relative error against 4^6"
              << " sub-triangles " << worst << std::endl;
    EXPECT_LT(worst, 1e-6);
}

TEST(Drag, skinOfAWholeFaceFromItsPlane)
{
    // Random prisms (3 to 12 sides) at random rotations: every face's skin
    // integrals from its plane kept in the body frame (FacePlane: the
    // expansion from the plane's moments, the closed form from its
    // coordinates and edge tangents) against skinIntegral of the face's
    // world polygon, with the centre of rotation from a fifth of a radius
    // to 1000 radii away (both sides of the switch)
    std::mt19937 gen(4141);
    std::uniform_real_distribution<double> U(-1, 1);
    // Worst relative difference: the closed form's side, measured against
    // twice its round-off (about 1e-15 D^3 each, skinUniformRatio's note in
    // SkinIntegral.H) and at least 1e-11 (the centre of rotation on the
    // face, near a vertex: 1.4e-12 measured; 1e-5 of the skin integrals'
    // tolerance), and the expansion's side, where both evaluate the same
    // polynomial (the moments summed over the edges or kept)
    double worstClosed = 0, worstExpansion = 0;
    int faces = 0;
    for (int trial = 0; trial < 40; ++trial)
    {
        const std::vector<Vec2> polygon =
            test::hydro::randomOutline(gen, 3 + trial % 10);
        const ConvexPolyhedron prism =
            ConvexPolyhedron::prism(polygon, -0.5, 0.5 + std::abs(U(gen)));
        const PolyhedronView P = prism.view();
        const Mat3 R =
            Quat(Eigen::AngleAxisd(M_PI*U(gen), Vec3(U(gen), U(gen), U(gen)).normalized()))
           .toRotationMatrix();
        for (int f = 0; f < int(P.faces().size()); ++f)
        {
            const int m = P.faces()[f].count;
            std::vector<Vec3> q;
            for (int k = 0; k < m; ++k)
            {
                q.push_back(R*P.vertices()[P.faceVertex(f, k)]);
            }
            const Vec3 n = R*P.faces()[f].normal;
            FacePlane plane;
            ASSERT_TRUE(makeFacePlane(P, f, plane));
            const double size = std::sqrt(plane.a2);
            for (double D : {0.2, 3.0, 50.0, 99.0, 101.0, 1000.0})
            {
                const Vec3 omega(0.3*U(gen), 0.3*U(gen), 0.3*U(gen));
                const Vec3 c = R*plane.centroid;
                const Vec3 t = n.unitOrthogonal();
                // centre of rotation D radii from the centroid
                const Vec3 w =
                    D*size*std::abs(omega.dot(n))*t - omega.cross(c)
                  + 0.1*U(gen)*n;
                Vec3 I, Ir, J, Jr;
                ASSERT_TRUE(skinIntegral(q.data(), m, n, w, omega, J, Jr));
                skinIntegralOfFace(plane, R, n, w, omega, I, Ir);
                const double scale = J.norm() + (Jr - c.cross(J)).norm()/size;
                const double diff =
                    ((I - J).norm() + (Ir - Jr).norm()/size)/scale;
                if (D < skinUniformRatio)
                {
                    worstClosed = std::max
                    (
                        worstClosed, diff/(2e-15*std::max(5000.0, D*D*D))
                    );
                }
                else
                {
                    worstExpansion = std::max(worstExpansion, diff);
                }
            }
            ++faces;
        }
    }
    std::cout << "skin integrals of " << faces << " whole faces from their"
              << " planes against their world polygons, worst relative"
              << " difference: closed form " << worstClosed
              << " of its bound, expansion " << worstExpansion << std::endl;
    EXPECT_LT(worstClosed, 1.0);
    EXPECT_LT(worstExpansion, 1e-13);

    // A face beyond the plane's room is refused (the caller's general path)
    {
        std::vector<Vec2> polygon;
        const int sides = FacePlane::maxVertices + 1;
        for (int k = 0; k < sides; ++k)
        {
            const double th = 2*M_PI*k/sides;
            polygon.push_back(Vec2(3*std::cos(th), 3*std::sin(th)));
        }
        const ConvexPolyhedron prism = ConvexPolyhedron::prism(polygon, 0, 1);
        const PolyhedronView P = prism.view();
        int big = -1;
        for (int f = 0; f < int(P.faces().size()); ++f)
        {
            if (P.faces()[f].count == sides) big = f;
        }
        ASSERT_GE(big, 0);
        FacePlane plane;
        EXPECT_FALSE(makeFacePlane(P, big, plane));
        EXPECT_EQ(plane.face, -1);
    }
}


TEST(Drag, skinExpansionWithinItsBound)
{
    // skinIntegralExpansion (the skin integrals where u_t is nearly
    // uniform) against the closed form on random convex polygons in any
    // plane, the centre of rotation D = 10 to 1000 polygon radii a from the
    // centroid: the relative error of I + Ir/a stays within the derivation's
    // bound 5/8 (a/D)^4 (up to its (1 - a/D)^-2 and the closed form's own
    // round-off); the 6-point conical rule it replaced, for comparison
    std::mt19937 gen(1617);
    std::uniform_real_distribution<double> U(-1, 1);
    const std::vector<double> ratios{10, 30, 100, 200, 1000};
    std::vector<double> worstExp(ratios.size(), 0);
    std::vector<double> worstRule(ratios.size(), 0);
    for (int trial = 0; trial < 200; ++trial)
    {
        const int m = 3 + trial % 8;
        const PlanePolygon P = randomEllipsePolygon(gen, m);
        const Vec3& n = P.n;
        const Vec3& t1 = P.t1;
        const Vec3& t2 = P.t2;
        const std::vector<Vec3>& q = P.q;
        Vec3 c = Vec3::Zero();
        double area = 0;
        for (int k = 1; k + 1 < m; ++k)
        {
            const double dA =
                0.5*((q[k] - q[0]).cross(q[k + 1] - q[0])).dot(n);
            area += dA;
            c += dA/3*(q[0] + q[k] + q[k + 1]);
        }
        c /= area;
        double radius = 0;
        for (const Vec3& p : q) radius = std::max(radius, (p - c).norm());
        const Vec3 omega(0.3*U(gen), 0.3*U(gen), 0.3*U(gen));
        const double Om = std::abs(omega.dot(n));
        const double angle = M_PI*U(gen);
        const Vec3 dir = std::cos(angle)*t1 + std::sin(angle)*t2;
        for (std::size_t j = 0; j < ratios.size(); ++j)
        {
            // u_t at the centroid of size D Om a, any direction in the plane
            const Vec3 w =
                ratios[j]*radius*Om*dir - omega.cross(c) + U(gen)*n;
            Vec3 I, Ir, Ie, Ier, Ic, Icr;
            ASSERT_TRUE(skinIntegralExpansion(q.data(), m, n, w, omega, I, Ir));
            ASSERT_TRUE
            (
                skinIntegralClosedForm(q.data(), m, n, w, omega, Ie, Ier)
            );
            ASSERT_TRUE(skinIntegralConical(q.data(), m, n, w, omega, Ic, Icr));
            const double scale = Ie.norm() + (Ier - c.cross(Ie)).norm()/radius;
            const double e =
                ((I - Ie).norm() + (Ir - Ier).norm()/radius)/scale;
            const double ec =
                ((Ic - Ie).norm() + (Icr - Ier).norm()/radius)/scale;
            worstExp[j] = std::max(worstExp[j], e);
            worstRule[j] = std::max(worstRule[j], ec);
        }
    }
    std::cout << "skin expansion vs closed form, worst of 200 polygons"
              << " (D/a: expansion, bound 5/8 (a/D)^4, 6-point rule):";
    for (std::size_t j = 0; j < ratios.size(); ++j)
    {
        const double rho = 1/ratios[j];
        const double bound = 0.625*std::pow(rho, 4)/std::pow(1 - rho, 2);
        std::cout << " " << ratios[j] << ": " << worstExp[j] << ", "
                  << bound << ", " << worstRule[j] << ";";
        // The closed form's own round-off grows about as (D/a)^3 1e-16
        const double roundOff = 1e-15*std::pow(ratios[j], 3);
        EXPECT_LT(worstExp[j], bound + roundOff) << "D/a " << ratios[j];
    }
    std::cout << std::endl;
    // Where skinIntegral takes it (D/a > 100), as accurate as the rule
    EXPECT_LT(worstExp[2], 1e-8);

    // A spinning floe drifting along: the expansion conserves the exact
    // symmetries (a square, u_t along a side: I along U, no sideways part
    // to second order, only the cubic c^3 Sxxx, which vanishes for it)
    {
        const std::vector<Vec3> sq
            {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
        Vec3 I, Ir;
        ASSERT_TRUE(skinIntegralExpansion(sq.data(), 4, Vec3::UnitZ(),
            Vec3(50, 0, 0), Vec3(0, 0, 0.1), I, Ir));
        EXPECT_NEAR(I.y(), 0, 1e-12*I.norm());
        // The integrand's moment has the spin's sense (the drag, -c Ir,
        // opposes it)
        EXPECT_GT(Ir.z(), 0.0);
    }
}
