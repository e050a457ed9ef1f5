/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Wind on the floes (hydro/Wind.H) against analytic results:
      - force and moment of a uniform relative wind equal the sum of the
        facet forces at their centroids (exact: the sample points integrate
        a uniform load exactly), computed here independently, on a
        symmetric floe (no yaw) and an asymmetric one (yaw moment);
      - free drift: a square prism floe at its draft in still water under a
        uniform wind along a side or a diagonal reaches the speed where the
        air drag balances the water drag,
            K_a |U_a - u|^2 = K_w |u|^2,
            u = U_a sqrt(K_a)/(sqrt(K_a) + sqrt(K_w)),
        K_a = rho_a (C_sa L^2 s + 1/2 C_fa L f),
        K_w = 1/2 rho_w (C_fw L d + C_sw L^2 s),
        with d = rho_i/rho_w h the draft, f = h - d the freeboard, and
        s = 1 along a side, s = sqrt(2) along a diagonal (the skin drag
        sees |w| w, the form drag each leading side w_n^2); no spin;
      - the same for a sparse field of floes of several sizes (no contacts);
      - a wind table is interpolated linearly; errors name the entry;
      - the exact integration (closed forms over the water frame's dry
        polygons) against the sampled sums on random poses, and the frame
        shared with the water's models;
      - 1 thread = 2 threads and restart = uninterrupted run, bit for bit,
        with wind (a turning table), buoyancy, drag and floe damping on.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "hydro/Buoyancy.H"
#include "hydro/Drag.H"
#include "hydro/FloeDamping.H"
#include "hydro/FlowVelocity.H"
#include "hydro/WaterFrame.H"
#include "hydro/Wind.H"
#include "hydroFixtures.H"
#include "testWorlds.H"

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
using test::expectSameState;
using test::restartFrom;

//- World of prism floes (true size: the outer polyhedron is the prism of
//  the given polygon, bottom zb, height h)
struct WindWorld
:
    test::hydro::BoxWorld
{
    using BoxWorld::BoxWorld;

    //- Box Lx x Ly x h with its bottom at zb
    int addBox
    (
        double Lx, double Ly, double h, double zb,
        const Vec3& centre = Vec3::Zero(),
        const Vec3& v = Vec3::Zero()
    )
    {
        return BoxWorld::addBox
        (
            Lx, Ly, h, zb, centre, Quat::Identity(), v, Vec3::Zero()
        );
    }

    void addWater
    (
        const WindSettings& ws,
        const WindHistory& wind,
        bool damping = true
    )
    {
        const WaterSettings water{rhoWater, 0};
        world->addForceModel(std::make_shared<Buoyancy>(water));
        world->addForceModel
        (
            std::make_shared<Drag>
            (
                water, DragSettings(),
                std::make_shared<UniformCurrent>(Vec3::Zero())
            )
        );
        world->addForceModel(std::make_shared<Wind>(water, ws, wind));
        if (damping)
        {
            world->addForceModel
            (
                std::make_shared<FloeDamping>(water, FloeDampingSettings())
            );
        }
    }
};

//- Analytic free-drift speed of a square floe L x L x h at its draft
//  under the wind Ua along a side (s = 1) or a diagonal (s = sqrt 2):
//  the speed along the wind
double freeDriftSpeed
(
    double L, double h, double Ua, double s,
    const WindSettings& ws, const DragSettings& ds
)
{
    const double d = rhoIce/rhoWater*h;
    const double f = h - d;
    const double Ka =
        ws.rhoAir*(ws.skinCoefficient*L*L*s + 0.5*ws.formCoefficient*L*f);
    const double Kw =
        0.5*rhoWater*(ds.formCoefficient*L*d + ds.skinCoefficient*L*L*s);
    return Ua*std::sqrt(Ka)/(std::sqrt(Ka) + std::sqrt(Kw));
}

} // anonymous namespace


