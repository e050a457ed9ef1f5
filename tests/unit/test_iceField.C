/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the Free
    Software Foundation, either version 3 of the License, or (at your option)
    any later version. See <http://www.gnu.org/licenses/>.

Description
    Unit tests of the floe core (field/IceFloe.H) and the Voronoi ice field
    generator (field/VoronoiField.H).
\*---------------------------------------------------------------------------*/

#include "field/IceFloe.H"
#include "field/VoronoiField.H"
#include "geometry/DilatedShape.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <tuple>
#include <limits>

using namespace iceDEM;

namespace
{

constexpr double pi = 3.14159265358979323846;

//- Expect f() to throw iceDEM::Error naming the entry
void expectError(const std::function<void()>& f, const std::string& entry)
{
    try
    {
        f();
        ADD_FAILURE() << "no Error thrown (expected entry '" << entry << "')";
    }
    catch (const Error& e)
    {
        EXPECT_EQ(e.entry(), entry) << "message: " << e.what();
    }
}

double zMin(const ConvexPolyhedron& p)
{
    double z = std::numeric_limits<double>::max();
    for (const Vec3& v : p.vertices()) z = std::min(z, v.z());
    return z;
}

double zMax(const ConvexPolyhedron& p)
{
    double z = -std::numeric_limits<double>::max();
    for (const Vec3& v : p.vertices()) z = std::max(z, v.z());
    return z;
}

//- Outline of the top face (normal +z) of a prism-like polyhedron
std::vector<Vec2> topOutline(const ConvexPolyhedron& p)
{
    for (int f = 0; f < int(p.faces().size()); ++f)
    {
        if (p.faces()[f].normal.z() > 0.5)
        {
            std::vector<Vec2> out;
            for (int k = 0; k < p.faces()[f].count; ++k)
            {
                const Vec3& v = p.vertices()[p.faceVertex(f, k)];
                out.emplace_back(v.x(), v.y());
            }
            return out;
        }
    }
    return {};
}

//- Separating-axis test: convex polygons strictly apart
bool separated(const std::vector<Vec2>& a, const std::vector<Vec2>& b)
{
    auto axisSeparates = [](const std::vector<Vec2>& p, const std::vector<Vec2>& q)
    {
        const std::size_t n = p.size();
        for (std::size_t i = 0; i < n; ++i)
        {
            const Vec2 e = p[(i + 1) % n] - p[i];
            const Vec2 ax(e.y(), -e.x());
            double pMin = 1e300, pMax = -1e300, qMin = 1e300, qMax = -1e300;
            for (const Vec2& v : p)
            {
                pMin = std::min(pMin, ax.dot(v));
                pMax = std::max(pMax, ax.dot(v));
            }
            for (const Vec2& v : q)
            {
                qMin = std::min(qMin, ax.dot(v));
                qMax = std::max(qMax, ax.dot(v));
            }
            if (pMax < qMin || qMax < pMin)
            {
                return true;
            }
        }
        return false;
    };
    return axisSeparates(a, b) || axisSeparates(b, a);
}

VoronoiFieldSettings baseSettings(double c)
{
    VoronoiFieldSettings s;
    s.xmin = -100;
    s.xmax = 100;
    s.ymin = -50;
    s.ymax = 50;
    s.nFloes = 150;
    s.concentration = c;
    s.thickness.value = 1.0;
    s.radius = 0.05;
    s.seed = 7;
    return s;
}

double totalArea(const std::vector<Floe>& floes)
{
    double a = 0;
    for (const Floe& f : floes) a += f.area();
    return a;
}

} // anonymous namespace


// * * * * * * * * * * * * * * * * floeCore * * * * * * * * * * * * * * * //

