/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    resolvedFlowVelocity: the least-squares linear fits of the sampled
    velocities, per floe and per wet face, that the drag evaluates between
    samplings.

\*---------------------------------------------------------------------------*/

#include "resolvedFlowVelocity.H"

#include "World.H"

#include <Eigen/Eigenvalues>

namespace
{
    //- Linear fit per floe: point spreads (eigenvalues of the points'
    //  scatter matrix) below this fraction of the largest count as none
    //  (round-off of points that lie in one plane)
    constexpr double relativeSpreadCutoff = 1e-9;
}

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

Foam::resolvedFlowVelocity::linearFit Foam::resolvedFlowVelocity::fit
(
    int i,
    size_t begin,
    size_t end
) const
{
    linearFit f;
    const std::vector<::iceDEM::Vec3>& pts = points_[i];
    const std::vector<::iceDEM::Vec3>& vals = values_[i];
    if (end <= begin)
    {
        return f;
    }
    const size_t n = end - begin;

    for (size_t k = begin; k < end; ++k)
    {
        f.centre += pts[k];
        f.mean += vals[k];
    }
    f.centre /= double(n);
    f.mean /= double(n);

    // Least squares: G C = B with C = sum dp dp^T, B = sum du dp^T
    ::iceDEM::Mat3 C = ::iceDEM::Mat3::Zero();
    ::iceDEM::Mat3 B = ::iceDEM::Mat3::Zero();
    for (size_t k = begin; k < end; ++k)
    {
        const ::iceDEM::Vec3 dp = pts[k] - f.centre;
        C += dp*dp.transpose();
        B += (vals[k] - f.mean)*dp.transpose();
    }

    // Pseudo-inverse of C: no gradient along directions without spread
    // (all points in one plane or on one line)
    const Eigen::SelfAdjointEigenSolver<::iceDEM::Mat3> eig(C);
    const ::iceDEM::Vec3 lambda = eig.eigenvalues();
    const double cut = relativeSpreadCutoff*lambda.maxCoeff();
    ::iceDEM::Mat3 Cinv = ::iceDEM::Mat3::Zero();
    for (int k = 0; k < 3; ++k)
    {
        if (lambda(k) > cut && lambda(k) > 0)
        {
            const ::iceDEM::Vec3 e = eig.eigenvectors().col(k);
            Cinv += (e*e.transpose())/lambda(k);
        }
    }
    f.gradient = B*Cinv;
    f.valid = true;
    return f;
}


void Foam::resolvedFlowVelocity::fitBody
(
    const ::iceDEM::World& world,
    int i
) const
{
    const size_t n = points_[i].size();
    fits_[i] = fit(i, 0, n);
    fitOrigin_[i] = world.bodies()[i].x;

    // One fit per wet face (its points are contiguous)
    std::vector<linearFit>& ff = faceFits_[i];
    ff.assign(world.shapeOf(i).outerFaceCount(), linearFit());
    const std::vector<int>& face = pointFaces_[i];
    for (size_t k = 0; k < n; )
    {
        size_t e = k + 1;
        while (e < n && face[e] == face[k])
        {
            ++e;
        }
        ff[face[k]] = fit(i, k, e);
        k = e;
    }
}


// ************************************************************************* //
