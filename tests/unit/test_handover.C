/*---------------------------------------------------------------------------*\
    iceDEM tests: contacts between general convex polyhedra hand over from
    one feature pair to the next without a jump in the contact potential
    (issue 18, section 1).
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "testWorlds.H"
#include "contact/NarrowPhase.H"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace iceDEM;
using namespace iceDEM::test;

namespace
{

//- Convex hull of n points drawn around the origin (radius 0.7-1.0+ of
//  scale): all faces triangles, 3 to 7 faces at a vertex. Redrawn until
//  every point is a hull vertex
ConvexPolyhedron randomHull(std::mt19937_64& rng, int n, double scale)
{
    std::normal_distribution<double> g(0, 1);
    std::vector<Vec3> p;
    while (true)
    {
        p.clear();
        for (int k = 0; k < n; ++k)
        {
            const Vec3 v(g(rng), g(rng), g(rng));
            p.push_back(scale*v.normalized()*(0.7 + 0.3*std::abs(g(rng))));
        }
        const ConvexPolyhedron P = ConvexPolyhedron::hull(p);
        if (int(P.vertices().size()) == n) return P;
    }
}

double totalEnergy(const World& w)
{
    const Energies e = w.energies();
    return e.kinetic + e.gravitational + e.elastic;
}

struct ImpactRecord
{
    int impacts = 0;
    double worst = 0;       //!< largest |E after - E before|/E0 of an impact
    double drift = 0;       //!< (E_end - E0)/E0
    double deepest = 0;     //!< largest overlap/smaller radius (broad battery)
    double youngsModulus = 0;   //!< chosen (broad battery)
    double timeStep = 0;
    int worstImpact = -1;   //!< index of the impact with the largest change
};

//- Diagnosis of a failing impact (issue 18 §1): one line for a step, the
//  step's energy change (of E0) and every term between the two bodies
//  (type, feature keys, weight W, overlap, point), as the World's narrow
//  phase gives them, and each term's support gap g = dist - gap(n): its
//  core distance less the separation of the cores along its own normal
//  (min over B of n . q - max over A of n . p), 0 for the closest pair of
//  convex cores and positive for every other
std::string listPairContacts(const World& w, int sa, int sb, double stepChange)
{
    const Body& a = w.bodies()[0];
    const Body& b = w.bodies()[1];
    std::vector<Vec3> va, vb;
    const Mat3 Ra = a.rotation(), Rb = b.rotation();
    for (const Vec3& p : w.shapes()[sa].core().vertices()) va.push_back(Ra*p + a.x);
    for (const Vec3& p : w.shapes()[sb].core().vertices()) vb.push_back(Rb*p + b.x);
    const BodyView A{&w.shapes()[sa], va.data(), Ra, a.x, a.q};
    const BodyView B{&w.shapes()[sb], vb.data(), Rb, b.x, b.q};
    FoundContact found[World::maxContactsPerPair];
    Vec3 axis = Vec3::Zero();
    const int n = findContacts(A, B, NarrowPhaseSettings(), axis, found, World::maxContactsPerPair);
    char buf[256];
    std::snprintf(buf, sizeof buf, "  t %.6f dE %+.2e:", w.time(), stepChange);
    std::string line(buf);
    for (int k = 0; k < n; ++k)
    {
        const ContactGeometry& g = found[k].g;
        double maxA = -std::numeric_limits<double>::max();
        double minB = std::numeric_limits<double>::max();
        for (const Vec3& p : va) maxA = std::max(maxA, g.normal.dot(p));
        for (const Vec3& q : vb) minB = std::min(minB, g.normal.dot(q));
        const double dist = w.shapes()[sa].radius() + w.shapes()[sb].radius() - g.overlap;
        std::snprintf
        (
            buf, sizeof buf, " [%s %x/%x W %.4f d %.3e g %.2e at %.4f %.4f %.4f]",
            featurePairName(g.type), found[k].featureA, found[k].featureB, g.weight,
            g.overlap, dist - (minB - maxA), g.point.x(), g.point.y(), g.point.z()
        );
        line += buf;
    }
    return line + "\n";
}

//- Two random hulls (7 and 10 vertices, r = 0.05), e = 1, mu = 0, gravity,
//  in the closed box [-1.5, 1.5]^3 for 'duration' s with dt = 2e-5 s (about
//  200 steps per contact): the energy change of every impact (from the
//  step before a contact starts to the step after the last one ends)
ImpactRecord randomPairInABox
(
    unsigned seed,
    double duration,
    const std::string& model,
    double timeStep = 2e-5,
    int listImpact = -1
)
{
    std::mt19937_64 rng(seed);
    WorldSettings s;
    s.timeStep = timeStep;
    s.contact.model = model;
    World w(s);
    const int m = w.addMaterial(ice(1e9));
    w.setPairProperties(m, m, PairProperties{0.0, 1.0});
    const int sa = w.addShape(DilatedShape(randomHull(rng, 7, 0.5), 0.05));
    const int sb = w.addShape(DilatedShape(randomHull(rng, 10, 0.6), 0.05));
    const Vec3 dirs[6] =
    {
        Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()
    };
    for (int k = 0; k < 6; ++k)
    {
        Wall wall;
        wall.name = "w" + std::to_string(k);
        wall.point = -1.5*dirs[k];
        wall.normal = dirs[k];
        wall.material = m;
        w.addWall(wall);
    }
    std::uniform_real_distribution<double> u(-1, 1);
    auto pose = [&]() { return Quat(Eigen::AngleAxisd(u(rng)*3, Vec3(u(rng), u(rng), u(rng)).normalized())); };
    auto vec = [&](double a) { return Vec3(a*u(rng), a*u(rng), a*u(rng)); };
    {
        const Quat q = pose();
        const Vec3 v = vec(3);
        w.addBody(sa, m, Vec3(-0.7, 0, 0), q, v, vec(3));
    }
    {
        const Quat q = pose();
        const Vec3 v = vec(3);
        w.addBody(sb, m, Vec3(0.7, 0, 0), q, v, vec(3));
    }
    w.initialise();

    ImpactRecord r;
    const double E0 = totalEnergy(w);
    double before = E0;
    bool inContact = false;
    std::string previous;
    while (w.time() < duration)
    {
        const double E = totalEnergy(w);
        w.step();
        const bool c = w.contactCount() > 0;
        if (c && !inContact) before = E;
        if (c && r.impacts == listImpact)
        {
            // The steps that change the energy by more than 1 % of the
            // bound of an impact, each with the step before
            const double change = (totalEnergy(w) - E)/E0;
            const std::string line = listPairContacts(w, sa, sb, change);
            if (std::abs(change) > 1e-6)
            {
                std::printf("%s%s", previous.c_str(), line.c_str());
                previous.clear();
            }
            else
            {
                previous = line;
            }
        }
        if (!c && inContact)
        {
            const double change = std::abs(totalEnergy(w) - before)/E0;
            if (change > r.worst) r.worstImpact = r.impacts;
            r.worst = std::max(r.worst, change);
            ++r.impacts;
        }
        inContact = c;
    }
    r.drift = (totalEnergy(w) - E0)/E0;
    return r;
}

//- A random point cloud of n points (4 to 20), Gaussian along three random
//  half-axes of 0.5 to 1 times scale (its hull: not every point need be a
//  vertex; at least 4 are)
std::vector<Vec3> cloud(std::mt19937_64& rng, int n, double scale)
{
    std::normal_distribution<double> g(0, 1);
    std::uniform_real_distribution<double> u(0.5, 1);
    const Vec3 axes(u(rng), u(rng), u(rng));
    std::vector<Vec3> p;
    for (int k = 0; k < n; ++k)
    {
        p.push_back(scale*Vec3(axes.x()*g(rng), axes.y()*g(rng), axes.z()*g(rng)));
    }
    return p;
}

//- Largest extent of a body in the broad battery: its origin at x = -+0.75
//  in the box [-1.5, 1.5]^3, it touches neither the walls nor the other body
//  at the start (a Gaussian cloud's outliers reach 3 scales: before, some
//  cores crossed a wall at the start and the wall contact's energy, far
//  outside the model, was released in the first steps)
constexpr double broadMaxExtent = 0.72;

//- The battery broadened as issue 18 asks: two hulls of random clouds of 4
//  to 20 points (scales 0.3 to 0.6), random radii (0.02 to 0.08), densities
//  (mass ratio up to about 100), orientations and velocities, e = 1, mu =
//  0, gravity, six walls.
//  The model (Hertz between dilated shapes) holds while an overlap stays
//  below the dilation radius. Young's modulus is chosen for each pair so
//  that no overlap can exceed half the smaller radius: one contact cannot
//  store more than the energy the pair can release, E_free = kinetic + m g
//  (height above the floor) summed over both bodies, and the Hertz energy
//  8/15 E* sqrt(R*) delta^(5/2) at delta = r_min/2 with the smallest R* of
//  the pair (r_A r_B/(r_A + r_B), the walls' being r) must hold it:
//      E* >= 15 E_free/(8 sqrt(R*) (r_min/2)^(5/2)),
//  E = max(1e10 Pa, 2 (1 - nu^2) E*). The time step is scaled from the
//  reference pair's 2e-5 s (m* = 180 kg, R* = 0.025 m, E = 1e9 Pa) by the
//  Hertz contact time, m*^(2/5) R*^(-1/5) E^(-2/5), so that no contact has
//  fewer steps than the reference's (about 200)
ImpactRecord broadPairInABox
(
    unsigned seed,
    double duration,
    const std::string& model,
    double youngsModulus = 0
)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> nPoints(4, 20);
    auto in = [&](double a, double b) { return a + (b - a)*0.5*(1 + u(rng)); };
    const double E = youngsModulus > 0 ? youngsModulus : 1e10;
    WorldSettings s;
    s.timeStep = 2e-5;
    s.contact.model = model;
    World w(s);
    const int ma = w.addMaterial(ice(E, 900));
    Material heavy = ice(E, 900*std::pow(10.0, u(rng)));
    heavy.name = "ice2";
    const int mb = w.addMaterial(heavy);
    for (int i : {ma, mb})
    {
        for (int j : {ma, mb}) w.setPairProperties(i, j, PairProperties{0.0, 1.0});
    }
    // Redrawn until the hull is a solid and the radius fits its core
    auto shape = [&](double& r)
    {
        while (true)
        {
            r = in(0.02, 0.08);
            try
            {
                // A cloud reaching farther than broadMaxExtent (with the
                // radius) from its input frame's origin, where addBody puts
                // it, is scaled down to it
                std::vector<Vec3> p = cloud(rng, nPoints(rng), in(0.3, 0.6));
                double far = 0;
                for (const Vec3& v : p) far = std::max(far, v.norm());
                if (far + r > broadMaxExtent)
                {
                    for (Vec3& v : p) v *= (broadMaxExtent - r)/far;
                }
                return w.addShape(DilatedShape(ConvexPolyhedron::hull(p), r));
            }
            catch (const Error&) {}
        }
    };
    double rA, rB;
    const int sa = shape(rA);
    const int sb = shape(rB);
    const Vec3 dirs[6] =
    {
        Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()
    };
    for (int k = 0; k < 6; ++k)
    {
        Wall wall;
        wall.name = "w" + std::to_string(k);
        wall.point = -1.5*dirs[k];
        wall.normal = dirs[k];
        wall.material = k % 2 ? ma : mb;
        w.addWall(wall);
    }
    auto pose = [&]() { return Quat(Eigen::AngleAxisd(u(rng)*3, Vec3(u(rng), u(rng), u(rng)).normalized())); };
    auto vec = [&](double a) { return Vec3(a*u(rng), a*u(rng), a*u(rng)); };
    {
        const Quat q = pose();
        const Vec3 v = vec(3);
        w.addBody(sa, ma, Vec3(-0.75, 0, 0), q, v, vec(3));
    }
    {
        const Quat q = pose();
        const Vec3 v = vec(3);
        w.addBody(sb, mb, Vec3(0.75, 0, 0), q, v, vec(3));
    }
    const double rMin = std::min(rA, rB);
    const double m1 = w.bodies()[0].mass, m2 = w.bodies()[1].mass;
    const double mStar = std::min(m1*m2/(m1 + m2), 0.5*std::min(m1, m2));
    const double rStar = std::max(rA*rB/(rA + rB), std::max(rA, rB));
    w.setTimeStep
    (
        std::min(1.0, std::pow(mStar/180, 0.4)*std::pow(rStar/0.025, -0.2))
       *2e-5*std::pow(E/1e9, -0.4)
    );
    w.initialise();
    if (!(youngsModulus > 0))
    {
        // Young's modulus from the bound above (the energies once
        // initialised), then the same pair again
        const Energies e = w.energies();
        double free = e.kinetic + e.gravitational;
        for (const Body& b : w.bodies()) free += b.mass*(-s.gravity.z())*1.5;
        const double nu = heavy.poissonsRatio;
        const double rStarMin = rA*rB/(rA + rB);
        const double EstarNeeded = 15*free/(8*std::sqrt(rStarMin)*std::pow(0.5*rMin, 2.5));
        return broadPairInABox
        (
            seed, duration, model, std::max(1e10, 2*(1 - nu*nu)*EstarNeeded)
        );
    }

    ImpactRecord r;
    r.youngsModulus = E;
    r.timeStep = w.settings().timeStep;
    const double E0 = totalEnergy(w);
    double before = E0;
    bool inContact = false;
    while (w.time() < duration)
    {
        const double Ebefore = totalEnergy(w);
        w.step();
        const bool c = w.contactCount() > 0;
        if (c && !inContact) before = Ebefore;
        if (!c && inContact)
        {
            ++r.impacts;
            r.worst = std::max(r.worst, std::abs(totalEnergy(w) - before)/E0);
        }
        if (c)
        {
            for (const World::ContactInfo& ci : w.contacts())
            {
                r.deepest = std::max(r.deepest, ci.overlap/rMin);
            }
        }
        inContact = c;
    }
    r.drift = (totalEnergy(w) - E0)/E0;
    return r;
}

//- Bound of one impact's energy error: the leapfrog's error over a contact
//  resolved by N steps is of order (pi/N)^2 of the energy the contact
//  exchanges, here (pi/200)^2 = 2.5e-4 of at most half the total
constexpr double impactBound = 1e-4;

} // anonymous namespace


// Cases of the kind from the battery below that the old windows got
// wrong (seeds 7, 24, 27: one impact changed the total energy by 6.8 %,
// 16 % and 20 %; an edge lying nearly parallel on a face whose crossing
// with the face's boundary vanished loaded as the edge passed parallel)
TEST(handover, edgeLyingOnAFaceHandsOverWithoutAJump)
{
    for (unsigned seed : {7u, 24u, 27u})
    {
        const ImpactRecord r = randomPairInABox(seed, 5.0, "hertzSimplified");
        EXPECT_GE(r.impacts, 30) << "seed " << seed;
        EXPECT_LT(r.worst, impactBound) << "seed " << seed;
        EXPECT_LT(std::abs(r.drift), 5e-3) << "seed " << seed;
    }
}


// The first battery (randomPairInABox: hulls of 7 and 10 points on a
// sphere's shell, E = 1e9 Pa, 5 s each): 40 seeds, about 2,000 impacts.
// On main (windowed feature pairs, tolerance bands, the merge partition) 2
// of the 37 pairs failed (seed 19, 8.9e-4: a band crossing appearing beside
// a vertex-face corner; seed 39, 2.0e-4: a nearly parallel crossing fading
// in a few steps; the designs tried before are listed in README.md's
// history of issue 18). The excess potential (NarrowPhase.H), continuous by
// construction: every impact within 6.0e-6 of the total energy, drift
// within 1.9e-5 (40 pairs, 2,249 impacts). Every seed runs: seeds 15, 23
// and 38, whose ten-point hull could not be dilated before the hull kept
// its faces consistent (geometry.everyHullWithVerticesOfManyFacesDilates),
// were skipped as errors until then (37 pairs, 2,092 impacts). About 6 s
// of CPU
TEST(handover, sevenAndTenVertexHullsConserveEnergyAtEveryImpact)
{
    int impacts = 0;
    for (unsigned seed = 1; seed <= 40; ++seed)
    {
        const ImpactRecord r = randomPairInABox(seed, 5.0, "hertzSimplified");
        impacts += r.impacts;
        std::printf("seed %u: %d impacts, worst %.3g, drift %.3g\n", seed, r.impacts, r.worst, r.drift);
        EXPECT_LT(r.worst, impactBound) << "seed " << seed;
        EXPECT_LT(std::abs(r.drift), 5e-3) << "seed " << seed;
    }
    EXPECT_GE(impacts, 1500);
}


// The same battery at three time steps (2e-5, 1.5e-5 and 1e-5 s: every
// pair follows three different trajectories, each impact resolved by 200
// to 400 steps). The pairs that fail at one step size are a sample of the
// configurations that jump: on main 2, 6 and 2 pairs failed (seeds 19 and
// 39; 19, 22, 27, 36, 37 and 39; 5 and 19), up to 1.8e-2 of the energy in
// one impact. The excess potential (NarrowPhase.H): 120 pair-runs, 6,795
// impacts, the worst impact 6.0e-6, 4.6e-6 and 2.8e-6 of the total energy
// at the three steps, drift at most 1.9e-5 (111 pair-runs while seeds 15,
// 23 and 38 were skipped, see above). Its first form (the boundary
// part a plain minimum of the four end distances) failed 2, 4 and 1 pairs
// (kinks where two ends tie, up to 1.7e-3); with a blend of the ends
// (weights g^-2), 0, 1 and 1 (seed 39: an edge lying along another edge,
// sine 0.0055, both ends in reach, 1.6e-3). A failing pair's worst impact
// is listed step by step (listPairContacts). About 26 s of CPU
TEST(handover, sevenAndTenVertexHullsAtThreeTimeSteps)
{
    for (const double dt : {2e-5, 1.5e-5, 1e-5})
    {
        int impacts = 0;
        for (unsigned seed = 1; seed <= 40; ++seed)
        {
            const ImpactRecord r = randomPairInABox(seed, 5.0, "hertzSimplified", dt);
            impacts += r.impacts;
            std::printf
            (
                "dt %.2g seed %u: %d impacts, worst %.3g (impact %d), drift %.3g\n",
                dt, seed, r.impacts, r.worst, r.worstImpact, r.drift
            );
            EXPECT_LT(r.worst, impactBound) << "dt " << dt << " seed " << seed;
            EXPECT_LT(std::abs(r.drift), 5e-3) << "dt " << dt << " seed " << seed;
            if (r.worst >= impactBound)
            {
                std::printf("  its worst impact, step by step:\n");
                randomPairInABox(seed, 5.0, "hertzSimplified", dt, r.worstImpact);
            }
        }
        EXPECT_GE(impacts, 1500) << "dt " << dt;
    }
}


// Quasi-static sweep of the mechanism: the bottom edge of a box
// turned 45 degrees lies on the top face of another box and hangs over its
// boundary edge; it is turned slowly through parallel at a held overlap.
// The contact potential must be continuous: halving the step must halve the
// largest change between consecutive poses (a jump would stay)
TEST(handover, edgeTurnedThroughParallelOnAFaceHasAContinuousPotential)
{
    auto largestStep = [](int nSteps)
    {
        WorldSettings s;
        s.timeStep = 1e-9;
        s.gravity = Vec3::Zero();
        s.contact.model = "hertzSimplified";
        World w(s);
        const int m = w.addMaterial(ice(1e9));
        w.setPairProperties(m, m, PairProperties{0.0, 1.0});
        const int base = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3(1, 1, 0.5)), 0.05));
        const int top = w.addShape(DilatedShape(ConvexPolyhedron::box(Vec3(0.5, 0.3, 0.3)), 0.05));
        w.addBody(base, m, Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3::Zero(), BodyMotion::fixed);
        // Bottom edge along x at height 0.5 + 0.1 - 0.008 (overlap 8e-3 of
        // r_A + r_B = 0.1), from x = 0.5 to 1.5: crosses the base's top
        // boundary edge x = 1
        const Quat q0(Eigen::AngleAxisd(M_PI/4, Vec3::UnitX()));
        const double h = 0.3*std::sqrt(2.0);
        const Vec3 x0(1.0, 0, 0.5 + 0.1 - 0.008 + h);
        // Added apart (no overlap at the start), then placed
        w.addBody(top, m, x0 + Vec3(0, 0, 0.2), q0, Vec3::Zero(), Vec3::Zero());
        w.initialise();
        double largest = 0, last = 0;
        for (int k = 0; k <= nSteps; ++k)
        {
            // Turn about y through the point of the edge above x = 1 (the
            // crossing: its overlap held)
            const double theta = -0.02 + 0.04*k/nSteps;
            const Quat turn(Eigen::AngleAxisd(theta, Vec3::UnitY()));
            const Vec3 pivot(1.0, 0, 0.5 + 0.1 - 0.008);
            Body& b = w.bodies()[1];
            b.q = turn*q0;
            b.x = pivot + turn*(x0 - pivot);
            b.v.setZero();
            b.L.setZero();
            w.step();
            const double U = w.energies().elastic;
            EXPECT_GT(U, 0);
            if (k > 0) largest = std::max(largest, std::abs(U - last));
            last = U;
        }
        return largest;
    };
    const double coarse = largestStep(200);
    const double fine = largestStep(400);
    EXPECT_LT(fine, 0.6*coarse) << "coarse " << coarse << ", fine " << fine;
}


namespace
{

//- Quasi-static sweep at a held overlap: hull B (10 vertices) turned once
//  about a random axis in 'poses' poses, at each pose moved along a fixed
//  direction (bisection on the distance) until its deepest contact with
//  hull A (7 vertices; both r = 0.05) overlaps by 'overlap'. Returns the
//  magnitude of the total contact force on B and the contacts' feature-pair
//  types at each pose (the poses depend on the overlaps only, not on the
//  contact law)
struct ForceSweep
{
    std::vector<double> F;                  //!< |F| at each pose
    std::vector<std::vector<int>> types;    //!< sorted feature-pair types
    std::vector<Vec3> force;                //!< total contact force on B
    std::vector<Vec3> moment;               //!< its moment about B's centroid
    double radiusB = 0;                     //!< B's bounding radius
};

ForceSweep forceSweep(unsigned seed, const std::string& model, int poses, double overlap)
{
    std::mt19937_64 rng(seed);
    WorldSettings s;
    s.timeStep = 1e-12;
    s.gravity = Vec3::Zero();
    s.contact.model = model;
    World w(s);
    const int m = w.addMaterial(ice(1e9));
    w.setPairProperties(m, m, PairProperties{0.0, 1.0});
    const int sa = w.addShape(DilatedShape(randomHull(rng, 7, 0.5), 0.05));
    const int sb = w.addShape(DilatedShape(randomHull(rng, 10, 0.6), 0.05));
    std::uniform_real_distribution<double> u(-1, 1);
    const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Quat q0(Eigen::AngleAxisd(3*u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    w.addBody(sa, m, Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3::Zero(), BodyMotion::fixed);
    const double far = 3.0;
    w.addBody(sb, m, far*dir, q0, Vec3::Zero(), Vec3::Zero());
    w.initialise();

    // Deepest overlap at distance d (infinite if the cores intersect), and
    // the total force on B and the sorted feature-pair types there. Cores
    // that intersect are not stepped: the World stops a run whose bodies
    // overlap by their radii's sum (beyond the contact model), which the
    // bisection's first, deep poses would reach
    std::vector<int> types;
    Vec3 F = Vec3::Zero();
    auto coresOfABIntersect = [&]()
    {
        auto view = [&](const Body& body, int shape, std::vector<Vec3>& v)
        {
            const Mat3 R = body.rotation();
            v.clear();
            for (const Vec3& p : w.shapes()[shape].core().vertices()) v.push_back(R*p + body.x);
            return BodyView{&w.shapes()[shape], v.data(), R, body.x, body.q};
        };
        std::vector<Vec3> wa, wb;
        const BodyView va = view(w.bodies()[0], sa, wa);
        const BodyView vb = view(w.bodies()[1], sb, wb);
        return coresIntersect(va, vb);
    };
    auto place = [&](const Quat& q, double d)
    {
        Body& b = w.bodies()[1];
        b.q = q;
        b.x = d*dir;
        b.v.setZero();
        b.L.setZero();
        if (coresOfABIntersect()) return std::numeric_limits<double>::infinity();
        w.step();
        types.clear();
        F.setZero();
        double deepest = 0;
        for (const World::ContactInfo& c : w.contacts())
        {
            deepest = std::max(deepest, c.overlap);
            types.push_back(int(c.type));
            F += c.j == 1 ? c.forceOnJ : Vec3(-c.forceOnJ);
        }
        std::sort(types.begin(), types.end());
        return coresOfABIntersect() ? std::numeric_limits<double>::infinity() : deepest;
    };

    ForceSweep r;
    for (int k = 0; k <= poses; ++k)
    {
        const Quat q = Quat(Eigen::AngleAxisd(2*M_PI*k/poses, axis))*q0;
        double lo = 0, hi = far;     // overlap(lo) > target >= overlap(hi)
        for (int it = 0; it < 40; ++it)
        {
            const double mid = 0.5*(lo + hi);
            (place(q, mid) > overlap ? lo : hi) = mid;
        }
        place(q, hi);
        r.F.push_back(F.norm());
        r.types.push_back(types);
        // Totals of the step's force evaluation: the contacts only (no
        // gravity, no walls), couples of weighted contacts included
        r.force.push_back(w.bodies()[1].force);
        r.moment.push_back(w.bodies()[1].torque);
    }
    r.radiusB = w.shapes()[sb].boundingRadius();
    return r;
}

} // anonymous namespace


// hertz: the equivalent radius R* depends on the feature pair (vertex-face
// r, vertex-edge r/sqrt(2), vertex-vertex r/2 for equal radii, edge-edge
// r/sin up to maxEdgeRadiusRatio r), so the force F ~ sqrt(R*) overlap^1.5
// jumps where a contact is handed over, by design. Five random hull pairs,
// 1440 poses per turn, overlap 5e-3 (5 % of r_A + r_B): the jump of
// |F_hertz|/|F_hertzSimplified| at the same poses isolates R*'s part (the
// raw jumps of |F| are printed too; hertzSimplified's own continuity is
// asserted by hertzSimplifiedForceAndMomentAreContinuous)
TEST(handover, hertzForceJumpAtHandOverIsBounded)
{
    const int poses = std::getenv("SWEEP_POSES") ? std::atoi(std::getenv("SWEEP_POSES")) : 1440;
    auto rel = [](double a, double b) { return std::abs(a - b)/std::max(std::abs(a), std::abs(b)); };
    double hertzJump = 0, simplifiedJump = 0, ratioJump = 0, ratioSmooth = 0;
    int handOvers = 0;
    for (unsigned seed = 101; seed <= 105; ++seed)
    {
        const ForceSweep h = forceSweep(seed, "hertz", poses, 5e-3);
        const ForceSweep hs = forceSweep(seed, "hertzSimplified", poses, 5e-3);
        // Raw jumps of |F| at hand-overs, and the jump of the ratio
        // |F_hertz|/|F_hertzSimplified| (same poses, same contacts: only R*
        // differs), which cancels the geometric part of a jump
        double hj = 0, sj = 0, rj = 0, rs = 0;
        int n = 0;
        for (int k = 1; k <= poses; ++k)
        {
            const double rho = h.F[k]/hs.F[k], rhoLast = h.F[k-1]/hs.F[k-1];
            if (h.types[k] != h.types[k-1])
            {
                ++n;
                hj = std::max(hj, rel(h.F[k], h.F[k-1]));
                sj = std::max(sj, rel(hs.F[k], hs.F[k-1]));
                rj = std::max(rj, rel(rho, rhoLast));
            }
            else
            {
                rs = std::max(rs, rel(rho, rhoLast));
            }
        }
        std::printf
        (
            "seed %u: %d hand-overs; largest jump of |F|: hertz %.3g,"
            " hertzSimplified %.3g; of |F_hertz|/|F_hertzSimplified| %.3g"
            " (between hand-overs %.3g)\n",
            seed, n, hj, sj, rj, rs
        );
        handOvers += n;
        hertzJump = std::max(hertzJump, hj);
        simplifiedJump = std::max(simplifiedJump, sj);
        ratioJump = std::max(ratioJump, rj);
        ratioSmooth = std::max(ratioSmooth, rs);
    }
    std::printf
    (
        "largest jump at a hand-over: |F| hertz %.4g, hertzSimplified %.4g;"
        " ratio %.4g (between hand-overs %.4g)\n",
        hertzJump, simplifiedJump, ratioJump, ratioSmooth
    );
    EXPECT_GE(handOvers, 50);
    // The excess potential (NarrowPhase.H): a vertex term takes the radius
    // of its closest feature's type (face r, edge r/sqrt(2), vertex r/2 for
    // equal radii: a factor sqrt(2) in R* at each change, 2^(1/4) in its
    // force, a relative jump of 1 - 2^(-1/4) = 0.159), its subtracted
    // vertex-vertex terms follow it, and the edge-edge term keeps its type
    // and fades out (its weight -> 0) at the end of its edge instead of
    // handing its force over. Measured: 0.229 (seed 103; 0.159 at seeds
    // 101, 102 and 105, 0.165 at 104), where a vertex term and a subtracted
    // vertex-vertex term change type at one pose. On main (windowed feature
    // pairs) the edge-edge contact at its cap k r handed over to
    // vertex-edge at full force: 1 - 1/sqrt(k sqrt(2)) = 0.734 for k = 10,
    // which the sweep reached; the excess potential must stay below it,
    // and above the single-term jump the sweep must reach
    const double k = WorldSettings().contact.maxEdgeRadiusRatio;
    const double mainBound = 1 - 1/std::sqrt(k*std::sqrt(2.0));
    EXPECT_LT(ratioJump, mainBound);
    EXPECT_GT(ratioJump, 1 - std::pow(2.0, -0.25) - 1e-2) << "the sweep no longer reaches a type change";
}


// hertzSimplified (one R* for every feature pair): the total contact force
// on B and its moment about B's centroid are continuous through every
// change of the pair's terms the sweep passes (five random hull pairs, B
// turned once at a held deepest overlap of 5 % of r_A + r_B, the sweep of
// hertzForceJumpAtHandOverIsBounded). A jump (a contact lost while loaded,
// one counted twice) keeps its size when the poses are doubled; a
// continuous change halves. The sweep runs at 5760 poses, the even ones
// being the 2880-pose sweep (same poses, bit for bit): for each pair the
// largest step between consecutive poses (|dF|/|F|, |dM|/(|F| R_B)) must
// fall below 0.7 of that at 2880 poses. Measured with the excess potential
// (NarrowPhase.H): at most 0.648 (seed 103, 231 hand-overs in the five
// pairs; main, windows and the merge partition: 0.62; without the
// partition 0.999)
TEST(handover, hertzSimplifiedForceAndMomentAreContinuous)
{
    const int poses = std::getenv("SWEEP_POSES") ? 2*std::atoi(std::getenv("SWEEP_POSES")) : 5760;
    int handOvers = 0;
    double worstRatio = 0;
    for (unsigned seed = 101; seed <= 105; ++seed)
    {
        const ForceSweep r = forceSweep(seed, "hertzSimplified", poses, 5e-3);
        // Largest relative steps of F and M, every pose (stride 1) or every
        // other one (stride 2)
        auto largest = [&](int stride, double& f, double& m)
        {
            f = m = 0;
            for (int k = stride; k <= poses; k += stride)
            {
                const double scale = std::max(r.F[k], r.F[k - stride]);
                ASSERT_GT(scale, 0) << "seed " << seed << ": no contact at pose " << k;
                f = std::max(f, (r.force[k] - r.force[k - stride]).norm()/scale);
                m = std::max(m, (r.moment[k] - r.moment[k - stride]).norm()/(scale*r.radiusB));
            }
        };
        double f1, m1, f2, m2;
        largest(1, f1, m1);
        largest(2, f2, m2);
        int n = 0;
        for (int k = 1; k <= poses; ++k) n += r.types[k] != r.types[k - 1];
        handOvers += n;
        std::printf
        (
            "seed %u: %d hand-overs; largest step of F %.3g (%d poses: %.3g),"
            " of M %.3g (%.3g)\n",
            seed, n, f1, poses/2, f2, m1, m2
        );
        EXPECT_LT(f1, 0.7*f2) << "seed " << seed << ": a jump of the force";
        EXPECT_LT(m1, 0.7*m2) << "seed " << seed << ": a jump of the moment";
        worstRatio = std::max(worstRatio, std::max(f1/f2, m1/m2));
    }
    std::printf("%d hand-overs; largest ratio of the steps (%d/%d poses) %.3g\n", handOvers, poses, poses/2, worstRatio);
    EXPECT_GE(handOvers, 50);
}


// The random-shape energy battery (broadPairInABox): 40 random pairs of
// hulls of clouds of 4 to 20 points, random radii, mass ratios, poses and
// velocities, e = 1, mu = 0, hertzSimplified, colliding with each other and
// with the six walls for 3 s each. Every impact (from the step before a
// contact starts to the step after the last one ends, wall contacts
// included) must keep the total energy within impactBound, each pair's
// drift below 5e-3, and no overlap may reach half the smaller radius (the
// model's range; Young's modulus is chosen for that, see broadPairInABox).
// Measured (1 thread) with the excess potential (NarrowPhase.H): 40 pairs,
// 1,397 impacts, the worst impact 1.5e-6 of the total energy, the worst
// drift 6.6e-6, overlaps up to 0.38 r (1,359 impacts, 1.5e-6, 3.2e-6 while
// a core that could not be dilated was redrawn: some clouds give other
// hulls since every hull dilates; main, windows and the merge
// partition: 1,413 impacts, 9.8e-7, 3.1e-6, 0.33 r). Before the
// vertex-edge band (main's history) one pair (seed 6) changed the energy
// by 14 % in one impact
TEST(handover, randomPolyhedraConserveEnergyAtEveryImpact)
{
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);     // two bodies: threads only add waiting
    int impacts = 0, pairs = 0;
    double worst = 0, drift = 0, deepest = 0;
    for (unsigned seed = 1; seed <= 40; ++seed)
    {
        const ImpactRecord r = broadPairInABox(seed, 3.0, "hertzSimplified");
        ++pairs;
        impacts += r.impacts;
        worst = std::max(worst, r.worst);
        drift = std::max(drift, std::abs(r.drift));
        deepest = std::max(deepest, r.deepest);
        std::printf
        (
            "seed %u: %d impacts, worst %.3g, drift %.3g, deepest overlap %.2g r_min,"
            " E %.3g Pa, dt %.3g s\n",
            seed, r.impacts, r.worst, r.drift, r.deepest, r.youngsModulus, r.timeStep
        );
        EXPECT_GE(r.impacts, 10) << "seed " << seed;
        EXPECT_LT(r.worst, impactBound) << "seed " << seed;
        EXPECT_LT(std::abs(r.drift), 5e-3) << "seed " << seed;
        EXPECT_LT(r.deepest, 0.5) << "seed " << seed;
    }
    omp_set_num_threads(threads);
    std::printf
    (
        "%d pairs, %d impacts: worst impact %.3g of the total energy (bound %g),"
        " worst drift %.3g, deepest overlap %.2g r_min\n",
        pairs, impacts, worst, impactBound, drift, deepest
    );
    EXPECT_GE(impacts, 1000);
}


namespace
{

//- The terms of the excess potential between hull A (fixed) and hull B at
//  B's pose (xB, qB), each with its law's potential w U, force on B and
//  moment about B's centroid (ContactLaw::evaluate at rest: no damping, no
//  tangential spring)
struct TermSum
{
    double U = 0;
    Vec3 F = Vec3::Zero();
    Vec3 M = Vec3::Zero();
};

//- The kind of a term from its keys and weight (NarrowPhase.H): 0 vertex
//  of A on B, 1 vertex of B on A, 2 vertex-vertex (subtracted), 3
//  edge-edge excess
int termKind(const FoundContact& c)
{
    const std::uint32_t kindA = c.featureA >> 30, kindB = c.featureB >> 30;
    if (kindA == kVertex && kindB == kFace) return 0;
    if (kindA == kFace && kindB == kVertex) return 1;
    if (kindA == kVertex && kindB == kVertex) return 2;
    return 3;
}

struct TermEvaluation
{
    TermSum kind[4];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> keys;
};

TermEvaluation evaluateTerms
(
    const DilatedShape& SA,
    const DilatedShape& SB,
    const Vec3& xB,
    const Quat& qB,
    const ContactLaw& law,
    const PairCoefficients& coeffs
)
{
    std::vector<Vec3> va(SA.core().vertices().begin(), SA.core().vertices().end());
    std::vector<Vec3> vb;
    const Mat3 RB = qB.toRotationMatrix();
    for (const Vec3& p : SB.core().vertices()) vb.push_back(RB*p + xB);
    const BodyView A{&SA, va.data(), Mat3::Identity(), Vec3::Zero(), Quat::Identity()};
    const BodyView B{&SB, vb.data(), RB, xB, qB};
    FoundContact found[World::maxContactsPerPair];
    Vec3 axis = Vec3::Zero();
    const int n = findContacts(A, B, NarrowPhaseSettings(), axis, found, World::maxContactsPerPair);
    TermEvaluation r;
    for (int k = 0; k < n; ++k)
    {
        Vec3 xi = Vec3::Zero();
        const ContactResult c = law.evaluate(coeffs, found[k].g, 1.0, Vec3::Zero(), xi, 0.0);
        TermSum& t = r.kind[termKind(found[k])];
        t.U += c.elasticEnergy;
        t.F += c.forceOnJ;
        t.M += (found[k].g.point - xB).cross(c.forceOnJ) + c.coupleOnJ;
        r.keys.emplace_back(found[k].featureA, found[k].featureB);
    }
    std::sort(r.keys.begin(), r.keys.end());
    return r;
}

} // anonymous namespace


// Every term of the excess potential (NarrowPhase.H) is a normal force
// along its closest-point direction, the edge-edge excess with the
// gradient of its weight: the force on B and its moment about B's centroid
// must be minus the gradient of the term's potential. Random hull pairs
// (7 and 10 vertices, r = 0.05) at random relative poses, B moved along a
// random direction until its deepest term overlaps by 3e-3 to 1.5e-2;
// central differences (h = 1e-6 m, 1e-6 rad; error O(h^2)) of each kind's
// potential (vertex of A on B, vertex of B on A, the subtracted
// vertex-vertex terms, the edge-edge excess) against its force and moment,
// for both laws (hertz: the edge-edge moment excepted, see below), at
// every pose where no term appears or ends within h. Each kind must be
// checked at 20 poses at least
TEST(handover, excessTermsForcesAreTheGradientOfTheirPotential)
{
    const PairCoefficients coeffs = PairCoefficients::make(ice(1e9), ice(1e9), PairProperties{0.0, 1.0});
    int checked[4] = {0, 0, 0, 0};
    double worst[4] = {0, 0, 0, 0};
    for (const std::string model : {"hertzSimplified", "hertz"})
    {
        ContactLawSettings ls;
        ls.model = model;
        const auto law = ContactLaw::New(ls);
        for (unsigned seed = 1; seed <= 60; ++seed)
        {
            std::mt19937_64 rng(seed);
            const auto SA = std::make_unique<DilatedShape>(randomHull(rng, 7, 0.5), 0.05);
            const auto SB = std::make_unique<DilatedShape>(randomHull(rng, 10, 0.6), 0.05);
            std::uniform_real_distribution<double> u(-1, 1);
            const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
            const Quat qB(Eigen::AngleAxisd(3*u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
            const double target = 3e-3 + 1.2e-2*0.5*(1 + u(rng));
            // Odd seeds: vertex on vertex (B's extreme vertex along -dir on
            // the line through A's extreme vertex along dir, so that the
            // closest points are the two vertices and the vertex-vertex
            // term is present); even seeds: B moved along dir from A's
            // centroid
            Vec3 origin = Vec3::Zero();
            if (seed % 2)
            {
                auto extreme = [](const DilatedShape& S, const Mat3& R, const Vec3& d)
                {
                    Vec3 best = R*S.core().vertices()[0];
                    for (const Vec3& p : S.core().vertices())
                    {
                        if ((R*p).dot(d) > best.dot(d)) best = R*p;
                    }
                    return best;
                };
                origin = extreme(*SA, Mat3::Identity(), dir) - extreme(*SB, qB.toRotationMatrix(), -dir);
            }
            // Bisection on the distance for the deepest term's overlap
            auto deepest = [&](double d)
            {
                std::vector<Vec3> va(SA->core().vertices().begin(), SA->core().vertices().end());
                std::vector<Vec3> vb;
                const Mat3 RB = qB.toRotationMatrix();
                const Vec3 x = origin + d*dir;
                for (const Vec3& p : SB->core().vertices()) vb.push_back(RB*p + x);
                const BodyView A{SA.get(), va.data(), Mat3::Identity(), Vec3::Zero(), Quat::Identity()};
                const BodyView B{SB.get(), vb.data(), RB, x, qB};
                if (coresIntersect(A, B)) return std::numeric_limits<double>::infinity();
                FoundContact found[World::maxContactsPerPair];
                Vec3 axis = Vec3::Zero();
                const int n = findContacts(A, B, NarrowPhaseSettings(), axis, found, World::maxContactsPerPair);
                double o = 0;
                for (int k = 0; k < n; ++k) o = std::max(o, found[k].g.overlap);
                return o;
            };
            double lo = seed % 2 ? -0.5 : 0, hi = seed % 2 ? 0.5 : 4;
            for (int it = 0; it < 50; ++it)
            {
                const double mid = 0.5*(lo + hi);
                (deepest(mid) > target ? lo : hi) = mid;
            }
            const Vec3 xB = origin + hi*dir;
            const TermEvaluation at = evaluateTerms(*SA, *SB, xB, qB, *law, coeffs);
            const double h = 1e-6;
            Vec3 gradX[4], gradPhi[4];
            bool stable = true;
            for (int c = 0; c < 3 && stable; ++c)
            {
                const Vec3 e = Vec3::Unit(c);
                const TermEvaluation px = evaluateTerms(*SA, *SB, xB + h*e, qB, *law, coeffs);
                const TermEvaluation mx = evaluateTerms(*SA, *SB, xB - h*e, qB, *law, coeffs);
                const Quat turnP(Eigen::AngleAxisd(h, e)), turnM(Eigen::AngleAxisd(-h, e));
                const TermEvaluation pp = evaluateTerms(*SA, *SB, xB, turnP*qB, *law, coeffs);
                const TermEvaluation mp = evaluateTerms(*SA, *SB, xB, turnM*qB, *law, coeffs);
                stable = px.keys == at.keys && mx.keys == at.keys && pp.keys == at.keys && mp.keys == at.keys;
                for (int k = 0; k < 4; ++k)
                {
                    gradX[k](c) = (px.kind[k].U - mx.kind[k].U)/(2*h);
                    gradPhi[k](c) = (pp.kind[k].U - mp.kind[k].U)/(2*h);
                }
            }
            if (!stable) continue;
            // Scale: the pair's total force
            Vec3 Ftot = Vec3::Zero();
            for (int k = 0; k < 4; ++k) Ftot += at.kind[k].F;
            const double scale = Ftot.norm() + 1e-300;
            for (int k = 0; k < 4; ++k)
            {
                if (at.kind[k].U == 0) continue;
                const double errF = (at.kind[k].F + gradX[k]).norm()/scale;
                const double errM = (at.kind[k].M + gradPhi[k]).norm()/(scale*SB->boundingRadius());
                worst[k] = std::max(worst[k], k == 3 && model == "hertz" ? errF : std::max(errF, errM));
                ++checked[k];
                EXPECT_LT(errF, 1e-4) << model << " seed " << seed << " kind " << k;
                // hertz: the edge-edge radius r/sin(theta) makes the term's
                // potential depend on the edges' angle, a moment the law
                // does not apply (as on main); its force is checked
                if (k == 3 && model == "hertz") continue;
                EXPECT_LT(errM, 1e-4) << model << " seed " << seed << " kind " << k;
            }
        }
    }
    std::printf
    (
        "poses checked (vertex of A, of B, vertex-vertex, edge-edge): %d %d %d %d;"
        " largest error of F, M over |F_total|: %.2g %.2g %.2g %.2g\n",
        checked[0], checked[1], checked[2], checked[3], worst[0], worst[1], worst[2], worst[3]
    );
    for (int k = 0; k < 4; ++k) EXPECT_GE(checked[k], 20) << "kind " << k;
}