TEST(IceFloe, SquareCoreIsExact)
{
    const double a = 10;
    const double r = 0.1;
    const double h = 1.0;
    const double zb = -0.88;
    const std::vector<Vec2> square{{0, 0}, {a, 0}, {a, a}, {0, a}};

    const std::vector<Vec2> c2 = shrinkConvexPolygon(square, r);
    ASSERT_EQ(c2.size(), 4u);
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (const Vec2& v : c2)
    {
        xmin = std::min(xmin, v.x()); xmax = std::max(xmax, v.x());
        ymin = std::min(ymin, v.y()); ymax = std::max(ymax, v.y());
    }
    EXPECT_NEAR(xmax - xmin, a - 2*r, 1e-12);
    EXPECT_NEAR(ymax - ymin, a - 2*r, 1e-12);
    EXPECT_NEAR(xmin, r, 1e-12);
    EXPECT_NEAR(ymin, r, 1e-12);

    const ConvexPolyhedron core = floeCore(square, zb, h, r);
    EXPECT_NEAR(zMin(core), zb + r, 1e-12);
    EXPECT_NEAR(zMax(core) - zMin(core), h - 2*r, 1e-12);
    EXPECT_NEAR(core.volume(), (a - 2*r)*(a - 2*r)*(h - 2*r), 1e-12);

    // Outer polyhedron of the core: the floe
    const ConvexPolyhedron outer = core.offset(r);
    EXPECT_NEAR(zMin(outer), zb, 1e-12);
    EXPECT_NEAR(zMax(outer) - zMin(outer), h, 1e-12);
    EXPECT_NEAR(std::abs(polygonSignedArea(topOutline(outer))), a*a, 1e-12*a*a);
    EXPECT_NEAR(outer.volume(), a*a*h, 1e-12*a*a*h);
}


TEST(IceFloe, IrregularOutlineRoundTrip)
{
    // A convex hexagon far from the origin, clockwise on input
    const Vec2 o(312.25, -187.5);
    std::vector<Vec2> outline{{0, 0}, {7.3, -1.1}, {11.8, 3.4}, {9.9, 9.2}, {2.2, 10.7}, {-2.5, 5.3}};
    for (Vec2& p : outline) p += o;
    std::reverse(outline.begin(), outline.end());

    const double r = 0.2;
    const double h = 1.3;
    const double zb = -1.1;
    const double A = std::abs(polygonSignedArea(outline));

    const ConvexPolyhedron core = floeCore(outline, zb, h, r);
    EXPECT_EQ(int(core.faces().size()), 6 + 2);

    const ConvexPolyhedron outer = core.offset(r);
    const std::vector<Vec2> top = topOutline(outer);
    ASSERT_EQ(top.size(), outline.size());
    EXPECT_NEAR(std::abs(polygonSignedArea(top)), A, 1e-12*A);
    EXPECT_NEAR(zMin(outer), zb, 1e-12);
    EXPECT_NEAR(zMax(outer) - zMin(outer), h, 1e-12);
    // Every original vertex is a vertex of the outer outline
    for (const Vec2& p : outline)
    {
        double d = 1e300;
        for (const Vec2& q : top) d = std::min(d, (p - q).norm());
        EXPECT_LT(d, 1e-10);
    }
}


TEST(IceFloe, VanishingEdgeIsDropped)
{
    // A short edge (length 0.1) between two corners of 115 deg vanishes for
    // r = 0.2: L < r (cot(a/2) + cot(b/2)) = 0.2*2*0.637
    const std::vector<Vec2> outline
    {
        {0, 0}, {10, 0}, {12, 0.95}, {12, 1.05}, {10, 2}, {0, 2}
    };
    const double r = 0.2;
    const std::vector<Vec2> core = shrinkConvexPolygon(outline, r);
    EXPECT_EQ(core.size(), 5u);

    // Every core vertex at distance >= r inside every original edge line,
    // and on exactly two moved lines
    const std::size_t n = outline.size();
    for (const Vec2& v : core)
    {
        int onLine = 0;
        for (std::size_t i = 0; i < n; ++i)
        {
            const Vec2 e = (outline[(i + 1) % n] - outline[i]).normalized();
            const Vec2 nrm(e.y(), -e.x());
            const double d = nrm.dot(outline[i] - v);
            EXPECT_GE(d, r - 1e-12);
            if (std::abs(d - r) < 1e-12) ++onLine;
        }
        EXPECT_EQ(onLine, 2);
    }
    // The tip is on the x-axis of symmetry
    const Vec2 tip = *std::max_element
    (
        core.begin(), core.end(),
        [](const Vec2& a, const Vec2& b) { return a.x() < b.x(); }
    );
    EXPECT_NEAR(tip.y(), 1.0, 1e-12);
}


