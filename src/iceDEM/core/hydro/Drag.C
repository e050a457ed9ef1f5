/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "Drag.H"
#include "WaterClip.H"
#include "WaterFrame.H"

#include <cmath>
#include <string>
#include <vector>

namespace iceDEM
{

void addFacetDrag
(
    const Vec3* q,
    int m,
    double nx,
    double ny,
    double nz,
    bool skin,
    double coeff,
    const Vec3& w,
    const Vec3& omega,
    Vec3& F,
    Vec3& M
)
{
    const Vec3 nrm(nx, ny, nz);
    if (skin)
    {
        // Skin drag |u_t| u_t: not a polynomial, but in closed form for a
        // rigid-body field (skinIntegral)
        Vec3 I, Ir;
        if (skinIntegral(q, m, nrm, w, omega, I, Ir))
        {
            F -= coeff*I;
            M -= coeff*Ir;
        }
        return;
    }

    // Form drag where the facet leads: u_n = (w + omega x r).n is linear,
    // so the leading part is the polygon clipped at u_n = 0 and
    // int u_n^2 dA, int r u_n^2 dA are exact on its fan triangles: with
    // vertex values f_i, S = sum f_i, Q = sum_{i<=j} f_i f_j,
    // int lambda_i f^2 dA = A/30 (Q + f_i (f_i + S)) (barycentric lambda_i)
    constexpr int cap = SubmergedFace::maxVertices + 1;
    double s[cap];
    Vec3 lead[cap + 1];
    double sl[cap + 1];
    int nLead = 0;
    // u_n = w.n + (omega x r).n = w.n + r.(n x omega): one dot per vertex
    const double wn = w.dot(nrm);
    const Vec3 nxo = nrm.cross(omega);
    for (int k = 0; k < m; ++k)
    {
        s[k] = -(wn + q[k].dot(nxo));
        nLead += s[k] < 0;
    }
    if (nLead == 0)
    {
        return;
    }
    // Leading everywhere: the polygon itself
    int ml = m;
    const Vec3* lp = q;
    const double* ls = s;
    if (nLead < m)
    {
        ml = clipNegative(q, s, m, lead, sl);
        lp = lead;
        ls = sl;
    }
    double I = 0;
    Vec3 Ir = Vec3::Zero();
    for (int k = 1; k + 1 < ml; ++k)
    {
        const Vec3& a = lp[0];
        const Vec3& bb = lp[k];
        const Vec3& c = lp[k + 1];
        const double A = 0.5*((bb - a).cross(c - a)).dot(nrm);
        const double fa = -ls[0], fb = -ls[k], fc = -ls[k + 1];
        const double S = fa + fb + fc;
        const double Q =
            fa*fa + fb*fb + fc*fc + fa*fb + fb*fc + fc*fa;
        const double wa = A/30.0*(Q + fa*(fa + S));
        const double wb = A/30.0*(Q + fb*(fb + S));
        const double wc = A/30.0*(Q + fc*(fc + S));
        I += wa + wb + wc;
        Ir += wa*a + wb*bb + wc*c;
    }
    F -= (coeff*I)*nrm;
    M -= coeff*Ir.cross(nrm);
}


void addWholeFaceSkinDrag
(
    const FacePlane& plane,
    const Mat3& R,
    const Vec3& n,
    double coeff,
    const Vec3& w,
    const Vec3& omega,
    Vec3& F,
    Vec3& M
)
{
    Vec3 I, Ir;
    skinIntegralOfFace(plane, R, n, w, omega, I, Ir);
    F -= coeff*I;
    M -= coeff*Ir;
}


DragIntegration dragIntegrationFromName(const std::string& name)
{
    if (name == "exact") return DragIntegration::exact;
    if (name == "sampled") return DragIntegration::sampled;
    throw Error
    (
        "drag: integration '" + name + "' is not one of: exact sampled",
        "integration"
    );
}


void checkDragSettings(const DragSettings& s)
{
    if (!(s.formCoefficient >= 0) || !std::isfinite(s.formCoefficient))
    {
        throw Error
        (
            "drag: formCoefficient " + std::to_string(s.formCoefficient)
          + " must be zero or positive",
            "formCoefficient"
        );
    }
    if (!(s.skinCoefficient >= 0) || !std::isfinite(s.skinCoefficient))
    {
        throw Error
        (
            "drag: skinCoefficient " + std::to_string(s.skinCoefficient)
          + " must be zero or positive",
            "skinCoefficient"
        );
    }
    if (s.subdivision < 0 || s.subdivision > DragSettings::maxSubdivision)
    {
        throw Error
        (
            "drag: subdivision " + std::to_string(s.subdivision)
          + " must be in 0.." + std::to_string(DragSettings::maxSubdivision)
          + " (4^subdivision sample points per facet triangle)",
            "subdivision"
        );
    }
    if (!(s.bottomCosine > 0 && s.bottomCosine <= 1))
    {
        throw Error
        (
            "drag: bottomCosine " + std::to_string(s.bottomCosine)
          + " must be in (0, 1]",
            "bottomCosine"
        );
    }
}


Drag::Drag
(
    const WaterSettings& water,
    const DragSettings& settings,
    std::shared_ptr<const FlowVelocity> flow
)
:
    water_(water),
    settings_(settings),
    flow_(std::move(flow))
{
    checkWaterSettings(water_);
    checkDragSettings(settings_);
    if (!flow_)
    {
        throw Error("drag: no water velocity model given", "type");
    }
}


void Drag::prepare(const World& world)
{
    flow_->prepare(world, *this);
}


const char* Drag::name() const
{
    return "drag";
}


double Drag::facetCoefficient(const Vec3& n, bool& skin) const
{
    skin = std::abs(n.z()) >= settings_.bottomCosine;
    const double halfRho = 0.5*water_.density;
    return
        halfRho
       *(skin ? settings_.skinCoefficient : settings_.formCoefficient);
}


void Drag::bodyDrag(const World& world, int i, Vec3& F, Vec3& M) const
{
    constexpr int capacity = 1 << (2*DragSettings::maxSubdivision);

    F.setZero();
    M.setZero();

    const Body& b = world.bodies()[i];
    const PolyhedronView P = outerForModels(world.shapeOf(i));

    Vec3 current;
    if
    (
        settings_.integration == DragIntegration::exact
     && flow_->uniform(current)
    )
    {
        // The floe's frame, shared with buoyancy and floe damping (its R
        // is b.rotation() at this pose, bit for bit)
        const WaterFrame& frame = waterFrame(world, i, water_.level);
        if (frame.valid())
        {
            if (!frame.wet()) return;
            frameDrag(P, frame, b, b.omega(frame.R), current, F, M);
            return;
        }
    }
    const Mat3 R = b.rotation();
    const Vec3 omega = b.omega(R);

    // Two-way coupling: the drag per face for the flow (this thread's
    // buffers grow to the largest floe once, then allocate nothing)
    const bool collect = flow_->collectsFaceForces();
    static thread_local std::vector<Vec3> faceF;
    static thread_local std::vector<double> faceK;

    // Nothing below the water plane: no drag
    {
        const Vec3 up = R.row(2).transpose();
        bool wet = false;
        for (const Vec3& v : P.vertices())
        {
            if (up.dot(v) + b.x.z() < water_.level)
            {
                wet = true;
                break;
            }
        }
        if (!wet)
        {
            if (collect)
            {
                flow_->faceForces(i, 0, nullptr, nullptr);
            }
            return;
        }
    }

    const int nf = static_cast<int>(P.faces().size());
    if (collect)
    {
        if (int(faceF.size()) < nf)
        {
            faceF.resize(nf);
            faceK.resize(nf);
        }
        for (int f = 0; f < nf; ++f)
        {
            faceF[f].setZero();
            faceK[f] = 0;
        }
    }

    const int sub = settings_.subdivision;

    SubmergedFace face;
    Vec3 points[capacity];
    double areas[capacity];
    Vec3 u[capacity];

    for (int f = 0; f < nf; ++f)
    {
        if (!submergedFace(P, f, R, b.x, water_.level, face))
        {
            continue;
        }

        const Vec3& n = face.normal;
        bool skin;
        const double coeff = facetCoefficient(n, skin);
        if (coeff == 0)
        {
            continue;
        }

        for (int k = 0; k < face.nVertices; ++k)
        {
            const int m = faceTriangleSamples(face, k, sub, points, areas);
            flow_->velocity(i, points, m, u);

            for (int j = 0; j < m; ++j)
            {
                const Vec3 r = points[j] - b.x;
                const Vec3 ur = b.v + omega.cross(r) - u[j];
                const double un = ur.dot(n);

                Vec3 dF;
                double k;   // dF = -k u_r (skin), -k u_n n (form)
                if (skin)
                {
                    const Vec3 ut = ur - un*n;
                    k = coeff*areas[j]*ut.norm();
                    dF = -k*ut;
                }
                else if (un > 0)
                {
                    k = coeff*areas[j]*un;
                    dF = (-k*un)*n;
                }
                else
                {
                    continue;
                }
                F += dF;
                M += r.cross(dF);
                if (collect)
                {
                    faceF[f] += dF;
                    faceK[f] += k;
                }
            }
        }
    }

    if (collect)
    {
        flow_->faceForces(i, nf, faceF.data(), faceK.data());
    }
}


void Drag::frameDrag
(
    const PolyhedronView& P,
    const WaterFrame& frame,
    const Body& b,
    const Vec3& omega,
    const Vec3& current,
    Vec3& F,
    Vec3& M
) const
{
    F.setZero();
    M.setZero();
    if (!frame.wet())
    {
        return;
    }

    // Velocity relative to the water: w + omega x r, linear over a face
    const Vec3 w = b.v - current;

    // The wet polygons (vertices relative to the centroid)
    addPolygonsDrag
    (
        P, frame.R, frame.nWet, frame.wetFace, frame.wetBegin,
        frame.wetWhole, frame.wetVertex, w, omega,
        [this](const Vec3& n, bool& skin)
        {
            return facetCoefficient(n, skin);
        },
        frame.caps, F, M
    );
}


void Drag::addForces
(
    const World& world,
    int begin,
    int end,
    Vec3* force,
    Vec3* torque
) const
{
    addFreeBodyForces
    (
        world, begin, end, force, torque,
        [&](int i, Vec3& F, Vec3& M) { bodyDrag(world, i, F, M); }
    );
}

} // namespace iceDEM
