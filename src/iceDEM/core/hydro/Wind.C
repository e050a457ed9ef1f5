/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "Wind.H"
#include "WaterFrame.H"

#include <cmath>
#include <string>

namespace iceDEM
{

// * * * * * * * * * * * * * * * * WindHistory * * * * * * * * * * * * * * //

WindHistory::WindHistory()
:
    table_{{0.0, Vec3::Zero()}}
{}


WindHistory::WindHistory(const Vec3& velocity)
:
    WindHistory(std::vector<std::pair<double, Vec3>>{{0.0, velocity}})
{}


WindHistory::WindHistory(std::vector<std::pair<double, Vec3>> table)
:
    table_(std::move(table))
{
    if (table_.empty())
    {
        throw Error("wind: the table has no rows", "table");
    }
    for (std::size_t k = 0; k < table_.size(); ++k)
    {
        const double t = table_[k].first;
        const Vec3& u = table_[k].second;
        if (!std::isfinite(t) || !u.allFinite())
        {
            throw Error
            (
                "wind: row " + std::to_string(k)
              + " of the table has a non-finite time or velocity",
                "table"
            );
        }
        if (k > 0 && !(t > table_[k - 1].first))
        {
            throw Error
            (
                "wind: the times of the table must increase strictly (row "
              + std::to_string(k) + ")",
                "table"
            );
        }
    }
}


Vec3 WindHistory::at(double t) const
{
    if (t <= table_.front().first) return table_.front().second;
    if (t >= table_.back().first) return table_.back().second;

    // Few rows: a linear search is fine (once per body-force evaluation)
    std::size_t k = 1;
    while (table_[k].first < t) ++k;
    const double t0 = table_[k - 1].first;
    const double t1 = table_[k].first;
    const double s = (t - t0)/(t1 - t0);
    // u0 + s (u1 - u0): a constant stretch gives u0 exactly
    return table_[k - 1].second + s*(table_[k].second - table_[k - 1].second);
}


// * * * * * * * * * * * * * * * * * Settings  * * * * * * * * * * * * * * //

void checkWindSettings(const WindSettings& s)
{
    auto nonNegative = [](double v, const char* entry, const char* what)
    {
        if (!std::isfinite(v) || !(v >= 0))
        {
            throw Error
            (
                std::string("wind: ") + entry + " " + std::to_string(v)
              + " must be zero or positive" + what,
                entry
            );
        }
    };
    nonNegative(s.rhoAir, "rhoAir", " [kg/m3]");
    nonNegative(s.skinCoefficient, "Cs", "");
    nonNegative(s.formCoefficient, "Cf", "");
    if (s.subdivision < 0 || s.subdivision > DragSettings::maxSubdivision)
    {
        throw Error
        (
            "wind: subdivision " + std::to_string(s.subdivision)
          + " must be in 0.." + std::to_string(DragSettings::maxSubdivision)
          + " (4^subdivision sample points per facet triangle)",
            "subdivision"
        );
    }
    if (!std::isfinite(s.topCosine) || !(s.topCosine > 0 && s.topCosine <= 1))
    {
        throw Error
        (
            "wind: topCosine " + std::to_string(s.topCosine)
          + " must be in (0, 1]",
            "topCosine"
        );
    }
}


Vec3 bluffWindForce
(
    double rhoAir,
    double Cd,
    double area,
    const Vec3& Ua,
    const Vec3& v
)
{
    const Vec3 w(Ua.x() - v.x(), Ua.y() - v.y(), 0);
    return (0.5*rhoAir*Cd*area*w.norm())*w;
}


// * * * * * * * * * * * * * * * * * * Wind  * * * * * * * * * * * * * * * //

Wind::Wind
(
    const WaterSettings& water,
    const WindSettings& settings,
    const WindHistory& history
)
:
    level_(water.level),
    settings_(settings),
    history_(history)
{
    checkWaterSettings(water);
    checkWindSettings(settings_);
}


const char* Wind::name() const
{
    return "wind";
}


double Wind::facetCoefficient(const Vec3& n, bool& skin) const
{
    skin = std::abs(n.z()) >= settings_.topCosine;
    const double rho = settings_.rhoAir;
    // Bulk skin formula without 1/2; form drag with 1/2
    return
        skin
      ? rho*settings_.skinCoefficient
      : 0.5*rho*settings_.formCoefficient;
}


void Wind::bodyWind
(
    const World& world,
    int i,
    const Vec3& Ua,
    Vec3& F,
    Vec3& M
) const
{
    constexpr int capacity = 1 << (2*DragSettings::maxSubdivision);

    F.setZero();
    M.setZero();

    const Body& b = world.bodies()[i];
    if (!b.isFree()) return;

    const PolyhedronView P = outerForModels(world.shapeOf(i));
    const Mat3 R = b.rotation();
    const Vec3 omega = b.omega(R);

    if (settings_.integration == DragIntegration::exact)
    {
        // The floe's frame, shared with buoyancy, drag and floe damping
        const WaterFrame& frame = waterFrame(world, i, level_);
        if (frameDry(P, frame))
        {
            frameWind(P, frame, b, omega, Ua, F, M);
            return;
        }
    }

    // Nothing above the water plane (overwashed): no wind
    {
        const Vec3 up = R.row(2).transpose();
        bool dry = false;
        for (const Vec3& v : P.vertices())
        {
            if (up.dot(v) + b.x.z() > level_)
            {
                dry = true;
                break;
            }
        }
        if (!dry) return;
    }

    const int sub = settings_.subdivision;

    SubmergedFace face;
    Vec3 points[capacity];
    double areas[capacity];

    const int nf = static_cast<int>(P.faces().size());
    for (int f = 0; f < nf; ++f)
    {
        if (!emergedFace(P, f, R, b.x, level_, face)) continue;

        const Vec3& n = face.normal;
        bool skin;
        const double coeff = facetCoefficient(n, skin);
        if (coeff == 0) continue;

        for (int k = 0; k < face.nVertices; ++k)
        {
            const int m = faceTriangleSamples(face, k, sub, points, areas);
            for (int j = 0; j < m; ++j)
            {
                const Vec3 r = points[j] - b.x;
                const Vec3 w = b.v + omega.cross(r) - Ua;
                const double wn = w.dot(n);

                Vec3 dF;
                if (skin)
                {
                    const Vec3 wt = w - wn*n;
                    dF = (-coeff*areas[j]*wt.norm())*wt;
                }
                else if (wn > 0)
                {
                    dF = (-coeff*areas[j]*wn*wn)*n;
                }
                else
                {
                    continue;
                }
                F += dF;
                M += r.cross(dF);
            }
        }
    }
}


void Wind::frameWind
(
    const PolyhedronView& P,
    const WaterFrame& frame,
    const Body& b,
    const Vec3& omega,
    const Vec3& Ua,
    Vec3& F,
    Vec3& M
) const
{
    F.setZero();
    M.setZero();
    if (!frame.dry())
    {
        return;
    }

    // Velocity relative to the air: w + omega x r, linear over a face
    const Vec3 w = b.v - Ua;

    // The dry polygons (vertices relative to the centroid)
    addPolygonsDrag
    (
        P, frame.R, frame.nDry, frame.dryFace, frame.dryBegin,
        frame.dryWhole, frame.dryVertex, w, omega,
        [this](const Vec3& n, bool& skin)
        {
            return facetCoefficient(n, skin);
        },
        frame.caps, F, M
    );
}


Vec3 Wind::totalForce(const World& world) const
{
    const Vec3 Ua = history_.at(world.time());
    Vec3 total = Vec3::Zero();
    const int N = static_cast<int>(world.bodies().size());
    for (int i = 0; i < N; ++i)
    {
        Vec3 F, M;
        bodyWind(world, i, Ua, F, M);
        total += F;
    }
    return total;
}


void Wind::addForces
(
    const World& world,
    int begin,
    int end,
    Vec3* force,
    Vec3* torque
) const
{
    const Vec3 Ua = history_.at(world.time());
    addFreeBodyForces
    (
        world, begin, end, force, torque,
        [&](int i, Vec3& F, Vec3& M) { bodyWind(world, i, Ua, F, M); }
    );
}

} // namespace iceDEM
