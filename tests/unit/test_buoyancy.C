/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Buoyancy (hydro/Buoyancy.H) of floes built as in the case files (core =
    outline shrunk by r, thickness h - 2r; massModel faceted), against the
    analytic hydrostatics of a box-shaped floe (method.md 7.5):
      - force rho_w g V at a given draft, no moment when level;
      - righting moment of a heeled wall-sided floe,
        GZ = sin(theta) (GM + BM/2 tan^2(theta)), GM = d/2 + B^2/(12 d) - h/2;
      - free heave: oscillation about the draft (rho_i/rho_w) h with the
        period 2 pi sqrt(d/g) (no added mass, no drag);
      - free roll: period 2 pi sqrt(I/(m g GM)), the floe rights itself;
      - with a linear damper (a test model, since drag does not damp heave
        or roll) a heeled floe dropped from too small a draft settles level
        at the draft.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "hydro/Buoyancy.H"
#include "hydroFixtures.H"

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

//- Single-floe world: a box floe Lx x Ly x h (true size), bottom at zb,
//  centred on the z-axis in its input frame, placed with orientation Q
//  about the input origin
struct FloeWorld
{
    std::unique_ptr<World> world;
    int body = -1;

    FloeWorld
    (
        double Lx,
        double Ly,
        double h,
        double zb,
        const Quat& Q = Quat::Identity(),
        double dt = 1e-3,
        const Vec3& gravity = Vec3(0, 0, -g)
    )
    {
        test::hydro::BoxWorld w(dt, gravity, 1e9);
        body = w.addBox
        (
            Lx, Ly, h, zb, Vec3::Zero(), Q, Vec3::Zero(), Vec3::Zero()
        );
        world = std::move(w.world);
    }

    const Body& floe() const { return world->bodies()[body]; }

    //- Orientation of the floe's input frame
    Quat inputOrientation() const
    {
        return floe().q*world->shapeOf(body).principalToInput().inverse();
    }

    //- Angle between the floe's vertical and the world's
    double tilt() const
    {
        const Vec3 up = inputOrientation()*Vec3::UnitZ();
        return std::atan2(up.head<2>().norm(), up.z());
    }
};

//- Linear damper of translation and rotation, F = -c m v, M = -c L: a
//  test stand-in for the wave radiation damping the DEM does not model
class LinearDamper
:
    public BodyForceModel
{
    double rate_;

public:

    explicit LinearDamper(double rate) : rate_(rate) {}

    const char* name() const override { return "linearDamper"; }

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
            force[i] -= rate_*b.mass*b.v;
            torque[i] -= rate_*b.L;
        }
    }
};


} // anonymous namespace


TEST(Buoyancy, settingsErrorsNameTheEntry)
{
    try
    {
        Buoyancy b(WaterSettings{-1025, 0});
        FAIL() << "negative density accepted";
    }
    catch (const Error& e)
    {
        EXPECT_EQ(e.entry(), "density");
    }
    try
    {
        Buoyancy b(WaterSettings{1025, std::nan("")});
        FAIL() << "non-finite level accepted";
    }
    catch (const Error& e)
    {
        EXPECT_EQ(e.entry(), "level");
    }
    EXPECT_NO_THROW(Buoyancy(WaterSettings{}));
    EXPECT_EQ(WaterSettings{}.density, 1025);
    EXPECT_EQ(WaterSettings{}.level, 0);
}


TEST(Buoyancy, forceAtGivenDraft)
{
    // 3 x 2 x 1 floe, bottom 0.6 below a water level of 0.25
    const double level = 0.25;
    FloeWorld fw(3, 2, 1, level - 0.6);
    Buoyancy model(WaterSettings{rhoWater, level});

    std::vector<Vec3> F(1, Vec3::Zero()), M(1, Vec3::Zero());
    model.addForces(*fw.world, 0, 1, F.data(), M.data());

    const double expected = rhoWater*g*3*2*0.6;
    EXPECT_NEAR(F[0].z(), expected, 1e-12*expected);
    EXPECT_NEAR(F[0].head<2>().norm(), 0, 1e-12*expected);
    EXPECT_NEAR(M[0].norm(), 0, 1e-12*expected);

    // Out of the water: nothing; no gravity: nothing
    FloeWorld dry(3, 2, 1, level + 0.01);
    F[0].setZero();
    model.addForces(*dry.world, 0, 1, F.data(), M.data());
    EXPECT_EQ(F[0].norm(), 0.0);

    FloeWorld noG(3, 2, 1, level - 0.6, Quat::Identity(), 1e-3, Vec3::Zero());
    F[0].setZero();
    model.addForces(*noG.world, 0, 1, F.data(), M.data());
    EXPECT_EQ(F[0].norm(), 0.0);
}


