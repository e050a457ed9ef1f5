/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "resolvedFlowVelocity.H"
#include "dictionaryChecks.H"

#include "World.H"
#include "hydro/Drag.H"
#include "hydro/WaterClip.H"

#include "Pstream.H"
#include "PstreamCombineReduceOps.H"
#include "treeDataCell.H"
#include "indexedOctree.H"

#include <chrono>
#include <cstring>

using namespace Foam::iceDEMChecks;

namespace
{
    //- Fewer bodies are sampled on one thread
    constexpr int minParallelBodies = 16;
}

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::resolvedFlowVelocity::resolvedFlowVelocity
(
    const fvMesh& mesh,
    const dictionary& dragDict
)
:
    mesh_(mesh),
    UName_(dragDict.getOrDefault<word>("U", "U")),
    current_(dragDict.getOrDefault<vector>("current", Zero)),
    maxWalk_(labelInRange(dragDict, "maxWalk", 1, labelMax, 100)),
    interp_(),
    unprepared_(0)
{
    if (!mesh_.foundObject<volVectorField>(UName_))
    {
        FatalIOErrorInFunction(dragDict)
            << "Entry 'U': drag type resolved samples the velocity field '"
            << UName_ << "', which the solver does not have." << nl
            << "    Velocity fields: "
            << flatOutput(mesh_.sortedNames<volVectorField>()) << nl
            << exit(FatalIOError);
    }
    if (!(mag(current_) < GREAT))
    {
        FatalIOErrorInFunction(dragDict)
            << "Entry 'current' " << current_ << " must be finite" << nl
            << exit(FatalIOError);
    }
}


// * * * * * * * * * * * * * * * * Destructor  * * * * * * * * * * * * * * //

Foam::resolvedFlowVelocity::~resolvedFlowVelocity()
{}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

const Foam::volVectorField& Foam::resolvedFlowVelocity::U() const
{
    const auto* Uptr = mesh_.findObject<volVectorField>(UName_);
    if (!Uptr)
    {
        FatalErrorInFunction
            << "The velocity field " << UName_ << " of the resolved drag is"
            << " no longer registered" << nl << exit(FatalError);
    }
    return *Uptr;
}