TEST(IceFloe, CleansCollinearAndRepeatedVertices)
{
    const std::vector<Vec2> outline
    {
        {0, 0}, {0, 4}, {0, 4}, {4, 4}, {4, 2}, {4, 0}, {2, 0}
    };
    const std::vector<Vec2> p = convexOutline(outline);
    EXPECT_EQ(p.size(), 4u);
    EXPECT_GT(polygonSignedArea(p), 0);
    EXPECT_NEAR(polygonSignedArea(p), 16, 1e-12);
}


TEST(IceFloe, BadInputNamesTheEntry)
{
    const std::vector<Vec2> square{{0, 0}, {4, 0}, {4, 4}, {0, 4}};
    expectError([&]{ floeCore(square, 0, 0.2, 0.1); }, "thickness");
    expectError([&]{ floeCore(square, 0, 0.1, 0.1); }, "thickness");
    // Up to 4r the core is thinner than 2r, which no dilated element
    // allows: refused here by the thickness, not later by the element's
    // radius
    expectError([&]{ floeCore(square, 0, 0.3, 0.1); }, "thickness");
    expectError([&]{ floeCore(square, 0, 0.4, 0.1); }, "thickness");
    // Above 4r by the tolerance, every floe's core is a valid element
    for (const double r : {0.01, 0.03, 0.05, 0.1, 0.13, 0.25})
    {
        const double h = DilatedShape::minOuterWidthInRadii*r*(1 + 2*defaultFloeTolerance);
        for (const double zBottom : {0.0, -0.9*h, -703.1})
        {
            EXPECT_NO_THROW(DilatedShape(floeCore(square, zBottom, h, r), r))
                << "r " << r << ", zBottom " << zBottom;
        }
    }
    expectError([&]{ floeCore(square, 0, 1.0, 0.0); }, "radius");
    expectError([&]{ floeCore(square, 0, 1.0, -0.1); }, "radius");

    // Non-convex (L shape), degenerate, too small for the radius
    const std::vector<Vec2> L{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
    expectError([&]{ floeCore(L, 0, 1.0, 0.1); }, "outline");
    expectError([&]{ floeCore({{0, 0}, {1, 0}}, 0, 1.0, 0.1); }, "outline");
    expectError([&]{ floeCore({{0, 0}, {1, 0}, {2, 0}}, 0, 1.0, 0.1); }, "outline");
    expectError
    (
        [&]{ floeCore({{0, 0}, {0.15, 0}, {0.15, 0.15}, {0, 0.15}}, 0, 1.0, 0.1); },
        "outline"
    );
    // Exactly 2r wide: the core is a point
    expectError
    (
        [&]{ floeCore({{0, 0}, {0.2, 0}, {0.2, 0.2}, {0, 0.2}}, 0, 1.0, 0.1); },
        "outline"
    );
    // Self-intersecting (a bow tie)
    expectError
    (
        [&]{ floeCore({{0, 0}, {4, 4}, {4, 0}, {0, 4}}, 0, 1.0, 0.1); },
        "outline"
    );
}


// * * * * * * * * * * * * * * * * Geometry * * * * * * * * * * * * * * * //

TEST(VoronoiField, CircleRectangleArea)
{
    const double R = 3;
    EXPECT_NEAR(circleRectangleArea({0, 0}, R, -5, 5, -5, 5), pi*R*R, 1e-12);
    EXPECT_NEAR(circleRectangleArea({0, 0}, R, 0, 5, 0, 5), pi*R*R/4, 1e-12);
    EXPECT_NEAR(circleRectangleArea({0, 0}, R, -5, 5, 0, 5), pi*R*R/2, 1e-12);
    EXPECT_NEAR(circleRectangleArea({0, 0}, R, 10, 15, 0, 5), 0, 1e-12);

    // Against a midpoint-rule integration of an off-centre case
    const Vec2 c(0.7, -0.4);
    const double x0 = -1.3, x1 = 2.9, y0 = -2.2, y1 = 1.1;
    const int n = 200000;
    double num = 0;
    for (int i = 0; i < n; ++i)
    {
        const double x = x0 + (x1 - x0)*(i + 0.5)/n;
        const double dx = x - c.x();
        if (std::abs(dx) >= R) continue;
        const double s = std::sqrt(R*R - dx*dx);
        const double lo = std::max(y0, c.y() - s);
        const double hi = std::min(y1, c.y() + s);
        if (hi > lo) num += (hi - lo)*(x1 - x0)/n;
    }
    EXPECT_NEAR(circleRectangleArea(c, R, x0, x1, y0, y1), num, 1e-6);
}


TEST(VoronoiField, CellsTileTheRectangle)
{
    FieldRandom rng(3);
    std::vector<Vec2> seeds(60);
    for (Vec2& p : seeds) p = Vec2(rng.uniform(0, 30), rng.uniform(0, 20));
    const auto cells = voronoiCells(seeds, 0, 30, 0, 20);
    ASSERT_EQ(cells.size(), seeds.size());
    double A = 0;
    for (std::size_t i = 0; i < cells.size(); ++i)
    {
        A += std::abs(polygonSignedArea(cells[i]));
        // The seed is in its own cell and nearer to it than to any other seed
        EXPECT_TRUE(pointInPolygon(seeds[i], cells[i]));
        const Vec2 g = polygonCentroid(cells[i]);
        for (std::size_t j = 0; j < seeds.size(); ++j)
        {
            EXPECT_LE((g - seeds[i]).norm(), (g - seeds[j]).norm() + 1e-12);
        }
    }
    EXPECT_NEAR(A, 600, 1e-9);
}


// * * * * * * * * * * * * * * * * Generator * * * * * * * * * * * * * * * //

TEST(VoronoiField, ConcentrationWithinOnePercent)
{
    for (const double c : {0.5, 0.7, 0.9})
    {
        VoronoiFieldSettings s = baseSettings(c);
        VoronoiFieldReport rep;
        const std::vector<Floe> floes = generateVoronoiField(s, rep);
        const double achieved = totalArea(floes)/(200.0*100.0);
        EXPECT_NEAR(achieved, c, 0.01*c) << "c = " << c;
        EXPECT_NEAR(rep.concentration, achieved, 1e-12);
        EXPECT_EQ(rep.nFloes, int(floes.size()));
        EXPECT_EQ(rep.nFloes + rep.nTooSmall, s.nFloes);
        // Without the correction the collapsed edges cost very little
        s.correctConcentration = false;
        const std::vector<Floe> raw = generateVoronoiField(s, rep);
        EXPECT_NEAR(totalArea(raw)/(200.0*100.0), c, 0.01*c) << "c = " << c;
    }
}


TEST(VoronoiField, NoOverlapAtStartAndInsideRegion)
{
    for (const double c : {0.5, 0.9, 0.99})
    {
        VoronoiFieldSettings s = baseSettings(c);
        s.lloydIterations = (c > 0.95 ? 2 : 0);
        VoronoiFieldReport rep;
        const std::vector<Floe> floes = generateVoronoiField(s, rep);
        for (std::size_t i = 0; i < floes.size(); ++i)
        {
            for (const Vec2& p : floes[i].outline)
            {
                EXPECT_GE(p.x(), s.xmin - 1e-12);
                EXPECT_LE(p.x(), s.xmax + 1e-12);
                EXPECT_GE(p.y(), s.ymin - 1e-12);
                EXPECT_LE(p.y(), s.ymax + 1e-12);
            }
            for (std::size_t j = i + 1; j < floes.size(); ++j)
            {
                EXPECT_TRUE(separated(floes[i].outline, floes[j].outline))
                    << "floes " << i << " and " << j << " overlap, c = " << c;
            }
        }
    }
}


TEST(VoronoiField, CountAndSizeStatistics)
{
    // meanFloeArea: N = round(c l w / A)
    VoronoiFieldSettings s = baseSettings(0.6);
    s.nFloes = 0;
    s.meanFloeArea = 60;
    VoronoiFieldReport rep;
    std::vector<Floe> floes = generateVoronoiField(s, rep);
    EXPECT_EQ(rep.nCells, 200);
    EXPECT_EQ(rep.nTooSmall, 0);
    EXPECT_EQ(rep.nFloes, 200);
    EXPECT_NEAR(rep.meanArea, 60, 0.01*60);

    double sum = 0, sum2 = 0;
    for (const Floe& f : floes) sum += f.area();
    const double mean = sum/floes.size();
    for (const Floe& f : floes) sum2 += (f.area() - mean)*(f.area() - mean);
    EXPECT_NEAR(rep.meanArea, mean, 1e-9);
    EXPECT_NEAR(rep.sdArea, std::sqrt(sum2/floes.size()), 1e-9);

    int nHist = 0;
    double edges = 0;
    for (std::size_t k = 0; k < rep.edgeHistogram.size(); ++k)
    {
        nHist += rep.edgeHistogram[k];
        edges += double(k)*rep.edgeHistogram[k];
    }
    EXPECT_EQ(nHist, rep.nFloes);
    // Mean edge count of a bounded Voronoi tessellation: a little below 6
    EXPECT_GT(edges/nHist, 4.5);
    EXPECT_LT(edges/nHist, 6.0);

    // Lloyd relaxation makes the floes more regular
    const double cv0 = rep.sdArea/rep.meanArea;
    s.lloydIterations = 20;
    generateVoronoiField(s, rep);
    const double cv20 = rep.sdArea/rep.meanArea;
    EXPECT_LT(cv20, 0.5*cv0) << "cv " << cv0 << " -> " << cv20;
}


TEST(VoronoiField, ThicknessAndFloating)
{
    VoronoiFieldSettings s = baseSettings(0.7);
    s.velocity = Vec3(0.3, -0.1, 0);
    VoronoiFieldReport rep;

    s.thickness.distribution = ThicknessSettings::Distribution::uniform;
    s.thickness.min = 0.8;
    s.thickness.max = 1.6;
    std::vector<Floe> floes = generateVoronoiField(s, rep);
    for (const Floe& f : floes)
    {
        EXPECT_GE(f.thickness, 0.8);
        EXPECT_LT(f.thickness, 1.6);
        EXPECT_NEAR(f.zBottom, -(900.0/1025.0)*f.thickness, 1e-15);
        EXPECT_EQ(f.radius, s.radius);
        EXPECT_EQ(f.velocity, s.velocity);
    }
    EXPECT_NEAR(rep.meanThickness, 1.2, 0.05);

    s.thickness.distribution = ThicknessSettings::Distribution::normal;
    s.thickness.mean = 1.0;
    s.thickness.standardDeviation = 0.2;
    s.thickness.min = 0.7;
    s.thickness.max = 1.5;
    floes = generateVoronoiField(s, rep);
    for (const Floe& f : floes)
    {
        EXPECT_GE(f.thickness, 0.7);
        EXPECT_LE(f.thickness, 1.5);
    }
    EXPECT_NEAR(rep.meanThickness, 1.0 + 0.02, 0.05);
}


TEST(VoronoiField, HilbertNumberingKeepsTheFloesAndBringsNeighboursTogether)
{
    // The same field in two numberings: the same floes (one is a
    // permutation of the other), and along the Hilbert curve consecutive
    // floes are neighbours, where in seed order they are anywhere
    VoronoiFieldSettings s = baseSettings(0.7);
    s.nFloes = 800;
    s.lloydIterations = 2;
    s.thickness.distribution = ThicknessSettings::Distribution::uniform;
    s.thickness.min = 0.8;
    s.thickness.max = 1.6;
    VoronoiFieldReport rep;
    s.floeNumbering = FloeNumbering::seed;
    const std::vector<Floe> bySeed = generateVoronoiField(s, rep);
    s.floeNumbering = FloeNumbering::hilbert;
    const std::vector<Floe> byCurve = generateVoronoiField(s, rep);
    ASSERT_EQ(bySeed.size(), byCurve.size());

    auto key = [](const Floe& f)
    {
        return std::make_tuple(f.centroid().x(), f.centroid().y(), f.thickness);
    };
    std::vector<std::tuple<double, double, double>> a, b;
    for (const Floe& f : bySeed) a.push_back(key(f));
    for (const Floe& f : byCurve) b.push_back(key(f));
    EXPECT_NE(a, b);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);

    auto meanStep = [](const std::vector<Floe>& floes)
    {
        double d = 0;
        for (std::size_t i = 1; i < floes.size(); ++i)
        {
            d += (floes[i].centroid() - floes[i - 1].centroid()).norm();
        }
        return d/double(floes.size() - 1);
    };
    // Floe spacing sqrt(region area/N) = 5 m. Along the curve a step is
    // about one spacing (6.0 m: neighbours, and a few jumps between the
    // curve's quadrants); in random order about a third of the region (80 m)
    const double spacing = std::sqrt(200.0*100.0/800.0);
    EXPECT_LT(meanStep(byCurve), 1.5*spacing) << "spacing " << spacing;
    EXPECT_GT(meanStep(bySeed), 10*spacing) << "spacing " << spacing;

    expectError
    (
        [&]{ floeNumberingFromName("random"); }, "floeNumbering"
    );
}