TEST(Buoyancy, wallSidedRightingMoment)
{
    // Floe B = 2 (y) by 3 (x) by h = 1 at its draft d, heeled by theta about
    // the x-axis through the centre of its water plane: a wall-sided floe
    // keeps its displacement, and (deck dry, bottom wet)
    //   GZ = sin(theta) (GM + BM/2 tan^2 theta),  BM = B^2/(12 d),
    //   GM = KB + BM - KG = d/2 + BM - h/2.
    const double B = 2, L = 3, h = 1;
    const double d = rhoIce/rhoWater*h;
    const double BM = B*B/(12*d);
    const double GM = d/2 + BM - h/2;
    ASSERT_GT(GM, 0);
    Buoyancy model(WaterSettings{rhoWater, 0});

    for (double theta : {0.02, 0.05, 5*M_PI/180})
    {
        ASSERT_LT(0.5*B*std::tan(theta), h - d);   // deck stays dry
        FloeWorld fw(L, B, h, -d, Quat(Eigen::AngleAxisd(theta, Vec3::UnitX())));

        std::vector<Vec3> F(1, Vec3::Zero()), M(1, Vec3::Zero());
        model.addForces(*fw.world, 0, 1, F.data(), M.data());

        const double W = rhoWater*g*L*B*d;
        const double GZ =
            std::sin(theta)*(GM + 0.5*BM*std::tan(theta)*std::tan(theta));
        SCOPED_TRACE("theta " + std::to_string(theta));
        EXPECT_NEAR(F[0].z(), W, 1e-12*W);
        // Heel about +x lifts the +y side: the moment turns it back
        EXPECT_NEAR(M[0].x(), -W*GZ, 1e-10*W*GZ);
        EXPECT_NEAR(M[0].y(), 0, 1e-10*W*GZ);
        EXPECT_NEAR(M[0].z(), 0, 1e-10*W*GZ);
    }
}


TEST(Buoyancy, heavePeriodAndDraft)
{
    const SingleThread oneThread;

    // 4 x 4 x 1 floe released at rest at 90 % of its draft: it oscillates
    // about the draft d = (rho_i/rho_w) h with the period 2 pi sqrt(d/g)
    // (wall-sided: the heave stiffness is linear while partly submerged)
    const double h = 1;
    const double d = rhoIce/rhoWater*h;
    FloeWorld fw(4, 4, h, -0.9*d);
    fw.world->addForceModel(std::make_shared<Buoyancy>(WaterSettings{rhoWater, 0}));

    const double zEq = 0.5*h - d;       // centroid height at the draft
    const double T = 2*M_PI*std::sqrt(d/g);

    std::vector<double> t, z;
    double zMin = 1e9, zMax = -1e9, tiltMax = 0;
    while (fw.world->time() < 4.5*T)
    {
        fw.world->step();
        // A world with a model keeps the box's derived outer polyhedron
        ASSERT_TRUE(fw.world->shapes()[0].outerKept());
        t.push_back(fw.world->time());
        z.push_back(fw.floe().x.z() - zEq);
        zMin = std::min(zMin, fw.floe().x.z());
        zMax = std::max(zMax, fw.floe().x.z());
        tiltMax = std::max(tiltMax, fw.tilt());
    }

    const std::vector<double> c = upCrossings(t, z);
    ASSERT_GE(c.size(), 4u);
    const double period = meanPeriod(c);
    std::cout << "heave period " << period << " s, analytic " << T
              << " s; draft from the mean position "
              << 0.5*h - 0.5*(zMin + zMax) << " m, analytic " << d << " m"
              << std::endl;
    EXPECT_NEAR(period, T, 0.03*T);

    // Oscillates about the draft, and stays level
    EXPECT_NEAR(0.5*h - 0.5*(zMin + zMax), d, 0.01*d);
    EXPECT_LT(tiltMax, 1e-9);
}


