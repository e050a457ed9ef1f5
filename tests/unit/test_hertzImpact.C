/*---------------------------------------------------------------------------*\
    iceDEM tests: Hertz impacts of each feature pair against the formulas of
    method.md section 7.1, and the restitution coefficient.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "testWorlds.H"

#include <gtest/gtest.h>

#include <set>

using namespace iceDEM;
using namespace iceDEM::test;

namespace
{

struct Impact
{
    double contactTime = 0;
    double peakForce = 0;
    double speedRatio = 0;
    std::set<FeaturePair> types;
    int maxContacts = 0;
};

//- Runs until the bodies separate; v measured along 'axis' on body 'probe'
//  (relative to body 'other' when it moves)
Impact runImpact(World& w, int a, int b, const Vec3& axis, double tEnd)
{
    Impact r;
    const double vBefore = (w.bodies()[b].v - w.bodies()[a].v).dot(axis);
    w.initialise();
    bool started = false, ended = false;
    double tStart = 0, tStop = 0;
    const double dt = w.settings().timeStep;
    while (w.time() < tEnd && !ended)
    {
        w.step();
        const int n = w.contactCount();
        if (n > 0)
        {
            if (!started) { started = true; tStart = w.time() - 0.5*dt; }
            tStop = w.time() + 0.5*dt;
            r.maxContacts = std::max(r.maxContacts, n);
            for (const auto& c : w.contacts()) r.types.insert(c.type);
            r.peakForce = std::max(r.peakForce, w.contactLoad(b).force.norm());
        }
        else if (started)
        {
            ended = true;
        }
    }
    r.contactTime = tStop - tStart;
    const double vAfter = (w.bodies()[b].v - w.bodies()[a].v).dot(axis);
    r.speedRatio = -vAfter/vBefore;
    return r;
}

WorldSettings impactSettings(double dt, double e)
{
    WorldSettings s;
    s.timeStep = dt;
    s.gravity = Vec3::Zero();
    (void)e;
    return s;
}

//- Cube with a corner pointing along 'dir' (world)
Quat cornerTowards(const Vec3& dir)
{
    return rotationFromTo(Vec3(1, 1, 1).normalized(), dir.normalized());
}

//- A cube of 0.5 m (r = 0.05 m, E = 1 GPa) dropped at 1 m/s (gravity off)
//  on a fixed slab whose top is at z = 0, its lowest point 1 mm above:
//  corner down (one vertex-face term) or flat (four of equal overlap), with
//  the pair's damping per contact or per pair
struct CubeDrop
{
    Impact impact;
    double mass;        //!< the cube's
    double vz;          //!< its vertical velocity after the impact
};

CubeDrop dropCubeOnSlab(double e, bool dampingPerPair, bool cornerDown)
{
    const double r = 0.05, h = 0.5, v = 1.0, E = 1e9;
    WorldSettings s = impactSettings(2e-5, e);
    s.contact.dampingPerPair = dampingPerPair;
    World w(s);
    const int mat = w.addMaterial(ice(E));
    w.setPairProperties(mat, mat, PairProperties{0.0, e});
    const int cube = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3::Constant(h)), r));
    const int slab = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3(5, 5, 1)), r));
    w.addBody(slab, mat, Vec3(0, 0, -1 - r), Quat::Identity(), Vec3::Zero(), Vec3::Zero(), BodyMotion::fixed);
    if (cornerDown)
    {
        const double zc = std::sqrt(3.0)*h + r + 1e-3;
        w.addBody(cube, mat, Vec3(0, 0, zc), cornerTowards(Vec3(0, 0, -1)), Vec3(0, 0, -v));
    }
    else
    {
        w.addBody(cube, mat, Vec3(0, 0, h + r + 1e-3), Quat::Identity(), Vec3(0, 0, -v));
    }
    CubeDrop d;
    d.impact = runImpact(w, 0, 1, Vec3(0, 0, 1), 1.0);
    d.mass = w.bodies()[1].mass;
    d.vz = w.bodies()[1].v.z();
    return d;
}

} // anonymous namespace


class hertzVertexFace : public ::testing::TestWithParam<double> {};

TEST_P(hertzVertexFace, contactTimePeakForceRestitution)
{
    const double e = GetParam();
    const double r = 0.05, v = 1.0, E = 1e9;    // dropCubeOnSlab's
    const CubeDrop d = dropCubeOnSlab(e, false, true);
    const Impact& imp = d.impact;

    const PairCoefficients c = PairCoefficients::make(ice(E), ice(E), PairProperties{0, 1});
    const HertzImpact ref(d.mass, r, c.Estar, v);

    EXPECT_EQ(imp.types, std::set<FeaturePair>{FeaturePair::vertexFace});
    EXPECT_EQ(imp.maxContacts, 1);
    EXPECT_NEAR(imp.speedRatio, e, 0.02*e);
    if (e == 1.0)
    {
        EXPECT_NEAR(imp.contactTime, ref.contactTime, 0.02*ref.contactTime);
        EXPECT_NEAR(imp.peakForce, ref.peakForce, 0.02*ref.peakForce);
    }
}

INSTANTIATE_TEST_SUITE_P(restitution, hertzVertexFace, ::testing::Values(1.0, 0.7, 0.3));


TEST(hertzImpact, vertexVertex)
{
    const double r = 0.05, h = 0.5, v = 1.0, E = 1e9;
    World w(impactSettings(2e-5, 1));
    const int mat = w.addMaterial(ice(E));
    w.setPairProperties(mat, mat, PairProperties{0.0, 1.0});
    const int cube = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3::Constant(h)), r));
    const double zc = std::sqrt(3.0)*h + r + 5e-4;
    w.addBody(cube, mat, Vec3(0, 0, -zc), cornerTowards(Vec3(0, 0, 1)), Vec3(0, 0, 0.5*v));
    w.addBody(cube, mat, Vec3(0, 0, zc), cornerTowards(Vec3(0, 0, -1)), Vec3(0, 0, -0.5*v));
    const double m = w.bodies()[0].mass;

    const Impact imp = runImpact(w, 0, 1, Vec3(0, 0, 1), 1.0);
    const PairCoefficients c = PairCoefficients::make(ice(E), ice(E), PairProperties{0, 1});
    const HertzImpact ref(0.5*m, 0.5*r, c.Estar, v);

    EXPECT_EQ(imp.types, std::set<FeaturePair>{FeaturePair::vertexVertex});
    // The excess potential (NarrowPhase.H) writes a vertex-vertex contact
    // as three terms: each vertex against the other core, less the
    // vertex-vertex double count; the peak force below checks it is
    // counted once (main, windowed feature pairs: one contact)
    EXPECT_EQ(imp.maxContacts, 3);
    EXPECT_NEAR(imp.contactTime, ref.contactTime, 0.02*ref.contactTime);
    EXPECT_NEAR(imp.peakForce, ref.peakForce, 0.02*ref.peakForce);
    EXPECT_NEAR(imp.speedRatio, 1.0, 0.02);
}


TEST(hertzImpact, crossedEdges)
{
    const double r = 0.05, v = 1.0, E = 1e9;
    World w(impactSettings(2e-5, 1));
    const int mat = w.addMaterial(ice(E));
    w.setPairProperties(mat, mat, PairProperties{0.0, 1.0});
    const double s = 0.3;
    const int barX = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3(1, s, s)), r));
    const int barY = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3(s, 1, s)), r));
    // Edge along x on top of the lower bar, edge along y under the upper bar
    const Quat qa(Eigen::AngleAxisd(M_PI/4, Vec3::UnitX()));
    const Quat qb(Eigen::AngleAxisd(M_PI/4, Vec3::UnitY()));
    const double zc = std::sqrt(2.0)*s + r + 5e-4;
    w.addBody(barX, mat, Vec3(0, 0, -zc), qa, Vec3(0, 0, 0.5*v));
    w.addBody(barY, mat, Vec3(0, 0, zc), qb, Vec3(0, 0, -0.5*v));
    const double m = w.bodies()[0].mass;

    const Impact imp = runImpact(w, 0, 1, Vec3(0, 0, 1), 1.0);
    const PairCoefficients c = PairCoefficients::make(ice(E), ice(E), PairProperties{0, 1});
    // Crossed at 90 degrees: R* = sqrt(r_i r_j)/sin(theta) = r
    const HertzImpact ref(0.5*m, r, c.Estar, v);

    EXPECT_EQ(imp.types, std::set<FeaturePair>{FeaturePair::edgeEdge});
    EXPECT_EQ(imp.maxContacts, 1);
    EXPECT_NEAR(imp.contactTime, ref.contactTime, 0.02*ref.contactTime);
    EXPECT_NEAR(imp.peakForce, ref.peakForce, 0.02*ref.peakForce);
    EXPECT_NEAR(imp.speedRatio, 1.0, 0.02);
}


TEST(hertzImpact, vertexEdge)
{
    // A corner onto the middle of an edge: R* = sqrt(r r r/(r + r))
    const double r = 0.05, h = 0.5, v = 1.0, E = 1e9;
    World w(impactSettings(2e-5, 1));
    const int mat = w.addMaterial(ice(E));
    w.setPairProperties(mat, mat, PairProperties{0.0, 1.0});
    const int cube = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3::Constant(h)), r));
    const int bar = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3(1, 0.3, 0.3)), r));
    const double zb = std::sqrt(2.0)*0.3 + r + 2.5e-4;
    const double zc = std::sqrt(3.0)*h + r + 2.5e-4;
    w.addBody(bar, mat, Vec3(0, 0, -zb), Quat(Eigen::AngleAxisd(M_PI/4, Vec3::UnitX())), Vec3(0, 0, 0.5*v));
    w.addBody(cube, mat, Vec3(0, 0, zc), cornerTowards(Vec3(0, 0, -1)), Vec3(0, 0, -0.5*v));
    const double m0 = w.bodies()[0].mass, m1 = w.bodies()[1].mass;

    const Impact imp = runImpact(w, 0, 1, Vec3(0, 0, 1), 1.0);
    const PairCoefficients c = PairCoefficients::make(ice(E), ice(E), PairProperties{0, 1});
    const HertzImpact ref(m0*m1/(m0 + m1), std::sqrt(r*r*r/(2*r)), c.Estar, v);

    EXPECT_EQ(imp.types, std::set<FeaturePair>{FeaturePair::vertexEdge});
    EXPECT_EQ(imp.maxContacts, 1);
    EXPECT_NEAR(imp.contactTime, ref.contactTime, 0.02*ref.contactTime);
    EXPECT_NEAR(imp.peakForce, ref.peakForce, 0.02*ref.peakForce);
}


TEST(restitution, hertzDampingGivesTheRestitution)
{
    for (double e : {0.1, 0.3, 0.5, 0.7, 0.9})
    {
        EXPECT_NEAR(hertzRestitution(hertzDampingBeta(e)), e, 1e-6) << "e = " << e;
    }
    EXPECT_EQ(hertzDampingBeta(1.0), 0.0);
    EXPECT_THROW(hertzDampingBeta(0.0), Error);
    EXPECT_THROW(hertzDampingBeta(1.5), Error);
}


// normalDamping perPair: the pair's damping is that of one contact of its
// terms' summed stiffness, so a face landing flat rebounds at e, as one
// contact does. perContact (method.md's damping for each term with the
// pair's m*): n equal terms damp as one contact of n times the stiffness
// with beta sqrt(n), so four rebound at hertzRestitution(2 beta(e))
TEST(restitution, aFaceLandingFlatReboundsAtEWithDampingPerPair)
{
    for (double e : {0.3, 0.7})
    {
        const CubeDrop perPair = dropCubeOnSlab(e, true, false);
        const CubeDrop perContact = dropCubeOnSlab(e, false, false);
        for (const CubeDrop* d : {&perPair, &perContact})
        {
            EXPECT_EQ(d->impact.maxContacts, 4);
            EXPECT_EQ(d->impact.types, std::set<FeaturePair>{FeaturePair::vertexFace});
        }
        const double fourTerms = hertzRestitution(2*hertzDampingBeta(e));
        EXPECT_NEAR(perPair.impact.speedRatio, e, 0.01*e) << "e = " << e;
        EXPECT_NEAR(perContact.impact.speedRatio, fourTerms, 0.02*fourTerms) << "e = " << e;
        std::printf("e %g: flat landing, perPair %.6f, perContact %.6f (four terms' analytic %.6f)\n",
                    e, perPair.impact.speedRatio, perContact.impact.speedRatio, fourTerms);
    }
}


// A pair whose contact is one term of weight 1 keeps the pair's m*: the
// same trajectory to the bit in both modes (the corner impact)
TEST(restitution, oneTermIsTheSameInBothDampings)
{
    const CubeDrop perContact = dropCubeOnSlab(0.3, false, true);
    const CubeDrop perPair = dropCubeOnSlab(0.3, true, true);
    EXPECT_EQ(perContact.impact.maxContacts, 1);
    EXPECT_EQ(perPair.impact.maxContacts, 1);
    EXPECT_EQ(perContact.vz, perPair.vz);
}


TEST(contactLaw, unknownModelNamesTheEntry)
{
    WorldSettings s;
    s.contact.model = "hertzz";
    try
    {
        World w(s);
        FAIL() << "no error for an unknown contact model";
    }
    catch (const Error& e)
    {
        EXPECT_EQ(e.entry(), "contactModel");
        EXPECT_NE(std::string(e.what()).find("hertzSimplified"), std::string::npos);
    }
}


TEST(contactLaw, timeStepTooLargeIsAnError)
{
    WorldSettings s;
    s.timeStep = 0.5;
    s.gravity = Vec3::Zero();
    World w(s);
    const int mat = w.addMaterial(ice());
    const int cube = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3::Constant(0.5)), 0.05));
    w.addBody(cube, mat, Vec3::Zero());
    try
    {
        w.initialise();
        FAIL() << "no error for a time step far above the contact time";
    }
    catch (const Error& e)
    {
        EXPECT_EQ(e.entry(), "deltaT");
    }
}


TEST(contactLaw, overlapAtStartIsAnError)
{
    WorldSettings s;
    s.gravity = Vec3::Zero();
    s.timeStep = 1e-5;
    World w(s);
    const int mat = w.addMaterial(ice());
    const int cube = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3::Constant(0.5)), 0.05));
    w.addBody(cube, mat, Vec3::Zero());
    w.addBody(cube, mat, Vec3(0.3, 0, 0));
    EXPECT_THROW(w.initialise(), Error);
}


TEST(hertzImpact, overlapBeyondTheDilationRadiiStopsTheRun)
{
    // A cube falls corner first at 5 m/s onto a fixed slab. Resolved
    // (dt = 2e-5 s) the overlap peaks far below r_i + r_j = 0.1 m and the
    // impact runs through; with dt = 0.03 s (the contact-time check
    // relaxed) the first step of contact carries the corner 0.15 m, into
    // the slab's core: World::step stops with an Error naming deltaT
    // instead of going on with forces beyond the contact model's range
    const double r = 0.05, h = 0.5, v = 5.0, E = 1e9;
    auto makeWorld = [&](double dt)
    {
        WorldSettings s = impactSettings(dt, 1);
        s.contactStepsMin = 0.1;
        s.contactStepsWarn = 0.1;
        auto w = std::make_unique<World>(s);
        const int mat = w->addMaterial(ice(E));
        w->setPairProperties(mat, mat, PairProperties{0.0, 1.0});
        const int cube = w->addShape(DilatedShape(ConvexPolyhedron::box(Vec3::Constant(h)), r));
        const int slab = w->addShape(DilatedShape(ConvexPolyhedron::box(Vec3(5, 5, 1)), r));
        w->addBody(slab, mat, Vec3(0, 0, -1 - r), Quat::Identity(), Vec3::Zero(), Vec3::Zero(), BodyMotion::fixed);
        const double zc = std::sqrt(3.0)*h + r + 1e-3;
        w->addBody(cube, mat, Vec3(0, 0, zc), cornerTowards(Vec3(0, 0, -1)), Vec3(0, 0, -v));
        w->initialise();
        return w;
    };

    auto resolved = makeWorld(2e-5);
    double deepest = 0;
    bool touched = false;
    while (resolved->time() < 0.2)
    {
        EXPECT_NO_THROW(resolved->step());
        for (const auto& c : resolved->contacts())
        {
            deepest = std::max(deepest, c.overlap);
            touched = true;
        }
        if (touched && resolved->contactCount() == 0) break;
    }
    EXPECT_TRUE(touched);
    EXPECT_GT(deepest, 0.005);
    EXPECT_LT(deepest, 0.5*2*r);
    EXPECT_GT(resolved->bodies()[1].v.z(), 0);     // bounced

    auto coarse = makeWorld(0.03);
    try
    {
        coarse->step();
        FAIL() << "no Error for an overlap beyond the dilation radii";
    }
    catch (const Error& err)
    {
        EXPECT_EQ(err.entry(), "deltaT");
        EXPECT_NE(std::string(err.what()).find("reduce deltaT"), std::string::npos) << err.what();
    }
}
