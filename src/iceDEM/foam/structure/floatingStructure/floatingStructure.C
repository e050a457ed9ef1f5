/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.

\*---------------------------------------------------------------------------*/

#include "floatingStructure.H"
#include "IFstream.H"
#include "caseEntries.H"
#include "OFstream.H"
#include "Tuple2.H"
#include "vector2D.H"
#include "mathematicalConstants.H"

#include <map>
#include <utility>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

const Foam::wordList Foam::floatingStructure::shapeTypes
({
    "box",
    "facetedHull"
});


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace Foam
{

//- Read a positive scalar entry or stop naming it
static scalar readPositive(const dictionary& dict, const word& key)
{
    const scalar value = dict.get<scalar>(key);
    if (!(value > 0))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' in " << dict.name() << " is " << value
            << ": a positive value is required." << nl
            << exit(FatalIOError);
    }
    return value;
}

} // End namespace Foam


// * * * * * * * * * * * * * * * Static Functions  * * * * * * * * * * * * * //

Foam::floatingStructure::submergedPart Foam::floatingStructure::clip
(
    const UList<point>& points,
    const UList<triFace>& faces,
    const scalar level
)
{
    submergedPart result;

    if (faces.empty())
    {
        return result;
    }

    // Apex of the tetrahedra: a point on the plane near the surface
    point O(Zero);
    for (const point& p : points)
    {
        O += p;
    }
    O /= max(points.size(), 1);
    O.z() = level;

    vector areaBelow(Zero);
    vector firstMoment(Zero);
    scalar volume = 0;

    // Part of one triangle below the plane: at most a quadrilateral
    FixedList<point, 4> poly;

    for (const triFace& f : faces)
    {
        label n = 0;
        for (label i = 0; i < 3; ++i)
        {
            const point& a = points[f[i]];
            const point& b = points[f[(i + 1) % 3]];
            const scalar da = a.z() - level;
            const scalar db = b.z() - level;

            if (da <= 0)
            {
                poly[n++] = a;
            }
            if ((da < 0 && db > 0) || (da > 0 && db < 0))
            {
                point x = a + (da/(da - db))*(b - a);
                x.z() = level;
                poly[n++] = x;
            }
        }

        // Fan of the polygon: tetrahedra with the apex O on the plane
        for (label k = 1; k + 1 < n; ++k)
        {
            const vector a = poly[0] - O;
            const vector b = poly[k] - O;
            const vector c = poly[k + 1] - O;
            const scalar v = (a & (b ^ c))/6.0;
            volume += v;
            firstMoment += v*(a + b + c)/4.0;
            areaBelow += 0.5*((b - a) ^ (c - a));
        }
    }

    result.volume = volume;
    result.centroid =
        (mag(volume) > VSMALL) ? O + firstMoment/volume : O;

    // The lid closes the clipped surface; the area vectors of a closed
    // surface sum to zero and the lid's outward normal is +z
    result.waterplaneArea = -areaBelow.z();

    return result;
}