TEST(Wind, settingsErrorsNameTheEntry)
{
    const WaterSettings w;
    WindSettings s;
    s.rhoAir = -1;
    expectError([&]{ Wind m(w, s, WindHistory()); }, "rhoAir");
    s = WindSettings();
    s.skinCoefficient = -1e-3;
    expectError([&]{ Wind m(w, s, WindHistory()); }, "Cs");
    s = WindSettings();
    s.formCoefficient = std::nan("");
    expectError([&]{ Wind m(w, s, WindHistory()); }, "Cf");
    s = WindSettings();
    s.subdivision = DragSettings::maxSubdivision + 1;
    expectError([&]{ Wind m(w, s, WindHistory()); }, "subdivision");
    s = WindSettings();
    s.topCosine = 0;
    expectError([&]{ Wind m(w, s, WindHistory()); }, "topCosine");

    expectError
    (
        [&]{ WindHistory h(Vec3(std::nan(""), 0, 0)); }, "table"
    );
    expectError
    (
        [&]{ WindHistory h({{0, Vec3(1, 0, 0)}, {0, Vec3(0, 1, 0)}}); },
        "table"
    );
    expectError
    (
        [&]
        {
            WindHistory h
            ({{0, Vec3(1, 0, 0)}, {INFINITY, Vec3(0, 1, 0)}});
        },
        "table"
    );
    expectError
    (
        [&]{ WindHistory h(std::vector<std::pair<double, Vec3>>{}); },
        "table"
    );

    // Documented defaults
    EXPECT_EQ(WindSettings().rhoAir, 1.3);
    EXPECT_EQ(WindSettings().skinCoefficient, 1.5e-3);
    EXPECT_EQ(WindSettings().formCoefficient, 1.0);
    EXPECT_EQ(WindHistory().at(3), Vec3::Zero());
}


TEST(Wind, tableIsInterpolatedLinearly)
{
    const WindHistory h
    ({
        {0, Vec3(10, 0, 0)}, {600, Vec3(0, 10, 0)}, {700, Vec3(0, 10, 0)}
    });
    EXPECT_EQ(h.at(-5), Vec3(10, 0, 0));
    EXPECT_EQ(h.at(0), Vec3(10, 0, 0));
    EXPECT_NEAR((h.at(150) - Vec3(7.5, 2.5, 0)).norm(), 0, 1e-12);
    EXPECT_NEAR((h.at(300) - Vec3(5, 5, 0)).norm(), 0, 1e-12);
    EXPECT_EQ(h.at(650), Vec3(0, 10, 0));
    EXPECT_EQ(h.at(1e6), Vec3(0, 10, 0));
}


namespace
{

//- Force and moment about G of a uniform relative wind w (floe relative
//  to the air) on a vertical prism with polygon 'poly' (counter-clockwise,
//  body = world frame), bottom zb, height h, centroid G, water level 0:
//  each side's emerged rectangle (height ztop) carries form drag at its
//  centroid where it leads, the top skin drag at the polygon's centroid
void facetSum
(
    const std::vector<Vec2>& poly, double zb, double h, const Vec3& G,
    const Vec3& w, const WindSettings& ws, Vec3& F, Vec3& M
)
{
    F.setZero();
    M.setZero();
    const double ztop = zb + h;
    const int n = static_cast<int>(poly.size());
    // Top: area and centroid of the polygon
    double A = 0;
    Vec2 c = Vec2::Zero();
    for (int k = 0; k < n; ++k)
    {
        const Vec2& p = poly[k];
        const Vec2& q = poly[(k + 1) % n];
        const double cr = p.x()*q.y() - q.x()*p.y();
        A += 0.5*cr;
        c += cr*(p + q)/6;
    }
    c /= A;
    const Vec3 wt(w.x(), w.y(), 0);
    const Vec3 Fs = -ws.rhoAir*ws.skinCoefficient*A*wt.norm()*wt;
    F += Fs;
    M += (Vec3(c.x(), c.y(), ztop) - G).cross(Fs);
    // Sides above z = 0
    for (int k = 0; k < n; ++k)
    {
        const Vec2& p = poly[k];
        const Vec2& q = poly[(k + 1) % n];
        const Vec2 e = q - p;
        const Vec3 nrm = Vec3(e.y(), -e.x(), 0).normalized();
        const double wn = w.dot(nrm);
        if (wn <= 0) continue;
        const double area = e.norm()*ztop;
        const Vec3 Ff = -0.5*ws.rhoAir*ws.formCoefficient*area*wn*wn*nrm;
        const Vec2 mid = 0.5*(p + q);
        F += Ff;
        M += (Vec3(mid.x(), mid.y(), 0.5*ztop) - G).cross(Ff);
    }
}

} // anonymous namespace


