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

    // Bounding sphere about the centroid
    double rMax = 0;
    for (const Vec3& v : core_.vertices())
    {
        rMax = std::max(rMax, v.norm());
    }
    boundingRadius_ = rMax + radius_;

    // Edge lengths, exactly as normalized() computes the norm it divides by
    const int nE = static_cast<int>(core_.edges().size());
    edgeLength_.resize(nE);
    for (int e = 0; e < nE; ++e)
    {
        const auto& ed = core_.edges()[e];
        const Vec3 d = core_.vertices()[ed[1]] - core_.vertices()[ed[0]];
        edgeLength_[e] = std::sqrt(d.squaredNorm());
    }
}


std::size_t DilatedShape::heapBytes() const
{
    return core_.heapBytes() + outer_.heapBytes()
        + edgeLength_.capacity()*sizeof(double);
}

} // namespace iceDEM
