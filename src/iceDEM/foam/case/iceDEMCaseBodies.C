/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Description
    Reading the bodies of constant/iceField (types box | prism | polyhedron)
    into the world. See doc/caseFiles.md.
\*---------------------------------------------------------------------------*/

#include "iceDEMCase.H"
#include "dictionaryChecks.H"

#include "field/IceFloe.H"
#include "geometry/DilatedShape.H"

#include "vector2D.H"
#include "boundBox.H"
#include "pointField.H"

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

//- Stop when an input point is not a vertex of the hull (non-convex list)
void checkHullVertices
(
    const Foam::dictionary& d,
    const Foam::List<Foam::vector>& points,
    const ::iceDEM::ConvexPolyhedron& hull
)
{
    using namespace Foam;

    // A point within the hull's tolerance of a vertex is that vertex (a
    // point listed twice with rounding is one corner)
    boundBox bb(pointField(points), false);
    const scalar tol =
        ::iceDEM::ConvexPolyhedron::hullTolerance*max(bb.mag(), VSMALL);

    forAll(points, k)
    {
        const ::iceDEM::Vec3 p = toVec3(points[k]);
        scalar dmin = GREAT;
        for (const ::iceDEM::Vec3& v : hull.vertices())
        {
            dmin = min(dmin, (v - p).norm());
        }
        if (dmin > tol)
        {
            FatalIOErrorInFunction(d)
                << "Entry 'points': point " << k << ' ' << points[k]
                << " is not a vertex of the convex hull of the points: the"
                << " core must be convex (every point a corner)" << nl
                << exit(FatalIOError);
        }
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::iceDEMCase::readBodies()
{
    if (!iceField_.isDict("bodies"))
    {
        FatalIOErrorInFunction(iceField_)
            << "Missing sub-dictionary 'bodies' (one sub-dictionary per"
            << " body, see doc/caseFiles.md)" << nl
            << exit(FatalIOError);
    }
    const dictionary& bodies = iceField_.subDict("bodies");

    const word massModelName =
        selectName
        (
            properties_, "massModel", wordList({"faceted", "dilated"}),
            "faceted"
        );
    const ::iceDEM::MassModel massModel =
        coreCall
        (
            properties_, "massModel",
            [&]{ return ::iceDEM::massModelFromName(massModelName); }
        );

    for (const entry& e : bodies)
    {
        const word& name = e.keyword();
        if (name.empty() || name[0] == '_')
        {
            continue;
        }
        if (!e.isDict())
        {
            FatalIOErrorInFunction(bodies)
                << "Entry '" << name << "' of 'bodies' must be a dictionary"
                << " (type box | prism | polyhedron; ...)" << nl
                << exit(FatalIOError);
        }
        const dictionary& d = e.dict();
        const string what("body " + name);

        const word type =
            selectName(d, "type", wordList({"box", "prism", "polyhedron"}));

        checkEntries
        (
            d, "constant/iceField",
            {
                type == "box" ? "bodies/*(type box)"
              : type == "prism" ? "bodies/*(type prism)"
              : "bodies/*(type polyhedron)"
            },
            what
        );

        const scalar r = positive(d, "radius");
        const label material = materialOf(d);
        const word motionName =
            selectName
            (
                d, "motion", wordList({"free", "fixed", "prescribed"}), "free"
            );
        const ::iceDEM::BodyMotion motion =
            coreCall
            (
                d, what,
                [&]{ return ::iceDEM::bodyMotionFromName(motionName); }
            );
        const vector velocity = d.getOrDefault<vector>("velocity", Zero);
        const vector omega = d.getOrDefault<vector>("omega", Zero);

        ::iceDEM::ConvexPolyhedron core;
        ::iceDEM::Vec3 position = ::iceDEM::Vec3::Zero();
        ::iceDEM::Quat orientation = ::iceDEM::Quat::Identity();

        if (type == "box")
        {
            // The box (2 halfExtents) at least minOuterWidthInRadii r wide:
            // every half extent at least 2 r (exact: h - r is)
            const vector h = d.get<vector>("halfExtents");
            if
            (
                !(2*cmptMin(h) >= ::iceDEM::DilatedShape::minOuterWidthInRadii*r)
            )
            {
                FatalIOErrorInFunction(d)
                    << "Entry 'halfExtents' " << h << " of " << what.c_str()
                    << ": every half extent (of the dilated box) must be"
                    << " at least twice the radius " << r
                    << " (core half extents = halfExtents - radius, and a"
                    << " dilated body's radius is at most half its core's"
                    << " thinnest width)" << nl
                    << exit(FatalIOError);
            }
            core = coreCall
            (
                d, what + ", entry 'halfExtents'",
                [&]{ return ::iceDEM::ConvexPolyhedron::box(toVec3(h - vector::uniform(r))); }
            );
            position = toVec3(d.get<vector>("centre"));
            orientation =
                ::iceDEM::Quat(toMat3(rotationTensor(d, "orientation")));
        }
        else if (type == "prism")
        {
            const List<vector2D> outline(d.get<List<vector2D>>("outline"));
            const scalar zBottom = d.get<scalar>("zBottom");
            const scalar thickness = positive(d, "thickness");

            std::vector<::iceDEM::Vec2> pts;
            pts.reserve(outline.size());
            for (const vector2D& p : outline)
            {
                pts.emplace_back(p.x(), p.y());
            }
            core = coreCall
            (
                d, what + ", entries 'outline', 'zBottom', 'thickness'",
                [&]{ return ::iceDEM::floeCore(pts, zBottom, thickness, r); }
            );
            // The core is in world coordinates
        }
        else
        {
            const List<vector> points(d.get<List<vector>>("points"));
            if (points.size() < 4)
            {
                FatalIOErrorInFunction(d)
                    << "Entry 'points' of " << what.c_str() << " has "
                    << points.size() << " points: a polyhedron needs at"
                    << " least 4 (not coplanar)" << nl
                    << exit(FatalIOError);
            }
            std::vector<::iceDEM::Vec3> pts;
            pts.reserve(points.size());
            for (const vector& p : points)
            {
                pts.push_back(toVec3(p));
            }
            core = coreCall
            (
                d, what + ", entry 'points'",
                [&]{ return ::iceDEM::ConvexPolyhedron::hull(pts); }
            );
            checkHullVertices(d, points, core);

            position = toVec3(d.get<vector>("centre"));
            orientation =
                ::iceDEM::Quat(toMat3(rotationTensor(d, "orientation")));
        }

        const label index = label(world_->bodies().size());

        coreCall
        (
            d, what,
            [&]
            {
                const int shape = world_->addShape
                (
                    ::iceDEM::DilatedShape(core, r, massModel)
                );
                world_->addBody
                (
                    shape,
                    material,
                    position,
                    orientation,
                    toVec3(velocity),
                    toVec3(omega),
                    motion,
                    index
                );
            }
        );

        bodyNames_.append(name);
    }

    if (bodyNames_.empty())
    {
        FatalIOErrorInFunction(bodies)
            << "No body in 'bodies': there is nothing to simulate (a"
            << " structure alone moves without constant/iceDEMProperties)"
            << nl << exit(FatalIOError);
    }
}


// ************************************************************************* //