TEST(Wind, forceAndMomentAreTheSumOfFacetForces)
{
    WindSettings ws;
    ws.skinCoefficient = 2e-3;
    ws.formCoefficient = 0.8;

    // A symmetric square floe along a side and along a diagonal: no yaw.
    // An asymmetric (trapezoidal) floe at an oblique wind: a yaw moment,
    // equal to the facet sum.
    const double h = 1, zb = -0.9;
    const std::vector<std::vector<Vec2>> polys =
    {
        {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}},
        {{-3, -1}, {2, -2}, {1.5, 2.5}, {-2.5, 1.5}}
    };
    const std::vector<Vec3> winds =
        {Vec3(12, 0, 0), Vec3(8, 8, 0), Vec3(-5, 9, 0)};

    for (std::size_t p = 0; p < polys.size(); ++p)
    {
        for (const Vec3& Ua : winds)
        {
            for (int sub : {-1, 0, 2})
            {
                // -1: the exact integration (default), else sampled
                ws.integration =
                    sub < 0 ? DragIntegration::exact : DragIntegration::sampled;
                ws.subdivision = std::max(sub, 0);
                // No dilation: the core is the outer polyhedron
                WindWorld ww(1e-3, Vec3::Zero());
                const int shape = ww.world->addShape
                (
                    DilatedShape
                    (
                        ConvexPolyhedron::prism(polys[p], zb, h), 1e-12
                    )
                );
                ww.world->addBody(shape, ww.ice, Vec3::Zero(), Quat::Identity());
                const Body& b = ww.body(0);
                const Wind wind(WaterSettings{rhoWater, 0}, ws, WindHistory(Ua));
                Vec3 F, M;
                wind.bodyWind(*ww.world, 0, Ua, F, M);

                // The input frame sits at the origin: the world polygon is
                // the input polygon, G the body's centroid
                Vec3 Fe, Me;
                facetSum(polys[p], zb, h, b.x, -Ua, ws, Fe, Me);

                SCOPED_TRACE("polygon " + std::to_string(p) + ", subdivision "
                    + std::to_string(sub));
                // The outer polyhedron is the prism offset by the dilation
                // radius 1e-12 m: relative differences of order 1e-11 on
                // the 0.1 m freeboard
                EXPECT_NEAR((F - Fe).norm(), 0, 1e-10*Fe.norm());
                EXPECT_NEAR((M - Me).norm(), 0, 1e-10*Me.norm());
                if (p == 0)
                {
                    // Symmetric: no yaw to round-off
                    EXPECT_NEAR(M.z(), 0, 1e-12*Me.norm());
                }
                else
                {
                    EXPECT_GT(std::abs(M.z()), 1e-3*Me.norm());
                }
            }
        }
    }

    // Nothing above water: no wind
    WindWorld sunk(1e-3, Vec3::Zero());
    sunk.addBox(4, 4, 1, -1.2);
    const Wind wind(WaterSettings{rhoWater, 0}, WindSettings(), WindHistory());
    Vec3 F, M;
    wind.bodyWind(*sunk.world, 0, Vec3(10, 0, 0), F, M);
    EXPECT_EQ(F.norm(), 0.0);
}


TEST(Wind, freeDriftSingleFloe)
{
    const SingleThread oneThread;
    const double L = 10, h = 1;
    const double d = rhoIce/rhoWater*h;
    const double Ua = 15;
    const WindSettings ws;

    for (bool diagonal : {false, true})
    {
        const Vec3 dir =
            diagonal ? Vec3(1, 1, 0).normalized() : Vec3(1, 0, 0);
        WindWorld ww(0.02);
        ww.addBox(L, L, h, -d);
        ww.addWater(ws, WindHistory(Ua*dir));

        const double u = freeDriftSpeed
        (
            L, h, Ua, diagonal ? std::sqrt(2.0) : 1.0, ws, DragSettings()
        );
        ww.world->advanceTo(600);
        const Vec3 v = ww.body(0).v;
        const double along = v.dot(dir);
        const double across = (v - along*dir).head<2>().norm();
        const double err = std::abs(along/u - 1);
        std::cout << "free drift (" << (diagonal ? "diagonal" : "side")
                  << "): U_a " << Ua << " m/s, analytic u = " << u
                  << " m/s (" << 100*u/Ua << " % of the wind), simulated "
                  << along << " m/s, relative error " << err
                  << ", across " << across << " m/s, spin "
                  << ww.body(0).omega().z() << " rad/s" << std::endl;
        EXPECT_LT(err, 0.02);
        EXPECT_LT(across, 1e-6*u);
        EXPECT_LT(std::abs(ww.body(0).omega().z()), 1e-9);
    }
}


