/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "DilatedShape.H"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>

namespace iceDEM
{

MassModel massModelFromName(const std::string& name)
{
    if (name == "faceted") return MassModel::faceted;
    if (name == "dilated") return MassModel::dilated;
    throw Error
    (
        "unknown massModel '" + name + "'; valid: 2(dilated faceted)",
        "massModel"
    );
}


DilatedShape::DilatedShape
(
    const ConvexPolyhedron& coreInput,
    double radius,
    MassModel massModel
)
:
    radius_(radius),
    massModel_(massModel)
{
    const double width = coreInput.minWidth();
    if (!(radius > 0) || !(radius <= 0.5*width))
    {
        std::ostringstream msg;
        msg << "dilation radius " << radius << " must be > 0 and at most half"
            << " the thinnest width of the core (" << 0.5*width << ")";
        throw Error(msg.str(), "radius");
    }

    const ConvexPolyhedron outerInput = coreInput.offset(radius);
    facetedVolume_ = outerInput.volume();
    dilatedVolume_ = steinerVolume(coreInput, radius);

    const MassProperties mp =
        massModel == MassModel::faceted
      ? polyhedronMassProperties(outerInput)
      : dilatedMassProperties(coreInput, radius);

    volume_ = mp.volume;
    centroidInput_ = mp.centroid;

    // Principal axes, right-handed
    Eigen::SelfAdjointEigenSolver<Mat3> eig(mp.inertia);
    Mat3 R = eig.eigenvectors();
    if (R.determinant() < 0)
    {
        R.col(2) = -R.col(2);
    }
    principalInertia_ = eig.eigenvalues();
    principalToInput_ = Quat(R);
    principalToInput_.normalize();

    const Mat3 Rt = R.transpose();
    core_ = coreInput.transformed(Rt, -Rt*centroidInput_);
    outer_ = outerInput.transformed(Rt, -Rt*centroidInput_);

    // Precomputed contact data, principal frame
    double rMax = 0;
    Vec3 lo = core_.vertices()[0], hi = lo;
    for (const Vec3& v : core_.vertices())
    {
        rMax = std::max(rMax, v.norm());
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    boundingRadius_ = rMax + radius_;
    coreHalfExtents_ = 0.5*(hi - lo);

    const int nE = static_cast<int>(core_.edges().size());
    edgeDirection_.resize(nE);
    edgeInward_.resize(nE);
    for (int e = 0; e < nE; ++e)
    {
        const auto& ed = core_.edges()[e];
        edgeDirection_[e] = (core_.vertices()[ed[1]] - core_.vertices()[ed[0]]).normalized();
        edgeInward_[e] = {core_.edgeInwardInFace(e, 0), core_.edgeInwardInFace(e, 1)};
    }

    vertexEdgeDirection_.resize(core_.vertexEdges().size());
    for (int v = 0; v < int(core_.vertices().size()); ++v)
    {
        for (int k = core_.vertexEdgeBegin(v); k < core_.vertexEdgeEnd(v); ++k)
        {
            const int e = core_.vertexEdges()[k];
            const int w = core_.otherVertex(e, v);
            vertexEdgeDirection_[k] = (core_.vertices()[w] - core_.vertices()[v]).normalized();
        }
    }

    faceEdgeNormal_.resize(core_.faceVertices().size());
    for (int f = 0; f < int(core_.faces().size()); ++f)
    {
        const auto& face = core_.faces()[f];
        for (int k = 0; k < face.count; ++k)
        {
            const Vec3& a = core_.vertices()[core_.faceVertex(f, k)];
            const Vec3& b = core_.vertices()[core_.faceVertex(f, (k + 1) % face.count)];
            faceEdgeNormal_[face.begin + k] = (b - a).cross(face.normal).normalized();
        }
    }
}

} // namespace iceDEM
