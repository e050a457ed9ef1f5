/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    resolvedFlowVelocity: locating a drag sample point in the mesh (a walk
    across cell faces, the cell octree) and, in a periodic DEM domain, its
    periodic images.

\*---------------------------------------------------------------------------*/

#include "resolvedFlowVelocity.H"

#include "World.H"
#include "domain/Domain.H"

#include "treeDataCell.H"
#include "indexedOctree.H"

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

Foam::label Foam::resolvedFlowVelocity::exitFace
(
    const point& p,
    label celli
) const
{
    const cell& c = mesh_.cells()[celli];
    const vectorField& Cf = mesh_.faceCentres();
    const labelList& own = mesh_.faceOwner();

    label best = -1;
    scalar bestDist = cellTolerance_[celli];
    forAll(c, k)
    {
        const label f = c[k];
        scalar d = (p - Cf[f]) & faceNormals_[f];
        if (own[f] != celli)
        {
            d = -d;
        }
        if (d > bestDist)
        {
            bestDist = d;
            best = f;
        }
    }
    return best;
}


Foam::label Foam::resolvedFlowVelocity::locate
(
    const point& p,
    label start
) const
{
    if (start >= 0)
    {
        label celli = start;
        for (label step = 0; step < maxWalk_; ++step)
        {
            const label f = exitFace(p, celli);
            if (f < 0)
            {
                // Inside every face plane of celli (the interpolation takes
                // the nearest tetrahedron of a warped cell)
                return celli;
            }
            if (f >= mesh_.nInternalFaces())
            {
                break;      // boundary: the octree decides
            }
            const label own = mesh_.faceOwner()[f];
            celli = (own == celli ? mesh_.faceNeighbour()[f] : own);
        }
    }

    if (!mesh_.bounds().contains(p))
    {
        return -1;
    }
    if (!treeBuilt_.load(std::memory_order_acquire))
    {
        // Built once per mesh motion by the first thread that needs it;
        // the others wait here and read it only once it is complete
        #pragma omp critical(iceDEM_resolvedFlowVelocity_cellTree)
        {
            if (!treeBuilt_.load(std::memory_order_relaxed))
            {
                (void)mesh_.tetBasePtIs();
                buildCellTree();
                treeBuilt_.store(true, std::memory_order_release);
            }
        }
    }
    return cellTree_->findInside(p);
}


void Foam::resolvedFlowVelocity::buildCellTree() const
{
    // The bounds and parameters of polyMesh::cellTree (OpenFOAM v1912)
    treeBoundBox bb(mesh_.points());
    Random rndGen(261782);
    bb = bb.extend(rndGen, 1e-4);
    bb.min() -= point(ROOTVSMALL, ROOTVSMALL, ROOTVSMALL);
    bb.max() += point(ROOTVSMALL, ROOTVSMALL, ROOTVSMALL);

    cellTree_.reset
    (
        new indexedOctree<treeDataCell>
        (
            treeDataCell(true, mesh_, polyMesh::CELL_TETS),
            bb,
            8,      // maxLevel
            10,     // leafsize
            5.0     // duplicity
        )
    );
}


Foam::label Foam::resolvedFlowVelocity::locateImage
(
    point& p,
    label start,
    const ::iceDEM::Domain* domain
) const
{
    const label celli = locate(p, start);
    if (celli >= 0 || !domain || !domain->active())
    {
        return celli;
    }

    // A periodic DEM box whose flow mesh covers one period, but not the
    // same one: the mesh follows the structure's drift, and a floe that
    // straddles a periodic side has points beyond it before its centroid
    // wraps. The periodic image of the point (the same water) is then in
    // the mesh: the first of the eight neighbouring images that a cell
    // holds (at most one can: the mesh is no longer than a period)
    for (int code = 0; code < 9; ++code)
    {
        const int sx = ::iceDEM::Domain::imageX(code);
        const int sy = ::iceDEM::Domain::imageY(code);
        if
        (
            (sx == 0 && sy == 0)
         || (sx != 0 && !domain->periodic(0))
         || (sy != 0 && !domain->periodic(1))
        )
        {
            continue;
        }
        const ::iceDEM::Vec3 s = domain->shift(code);
        const point q(p.x() + s.x(), p.y() + s.y(), p.z() + s.z());
        const label cellq = locate(q, -1);
        if (cellq >= 0)
        {
            p = q;
            return cellq;
        }
    }
    return -1;
}


// ************************************************************************* //
