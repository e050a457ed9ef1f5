/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "Drag.H"
#include "WaterClip.H"

#include <cmath>
#include <string>
#include <vector>

namespace iceDEM
{

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


const char* Drag::name() const
{
    return "drag";
}


void Drag::bodyDrag(const World& world, int i, Vec3& F, Vec3& M) const
{
    constexpr int capacity = 1 << (2*DragSettings::maxSubdivision);

    F.setZero();
    M.setZero();

    const Body& b = world.bodies()[i];
    // This thread's room for derived outer polyhedra (no allocation once
    // it has grown to the largest floe)
    static thread_local PolyhedronBuffer outerBuffer;
    const PolyhedronView P = world.shapeOf(i).outer(outerBuffer);
    const Mat3 R = b.rotation();
    const Vec3 omega = R*(b.invInertia.cwiseProduct(R.transpose()*b.L));

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

    const double halfRho = 0.5*water_.density;
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
        const bool skin = std::abs(n.z()) >= settings_.bottomCosine;
        const double coeff =
            halfRho
           *(skin ? settings_.skinCoefficient : settings_.formCoefficient);
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


void Drag::addForces
(
    const World& world,
    int begin,
    int end,
    Vec3* force,
    Vec3* torque
) const
{
    for (int i = begin; i < end; ++i)
    {
        // Fixed and prescribed bodies (a structure) do not move with it
        if (!world.bodies()[i].isFree()) continue;
        Vec3 F, M;
        bodyDrag(world, i, F, M);
        force[i] += F;
        torque[i] += M;
    }
}

} // namespace iceDEM
