/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "ContactLaw.H"
#include "twoLanes.H"

#include <algorithm>
#include <cmath>

namespace iceDEM
{

const char* featurePairName(FeaturePair t)
{
    switch (t)
    {
        case FeaturePair::vertexVertex: return "vertexVertex";
        case FeaturePair::vertexEdge: return "vertexEdge";
        case FeaturePair::vertexFace: return "vertexFace";
        case FeaturePair::edgeEdge: return "edgeEdge";
        case FeaturePair::vertexWall: return "vertexWall";
    }
    return "unknown";
}


namespace
{

//- Hertz with the equivalent radius of each feature pair
class HertzLaw : public ContactLaw
{
public:
    using ContactLaw::ContactLaw;

    const char* name() const override { return "hertz"; }

    double equivalentRadius(const ContactGeometry& g) const override
    {
        const double ri = g.radiusI, rj = g.radiusJ;
        switch (g.type)
        {
            case FeaturePair::vertexVertex:
                return ri*rj/(ri + rj);
            case FeaturePair::vertexEdge:
                return std::sqrt(ri*ri*rj/(ri + rj));
            case FeaturePair::vertexFace:
            case FeaturePair::vertexWall:
                return ri;
            case FeaturePair::edgeEdge:
            {
                const double r = std::sqrt(ri*rj);
                return std::min(r/g.sinAngle, settings_.maxEdgeRadiusRatio*r);
            }
        }
        return ri;
    }
};


//- Hertz with one equivalent radius for every feature pair
class HertzSimplifiedLaw : public ContactLaw
{
public:
    using ContactLaw::ContactLaw;

    const char* name() const override { return "hertzSimplified"; }