TEST(Wind, freeDriftObliqueWindSpeedAndDirection)
{
    // A rectangular floe Lx x Ly under a wind at 30 deg to its long side:
    // the form drag acts on each leading side separately (per axis), the
    // skin drag along the relative velocity, so the drift is not along the
    // wind. The steady velocity u solves, with W = U_a - u,
    //   rho_a C_s A |W| W + 1/2 rho_a C_f f (Ly W_x|W_x|, Lx W_y|W_y|)
    // = 1/2 rho_w C_s,w A |u| u + 1/2 rho_w C_f,w d (Ly u_x|u_x|, Lx u_y|u_y|)
    // (A = Lx Ly; every force acts on a centre line: no yaw), solved here
    // by Newton's method; speed and direction within 2 %.
    const SingleThread oneThread;
    const double Lx = 14, Ly = 6, h = 1.2;
    const double d = rhoIce/rhoWater*h, f = h - d, A = Lx*Ly;
    const WindSettings ws;
    const DragSettings ds;
    const double ang = 30*M_PI/180;
    const Vec2 Ua = 15*Vec2(std::cos(ang), std::sin(ang));

    auto residual = [&](const Vec2& u) -> Vec2
    {
        const Vec2 W = Ua - u;
        const Vec2 air =
            ws.rhoAir*ws.skinCoefficient*A*W.norm()*W
          + 0.5*ws.rhoAir*ws.formCoefficient*f
           *Vec2(Ly*W.x()*std::abs(W.x()), Lx*W.y()*std::abs(W.y()));
        const Vec2 water =
            0.5*rhoWater*ds.skinCoefficient*A*u.norm()*u
          + 0.5*rhoWater*ds.formCoefficient*d
           *Vec2(Ly*u.x()*std::abs(u.x()), Lx*u.y()*std::abs(u.y()));
        return air - water;
    };
    Vec2 u = 0.015*Ua;
    for (int it = 0; it < 50; ++it)
    {
        const Vec2 r = residual(u);
        Eigen::Matrix2d J;
        const double e = 1e-7;
        for (int c = 0; c < 2; ++c)
        {
            Vec2 du = Vec2::Zero();
            du[c] = e;
            J.col(c) = (residual(u + du) - residual(u - du))/(2*e);
        }
        u -= J.partialPivLu().solve(r);
    }
    ASSERT_LT(residual(u).norm(), 1e-9);

    WindWorld ww(0.02);
    ww.addBox(Lx, Ly, h, -d);
    ww.addWater(ws, WindHistory(Vec3(Ua.x(), Ua.y(), 0)));
    ww.world->advanceTo(600);
    const Vec2 v = ww.body(0).v.head<2>();
    const double speedErr = std::abs(v.norm()/u.norm() - 1);
    const double dirErr =
        std::abs(std::atan2(v.y(), v.x()) - std::atan2(u.y(), u.x()));
    const double windDir = std::atan2(Ua.y(), Ua.x());
    std::cout << "oblique wind at 30 deg: analytic drift " << u.norm()
              << " m/s at " << std::atan2(u.y(), u.x())*180/M_PI
              << " deg, simulated " << v.norm() << " m/s at "
              << std::atan2(v.y(), v.x())*180/M_PI << " deg; errors: speed "
              << speedErr << ", direction " << dirErr*180/M_PI << " deg"
              << std::endl;
    EXPECT_LT(speedErr, 0.02);
    // Direction within 2 % of the deviation from the wind plus round-off
    EXPECT_LT
    (
        dirErr,
        0.02*std::abs(std::atan2(u.y(), u.x()) - windDir) + 1e-9
    );
    EXPECT_LT(std::abs(ww.body(0).omega().z()), 1e-6);
}


