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
    for (int e = 0; e < nE; ++e)
    {
        const auto& ed = core_.edges()[e];
        edgeDirection_[e] = (core_.vertices()[ed[1]] - core_.vertices()[ed[0]]).normalized();
    }

    // Edge of each face loop slot: the edge at its first vertex that ends
    // at the next one
    faceEdge_.assign(core_.faceVertices().size(), -1);
    for (int f = 0; f < int(core_.faces().size()); ++f)
    {
        const auto& face = core_.faces()[f];
        for (int k = 0; k < face.count; ++k)
        {
            const int a = core_.faceVertex(f, k);
            const int b = core_.faceVertex(f, (k + 1) % face.count);
            for (int m = core_.vertexEdgeBegin(a); m < core_.vertexEdgeEnd(a); ++m)
            {
                if (core_.otherVertex(core_.vertexEdges()[m], a) == b)
                {
                    faceEdge_[face.begin + k] = core_.vertexEdges()[m];
                }
            }
        }
    }
}


std::size_t DilatedShape::heapBytes() const
{
    return core_.heapBytes() + outer_.heapBytes()
        + edgeDirection_.capacity()*sizeof(Vec3)
        + faceEdge_.capacity()*sizeof(int);
}

} // namespace iceDEM
