/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    The flux count of ice past a structure (statistics/IceClearance.H)
    against floes on known straight paths: which pass under the structure,
    which around and which outside the gate follows from each path's
    lateral offset alone; the counts and volumes must be exactly those, for
    a drift at an angle and a structure that moves. A floe rocking on the
    gate's line adds nothing net; periodic wraps, floes that appear and
    the transient are not counted; a floe pushed under the water near the
    structure is counted as such when it passes; bad settings name their
    entry.
\*---------------------------------------------------------------------------*/

#include "statistics/IceClearance.H"
#include "types.H"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using iceDEM::statistics::IceClearance;

namespace
{

IceClearance::Settings kullukGate(double angle = 0)
{
    IceClearance::Settings s;
    s.underRadius = 35;
    s.nearRadius = 60;
    s.dirX = 2*std::cos(angle);     // not normalised on purpose
    s.dirY = 2*std::sin(angle);
    s.maxStep = 30;
    return s;
}

} // End anonymous namespace


TEST(IceClearance, straightPathsAreCountedByTheirLateralOffset)
{
    const double angle = 0.5;
    const double ux = std::cos(angle), uy = std::sin(angle);
    // Lateral unit vector (left of the drift)
    const double px = -uy, py = ux;
    IceClearance counter(kullukGate(angle));

    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> offset(-90, 90), start(-200, -60),
        volume(50, 300), speed(0.2, 0.6), slope(-0.5, 0.5);
    // Oblique paths l = l0 + k s: where a path crosses the line s = 0 (l0)
    // is between two samples, not at one
    struct Path { double l, s0, v, vol, k; };
    std::vector<Path> paths;
    long under = 0, around = 0;
    double volUnder = 0, volAround = 0;
    for (int k = 0; k < 200; ++k)
    {
        Path p{offset(rng), start(rng), speed(rng), volume(rng), slope(rng)};
        // Keep clear of the class borders by more than round-off
        if (std::abs(std::abs(p.l) - 35) < 1e-6 || std::abs(std::abs(p.l) - 60) < 1e-6)
        {
            continue;
        }
        paths.push_back(p);
        if (std::abs(p.l) < 35) { ++under; volUnder += p.vol; }
        else if (std::abs(p.l) < 60) { ++around; volAround += p.vol; }
    }
    ASSERT_GT(under, 30);
    ASSERT_GT(around, 30);

    // The structure surges: the axis moves along x by a few metres. Samples
    // 20 s apart: a floe moves up to 13.4 m between them (maxStep 30 m)
    const double dt = 20;
    std::vector<IceClearance::Floe> floes(paths.size());
    for (int n = 0; n <= 100; ++n)
    {
        const double t = n*dt;
        const double ax = 3*std::sin(0.01*t), ay = -1.5;
        for (std::size_t k = 0; k < paths.size(); ++k)
        {
            const Path& p = paths[k];
            const double s = p.s0 + p.v*t;
            const double l = p.l + p.k*s;
            floes[k] = {int(k), ax + s*ux + l*px, ay + s*uy + l*py, 0.1, p.vol};
        }
        counter.sample(ax, ay, floes, true);
    }
    // Every path has crossed (s0 + 0.2*2000 > 0)
    EXPECT_EQ(counter.counts().passedUnder, under);
    EXPECT_EQ(counter.counts().passedAround, around);
    EXPECT_EQ(counter.counts().passedSubmerged, 0);
    EXPECT_NEAR(counter.counts().volumeUnder, volUnder, 1e-9*volUnder);
    EXPECT_NEAR(counter.counts().volumeAround, volAround, 1e-9*volAround);
}


TEST(IceClearance, aFloeRockingOnTheLineAddsNothingNet)
{
    IceClearance counter(kullukGate());
    std::vector<IceClearance::Floe> floes(1);
    // 20 oscillations across s = 0 at lateral 10 m (under), ending upstream
    for (int n = 0; n <= 400; ++n)
    {
        const double s = -1 + 2*std::sin(0.1*M_PI*n + 0.3);
        floes[0] = {42, s, 10, 0.1, 100};
        counter.sample(0, 0, floes, true);
    }
    const double sEnd = -1 + 2*std::sin(0.1*M_PI*400 + 0.3);
    const long expected = sEnd >= 0 ? 1 : 0;   // started upstream (s < 0)
    EXPECT_EQ(counter.counts().passedUnder, expected);
    EXPECT_EQ(counter.counts().passedAround, 0);
    EXPECT_NEAR(counter.counts().volumeUnder, 100.0*expected, 1e-12);
}


