/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "Material.H"

#include <cmath>
#include <map>
#include <mutex>
#include <sstream>

namespace iceDEM
{

void checkMaterial(const Material& m)
{
    auto bad = [&](const std::string& entry, const std::string& allowed, double value)
    {
        std::ostringstream msg;
        msg << "material " << m.name << ": " << entry << " = " << value
            << " is not allowed (" << allowed << ")";
        throw Error(msg.str(), entry);
    };
    if (!(m.density > 0)) bad("density", "> 0", m.density);
    if (!(m.youngsModulus > 0)) bad("youngsModulus", "> 0", m.youngsModulus);
    if (!(m.poissonsRatio > -1 && m.poissonsRatio < 0.5))
    {
        bad("poissonsRatio", "-1 < nu < 0.5", m.poissonsRatio);
    }
}


void checkPairProperties(const PairProperties& p)
{
    if (!(p.friction >= 0))
    {
        throw Error("friction must be >= 0", "friction");
    }
    if (!(p.restitution > 0 && p.restitution <= 1))
    {
        throw Error("restitution must be in (0, 1]", "restitution");
    }
}

double hertzRestitution(double beta)
{
    // x'' = -max(0, x^(3/2) + sqrt(5) beta x^(1/4) x'), x(0) = 0, x'(0) = 1,
    // velocity Verlet with a step small against the contact time (~3.2)
    constexpr double h = 2e-4;
    const double g = std::sqrt(5.0)*beta;
    auto acc = [g](double x, double v)
    {
        if (x <= 0) return 0.0;
        return -std::max(0.0, std::pow(x, 1.5) + g*std::pow(x, 0.25)*v);
    };
    double x = 0, v = 1, a = 0;
    for (long k = 0; k < 10000000L; ++k)
    {
        const double xOld = x;
        v += 0.5*h*a;
        x += h*v;
        a = acc(x, v);
        v += 0.5*h*a;
        if (x <= 0 && xOld > 0)
        {
            return -v;
        }
    }
    // Overdamped: the overlap creeps back without separating in this time
    return 0;
}


double hertzDampingBeta(double e)
{
    if (!(e > 0 && e <= 1))
    {
        throw Error("restitution must be in (0, 1]", "restitution");
    }
    if (e == 1)
    {
        return 0;
    }
    static std::mutex mutex;
    static std::map<double, double> cache;
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(e);
    if (it != cache.end())
    {
        return it->second;
    }

    // restitution(beta) decreases monotonically: bracket, then bisect
    double lo = 0, hi = 1;
    while (hertzRestitution(hi) > e && hi < 1e3)
    {
        lo = hi;
        hi *= 2;
    }
    for (int k = 0; k < 60 && hi - lo > 1e-9*hi; ++k)
    {
        const double mid = 0.5*(lo + hi);
        (hertzRestitution(mid) > e ? lo : hi) = mid;
    }
    const double beta = 0.5*(lo + hi);
    cache[e] = beta;
    return beta;
}

} // namespace iceDEM