TEST(Buoyancy, rollPeriodAndRighting)
{
    const SingleThread oneThread;

    // 4 x 4 x 1 floe at its draft, heeled by 3 deg (deck dry) and released:
    // it rolls back through level (rights itself) with the small-angle
    // period 2 pi sqrt(I/(m g GM)), I = m (B^2 + h^2)/12
    const double B = 4, h = 1;
    const double d = rhoIce/rhoWater*h;
    const double GM = d/2 + B*B/(12*d) - h/2;
    const double theta0 = 3*M_PI/180;
    ASSERT_LT(0.5*B*std::tan(theta0), h - d);
    const double T = 2*M_PI*std::sqrt((B*B + h*h)/12/(g*GM));

    FloeWorld fw(B, B, h, -d, Quat(Eigen::AngleAxisd(theta0, Vec3::UnitX())));
    fw.world->addForceModel(std::make_shared<Buoyancy>(WaterSettings{rhoWater, 0}));

    // Signed heel: the y-component of the floe's vertical
    std::vector<double> t, heel;
    double heelMax = 0;
    while (fw.world->time() < 4.5*T)
    {
        fw.world->step();
        const Vec3 up = fw.inputOrientation()*Vec3::UnitZ();
        t.push_back(fw.world->time());
        heel.push_back(-std::asin(up.y()));
        heelMax = std::max(heelMax, std::abs(heel.back()));
    }

    const std::vector<double> c = upCrossings(t, heel);
    ASSERT_GE(c.size(), 4u);
    const double period = meanPeriod(c);
    std::cout << "roll period " << period << " s, analytic " << T
              << " s (GM " << GM << " m)" << std::endl;
    EXPECT_NEAR(period, T, 0.03*T);

    // Rights itself: back to level after a quarter period; never heels
    // beyond the start (no damping: the energy is conserved)
    std::size_t k = 0;
    while (k < heel.size() && heel[k] > 0) ++k;
    ASSERT_LT(k, heel.size());
    EXPECT_NEAR(t[k], 0.25*T, 0.03*T);
    EXPECT_LT(heelMax, theta0*1.01);
}


TEST(Buoyancy, heeledFloeSettlesLevelAtDraft)
{
    const SingleThread oneThread;

    // 10 x 10 x 1 floe dropped at half its draft, heeled by 8 deg (the deck
    // dips): with a linear damper it settles level at (rho_i/rho_w) h
    const double h = 1;
    const double d = rhoIce/rhoWater*h;
    const double theta0 = 8*M_PI/180;
    FloeWorld fw
    (
        10, 10, h, -0.5*d,
        Quat(Eigen::AngleAxisd(theta0, Vec3(1, 1, 0).normalized())),
        2e-3
    );
    fw.world->addForceModel(std::make_shared<Buoyancy>(WaterSettings{rhoWater, 0}));
    fw.world->addForceModel(std::make_shared<LinearDamper>(1.5));

    fw.world->advanceTo(30);

    const double draft = 0.5*h - fw.floe().x.z();
    std::cout << "settled draft " << draft << " m (analytic " << d
              << " m), tilt " << fw.tilt() << " rad" << std::endl;
    EXPECT_NEAR(draft, d, 0.01*d);
    EXPECT_LT(fw.tilt(), 1e-3);
    EXPECT_LT(fw.floe().v.norm(), 1e-4);
}


TEST(Buoyancy, worldKeepsOuterPolyhedraOnlyForModelsThatReadThem)
{
    // A model that does not clip (the damper) leaves the shapes deriving
    // their outer polyhedra on demand (memory per floe); buoyancy, added
    // later, makes the world keep them
    FloeWorld fw(4, 4, 1, -0.5);
    fw.world->addForceModel(std::make_shared<LinearDamper>(1.5));
    fw.world->step();
    EXPECT_FALSE(fw.world->shapes()[0].outerKept());
    fw.world->addForceModel(std::make_shared<Buoyancy>(WaterSettings{rhoWater, 0}));
    EXPECT_TRUE(fw.world->shapes()[0].outerKept());
    EXPECT_FALSE(fw.world->shapes()[0].outerStored());
}
