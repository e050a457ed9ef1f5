/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    resolvedFlowVelocity: the two-way coupling part (the floes' drag per
    face, its impulse over the sub-cycle and its deposit into the cells of
    the sample points). See resolvedFlowVelocity.H.
\*---------------------------------------------------------------------------*/

#include "resolvedFlowVelocity.H"

// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void Foam::resolvedFlowVelocity::faceForces
(
    int body,
    int nFaces,
    const ::iceDEM::Vec3* F,
    const double* K
) const
{
    // Only the thread that owns 'body' writes faceDrag_[body]; the list of
    // bodies is sized in accumulate() (serial), or here by a new body count
    if (body < 0 || size_t(body) >= faceDrag_.size())
    {
        return;     // sized at the next accumulate(); see there
    }
    std::vector<faceDrag>& fd = faceDrag_[body];
    if (int(fd.size()) < nFaces)
    {
        fd.resize(nFaces);      // once per body
    }
    for (size_t f = 0; f < fd.size(); ++f)
    {
        faceDrag& d = fd[f];
        if (int(f) < nFaces)
        {
            d.Fnew = F[f];
            d.Knew = K[f];
        }
        else
        {
            d.Fnew.setZero();
            d.Knew = 0;
        }
    }
}


void Foam::resolvedFlowVelocity::accumulate(scalar dt, label kick)
{
    // The kick force of this step: kick times the drag of its evaluation
    // (the multi-rate step's impulse; 1 at the single rate), zero on a step
    // that did not evaluate the body forces
    const double k = double(kick);
    for (std::vector<faceDrag>& fd : faceDrag_)
    {
        for (faceDrag& d : fd)
        {
            const ::iceDEM::Vec3 G = k*d.Fnew;
            const double GK = k*d.Knew;

            // Velocity Verlet: half a kick with the last step's kick force,
            // half with this step's
            d.J += (0.5*dt)*(d.Fold + G);
            d.KT += 0.5*dt*(d.Kold + GK);
            d.Fold = G;
            d.Kold = GK;
        }
    }
}


::iceDEM::Vec3 Foam::resolvedFlowVelocity::deposit
(
    vectorField& reactionImpulse,
    scalarField& KIntegral,
    ::iceDEM::Vec3& lost
)
{
    ::iceDEM::Vec3 total = ::iceDEM::Vec3::Zero();
    lost.setZero();

    const size_t N = faceDrag_.size();
    for (size_t i = 0; i < N; ++i)
    {
        std::vector<faceDrag>& fd = faceDrag_[i];
        const bool sampled = i < points_.size() && sampled_[i];
        const size_t n = sampled ? points_[i].size() : 0;

        // Area of the found points of each face and of the whole floe
        // (found by any processor: the same on all)
        double floeArea = 0;
        for (size_t k = 0; k < n; ++k)
        {
            if (hits_[i][k] > 0) floeArea += areas_[i][k];
        }

        for (size_t f = 0; f < fd.size(); ++f)
        {
            faceDrag& d = fd[f];
            if (d.J.squaredNorm() == 0 && d.KT == 0)
            {
                continue;
            }
            total += d.J;

            double faceArea = 0;
            for (size_t k = 0; k < n; ++k)
            {
                if (pointFaces_[i][k] == int(f) && hits_[i][k] > 0)
                {
                    faceArea += areas_[i][k];
                }
            }
            // A face dry (or outside the mesh) at the sampling: the floe's
            // points take its drag
            const bool ownFace = faceArea > 0;
            const double area = ownFace ? faceArea : floeArea;
            if (!(area > 0))
            {
                lost += d.J;
            }
            else
            {
                for (size_t k = 0; k < n; ++k)
                {
                    const label celli = cells_[i][k];
                    if
                    (
                        celli < 0
                     || (ownFace && pointFaces_[i][k] != int(f))
                    )
                    {
                        continue;
                    }
                    const double w = areas_[i][k]/(area*hits_[i][k]);
                    const ::iceDEM::Vec3 dJ = -w*d.J;
                    reactionImpulse[celli] += vector(dJ.x(), dJ.y(), dJ.z());
                    KIntegral[celli] += w*d.KT;
                }
            }
            d.J.setZero();
            d.KT = 0;
        }
    }
    return total;
}


void Foam::resolvedFlowVelocity::getFaceDrag
(
    labelList& nFaces,
    List<vector>& F,
    List<scalar>& K
) const
{
    nFaces.setSize(faceDrag_.size());
    label m = 0;
    forAll(nFaces, i)
    {
        nFaces[i] = label(faceDrag_[i].size());
        m += nFaces[i];
    }
    F.setSize(m);
    K.setSize(m);
    m = 0;
    for (const std::vector<faceDrag>& fd : faceDrag_)
    {
        for (const faceDrag& d : fd)
        {
            F[m] = vector(d.Fold.x(), d.Fold.y(), d.Fold.z());
            K[m] = d.Kold;
            ++m;
        }
    }
}


void Foam::resolvedFlowVelocity::setFaceDrag
(
    const labelList& nFaces,
    const List<vector>& F,
    const List<scalar>& K
)
{
    faceDrag_.assign(nFaces.size(), {});
    label m = 0;
    forAll(nFaces, i)
    {
        faceDrag_[i].resize(nFaces[i]);
        for (faceDrag& d : faceDrag_[i])
        {
            if (m >= F.size() || m >= K.size())
            {
                FatalErrorInFunction
                    << "two-way drag state: " << F.size() << " face forces"
                    << " for " << sum(nFaces) << " faces" << nl
                    << exit(FatalError);
            }
            d.Fold = ::iceDEM::Vec3(F[m].x(), F[m].y(), F[m].z());
            d.Kold = K[m];
            ++m;
        }
    }
}


// ************************************************************************* //