Foam::floatingStructure::solidProperties Foam::floatingStructure::solid
(
    const UList<point>& points,
    const UList<triFace>& faces
)
{
    solidProperties result;

    point O(Zero);
    for (const point& p : points)
    {
        O += p;
    }
    O /= max(points.size(), 1);

    scalar V = 0;
    vector m1(Zero);
    symmTensor m2(Zero);

    for (const triFace& f : faces)
    {
        const vector a = points[f[0]] - O;
        const vector b = points[f[1]] - O;
        const vector c = points[f[2]] - O;
        const scalar det = a & (b ^ c);
        const vector s = a + b + c;

        V += det/6.0;
        m1 += det/24.0*s;
        // int r r^T over the tetrahedron (O, a, b, c)
        m2 += det/120.0*(sqr(a) + sqr(b) + sqr(c) + sqr(s));
    }

    result.volume = V;
    if (mag(V) > VSMALL)
    {
        const vector d = m1/V;
        result.centroid = O + d;
        result.secondMoment = m2 - V*sqr(d);
    }
    else
    {
        result.centroid = O;
    }

    return result;
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::floatingStructure::buildFacetedHull(const dictionary& dict)
{
    const vector2D position
    (
        dict.lookupOrDefault<vector2D>("position", vector2D(0, 0))
    );

    const label nFacets = dict.get<label>("nFacets");
    if (nFacets < 3)
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'nFacets' in " << dict.name() << " is " << nFacets
            << ": at least 3 facets are required." << nl
            << exit(FatalIOError);
    }

    const word diameters(dict.get<word>("diameters"));
    scalar radiusFactor = 0.5;
    if (diameters == "corners")
    {
        radiusFactor = 0.5;
    }
    else if (diameters == "flats")
    {
        radiusFactor =
            0.5/Foam::cos(constant::mathematical::pi/scalar(nFacets));
    }
    else
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'diameters " << diameters << "' in " << dict.name()
            << " is not valid. Valid: (corners flats): the profile gives the"
            << " diameter across the corners or across the flats." << nl
            << exit(FatalIOError);
    }

    draft_ = readPositive(dict, "draft");

    const List<Tuple2<scalar, scalar>> profile
    (
        dict.get<List<Tuple2<scalar, scalar>>>("profile")
    );

    if (profile.size() < 2)
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'profile' in " << dict.name() << " has "
            << profile.size() << " stations: at least 2 "
            << "(height above keel, diameter) stations are required." << nl
            << exit(FatalIOError);
    }
    if (mag(profile[0].first()) > SMALL)
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'profile' in " << dict.name() << ": the first station"
            << " is the keel and must have height 0, not "
            << profile[0].first() << "." << nl
            << exit(FatalIOError);
    }
    forAll(profile, i)
    {
        if (!(profile[i].second() > 0))
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'profile' in " << dict.name() << ": station " << i
                << " has diameter " << profile[i].second()
                << "; every diameter must be positive (a closed hull)." << nl
                << exit(FatalIOError);
        }
        if (i > 0 && !(profile[i].first() > profile[i - 1].first()))
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'profile' in " << dict.name() << ": heights must"
                << " increase strictly from the keel up; station " << i
                << " is at " << profile[i].first() << " after "
                << profile[i - 1].first() << "." << nl
                << exit(FatalIOError);
        }
    }
    const scalar depth = profile.last().first();
    if (!(draft_ < depth))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'draft " << draft_ << "' in " << dict.name()
            << " must be less than the hull depth " << depth
            << " (height of the last profile station)." << nl
            << exit(FatalIOError);
    }

    const label nRings = profile.size();
    const scalar zKeel = level_ - draft_;
    const scalar dPhi = constant::mathematical::twoPi/scalar(nFacets);

    // Points: keel centre, the rings (nFacets each), deck centre
    points_.setSize(nRings*nFacets + 2);
    points_[0] = point(position.x(), position.y(), zKeel);
    for (label i = 0; i < nRings; ++i)
    {
        const scalar R = radiusFactor*profile[i].second();
        const scalar z = zKeel + profile[i].first();
        for (label k = 0; k < nFacets; ++k)
        {
            points_[1 + i*nFacets + k] = point
            (
                position.x() + R*Foam::cos(k*dPhi),
                position.y() + R*Foam::sin(k*dPhi),
                z
            );
        }
    }
    const label top = nRings*nFacets + 1;
    points_[top] = point(position.x(), position.y(), zKeel + depth);

    auto ring = [nFacets](label i, label k)
    {
        return 1 + i*nFacets + ((k % nFacets) + nFacets) % nFacets;
    };

    // Faces, outward
    DynamicList<triFace> faces(2*nFacets*nRings);
    for (label k = 0; k < nFacets; ++k)
    {
        faces.append(triFace(0, ring(0, k + 1), ring(0, k)));
    }
    for (label i = 0; i + 1 < nRings; ++i)
    {
        for (label k = 0; k < nFacets; ++k)
        {
            const label a = ring(i, k);
            const label b = ring(i, k + 1);
            const label c = ring(i + 1, k + 1);
            const label d = ring(i + 1, k);
            faces.append(triFace(a, b, c));
            faces.append(triFace(a, c, d));
        }
    }
    for (label k = 0; k < nFacets; ++k)
    {
        faces.append(triFace(top, ring(nRings - 1, k), ring(nRings - 1, k + 1)));
    }
    faces_.transfer(faces);

    // Convex pieces: the radius must be a concave function of height inside
    // a piece (slopes not increasing); a new piece starts where it is not
    DynamicList<label> starts;
    starts.append(0);
    for (label i = 1; i + 1 < nRings; ++i)
    {
        const scalar s0 =
            (profile[i].second() - profile[i - 1].second())
           /(profile[i].first() - profile[i - 1].first());
        const scalar s1 =
            (profile[i + 1].second() - profile[i].second())
           /(profile[i + 1].first() - profile[i].first());
        if (s1 > s0 + 1e-9*(1 + mag(s0)))
        {
            starts.append(i);
        }
    }
    starts.append(nRings - 1);

    pieces_.setSize(starts.size() - 1);
    forAll(pieces_, pi)
    {
        const label i0 = starts[pi];
        const label i1 = starts[pi + 1];
        pointField& pts = pieces_[pi];
        pts.setSize((i1 - i0 + 1)*nFacets);
        label n = 0;
        for (label i = i0; i <= i1; ++i)
        {
            for (label k = 0; k < nFacets; ++k)
            {
                pts[n++] = points_[ring(i, k)];
            }
        }
    }
}