TEST(Wind, freeDriftSparseField)
{
    const SingleThread oneThread;
    const double Ua = 15;
    const Vec3 dir(1, 0, 0);
    const WindSettings ws;
    const std::vector<std::pair<double, double>> sizes =
        {{4, 0.6}, {6, 0.8}, {8, 1.2}, {12, 1.5}, {5, 1.0}};

    WindWorld ww(0.02);
    for (std::size_t k = 0; k < sizes.size(); ++k)
    {
        const double L = sizes[k].first, h = sizes[k].second;
        ww.addBox(L, L, h, -rhoIce/rhoWater*h, Vec3(0, 40.0*k, 0));
    }
    ww.addWater(ws, WindHistory(Ua*dir));
    int contacts = 0;
    while (ww.world->time() < 600 - 1e-9)
    {
        ww.world->advanceTo(ww.world->time() + 10);
        contacts = std::max(contacts, ww.world->contactCount());
    }
    EXPECT_EQ(contacts, 0);
    double worst = 0;
    for (std::size_t k = 0; k < sizes.size(); ++k)
    {
        const double u = freeDriftSpeed
        (
            sizes[k].first, sizes[k].second, Ua, 1.0, ws, DragSettings()
        );
        const Vec3 v = ww.body(k).v;
        const double err = std::abs(v.x()/u - 1);
        worst = std::max(worst, err);
        std::cout << "field floe " << k << " (" << sizes[k].first << " m, "
                  << sizes[k].second << " m): analytic " << u
                  << " m/s, simulated " << v.x() << " m/s, error " << err
                  << std::endl;
        EXPECT_LT(err, 0.02);
        EXPECT_LT(std::abs(v.y()), 1e-6*u);
    }
    std::cout << "sparse field: largest relative error " << worst << std::endl;
}


TEST(Wind, independentOfThreadCount)
{
    // 1200 floes: the body-force models run on the threads' chunks
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    auto a = windyFloeField(1200, 5);
    a->advanceTo(0.1);
    omp_set_num_threads(std::max(2, threads));
    auto b = windyFloeField(1200, 5);
    b->advanceTo(0.1);
    omp_set_num_threads(threads);
    EXPECT_GT(a->contactPairCount() + a->contactCount(), 0);
    expectSameState(*a, *b);
}


TEST(Wind, restartEqualsUninterruptedRun)
{
    // The wind turns over the run (table): a restart must pick it up at
    // the restart time. As in the solvers, both runs stop at the write time
    // (advanceTo snaps the time to it), the restarted one starts there.
    const double cut = 0.3;
    auto a = windyFloeField(100, 11);
    a->advanceTo(cut);
    a->advanceTo(0.8);

    auto b = windyFloeField(100, 11);
    b->advanceTo(cut);
    auto c = windyFloeField(100, 11);
    restartFrom(*c, *b);
    c->advanceTo(0.8);
    EXPECT_GT(b->contactCount(), 0);
    expectSameState(*a, *c);
}


TEST(Wind, bluffBodyForceOfTheHull)
{
    // F = 1/2 rho_a C_d A |w| w, w the horizontal part of U_a - v
    const Vec3 Ua(12, -5, 3);       // a vertical component is ignored
    const Vec3 v(0.5, 0.2, -0.1);
    const double rho = 1.3, Cd = 0.9, A = 2500;
    const Vec3 F = bluffWindForce(rho, Cd, A, Ua, v);
    const Vec3 w(11.5, -5.2, 0);
    const Vec3 expected = 0.5*rho*Cd*A*w.norm()*w;
    EXPECT_NEAR((F - expected).norm(), 0, 1e-12*expected.norm());
    EXPECT_EQ(F.z(), 0.0);
    // Moving with the wind: no force
    EXPECT_EQ(bluffWindForce(rho, Cd, A, Ua, Vec3(12, -5, 0)).norm(), 0.0);
}