TEST(VoronoiField, ReproducibleFromTheSeed)
{
    VoronoiFieldSettings s = baseSettings(0.7);
    s.lloydIterations = 3;
    s.thickness.distribution = ThicknessSettings::Distribution::normal;
    s.thickness.min = 0.5;
    s.thickness.max = 1.5;
    s.exclusionZones.push_back({"hull", ExclusionZone::Type::circle, {10, 5}, 15, {}});
    VoronoiFieldReport r1, r2, r3;
    const std::vector<Floe> a = generateVoronoiField(s, r1);
    const std::vector<Floe> b = generateVoronoiField(s, r2);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        ASSERT_EQ(a[i].outline.size(), b[i].outline.size());
        for (std::size_t k = 0; k < a[i].outline.size(); ++k)
        {
            EXPECT_EQ(a[i].outline[k].x(), b[i].outline[k].x());
            EXPECT_EQ(a[i].outline[k].y(), b[i].outline[k].y());
        }
        EXPECT_EQ(a[i].thickness, b[i].thickness);
    }
    EXPECT_EQ(r1.concentration, r2.concentration);

    s.seed = 8;
    const std::vector<Floe> c = generateVoronoiField(s, r3);
    EXPECT_NE(c[0].outline[0].x(), a[0].outline[0].x());

    // The random stream itself is fixed by the standard
    FieldRandom rng(1);
    std::mt19937_64 ref(1);
    EXPECT_EQ(rng.uniform01(), double(ref() >> 11)*0x1.0p-53);
}