void Foam::floatingStructure::buildBox(const dictionary& dict)
{
    const vector2D position
    (
        dict.lookupOrDefault<vector2D>("position", vector2D(0, 0))
    );
    const scalar L = readPositive(dict, "length");
    const scalar W = readPositive(dict, "width");
    const scalar H = readPositive(dict, "height");
    draft_ = readPositive(dict, "draft");

    if (!(draft_ < H))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'draft " << draft_ << "' in " << dict.name()
            << " must be less than 'height " << H << "'." << nl
            << exit(FatalIOError);
    }

    const scalar z0 = level_ - draft_;
    const scalar x0 = position.x() - 0.5*L;
    const scalar y0 = position.y() - 0.5*W;

    points_.setSize(8);
    for (label i = 0; i < 8; ++i)
    {
        points_[i] = point
        (
            x0 + ((i & 1) ? L : 0),
            y0 + ((i & 2) ? W : 0),
            z0 + ((i & 4) ? H : 0)
        );
    }

    // Quads (outward, counter-clockwise seen from outside) split in two
    const label quads[6][4] =
    {
        {0, 2, 3, 1},   // z-
        {4, 5, 7, 6},   // z+
        {0, 1, 5, 4},   // y-
        {2, 6, 7, 3},   // y+
        {0, 4, 6, 2},   // x-
        {1, 3, 7, 5}    // x+
    };
    faces_.setSize(12);
    for (label q = 0; q < 6; ++q)
    {
        faces_[2*q] = triFace(quads[q][0], quads[q][1], quads[q][2]);
        faces_[2*q + 1] = triFace(quads[q][0], quads[q][2], quads[q][3]);
    }

    pieces_.setSize(1);
    pieces_[0] = points_;
}


void Foam::floatingStructure::checkSurface(const dictionary& dict) const
{
    // Every directed edge once, and its reverse once: closed and consistently
    // oriented
    std::map<std::pair<label, label>, label> count;
    for (const triFace& f : faces_)
    {
        for (label i = 0; i < 3; ++i)
        {
            ++count[std::make_pair(f[i], f[(i + 1) % 3])];
        }
    }
    for (const auto& e : count)
    {
        const auto rev = count.find(std::make_pair(e.first.second, e.first.first));
        if (e.second != 1 || rev == count.end() || rev->second != 1)
        {
            FatalIOErrorInFunction(dict)
                << "The " << type_ << " surface defined in " << dict.name()
                << " does not close (edge " << e.first.first << "-"
                << e.first.second << " is not shared by exactly two"
                << " consistently oriented triangles)." << nl
                << exit(FatalIOError);
        }
    }

    const solidProperties s = solid(points_, faces_);
    if (!(s.volume > 0))
    {
        FatalIOErrorInFunction(dict)
            << "The " << type_ << " surface defined in " << dict.name()
            << " encloses volume " << s.volume << " (must be positive)."
            << nl << exit(FatalIOError);
    }
}