TEST(Wind, samplingOfASpinningFloeConverges)
{
    // A 10 x 10 x 1 floe at its draft spinning at 0.05 rad/s (0.35 m/s at
    // the corners) and drifting in a 15 m/s wind: the relative wind varies
    // across the floe, so the sampled force and moment depend on the
    // subdivision. The error against the finest sampling falls with every
    // refinement (second order: about 4x per level); the default (1) is
    // within 1e-4 of it in force and 2 % in moment (the moment about G is a
    // small difference of large facet moments), which is what the default
    // trades for half the cost of subdivision 2.
    const double h = 1, d = rhoIce/rhoWater*h;
    const Vec3 Ua(15, 5, 0);
    auto load = [&](int sub, Vec3& F, Vec3& M)
    {
        WindSettings ws;
        ws.integration = DragIntegration::sampled;
        ws.subdivision = sub;
        WindWorld ww(1e-3, Vec3::Zero());
        const int shape = ww.world->addShape
        (
            DilatedShape
            (
                ConvexPolyhedron::prism
                (
                    {{-5 + radius, -5 + radius}, {5 - radius, -5 + radius},
                     {5 - radius, 5 - radius}, {-5 + radius, 5 - radius}},
                    -d + radius, h - 2*radius
                ),
                radius
            )
        );
        ww.world->addBody
        (
            shape, ww.ice, Vec3::Zero(),
            Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())),
            Vec3(0.2, 0.05, 0), Vec3(0, 0, 0.05)
        );
        const Wind wind(WaterSettings{rhoWater, 0}, ws, WindHistory(Ua));
        wind.bodyWind(*ww.world, 0, Ua, F, M);
    };
    const int finest = DragSettings::maxSubdivision;
    Vec3 Ff, Mf;
    load(finest, Ff, Mf);
    std::vector<double> eF, eM;
    for (int sub = 0; sub < finest; ++sub)
    {
        Vec3 F, M;
        load(sub, F, M);
        eF.push_back((F - Ff).norm()/Ff.norm());
        eM.push_back((M - Mf).norm()/Mf.norm());
        std::cout << "spinning floe in wind: subdivision " << sub
                  << ": relative difference from " << finest << ": force "
                  << eF.back() << ", moment " << eM.back() << std::endl;
    }
    for (std::size_t k = 1; k < eF.size(); ++k)
    {
        EXPECT_LT(eF[k], eF[k - 1]);
        EXPECT_LT(eM[k], eM[k - 1]);
    }
    const int def = WindSettings().subdivision;
    EXPECT_LT(eF[def], 1e-4);
    EXPECT_LT(eM[def], 0.02);
}


TEST(Wind, exactAgreesWithSampledOnRandomPoses)
{
    // The closed forms (integration exact: the frame's dry polygons, the
    // drag's addFacetDrag) against the sampled sums on random poses of box
    // floes (nearly level, or any attitude: on edge, mostly in the air),
    // random drift, spin and wind. The form drag of the freeboard is exact,
    // so the sampled sums converge to it at the rate h^2 (a factor about 4
    // per subdivision); the skin drag of the top against the Richardson
    // limit (4 S_4 - S_3)/3 of the sampled sums. Relative error of
    // force + moment/size.
    const SingleThread oneThread;
    std::mt19937 gen(61);
    std::uniform_real_distribution<double> U(-1, 1);

    ExactVsSampled stats;
    constexpr int nSub = ExactVsSampled::nSub;

    for (int trial = 0; trial < 200; ++trial)
    {
        WindWorld ww(1e-3, Vec3::Zero());
        const double Lx = 2 + 3*std::abs(U(gen));
        const double Ly = 2 + 3*std::abs(U(gen));
        ww.addBox(Lx, Ly, 1, -0.5);
        // Spins from slow (the relative wind nearly uniform) to fast
        const double spin = trial % 3 == 0 ? 2.0 : 0.3;
        randomHydroPose(ww.world->bodies()[0], gen, trial % 2, spin);
        const Vec3 Ua(20*U(gen), 20*U(gen), 0);
        const double size = std::max(Lx, Ly);

        auto wind = [&](bool form, DragIntegration integration, int sub,
                        Vec3& F, Vec3& M)
        {
            WindSettings ws;
            ws.formCoefficient = form ? 1.0 : 0.0;
            ws.skinCoefficient = form ? 0.0 : 1.5e-3;
            ws.integration = integration;
            ws.subdivision = sub;
            const Wind wd(WaterSettings{rhoWater, 0}, ws, WindHistory(Ua));
            wd.bodyWind(*ww.world, 0, Ua, F, M);
        };
        // skipped: overwashed, nothing leading or no top in the air
        stats.add(wind, size);
    }

    ASSERT_GT(stats.nPoses, 100);
    stats.print("wind", "skin");

    // The sampled form drag converges to the closed form at the rate h^2
    for (int sub = 1; sub < nSub; ++sub)
    {
        EXPECT_GT(stats.formRms(sub - 1)/stats.formRms(sub), 3.0)
            << "subdivision " << sub;
    }
    EXPECT_LT(stats.formRms(nSub - 1), 1e-3);
    // The skin drag: the closed form within the Richardson limit's own
    // error (of order the last correction, skinSq[4]/skinSq[3] ~ 1/16
    // of subdivision 4's), far below the default sampling (subdivision 1)
    EXPECT_LT(stats.exactRms(), 0.1*stats.skinRms(nSub - 1));
    EXPECT_LT(stats.exactMax, 0.1*stats.skinMax[nSub - 1]);
}