Foam::label Foam::resolvedFlowVelocity::exitFace
(
    const point& p,
    label celli
) const
{
    const cell& c = mesh_.cells()[celli];
    const vectorField& Cf = mesh_.faceCentres();
    const vectorField& Sf = mesh_.faceAreas();
    const labelList& own = mesh_.faceOwner();

    // Relative tolerance on the distance to a face plane
    const scalar tol = 1e-10*cbrt(mesh_.cellVolumes()[celli]);

    label best = -1;
    scalar bestDist = tol;
    forAll(c, k)
    {
        const label f = c[k];
        const scalar a = mag(Sf[f]);
        if (a < VSMALL)
        {
            continue;
        }
        scalar d = ((p - Cf[f]) & Sf[f])/a;
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
    return mesh_.cellTree().findInside(p);
}


void Foam::resolvedFlowVelocity::samplePoints
(
    const ::iceDEM::World& world,
    const ::iceDEM::Drag& drag,
    int i,
    std::vector<::iceDEM::Vec3>& points
) const
{
    // The traversal of iceDEM::Drag::bodyDrag (same order, same arithmetic)
    constexpr int capacity = 1 << (2*::iceDEM::DragSettings::maxSubdivision);

    points.clear();

    const ::iceDEM::Body& b = world.bodies()[i];
    const ::iceDEM::ConvexPolyhedron& P = world.shapeOf(i).outer();
    const ::iceDEM::Mat3 R = b.rotation();
    const double level = drag.water().level;
    const ::iceDEM::DragSettings& s = drag.settings();

    {
        const ::iceDEM::Vec3 up = R.row(2).transpose();
        bool wet = false;
        for (const ::iceDEM::Vec3& v : P.vertices())
        {
            if (up.dot(v) + b.x.z() < level)
            {
                wet = true;
                break;
            }
        }
        if (!wet)
        {
            return;
        }
    }

    ::iceDEM::SubmergedFace face;
    ::iceDEM::Vec3 pts[capacity];
    double areas[capacity];

    const int nf = static_cast<int>(P.faces().size());
    for (int f = 0; f < nf; ++f)
    {
        if (!::iceDEM::submergedFace(P, f, R, b.x, level, face))
        {
            continue;
        }
        const bool skin = std::abs(face.normal.z()) >= s.bottomCosine;
        const double coeff = skin ? s.skinCoefficient : s.formCoefficient;
        if (coeff == 0)
        {
            continue;
        }
        for (int k = 0; k < face.nVertices; ++k)
        {
            const int m =
                ::iceDEM::faceTriangleSamples(face, k, s.subdivision, pts, areas);
            points.insert(points.end(), pts, pts + m);
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void Foam::resolvedFlowVelocity::update()
{
    // Demand-driven geometry and addressing built here, serially, so the
    // threads of prepare() only read it
    (void)mesh_.cells();
    (void)mesh_.faceCentres();
    (void)mesh_.faceAreas();
    (void)mesh_.cellCentres();
    (void)mesh_.cellVolumes();
    (void)mesh_.tetBasePtIs();
    (void)mesh_.bounds();
    (void)mesh_.cellTree();

    interp_.reset(new interpolationCellPoint<vector>(U()));

    stats_ = statistics();
    unprepared_ = 0;
}


void Foam::resolvedFlowVelocity::prepare
(
    const ::iceDEM::World& world,
    const ::iceDEM::Drag& drag
) const
{
    if (!interp_)
    {
        FatalErrorInFunction
            << "resolved drag: update() was not called before the DEM step"
            << nl << exit(FatalError);
    }
    const auto started = std::chrono::steady_clock::now();

    const int N = static_cast<int>(world.bodies().size());
    if (int(hint_.size()) != N)
    {
        hint_.assign(N, -1);
        points_.assign(N, {});
        values_.assign(N, {});
        found_.assign(N, {});
        cursor_.assign(N, 0);
        sampled_.assign(N, 0);
    }

    // 1.-2. Sample points and local interpolation, per body
    // (a parallel region costs more than a few bodies' sampling)
    #pragma omp parallel for schedule(dynamic, 4) if(N >= minParallelBodies)
    for (int i = 0; i < N; ++i)
    {
        cursor_[i] = 0;
        std::vector<::iceDEM::Vec3>& pts = points_[i];
        if (!world.bodies()[i].isFree())
        {
            pts.clear();
            sampled_[i] = 0;
            continue;
        }
        sampled_[i] = 1;
        samplePoints(world, drag, i, pts);

        const size_t n = pts.size();
        values_[i].resize(n);
        found_[i].resize(n);
        label hint = hint_[i];
        for (size_t k = 0; k < n; ++k)
        {
            const point p(pts[k].x(), pts[k].y(), pts[k].z());
            const label celli = locate(p, hint);
            if (celli >= 0)
            {
                const vector u = interp_->interpolate(p, celli);
                values_[i][k] = ::iceDEM::Vec3(u.x(), u.y(), u.z());
                found_[i][k] = 1;
                hint = celli;
            }
            else
            {
                values_[i][k].setZero();
                found_[i][k] = 0;
            }
        }
        hint_[i] = hint;
    }

    // 3. Combine over the processors; far-field current where nobody found
    label total = 0;
    for (int i = 0; i < N; ++i)
    {
        total += label(points_[i].size());
    }

    if (Pstream::parRun())
    {
        label maxTotal = total;
        reduce(maxTotal, maxOp<label>());
        if (maxTotal != total)
        {
            FatalErrorInFunction
                << "resolved drag: " << total << " sample points on processor "
                << Pstream::myProcNo() << ", " << maxTotal << " on another:"
                << " the replicated DEM differs between processors" << nl
                << exit(FatalError);
        }

        List<scalar> buf(4*total);
        label m = 0;
        for (int i = 0; i < N; ++i)
        {
            for (size_t k = 0; k < points_[i].size(); ++k)
            {
                const bool hit = found_[i][k];
                buf[m++] = hit ? values_[i][k].x() : 0;
                buf[m++] = hit ? values_[i][k].y() : 0;
                buf[m++] = hit ? values_[i][k].z() : 0;
                buf[m++] = hit ? 1 : 0;
            }
        }
        Pstream::listCombineGather(buf, plusEqOp<scalar>());
        Pstream::listCombineScatter(buf);

        m = 0;
        for (int i = 0; i < N; ++i)
        {
            for (size_t k = 0; k < points_[i].size(); ++k)
            {
                const scalar hits = buf[m + 3];
                if (hits > 0)
                {
                    values_[i][k] =
                        ::iceDEM::Vec3(buf[m], buf[m + 1], buf[m + 2])/hits;
                    found_[i][k] = 1;
                }
                else
                {
                    found_[i][k] = 0;
                }
                m += 4;
            }
        }
    }

    label outside = 0;
    const ::iceDEM::Vec3 far(current_.x(), current_.y(), current_.z());
    for (int i = 0; i < N; ++i)
    {
        for (size_t k = 0; k < points_[i].size(); ++k)
        {
            if (!found_[i][k])
            {
                values_[i][k] = far;
                ++outside;
            }
        }
    }

    ++stats_.evaluations;
    stats_.points += total;
    stats_.outside += outside;
    stats_.seconds += std::chrono::duration<double>
    (
        std::chrono::steady_clock::now() - started
    ).count();
}


void Foam::resolvedFlowVelocity::velocity
(
    int body,
    const ::iceDEM::Vec3* points,
    int n,
    ::iceDEM::Vec3* u
) const
{
    const ::iceDEM::Vec3 far(current_.x(), current_.y(), current_.z());

    if
    (
        body < 0 || size_t(body) >= sampled_.size() || !sampled_[body]
    )
    {
        // Not a sampled body (the structure), or nothing prepared yet
        for (int k = 0; k < n; ++k)
        {
            u[k] = far;
        }
        return;
    }

    const std::vector<::iceDEM::Vec3>& pts = points_[body];
    const std::vector<::iceDEM::Vec3>& vals = values_[body];
    const label size = label(pts.size());

    auto matches = [&](label start)
    {
        if (start + n > size)
        {
            return false;
        }
        return
            std::memcmp
            (
                static_cast<const void*>(pts.data() + start),
                static_cast<const void*>(points),
                sizeof(::iceDEM::Vec3)*n
            ) == 0;
    };

    label start = cursor_[body];
    if (!matches(start))
    {
        start = -1;
        for (label s = 0; s + n <= size; ++s)
        {
            if (matches(s))
            {
                start = s;
                break;
            }
        }
    }

    if (start >= 0)
    {
        for (int k = 0; k < n; ++k)
        {
            u[k] = vals[start + k];
        }
        cursor_[body] = start + n;
        return;
    }

    // Not prepared: interpolate locally (serial-correct only)
    unprepared_ += n;
    label hint = hint_[body];
    for (int k = 0; k < n; ++k)
    {
        const point p(points[k].x(), points[k].y(), points[k].z());
        const label celli = interp_ ? locate(p, hint) : -1;
        if (celli >= 0)
        {
            const vector v = interp_->interpolate(p, celli);
            u[k] = ::iceDEM::Vec3(v.x(), v.y(), v.z());
        }
        else
        {
            u[k] = far;
        }
    }
}


Foam::resolvedFlowVelocity::statistics
Foam::resolvedFlowVelocity::stats() const
{
    statistics s = stats_;
    s.unprepared = label(unprepared_.load());
    return s;
}


// ************************************************************************* //
