/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "resolvedFlowVelocity.H"
#include "dictionaryChecks.H"

#include "World.H"
#include "hydro/Drag.H"
#include "hydro/WaterClip.H"
#include "domain/Domain.H"

#include "Pstream.H"
#include "PstreamCombineReduceOps.H"
#include "fvcGrad.H"

#include <algorithm>
#include <chrono>
#include <cstring>

using namespace Foam::iceDEMChecks;

namespace
{
    //- Fewer bodies are sampled on one thread
    constexpr int minParallelBodies = 16;

    //- Tolerance of the walk's point-in-cell test, relative to the cell's
    //  size (round-off of the face-plane distances)
    constexpr Foam::scalar relativeWalkTolerance = 1e-10;

    //- A boolean entry (true/false, on/off, yes/no); FatalIOError naming
    //  the entry for anything else
    bool readSwitch(const Foam::dictionary& dict, const Foam::word& key, bool deflt)
    {
        using namespace Foam;
        const entry* e = dict.findEntry(key, keyType::LITERAL);
        if (!e)
        {
            return deflt;
        }
        ITstream& is = e->stream();
        const token t(is);
        if (t.isWord() && is.nRemainingTokens() == 0)
        {
            const Switch sw(t.wordToken(), true);
            if (sw.valid())
            {
                return bool(sw);
            }
        }
        if (t.isBool() && is.nRemainingTokens() == 0)
        {
            return t.boolToken();
        }
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' must be a boolean (true or false,"
            << " on or off, yes or no), not ";
        if (is.size() == 1)
        {
            FatalIOError << "'" << t << "'";
        }
        else
        {
            FatalIOError << is.size() << " tokens";
        }
        FatalIOError << nl << exit(FatalIOError);
        return deflt;
    }
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
    interpolationType_
    (
        dragDict.getOrDefault<word>("interpolation", "cellGradient")
    ),
    interp_(),
    gradU_(),
    samplePerDemStep_(false),
    sampledThisStep_(false),
    updated_(false),
    Ucurrent_(nullptr),
    world_(nullptr),
    treeBuilt_(false),
    cellTree_(),
    treeEvent_(-1),
    twoWay_(false),
    unprepared_(0)
{
    twoWay_ = readSwitch(dragDict, "twoWay", false);
    if (!mesh_.foundObject<volVectorField>(UName_))
    {
        FatalIOErrorInFunction(dragDict)
            << "Entry 'U': drag type resolved samples the velocity field '"
            << UName_ << "', which the solver does not have." << nl
            << "    Velocity fields: "
            << flatOutput(mesh_.sortedNames<volVectorField>()) << nl
            << exit(FatalIOError);
    }
    if
    (
        interpolationType_ != "cellGradient"
     && !interpolation<vector>::dictionaryConstructorTablePtr_->found
        (
            interpolationType_
        )
    )
    {
        FatalIOErrorInFunction(dragDict)
            << "Entry 'interpolation': unknown scheme '" << interpolationType_
            << "'." << nl << "    Allowed: cellGradient "
            << flatOutput
               (
                   interpolation<vector>::dictionaryConstructorTablePtr_
                  ->sortedToc()
               )
            << nl << exit(FatalIOError);
    }
    {
        const word sampling =
            dragDict.getOrDefault<word>("sampling", "flowStep");
        if (sampling != "flowStep" && sampling != "demStep")
        {
            FatalIOErrorInFunction(dragDict)
                << "Entry 'sampling': unknown '" << sampling << "'." << nl
                << "    Allowed: flowStep (once per flow step, a linear fit"
                << " per floe) or demStep (every DEM force evaluation)" << nl
                << exit(FatalIOError);
        }
        samplePerDemStep_ = (sampling == "demStep");
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


Foam::vector Foam::resolvedFlowVelocity::interpolate
(
    const point& p,
    label celli
) const
{
    if (gradU_)
    {
        // Linear reconstruction in the cell
        return
            Ucurrent_->primitiveField()[celli]
          + ((p - mesh_.cellCentres()[celli]) & gradU_->primitiveField()[celli]);
    }
    return interp_->interpolate(p, celli);
}


void Foam::resolvedFlowVelocity::samplePoints
(
    const ::iceDEM::World& world,
    const ::iceDEM::Drag& drag,
    int i,
    std::vector<::iceDEM::Vec3>& points,
    std::vector<int>& faces,
    std::vector<double>& pointAreas
) const
{
    // The traversal of iceDEM::Drag::bodyDrag (same order, same arithmetic)
    constexpr int capacity = 1 << (2*::iceDEM::DragSettings::maxSubdivision);

    points.clear();
    faces.clear();
    pointAreas.clear();

    const ::iceDEM::Body& b = world.bodies()[i];
    static thread_local ::iceDEM::PolyhedronBuffer outerBuffer;
    const ::iceDEM::PolyhedronView P = world.shapeOf(i).outer(outerBuffer);
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
            faces.insert(faces.end(), m, f);
            pointAreas.insert(pointAreas.end(), areas, areas + m);
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void Foam::resolvedFlowVelocity::update()
{
    const auto started = std::chrono::steady_clock::now();

    // Demand-driven geometry and addressing built here, serially, so the
    // threads of prepare() only read it
    (void)mesh_.cells();
    (void)mesh_.faceCentres();
    (void)mesh_.faceAreas();
    (void)mesh_.cellCentres();
    (void)mesh_.cellVolumes();
    (void)mesh_.bounds();
    if (interpolationType_ != "cellGradient")
    {
        // The tetrahedra of the cells (cellPoint and its kin)
        (void)mesh_.tetBasePtIs();
    }
    // The cell octree (and the tetrahedra it tests with) only when a walk
    // needs it, and again only after the mesh moved (polyMesh::movePoints
    // gives the points a new event number)
    const regIOobject* meshPoints = mesh_.findObject<regIOobject>("points");
    const label event = meshPoints ? meshPoints->eventNo() : -1;
    if (event < 0 || event != treeEvent_)
    {
        treeBuilt_ = false;
        treeEvent_ = event;
    }

    // The walk's face planes: unit normals (zero for a degenerate face, which
    // then never decides) and a tolerance relative to the cell size
    const vectorField& Sf = mesh_.faceAreas();
    faceNormals_.setSize(Sf.size());
    forAll(Sf, f)
    {
        const scalar a = mag(Sf[f]);
        faceNormals_[f] = a > VSMALL ? Sf[f]/a : Zero;
    }
    const scalarField& V = mesh_.cellVolumes();
    cellTolerance_.setSize(V.size());
    forAll(V, celli)
    {
        cellTolerance_[celli] = relativeWalkTolerance*cbrt(V[celli]);
    }

    Ucurrent_ = &U();
    if (interpolationType_ == "cellGradient")
    {
        interp_.reset();
        gradU_.reset(new volTensorField(fvc::grad(U())));
    }
    else
    {
        gradU_.reset();
        interp_.reset(interpolation<vector>::New(interpolationType_, U()).ptr());
    }
    updated_ = true;
    sampledThisStep_ = false;

    stats_ = statistics();
    unprepared_ = 0;
    stats_.seconds = std::chrono::duration<double>
    (
        std::chrono::steady_clock::now() - started
    ).count();
}


std::vector<char> Foam::resolvedFlowVelocity::followBodies
(
    const ::iceDEM::World& world
) const
{
    const std::vector<::iceDEM::Body>& bodies = world.bodies();
    const int N = static_cast<int>(bodies.size());
    bool same = int(ids_.size()) == N;
    for (int i = 0; same && i < N; ++i)
    {
        same = ids_[i] == bodies[i].id;
    }
    if (same)
    {
        return {};
    }

    // Old index of every id; the bodies keep their order, so one pass
    std::vector<int> from(N, -1);
    std::vector<char> fresh(N, 1);
    {
        std::size_t o = 0;
        for (int i = 0; i < N; ++i)
        {
            std::size_t k = o;
            while (k < ids_.size() && ids_[k] != bodies[i].id) ++k;
            if (k < ids_.size())
            {
                from[i] = int(k);
                fresh[i] = 0;
                o = k + 1;
            }
        }
    }

    // Moves the entries of v to the new order (new bodies: default)
    auto follow = [&from, N](auto& v)
    {
        using Vector = typename std::decay<decltype(v)>::type;
        Vector w(N);
        for (int i = 0; i < N; ++i)
        {
            if (from[i] >= 0 && std::size_t(from[i]) < v.size())
            {
                w[i] = std::move(v[from[i]]);
            }
        }
        v.swap(w);
    };
    follow(points_);
    follow(pointFaces_);
    follow(values_);
    follow(found_);
    follow(cursor_);
    follow(sampled_);
    follow(areas_);
    follow(cells_);
    follow(hits_);
    follow(fits_);
    follow(faceFits_);
    follow(fitOrigin_);
    std::vector<label> hint(N, -1);
    for (int i = 0; i < N; ++i)
    {
        if (from[i] >= 0 && std::size_t(from[i]) < hint_.size())
        {
            hint[i] = hint_[from[i]];
        }
    }
    hint_.swap(hint);

    ids_.resize(N);
    for (int i = 0; i < N; ++i)
    {
        ids_[i] = bodies[i].id;
    }
    return fresh;
}


void Foam::resolvedFlowVelocity::sampleAll
(
    const ::iceDEM::World& world,
    const ::iceDEM::Drag& drag,
    const std::vector<char>* only
) const
{
    const int N = static_cast<int>(world.bodies().size());
    auto chosen = [only](int i) { return !only || (*only)[i]; };

    // Periodic images of points outside the mesh (nullptr: none)
    const ::iceDEM::Domain* domain = world.domain();

    // 1.-2. Sample points and local interpolation, per body
    // (a parallel region costs more than a few bodies' sampling)
    label images = 0;
    #pragma omp parallel for schedule(dynamic, 4) if(N >= minParallelBodies) \
        reduction(+:images)
    for (int i = 0; i < N; ++i)
    {
        if (!chosen(i))
        {
            continue;
        }
        cursor_[i] = 0;
        std::vector<::iceDEM::Vec3>& pts = points_[i];
        if (!world.bodies()[i].isFree())
        {
            pts.clear();
            sampled_[i] = 0;
            continue;
        }
        sampled_[i] = 1;
        samplePoints(world, drag, i, pts, pointFaces_[i], areas_[i]);

        const size_t n = pts.size();
        values_[i].resize(n);
        found_[i].resize(n);
        cells_[i].resize(n);
        hits_[i].resize(n);
        label hint = hint_[i];
        for (size_t k = 0; k < n; ++k)
        {
            point p(pts[k].x(), pts[k].y(), pts[k].z());
            const label celli = locateImage(p, hint, domain);
            if (celli >= 0)
            {
                if (p.x() != pts[k].x() || p.y() != pts[k].y())
                {
                    ++images;
                }
                // p: the point or, outside the mesh, its periodic image
                const vector u = interpolate(p, celli);
                values_[i][k] = ::iceDEM::Vec3(u.x(), u.y(), u.z());
                found_[i][k] = 1;
                cells_[i][k] = celli;
                hits_[i][k] = 1;
                hint = celli;
            }
            else
            {
                values_[i][k].setZero();
                found_[i][k] = 0;
                cells_[i][k] = -1;
                hits_[i][k] = 0;
            }
        }
        hint_[i] = hint;
    }

    // 3. Combine over the processors; far-field current where nobody found
    label total = 0;
    for (int i = 0; i < N; ++i)
    {
        if (chosen(i)) total += label(points_[i].size());
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
            if (!chosen(i)) continue;
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
            if (!chosen(i)) continue;
            for (size_t k = 0; k < points_[i].size(); ++k)
            {
                const scalar hits = buf[m + 3];
                hits_[i][k] = label(hits + 0.5);
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

    if (Pstream::parRun())
    {
        reduce(images, sumOp<label>());
    }
    stats_.images += images;

    label outside = 0;
    const ::iceDEM::Vec3 far(current_.x(), current_.y(), current_.z());
    for (int i = 0; i < N; ++i)
    {
        if (!chosen(i)) continue;
        for (size_t k = 0; k < points_[i].size(); ++k)
        {
            if (!found_[i][k])
            {
                values_[i][k] = far;
                ++outside;
            }
        }
    }

    if (!only) ++stats_.evaluations;
    stats_.points += total;
    stats_.outside += outside;
}


void Foam::resolvedFlowVelocity::prepare
(
    const ::iceDEM::World& world,
    const ::iceDEM::Drag& drag
) const
{
    if (!updated_)
    {
        FatalErrorInFunction
            << "resolved drag: update() was not called before the DEM step"
            << nl << exit(FatalError);
    }
    if (twoWay_ && faceDrag_.size() != world.bodies().size())
    {
        // Serial, before the threads of the force evaluation
        faceDrag_.resize(world.bodies().size());
    }

    // Bodies removed and inserted since the last call (inflow/outflow;
    // two-way is refused with it): the data follow their bodies, and new
    // bodies are sampled at once if this flow step's fits were made
    const std::vector<char> fresh = followBodies(world);
    const int N = static_cast<int>(world.bodies().size());
    const bool freshOnly = !samplePerDemStep_ && sampledThisStep_;
    if (freshOnly && std::find(fresh.begin(), fresh.end(), 1) == fresh.end())
    {
        return;     // the fits of this flow step hold
    }
    const auto started = std::chrono::steady_clock::now();

    sampleAll(world, drag, freshOnly ? &fresh : nullptr);

    if (!samplePerDemStep_)
    {
        // (followBodies sized the per-body data)
        #pragma omp parallel for schedule(dynamic, 16) if(N >= minParallelBodies)
        for (int i = 0; i < N; ++i)
        {
            if (!freshOnly || fresh[i]) fitBody(world, i);
        }
        world_ = &world;
        sampledThisStep_ = true;
    }

    stats_.seconds += std::chrono::duration<double>
    (
        std::chrono::steady_clock::now() - started
    ).count();
}


::iceDEM::Vec3 Foam::resolvedFlowVelocity::wrapShift
(
    const ::iceDEM::Vec3& moved
) const
{
    ::iceDEM::Vec3 s = ::iceDEM::Vec3::Zero();
    const ::iceDEM::Domain* domain = world_->domain();
    if (!domain)
    {
        return s;
    }
    for (int d = 0; d < 2; ++d)
    {
        if (domain->periodic(d))
        {
            const double L = domain->length(d);
            s[d] = L*std::round(moved[d]/L);
        }
    }
    return s;
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

    if (!samplePerDemStep_)
    {
        const linearFit* f =
            size_t(body) < fits_.size() && fits_[body].valid
          ? &fits_[body] : nullptr;
        const ::iceDEM::Body& b = world_->bodies()[body];
        if (f && n > 0)
        {
            // The face the points lie on: the face plane (body frame)
            // nearest to the first point. A face that was dry at the
            // sampling takes the whole floe's fit.
            static thread_local ::iceDEM::PolyhedronBuffer outerBuffer;
            const ::iceDEM::PolyhedronView P =
                world_->shapeOf(body).outer(outerBuffer);
            const ::iceDEM::Vec3 q =
                b.rotation().transpose()*(points[0] - b.x);
            int best = -1;
            double bestDist = 0;
            const int nf = static_cast<int>(P.faces().size());
            for (int g = 0; g < nf; ++g)
            {
                const double d =
                    std::abs(P.faces()[g].normal.dot(q) - P.faces()[g].offset);
                if (best < 0 || d < bestDist)
                {
                    best = g;
                    bestDist = d;
                }
            }
            const std::vector<linearFit>& ff = faceFits_[body];
            if (best >= 0 && size_t(best) < ff.size() && ff[best].valid)
            {
                f = &ff[best];
            }
        }
        if (f)
        {
            // The periodic lattice vector the body wrapped by since the
            // sampling (zero, exactly, if it did not: it moves a small
            // fraction of a period in one flow step)
            const ::iceDEM::Vec3 centre =
                f->centre + wrapShift(b.x - fitOrigin_[body]);
            for (int k = 0; k < n; ++k)
            {
                u[k] = f->mean + f->gradient*(points[k] - centre);
            }
        }
        else
        {
            // Dry at the sampling, wet now: the far field until the next
            // flow step
            unprepared_ += n;
            for (int k = 0; k < n; ++k)
            {
                u[k] = far;
            }
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
        const label celli = updated_ ? locate(p, hint) : -1;
        if (celli >= 0)
        {
            const vector v = interpolate(p, celli);
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