TEST(VoronoiField, ExclusionZonesHonoured)
{
    VoronoiFieldSettings s = baseSettings(0.7);
    s.nFloes = 300;
    const Vec2 hc(-30, 0);
    const double hr = 25;
    s.exclusionZones.push_back({"hull", ExclusionZone::Type::circle, hc, hr, {}});
    const std::vector<Vec2> box{{40, -20}, {70, -20}, {70, 20}, {40, 20}};
    s.exclusionZones.push_back({"box", ExclusionZone::Type::polygon, {}, 0, box});

    VoronoiFieldReport rep;
    const std::vector<Floe> floes = generateVoronoiField(s, rep);
    EXPECT_GT(rep.nExcluded, 0);

    const double excluded = pi*hr*hr + 30*40;
    EXPECT_NEAR(rep.excludedArea, excluded, 1e-9);
    const double achieved = totalArea(floes)/(200*100 - excluded);
    EXPECT_NEAR(achieved, 0.7, 0.01*0.7);
    EXPECT_NEAR(rep.concentration, achieved, 1e-12);

    for (const Floe& f : floes)
    {
        EXPECT_TRUE(separated(f.outline, box));
        const std::size_t n = f.outline.size();
        EXPECT_FALSE(pointInPolygon(hc, f.outline));
        for (std::size_t i = 0; i < n; ++i)
        {
            const Vec2 a = f.outline[i];
            const Vec2 ab = f.outline[(i + 1) % n] - a;
            const double t = std::clamp((hc - a).dot(ab)/ab.squaredNorm(), 0.0, 1.0);
            EXPECT_GT((hc - (a + t*ab)).norm(), hr);
        }
    }

    // Without the correction the ice-free ring lowers the concentration
    s.correctConcentration = false;
    VoronoiFieldReport raw;
    generateVoronoiField(s, raw);
    EXPECT_LT(raw.concentration, rep.concentration);
}