TEST(Wind, exactSharesTheWaterFrame)
{
    // The wind's exact path reads the dry polygons of the same frame as
    // buoyancy, drag and floe damping: called first (the frame computed for
    // it) or after the drag has recomputed the frame (the slot held another
    // floe's) it gives the same force bit for bit, and the
    // dry polygons' area is the faces' area minus the wet polygons' area
    // (the two sides of one clip) on random poses
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> U(-1, 1);
    for (int trial = 0; trial < 50; ++trial)
    {
        WindWorld ww(1e-3, Vec3::Zero());
        ww.addBox(4 + U(gen), 3 + U(gen), 1, -0.5);
        // A second floe: its frame replaces the first one's in the slot
        ww.addBox(3, 3, 1, -0.5, Vec3(50, 0, 0));
        Body& b = ww.world->bodies()[0];
        b.q = Quat(Eigen::AngleAxisd
        (
            (trial % 2 ? 0.2 : M_PI)*U(gen),
            Vec3(U(gen), U(gen), U(gen)).normalized()
        ));
        b.x = Vec3(U(gen), U(gen), 0.8*U(gen));
        b.setOmega(Vec3(0.1*U(gen), 0.1*U(gen), 0.5*U(gen)));
        const Vec3 Ua(15, 5*U(gen), 0);
        const WaterSettings water{rhoWater, 0};
        const Wind wind(water, WindSettings(), WindHistory(Ua));
        Vec3 F1, M1, F2, M2;
        wind.bodyWind(*ww.world, 0, Ua, F1, M1);
        // The frame as the water's models leave it (wet side first)
        const Drag drag
        (
            water, DragSettings(), std::make_shared<UniformCurrent>(Vec3::Zero())
        );
        Vec3 Fd, Md;
        drag.bodyDrag(*ww.world, 1, Fd, Md);
        drag.bodyDrag(*ww.world, 0, Fd, Md);
        wind.bodyWind(*ww.world, 0, Ua, F2, M2);
        EXPECT_EQ(F1, F2);
        EXPECT_EQ(M1, M2);

        PolyhedronBuffer buf;
        const PolyhedronView P = ww.world->shapeOf(0).outer(buf);
        const WaterFrame& frame = waterFrame(*ww.world, 0, water.level);
        ASSERT_TRUE(frameDry(P, frame));
        auto area = [&](const Vec3* q, int m, const Vec3& n)
        {
            double a = 0;
            for (int k = 1; k + 1 < m; ++k)
            {
                a += 0.5*((q[k] - q[0]).cross(q[k + 1] - q[0])).dot(n);
            }
            return a;
        };
        double total = 0, wet = 0, dry = 0;
        for (int f = 0; f < int(P.faces().size()); ++f)
        {
            Vec3 q[SubmergedFace::maxVertices];
            const int m = P.faces()[f].count;
            for (int k = 0; k < m; ++k) q[k] = frame.r[P.faceVertex(f, k)];
            total += area(q, m, frame.R*P.faces()[f].normal);
        }
        for (int k = 0; k < frame.nWet; ++k)
        {
            wet += area
            (
                frame.wetVertex + frame.wetBegin[k],
                frame.wetBegin[k + 1] - frame.wetBegin[k],
                frame.R*P.faces()[frame.wetFace[k]].normal
            );
        }
        for (int k = 0; k < frame.nDry; ++k)
        {
            dry += area
            (
                frame.dryVertex + frame.dryBegin[k],
                frame.dryBegin[k + 1] - frame.dryBegin[k],
                frame.R*P.faces()[frame.dryFace[k]].normal
            );
        }
        EXPECT_NEAR(wet + dry, total, 1e-12*total) << "trial " << trial;
    }
}