TEST(IceClearance, wrapsAndNewFloesAreNotCounted)
{
    IceClearance counter(kullukGate());
    std::vector<IceClearance::Floe> floes
    {
        {1, 499, 45, 0.1, 1},     // about to wrap along the drift
        {2, -1, 499, 0.1, 1},     // crosses the line while wrapping across
        {3, -5, -40, 0.1, 1}      // an ordinary floe passing around
    };
    counter.sample(0, 0, floes, true);
    floes[0].x = -499;            // periodic wrap in x: s from + to -
    floes[1].x = 1; floes[1].y = -499;
    floes[2].x = 5;
    counter.sample(0, 0, floes, true);
    EXPECT_EQ(counter.counts().passedUnder, 0);
    EXPECT_EQ(counter.counts().passedAround, 1);

    // Floe 3 leaves (outflow), a new floe with its id appears downstream of
    // where it was: only recorded, then followed
    floes.pop_back();
    counter.sample(0, 0, floes, true);
    floes.push_back({3, -2, 0, 0.1, 1});
    counter.sample(0, 0, floes, true);
    EXPECT_EQ(counter.counts().passedUnder, 0);
    floes.back().x = 2;
    counter.sample(0, 0, floes, true);
    EXPECT_EQ(counter.counts().passedUnder, 1);
    EXPECT_EQ(counter.counts().passedAround, 1);
}


TEST(IceClearance, theTransientIsFollowedButNotCounted)
{
    IceClearance counter(kullukGate());
    std::vector<IceClearance::Floe> floes{{1, -1, 0, 0.1, 1}};
    counter.sample(0, 0, floes, false);
    floes[0].x = 1;                // crosses during the transient
    counter.sample(0, 0, floes, false);
    floes[0].x = 3;
    counter.sample(0, 0, floes, true);
    EXPECT_EQ(counter.counts().passedUnder, 0);
    floes[0].x = -1;               // back upstream after it: counted -1
    counter.sample(0, 0, floes, true);
    EXPECT_EQ(counter.counts().passedUnder, -1);
}


TEST(IceClearance, aFloePushedUnderNearTheHullIsCountedWhenItPasses)
{
    IceClearance counter(kullukGate());
    // Floe 1: submerged 50 m upstream, surfaces, passes around at 45 m;
    // floe 2: submerged 100 m away (outside the gate's radius), passes
    // around; floe 3: submerged while it passes under
    std::vector<IceClearance::Floe> floes
    {
        {1, -20, 45, -0.2, 1}, {2, -100, 45, -0.2, 1}, {3, -3, 0, -1.0, 1}
    };
    counter.sample(0, 0, floes, true);
    EXPECT_EQ(counter.now().near, 2);
    EXPECT_EQ(counter.now().under, 1);
    EXPECT_EQ(counter.now().submergedNear, 2);
    floes[0].top = 0.1;           // surfaced, still near: the mark stays
    floes[1] = {2, -2, 45, 0.1, 1};
    counter.sample(0, 0, floes, true);
    floes[0].x = 2;  floes[1].x = 2;  floes[2].x = 3;
    counter.sample(0, 0, floes, true);
    EXPECT_EQ(counter.counts().passedAround, 2);
    EXPECT_EQ(counter.counts().passedUnder, 1);
    EXPECT_EQ(counter.counts().passedSubmerged, 2);
}


TEST(IceClearance, badSettingsNameTheirEntry)
{
    auto entryOf = [](IceClearance::Settings s) -> std::string
    {
        try { IceClearance c(s); }
        catch (const iceDEM::Error& e) { return e.entry(); }
        return "";
    };
    IceClearance::Settings s = kullukGate();
    s.underRadius = 0;
    EXPECT_EQ(entryOf(s), "underRadius");
    s = kullukGate();
    s.nearRadius = 35;
    EXPECT_EQ(entryOf(s), "nearRadius");
    s = kullukGate();
    s.maxStep = NAN;
    EXPECT_EQ(entryOf(s), "maxStep");
    s = kullukGate();
    s.dirX = 0;  s.dirY = 0;
    EXPECT_EQ(entryOf(s), "direction");
    EXPECT_EQ(entryOf(kullukGate()), "");
}