void Foam::floatingStructure::checkPieces(const dictionary& dict) const
{
    // A piece is a stack of rings of equal size; check every vertex lies on
    // the inner side of the plane of every side facet of the stack, and of
    // the two caps
    forAll(pieces_, pi)
    {
        if (type_ == "box")
        {
            continue;   // an axis-aligned box is convex by construction
        }
        const pointField& pts = pieces_[pi];

        const label n = pts.size();
        point c(Zero);
        for (const point& p : pts)
        {
            c += p;
        }
        c /= n;

        scalar size = 0;
        for (const point& p : pts)
        {
            size = max(size, mag(p - c));
        }
        const scalar tol = 1e-9*size;

        // Rings: points sharing the first point's z belong to ring 0
        label perRing = 0;
        while (perRing < n && mag(pts[perRing].z() - pts[0].z()) < tol)
        {
            ++perRing;
        }
        const label nRings = n/max(perRing, label(1));

        for (label i = 0; i + 1 < nRings; ++i)
        {
            for (label k = 0; k < perRing; ++k)
            {
                const point& a = pts[i*perRing + k];
                const point& b = pts[i*perRing + (k + 1) % perRing];
                const point& d = pts[(i + 1)*perRing + k];
                vector nrm = (b - a) ^ (d - a);
                nrm /= mag(nrm) + VSMALL;
                for (const point& p : pts)
                {
                    if (((p - a) & nrm) > tol)
                    {
                        FatalIOErrorInFunction(dict)
                            << "Convex piece " << pi << " of the " << type_
                            << " defined in " << dict.name()
                            << " is not convex (a vertex lies outside"
                            << " facet " << k << " of segment " << i
                            << ")." << nl << exit(FatalIOError);
                    }
                }
            }
        }
    }
}


void Foam::floatingStructure::calcMassProperties(const dictionary& dict)
{
    const submergedPart sub = submerged();
    mass_ = rhoWater_*sub.volume;

    const solidProperties s = solid(points_, faces_);

    centreOfMass_ = dict.lookupOrDefault<point>("centreOfMass", s.centroid);

    if (dict.found("momentOfInertia"))
    {
        momentOfInertia_ = dict.get<diagTensor>("momentOfInertia");
        if
        (
            !(momentOfInertia_.xx() > 0)
         || !(momentOfInertia_.yy() > 0)
         || !(momentOfInertia_.zz() > 0)
        )
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'momentOfInertia' in " << dict.name()
                << " must have three positive principal moments." << nl
                << exit(FatalIOError);
        }
        return;
    }

    // Uniform solid of the closed surface with the hull's mass, about the
    // centre of mass (parallel axes if it was given elsewhere)
    const scalar rhoSolid = mass_/s.volume;
    const vector d = centreOfMass_ - s.centroid;
    const symmTensor S = s.secondMoment + s.volume*sqr(d);
    const symmTensor J = rhoSolid*(tr(S)*symmTensor(I) - S);

    const scalar offDiag = mag(J.xy()) + mag(J.xz()) + mag(J.yz());
    if (offDiag > 1e-6*tr(J))
    {
        FatalIOErrorInFunction(dict)
            << "The inertia of the " << type_ << " defined in "
            << dict.name() << " about " << centreOfMass_
            << " is not diagonal in the global axes: " << J << nl
            << "Give 'momentOfInertia' (principal moments) explicitly."
            << nl << exit(FatalIOError);
    }
    momentOfInertia_ = diagTensor(J.xx(), J.yy(), J.zz());
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::floatingStructure::floatingStructure(const dictionary& dict)
:
    dictName_(dict.name()),
    type_(dict.get<word>("type")),
    rhoWater_(1025),
    level_(0),
    draft_(0),
    points_(),
    faces_(),
    pieces_(),
    mass_(0),
    centreOfMass_(Zero),
    momentOfInertia_(Zero)
{
    if (!shapeTypes.found(type_))
    {
        FatalIOErrorInFunction(dict)
            << "Unknown structure type '" << type_ << "' in " << dict.name()
            << nl << "Valid types: " << shapeTypes << nl
            << exit(FatalIOError);
    }

    using iceDEMChecks::checkEntries;
    checkEntries(dict, "constant/structureDict", {""}, "the top level");

    const dictionary& waterDict = dict.subOrEmptyDict("water");
    checkEntries(waterDict, "constant/structureDict", {"water"}, "water");
    rhoWater_ = waterDict.lookupOrDefault<scalar>("density", 1025);
    level_ = waterDict.lookupOrDefault<scalar>("level", 0);
    if (!(rhoWater_ > 0))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'water { density " << rhoWater_ << "; }' in "
            << dict.name() << " must be positive." << nl
            << exit(FatalIOError);
    }

    if (!dict.isDict(type_))
    {
        FatalIOErrorInFunction(dict)
            << "Missing sub-dictionary '" << type_ << "' in " << dict.name()
            << " (the coefficients of 'type " << type_ << "')." << nl
            << exit(FatalIOError);
    }
    const dictionary& shapeDict = dict.subDict(type_);
    checkEntries
    (
        shapeDict, "constant/structureDict",
        {type_ == "box" ? "box" : "facetedHull"}, type_
    );

    if (type_ == "facetedHull")
    {
        buildFacetedHull(shapeDict);
    }
    else
    {
        buildBox(shapeDict);
    }

    checkSurface(shapeDict);
    checkPieces(shapeDict);
    calcMassProperties(dict);
}


