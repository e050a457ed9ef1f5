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

namespace
{

// Smallest |n_a . (n_b x n_c)| of the three face normals at a core vertex
// for which the outer vertex is derived (DilatedShape::outer): the meeting
// point of the moved planes divides by it. Below it (three nearly dependent
// normals) the outer is built by offset() and stored instead.
constexpr double minVertexNormalsDeterminant = 1e-6;

// The three faces that meet at vertex v of P; false where more meet
bool threeFacesAt(const ConvexPolyhedron& P, int v, int faces[3])
{
    const int begin = P.vertexEdgeBegin(v);
    if (P.vertexEdgeEnd(v) - begin != 3)
    {
        return false;
    }
    const auto& first = P.edgeFaces()[P.vertexEdges()[begin]];
    const auto& second = P.edgeFaces()[P.vertexEdges()[begin + 1]];
    faces[0] = first[0];
    faces[1] = first[1];
    faces[2] =
        (second[0] == first[0] || second[0] == first[1]) ? second[1] : second[0];
    return true;
}

// The displacement w of a vertex whose three planes (unit normals a, b, c)
// each move out by 1: a.w = b.w = c.w = 1, so w = (b x c + c x a + a x b)
// / det with det = a . (b x c) (returned in det)
Vec3 unitOffsetDisplacement(const Vec3& a, const Vec3& b, const Vec3& c, double& det)
{
    const Vec3 bc = b.cross(c);
    det = a.dot(bc);
    return (bc + c.cross(a) + a.cross(b))/det;
}

// Whether the outer polyhedron of core P can be derived from it (see
// DilatedShape::outer)
bool outerDerivable(const ConvexPolyhedron& P)
{
    const auto F = P.faces();
    for (int v = 0; v < static_cast<int>(P.vertices().size()); ++v)
    {
        int f[3];
        if (!threeFacesAt(P, v, f))
        {
            return false;
        }
        double det;
        unitOffsetDisplacement(F[f[0]].normal, F[f[1]].normal, F[f[2]].normal, det);
        if (!(std::abs(det) >= minVertexNormalsDeterminant))
        {
            return false;
        }
    }
    return true;
}

} // End anonymous namespace


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
    if (!(radius > 0) || !(radius*minCoreWidthInRadii <= width))
    {
        std::ostringstream msg;
        msg << "dilation radius " << radius << " must be > 0 and at most half"
            << " the thinnest width of the core (" << width/minCoreWidthInRadii << ")";
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
    if (!outerDerivable(core_))
    {
        storedOuter_ = std::make_shared<const ConvexPolyhedron>
        (
            outerInput.transformed(Rt, -Rt*centroidInput_)
        );
    }

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


PolyhedronView DilatedShape::derivedOuter(PolyhedronBuffer& buffer) const
{
    const auto V = core_.vertices();
    const auto F = core_.faces();
    buffer.vertices.resize(V.size());
    buffer.planes.resize(F.size());
    for (std::size_t f = 0; f < F.size(); ++f)
    {
        const ConvexPolyhedron::Face face = F[f];
        buffer.planes[f] = {face.normal, face.offset + radius_};
    }
    for (int v = 0; v < static_cast<int>(V.size()); ++v)
    {
        int f[3];
        threeFacesAt(core_, v, f);
        double det;
        buffer.vertices[v] = V[v] + radius_*unitOffsetDisplacement
        (
            F[f[0]].normal, F[f[1]].normal, F[f[2]].normal, det
        );
    }
    return PolyhedronView(core_.topology(), buffer.vertices.data(), buffer.planes.data());
}


void DilatedShape::keepOuter()
{
    if (!storedOuter_)
    {
        PolyhedronBuffer derived;
        outer(derived);
        storedOuter_ = std::make_shared<const ConvexPolyhedron>
        (
            core_.sharedTopology(), derived.vertices.data(),
            derived.planes.data()
        );
        outerKept_ = true;
    }
    if (!prismCapsSearched_)
    {
        prismCapsSearched_ = true;
        PrismCaps caps;
        if (findPrismCaps(storedOuter_->view(), caps))
        {
            prismCaps_ = std::make_shared<const PrismCaps>(caps);
        }
    }
}


std::size_t DilatedShape::heapBytes() const
{
    return core_.heapBytes()
        + (storedOuter_ ? sizeof(ConvexPolyhedron) + storedOuter_->heapBytes() : 0)
        + (prismCaps_ ? sizeof(PrismCaps) : 0)
        + edgeLength_.capacity()*sizeof(double);
}

} // namespace iceDEM
