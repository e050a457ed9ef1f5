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

//- R* of a contact: one for every feature pair (r_i r_j/(r_i + r_j), r_i
//  on a wall) where oneRadius, else the feature pair's own (method.md
//  section 3), an edge pair's capped at maxEdgeRadiusRatio sqrt(r_i r_j)
inline double hertzRadius
(
    const ContactGeometry& g,
    bool oneRadius,
    double maxEdgeRadiusRatio
)
{
    const double ri = g.radiusI, rj = g.radiusJ;
    if (oneRadius)
    {
        return g.type == FeaturePair::vertexWall ? ri : ri*rj/(ri + rj);
    }
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
            return std::min(r/g.sinAngle, maxEdgeRadiusRatio*r);
        }
    }
    return ri;
}


//- Hertz with the equivalent radius of each feature pair
class HertzLaw : public ContactLaw
{
public:
    explicit HertzLaw(const ContactLawSettings& s) : ContactLaw(s, false) {}
    const char* name() const override { return "hertz"; }
};


//- Hertz with one equivalent radius for every feature pair
class HertzSimplifiedLaw : public ContactLaw
{
public:
    explicit HertzSimplifiedLaw(const ContactLawSettings& s) : ContactLaw(s, true) {}
    const char* name() const override { return "hertzSimplified"; }
};

} // anonymous namespace


ContactLaw::ContactLaw(const ContactLawSettings& s, bool oneRadius)
:
    settings_(s),
    mindlin_(s.tangentialModel == "mindlin"),
    oneRadius_(oneRadius)
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


namespace
{

// The law is one code (hertzLaw) for one contact (double, Vec3) and for two
// side by side (twoLanes::Double2, Vec3x2): the same operations in the same
// order on every lane, so that evaluateTwo gives evaluate's results to the
// bit. Where it branches, the helpers below are written once per type: a
// branch for one contact, a selection for two, where a division a lane does
// not take gets a harmless operand (no floating-point trap in a lane that
// is discarded)
using twoLanes::sqrtOf;
using twoLanes::absOf;
using twoLanes::dotOf;

//- m ? (num/den) v : v
inline Vec3 scaledWhere(bool m, double num, double den, const Vec3& v)
{
    return m ? Vec3((num/den)*v) : v;
}
template<class Mask>
inline twoLanes::Vec3x2 scaledWhere
(
    Mask m, twoLanes::Double2 num, twoLanes::Double2 den, const twoLanes::Vec3x2& v
)
{
    return twoLanes::select(m, (num/(m ? den : twoLanes::both(1.0)))*v, v);
}
//- m ? num/den : 0
inline double quotientWhere(bool m, double num, double den)
{
    return m ? num/den : 0.0;
}
template<class Mask>
inline twoLanes::Double2 quotientWhere
(
    Mask m, twoLanes::Double2 num, twoLanes::Double2 den
)
{
    return m ? num/(m ? den : twoLanes::both(1.0)) : twoLanes::both(0.0);
}
//- Where sliding, the spring that holds the force F (-F/k, none where the
//  stiffness k is zero); elsewhere xi
inline Vec3 heldWhere(bool sliding, const Vec3& F, double k, const Vec3& xi)
{
    if (!sliding) return xi;
    return k > 0 ? Vec3(-F/k) : Vec3(Vec3::Zero());
}
template<class Mask>
inline twoLanes::Vec3x2 heldWhere
(
    Mask sliding, const twoLanes::Vec3x2& F, twoLanes::Double2 k, const twoLanes::Vec3x2& xi
)
{
    using namespace twoLanes;
    const auto stiff = k > both(0.0);
    const Vec3x2 held = (-F)/(stiff ? k : both(1.0));
    return select(sliding, select(stiff, held, Vec3x2{}), xi);
}

//- A contact's geometry and motion (one lane's)
template<class Real, class V>
struct LawInput
{
    Real R;             //!< equivalent radius
    Real delta;         //!< overlap
    Real mEff;          //!< effective mass of its damping
    Real w;             //!< the term's weight (+1, -1 or a fraction)
    V n;                //!< normal, from i to j
    V vRel;             //!< velocity of j relative to i at the contact
    V gradX, grad;      //!< the weight's gradients
};

//- Its force, couple and energy (one lane's)
template<class Real, class V>
struct LawOutput
{
    V forceOnJ, coupleOnJ;
    Real normalForce, elasticEnergy;
};

template<class Real, class V>
void hertzLaw
(
    const PairCoefficients& c,
    double dt,
    bool mindlin,
    double tangentialStiffnessRatio,
    const LawInput<Real, V>& in,
    V& xi,
    LawOutput<Real, V>& out
)
{
    const Real zero{}, one = zero + 1.0;
    const Real delta = in.delta;
    const Real sqrtRd = sqrtOf(in.R*delta);
    const V& n = in.n;

    // Normal: Hertz + viscous damping, never tensile
    const Real vn = dotOf(in.vRel, n);                  // > 0: separating
    const Real Sn = 2*c.Estar*sqrtRd;                   // dF/ddelta
    const Real elastic = 4.0/3.0*c.Estar*sqrtRd*delta;
    const Real damping = 2*std::sqrt(5.0/6.0)*c.beta*sqrtOf(in.mEff*Sn);
    // A term of the excess potential (NarrowPhase.H) carries a sign w = +1
    // or -1 (a subtracted term): its potential is w U(delta), and its
    // normal force, damping included, and its tangential spring are those
    // of a positive term times w (so that a subtracted term cancels the
    // positive term it duplicates, history and all, while the two
    // coincide); the friction cap applies to each term's own magnitude.
    // The weight's gradient (zero for every term of the excess potential)
    // would give a couple
    const Real w = in.w;
    const Real sign = w < zero ? -one : one;
    const Real wAbs = absOf(w);
    const Real push = elastic - damping*vn;
    const Real FnAbs = wAbs*(zero < push ? push : zero);
    const Real Fn = sign*FnAbs;

    // Tangential spring: rotate into the current tangent plane, keep length
    const Real xiLen = sqrtOf(dotOf(xi, xi));
    xi = xi - dotOf(xi, n)*n;
    const Real xiProj = sqrtOf(dotOf(xi, xi));
    xi = scaledWhere(xiProj > zero, xiLen, xiProj, xi);
    const V vt = in.vRel - vn*n;
    xi = xi + dt*vt;

    const Real kt =
        wAbs*(mindlin ? 8*c.Gstar*sqrtRd : tangentialStiffnessRatio*Sn);
    V Ft = (-kt)*xi;
    const Real FtMax = c.friction*FnAbs;
    const Real FtLen = sqrtOf(dotOf(Ft, Ft));
    // Sliding: the spring holds the Coulomb limit
    const auto sliding = FtLen > FtMax;
    Ft = scaledWhere(sliding & (FtLen > zero), FtMax, FtLen, Ft);
    xi = heldWhere(sliding, Ft, kt, xi);

    // Force on j: pushed along +n
    const Real U = 0.4*elastic*delta;
    out.forceOnJ = (Fn*n + sign*Ft) - U*in.gradX;
    out.normalForce = Fn;
    const Real spring = quotientWhere(kt > zero, 0.5*dotOf(Ft, Ft), kt);
    out.elasticEnergy = w*U + sign*spring;
    out.coupleOnJ = (-U)*in.grad;
}

} // anonymous namespace


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
    const LawInput<double, Vec3> in
    {
        hertzRadius(g, oneRadius_, settings_.maxEdgeRadiusRatio),
        g.overlap, mEff, g.weight, g.normal, vRel,
        g.weightGradientX, g.weightGradient
    };
    LawOutput<double, Vec3> out;
    hertzLaw(c, dt, mindlin_, settings_.tangentialStiffnessRatio, in, xi, out);
    ContactResult r;
    r.forceOnJ = out.forceOnJ;
    r.normalForce = out.normalForce;
    r.elasticEnergy = out.elasticEnergy;
    r.coupleOnJ = out.coupleOnJ;
    return r;
}