    double equivalentRadius(const ContactGeometry& g) const override
    {
        if (g.type == FeaturePair::vertexWall)
        {
            return g.radiusI;
        }
        return g.radiusI*g.radiusJ/(g.radiusI + g.radiusJ);
    }
};

} // anonymous namespace


ContactLaw::ContactLaw(const ContactLawSettings& s)
:
    settings_(s),
    mindlin_(s.tangentialModel == "mindlin")
{
    if (s.tangentialModel != "mindlin" && s.tangentialModel != "ratio")
    {
        throw Error
        (
            "unknown tangentialModel '" + s.tangentialModel
          + "'; valid: 2(mindlin ratio)",
            "tangentialModel"
        );
    }
    if (!(s.tangentialStiffnessRatio >= 0))
    {
        throw Error("tangentialStiffnessRatio must be >= 0", "tangentialStiffnessRatio");
    }
    if (!(s.maxEdgeRadiusRatio >= 1))
    {
        throw Error("maxEdgeRadiusRatio must be >= 1", "maxEdgeRadiusRatio");
    }
}


std::vector<std::string> ContactLaw::names()
{
    return {"hertz", "hertzSimplified"};
}


std::unique_ptr<ContactLaw> ContactLaw::New(const ContactLawSettings& s)
{
    if (s.model == "hertz") return std::make_unique<HertzLaw>(s);
    if (s.model == "hertzSimplified") return std::make_unique<HertzSimplifiedLaw>(s);

    std::string valid;
    for (const auto& n : names()) valid += " " + n;
    throw Error
    (
        "unknown contactModel '" + s.model + "'; valid: "
      + std::to_string(names().size()) + "(" + valid.substr(1) + ")",
        "contactModel"
    );
}


ContactResult ContactLaw::evaluate
(
    const PairCoefficients& c,
    const ContactGeometry& g,
    double mEff,
    const Vec3& vRel,
    Vec3& xi,
    double dt
) const
{
    const double R = equivalentRadius(g);
    const double delta = g.overlap;
    const double sqrtRd = std::sqrt(R*delta);
    const Vec3& n = g.normal;

    // Normal: Hertz + viscous damping, never tensile
    const double vn = vRel.dot(n);                      // > 0: separating
    const double Sn = 2*c.Estar*sqrtRd;                 // dF/ddelta
    const double elastic = 4.0/3.0*c.Estar*sqrtRd*delta;
    const double damping = 2*std::sqrt(5.0/6.0)*c.beta*std::sqrt(mEff*Sn);
    // A term of the excess potential (NarrowPhase.H) carries a sign w = +1
    // or -1 (a subtracted term): its potential is w U(delta), and its
    // normal force, damping included, and its tangential spring are those
    // of a positive term times w (so that a subtracted term cancels the
    // positive term it duplicates, history and all, while the two
    // coincide); the friction cap applies to each term's own magnitude.
    // The weight's gradient (zero for every term of the excess potential)
    // would give a couple
    const double w = g.weight;
    const double sign = w < 0 ? -1.0 : 1.0;
    const double wAbs = std::abs(w);
    const double FnAbs = wAbs*std::max(0.0, elastic - damping*vn);
    const double Fn = sign*FnAbs;

    // Tangential spring: rotate into the current tangent plane, keep length
    const double xiLen = xi.norm();
    xi -= xi.dot(n)*n;
    const double xiProj = xi.norm();
    if (xiProj > 0)
    {
        xi *= xiLen/xiProj;
    }
    const Vec3 vt = vRel - vn*n;
    xi += vt*dt;

    const double kt = wAbs*(mindlin_ ? 8*c.Gstar*sqrtRd : settings_.tangentialStiffnessRatio*Sn);
    Vec3 Ft = -kt*xi;
    const double FtMax = c.friction*FnAbs;
    const double FtLen = Ft.norm();
    if (FtLen > FtMax)
    {
        // Sliding: the spring holds the Coulomb limit
        if (FtLen > 0)
        {
            Ft *= FtMax/FtLen;
        }
        xi = kt > 0 ? Vec3(-Ft/kt) : Vec3(Vec3::Zero());
    }

    ContactResult r;
    // Force on j: pushed along +n
    const double U = 0.4*elastic*delta;
    r.forceOnJ = Fn*n + sign*Ft - U*g.weightGradientX;
    r.normalForce = Fn;
    r.elasticEnergy = w*U + sign*(kt > 0 ? 0.5*Ft.squaredNorm()/kt : 0.0);
    r.coupleOnJ = -U*g.weightGradient;
    return r;
}


using namespace twoLanes;


void ContactLaw::evaluateTwo
(
    const PairCoefficients& c,
    const ContactGeometry* const g[2],
    double mEff,
    const Vec3 vRel[2],
    Vec3* const xi[2],
    double dt,
    ContactResult r[2]
) const
{
    // evaluate, line by line, on two lanes; its branches are selections,
    // and a division or root a lane does not take gets a harmless operand
    // (no floating-point trap in a lane that is discarded)
    const Double2 zero = both(0.0), one = both(1.0);
    const Double2 R{equivalentRadius(*g[0]), equivalentRadius(*g[1])};
    const Double2 delta{g[0]->overlap, g[1]->overlap};
    const Double2 sqrtRd = sqrt2(R*delta);
    const Vec3x2 n = lanes(g[0]->normal, g[1]->normal);
    const Vec3x2 v = lanes(vRel[0], vRel[1]);

    const Double2 vn = dot(v, n);
    const Double2 Sn = both(2*c.Estar)*sqrtRd;
    const Double2 elastic = both(4.0/3.0*c.Estar)*sqrtRd*delta;
    const Double2 damping = both(2*std::sqrt(5.0/6.0)*c.beta)*sqrt2(both(mEff)*Sn);
    const Double2 w{g[0]->weight, g[1]->weight};
    const Double2 sign = w < zero ? -one : one;
    const Double2 wAbs{std::abs(g[0]->weight), std::abs(g[1]->weight)};
    const Double2 push = elastic - damping*vn;
    const Double2 FnAbs = wAbs*(zero < push ? push : zero);
    const Double2 Fn = sign*FnAbs;

    Vec3x2 s = lanes(*xi[0], *xi[1]);
    const Double2 xiLen = sqrt2(dot(s, s));
    s = s - dot(s, n)*n;
    const Double2 xiProj = sqrt2(dot(s, s));
    const Mask2 rotated = xiProj > zero;
    s = select(rotated, (xiLen/(rotated ? xiProj : one))*s, s);
    const Vec3x2 vt = v - vn*n;
    s = s + both(dt)*vt;

    const Double2 kt =
        wAbs
       *(
            mindlin_
          ? both(8*c.Gstar)*sqrtRd
          : both(settings_.tangentialStiffnessRatio)*Sn
        );
    Vec3x2 Ft = (-kt)*s;
    const Double2 FtMax = both(c.friction)*FnAbs;
    const Double2 FtLen = sqrt2(dot(Ft, Ft));
    const Mask2 sliding = FtLen > FtMax;
    const Mask2 capped = sliding & (FtLen > zero);
    Ft = select(capped, (FtMax/(capped ? FtLen : one))*Ft, Ft);
    const Mask2 stiff = kt > zero;
    const Double2 ktOrOne = stiff ? kt : one;
    const Vec3x2 held{(-Ft.x)/ktOrOne, (-Ft.y)/ktOrOne, (-Ft.z)/ktOrOne};
    s = select(sliding, select(stiff, held, Vec3x2{zero, zero, zero}), s);

    const Double2 U = both(0.4)*elastic*delta;
    const Vec3x2 gradX = lanes(g[0]->weightGradientX, g[1]->weightGradientX);
    const Vec3x2 grad = lanes(g[0]->weightGradient, g[1]->weightGradient);
    const Vec3x2 forceOnJ = (Fn*n + sign*Ft) - U*gradX;
    const Double2 spring = stiff ? (both(0.5)*dot(Ft, Ft))/ktOrOne : zero;
    const Double2 energy = w*U + sign*spring;
    const Vec3x2 couple = (-U)*grad;
    for (int k = 0; k < 2; ++k)
    {
        *xi[k] = lane(s, k);
        r[k].forceOnJ = lane(forceOnJ, k);
        r[k].normalForce = Fn[k];
        r[k].elasticEnergy = energy[k];
        r[k].coupleOnJ = lane(couple, k);
    }
}


double ContactLaw::hertzContactTime
(
    double mEff,
    double Rstar,
    double Estar,
    double v
)
{
    return 2.87*std::pow(mEff*mEff/(Rstar*Estar*Estar*v), 0.2);
}

} // namespace iceDEM