Foam::floatingStructure Foam::floatingStructure::read
(
    const fileName& casePath,
    const word& name
)
{
    const fileName file(casePath/"constant"/name);
    IFstream is(file);
    if (!is.good())
    {
        FatalErrorInFunction
            << "Cannot open the structure dictionary " << file << nl
            << "It defines the hull (see tutorials/iceFloatingFoam)." << nl
            << exit(FatalError);
    }
    dictionary dict(is);
    dict.name() = file;
    return floatingStructure(dict);
}


// * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * * //

void Foam::floatingStructure::writeSTL
(
    const fileName& file,
    const word& solidName
) const
{
    OFstream os(file);
    os.precision(12);
    os  << "solid " << solidName << nl;
    for (const triFace& f : faces_)
    {
        vector n = f.areaNormal(points_);
        n /= mag(n) + VSMALL;
        os  << "  facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << nl
            << "    outer loop" << nl;
        for (label i = 0; i < 3; ++i)
        {
            const point& p = points_[f[i]];
            os  << "      vertex " << p.x() << ' ' << p.y() << ' ' << p.z()
                << nl;
        }
        os  << "    endloop" << nl
            << "  endfacet" << nl;
    }
    os  << "endsolid " << solidName << nl;
}


void Foam::floatingStructure::writeMassProperties(Ostream& os) const
{
    const submergedPart sub = submerged();
    os  << "// Written by createStructure from " << dictName_ << nl
        << "// Do not edit: change the structure dictionary and rerun." << nl
        << "// displaced volume at the draft " << sub.volume << " m3,"
        << " waterplane area " << sub.waterplaneArea << " m2" << nl
        << "// centre of buoyancy " << sub.centroid << nl;
    os.writeEntry("mass", mass_);
    os.writeEntry("centreOfMass", centreOfMass_);
    os.writeEntry("momentOfInertia", momentOfInertia_);
}


void Foam::floatingStructure::writePieces(Ostream& os) const
{
    os  << "// Convex pieces of the " << type_ << " (vertices, design pose),"
        << " written by createStructure from " << dictName_ << nl;
    os.writeEntry("centreOfMass", centreOfMass_);
    os.writeKeyword("pieces") << nl << token::BEGIN_LIST << nl;
    forAll(pieces_, pi)
    {
        os  << pieces_[pi] << nl;
    }
    os  << token::END_LIST << token::END_STATEMENT << nl;
}


void Foam::floatingStructure::report(Ostream& os) const
{
    const submergedPart sub = submerged();
    const solidProperties s = solid(points_, faces_);

    os  << "Structure " << type_ << " from " << dictName_ << nl
        << "    surface: " << points_.size() << " points, "
        << faces_.size() << " triangles, closed volume " << s.volume
        << " m3" << nl
        << "    convex pieces: " << pieces_.size() << nl
        << "    water: density " << rhoWater_ << " kg/m3, level " << level_
        << " m, draft " << draft_ << " m" << nl
        << "    displaced volume " << sub.volume << " m3, centre of buoyancy "
        << sub.centroid << nl
        << "    waterplane area " << sub.waterplaneArea << " m2" << nl
        << "    mass " << mass_ << " kg (= density x displaced volume)" << nl
        << "    centre of mass " << centreOfMass_ << nl
        << "    principal moments of inertia " << momentOfInertia_ << nl;
}


// ************************************************************************* //