void ContactLaw::evaluateTwo
(
    const PairCoefficients& c,
    const ContactGeometry* const g[2],
    const double mEff[2],
    const Vec3 vRel[2],
    Vec3* const xi[2],
    double dt,
    ContactResult r[2]
) const
{
    using namespace twoLanes;
    const LawInput<Double2, Vec3x2> in
    {
        Double2
        {
            hertzRadius(*g[0], oneRadius_, settings_.maxEdgeRadiusRatio),
            hertzRadius(*g[1], oneRadius_, settings_.maxEdgeRadiusRatio)
        },
        Double2{g[0]->overlap, g[1]->overlap},
        Double2{mEff[0], mEff[1]},
        Double2{g[0]->weight, g[1]->weight},
        lanes(g[0]->normal, g[1]->normal),
        lanes(vRel[0], vRel[1]),
        lanes(g[0]->weightGradientX, g[1]->weightGradientX),
        lanes(g[0]->weightGradient, g[1]->weightGradient)
    };
    Vec3x2 s = lanes(*xi[0], *xi[1]);
    LawOutput<Double2, Vec3x2> out;
    hertzLaw(c, dt, mindlin_, settings_.tangentialStiffnessRatio, in, s, out);
    for (int k = 0; k < 2; ++k)
    {
        *xi[k] = lane(s, k);
        r[k].forceOnJ = lane(out.forceOnJ, k);
        r[k].normalForce = out.normalForce[k];
        r[k].elasticEnergy = out.elasticEnergy[k];
        r[k].coupleOnJ = lane(out.coupleOnJ, k);
    }
}


double ContactLaw::normalStiffness
(
    const PairCoefficients& c,
    const ContactGeometry& g
) const
{
    return 2*c.Estar*std::sqrt(hertzRadius(g, oneRadius_, settings_.maxEdgeRadiusRatio)*g.overlap);
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