TEST(VoronoiField, GeneratedFloesHaveExactCores)
{
    VoronoiFieldSettings s = baseSettings(0.8);
    s.nFloes = 40;
    s.radius = 0.2;
    VoronoiFieldReport rep;
    const std::vector<Floe> floes = generateVoronoiField(s, rep);
    for (const Floe& f : floes)
    {
        const ConvexPolyhedron outer = f.core().offset(f.radius);
        const std::vector<Vec2> top = topOutline(outer);
        EXPECT_EQ(top.size(), f.outline.size());
        EXPECT_NEAR(std::abs(polygonSignedArea(top)), f.area(), 1e-10*f.area());
        EXPECT_NEAR(zMax(outer) - zMin(outer), f.thickness, 1e-12);
        EXPECT_GE(convexPolygonWidth(shrinkConvexPolygon(f.outline, f.radius)), 2*f.radius);
    }
}


TEST(VoronoiField, BadInputNamesTheEntry)
{
    auto gen = [](const VoronoiFieldSettings& s)
    {
        VoronoiFieldReport rep;
        generateVoronoiField(s, rep);
    };
    VoronoiFieldSettings s;

    s = baseSettings(0.0);  expectError([&]{ gen(s); }, "concentration");
    s = baseSettings(1.2);  expectError([&]{ gen(s); }, "concentration");
    s = baseSettings(-0.5); expectError([&]{ gen(s); }, "concentration");
    // At 1 (or below it by less than the tolerance) the floes tile the
    // region and touch their neighbours, which the DEM refuses at the start
    s = baseSettings(1.0);  expectError([&]{ gen(s); }, "concentration");
    s = baseSettings(1 - 1e-12);  expectError([&]{ gen(s); }, "concentration");
    // Thinner than 2r in the plane: no element
    s = baseSettings(0.5);
    s.minCoreWidthRatio = 1.9;
    expectError([&]{ gen(s); }, "minCoreWidthRatio");

    s = baseSettings(0.5);
    s.thickness.value = 0.1;
    expectError([&]{ gen(s); }, "thickness");
    s.thickness.distribution = ThicknessSettings::Distribution::uniform;
    s.thickness.min = 0.05;
    s.thickness.max = 1;
    expectError([&]{ gen(s); }, "thickness");

    s = baseSettings(0.5);
    s.radius = 0;
    expectError([&]{ gen(s); }, "radius");

    s = baseSettings(0.5);
    s.xmax = s.xmin;
    expectError([&]{ gen(s); }, "region");
    s = baseSettings(0.5);
    s.xmax = s.xmin + 0.1;
    expectError([&]{ gen(s); }, "region");

    s = baseSettings(0.5);
    s.nFloes = 0;
    s.meanFloeArea = 1e6;
    expectError([&]{ gen(s); }, "meanFloeArea");
    s = baseSettings(0.5);
    s.nFloes = 1000000;
    expectError([&]{ gen(s); }, "nFloes");

    s = baseSettings(0.5);
    s.iceDensity = -900;
    expectError([&]{ gen(s); }, "iceDensity");
    s = baseSettings(0.5);
    s.waterDensity = -1025;
    expectError([&]{ gen(s); }, "waterDensity");

    s = baseSettings(0.5);
    s.lloydIterations = -1;
    expectError([&]{ gen(s); }, "lloydIterations");

    // A zone covering the region, overlapping zones, a bad polygon
    s = baseSettings(0.5);
    s.exclusionZones.push_back({"big", ExclusionZone::Type::circle, {0, 0}, 500, {}});
    expectError([&]{ gen(s); }, "exclusionZones");
    s = baseSettings(0.5);
    s.exclusionZones.push_back
    (
        {"all", ExclusionZone::Type::polygon, {}, 0, {{-200, -200}, {200, -200}, {200, 200}, {-200, 200}}}
    );
    expectError([&]{ gen(s); }, "exclusionZones");
    s = baseSettings(0.5);
    s.exclusionZones.push_back({"a", ExclusionZone::Type::circle, {0, 0}, 10, {}});
    s.exclusionZones.push_back({"b", ExclusionZone::Type::circle, {15, 0}, 10, {}});
    expectError([&]{ gen(s); }, "exclusionZones");
    s = baseSettings(0.5);
    s.exclusionZones.push_back
    (
        {"bowtie", ExclusionZone::Type::polygon, {}, 0, {{0, 0}, {10, 10}, {10, 0}, {0, 10}}}
    );
    expectError([&]{ gen(s); }, "exclusionZones");

    expectError([]{ thicknessDistributionFromName("lognormal"); }, "thickness");
}
