/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "iceDEMOutput.H"
#include "dictionaryChecks.H"
#include "postProcessingFile.H"

#include "OSspecific.H"
#include "Pstream.H"

#include <cstring>
#include <fstream>
#include <sstream>

using namespace Foam::iceDEMChecks;

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * //

namespace
{

//- Big-endian copy of a value (legacy VTK binary)
template<class T>
void writeBE(std::ostream& os, T value)
{
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    const unsigned one = 1;
    if (*reinterpret_cast<const unsigned char*>(&one) == 1)
    {
        for (unsigned k = 0; k < sizeof(T)/2; ++k)
        {
            std::swap(bytes[k], bytes[sizeof(T) - 1 - k]);
        }
    }
    os.write(reinterpret_cast<const char*>(bytes), sizeof(T));
}


//- Values to a legacy VTK file, binary or ascii (one per line for ascii
//  vectors, as groups of 'perLine')
template<class T>
void writeValues
(
    std::ostream& os,
    const std::vector<T>& values,
    bool binary,
    int perLine
)
{
    if (binary)
    {
        for (const T& v : values)
        {
            writeBE(os, v);
        }
        os << '\n';
    }
    else
    {
        for (size_t k = 0; k < values.size(); ++k)
        {
            os << values[k] << ((k + 1) % perLine ? ' ' : '\n');
        }
        if (values.size() % perLine)
        {
            os << '\n';
        }
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * //

Foam::iceDEMOutput::iceDEMOutput(const iceDEMCase& demCase)
:
    case_(demCase),
    dir_
    (
        demCase.time().globalPath()/"postProcessing"/"iceDEM"
       /demCase.time().timeName()
    ),
    precision_(12),
    vtk_(true),
    surface_(::iceDEM::SurfaceKind::dilated),
    resolution_(3),
    binary_(true),
    lastEnergyTime_(-GREAT),
    lastBodiesTime_(-GREAT)
{
    const dictionary& d = demCase.outputDict();
    if (demCase.properties().isDict("output"))
    {
        checkEntries(d, "constant/iceDEMProperties", {"output"}, "output");
    }

    precision_ = labelInRange(d, "precision", 4, 17, 12);
    vtk_ = d.getOrDefault<bool>("vtk", true);
    const word surf =
        selectName
        (
            d, "vtkSurface", wordList({"dilated", "outer", "core"}), "dilated"
        );
    surface_ =
        surf == "outer" ? ::iceDEM::SurfaceKind::outer
      : surf == "core" ? ::iceDEM::SurfaceKind::core
      : ::iceDEM::SurfaceKind::dilated;
    resolution_ = labelInRange(d, "vtkResolution", 1, 16, 3);
    binary_ =
        selectName
        (
            d, "vtkFormat", wordList({"binary", "ascii"}), "binary"
        ) == "binary";

    if (Pstream::master())
    {
        mkDir(dir_);

        bodiesFile_.reset
        (
            new OFstream(newOutputFile(demCase.time(), dir_, "bodies.dat"))
        );
        bodiesFile_().precision(precision_);
        bodiesFile_()
            << "# time id x y z vx vy vz wx wy wz qw qx qy qz" << endl;

        energyFile_.reset
        (
            new OFstream(newOutputFile(demCase.time(), dir_, "energy.dat"))
        );
        energyFile_().precision(precision_);
        energyFile_()
            << "# time kinetic gravitational elastic contacts contactPairs"
            << endl;

        if (vtk_)
        {
            mkDir(dir_/"VTK");
        }
    }
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void Foam::iceDEMOutput::writeBodies()
{
    const ::iceDEM::World& w = case_.world();
    const scalar t = case_.time().value();
    OFstream& os = bodiesFile_();

    const auto& bodies = w.bodies();
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        const ::iceDEM::Body& b = bodies[i];
        const ::iceDEM::Vec3 omega = b.omega();
        const ::iceDEM::Quat q =
            b.q*w.shapeOf(int(i)).principalToInput().conjugate();

        os  << t << ' ' << b.id << ' '
            << b.x.x() << ' ' << b.x.y() << ' ' << b.x.z() << ' '
            << b.v.x() << ' ' << b.v.y() << ' ' << b.v.z() << ' '
            << omega.x() << ' ' << omega.y() << ' ' << omega.z() << ' '
            << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z()
            << nl;
    }
    os.flush();
}


void Foam::iceDEMOutput::writeEnergy()
{
    const ::iceDEM::World& w = case_.world();
    const ::iceDEM::Energies e = w.energies();

    energyFile_()
        << case_.time().value() << ' '
        << e.kinetic << ' ' << e.gravitational << ' ' << e.elastic << ' '
        << w.contactCount() << ' ' << w.contactPairCount() << endl;
}


void Foam::iceDEMOutput::writeVTK()
{
    const ::iceDEM::World& w = case_.world();
    const Time& runTime = case_.time();
    const auto& bodies = w.bodies();

    if (surfaces_.size() != w.shapes().size())
    {
        surfaces_.clear();
        for (const ::iceDEM::DilatedShape& s : w.shapes())
        {
            surfaces_.push_back
            (
                ::iceDEM::dilatedSurface(s, surface_, resolution_)
            );
        }
    }

    std::vector<double> points;
    std::vector<int> polys;
    std::vector<int> ids;
    std::vector<double> vel, omg;
    int nPolys = 0;

    for (size_t i = 0; i < bodies.size(); ++i)
    {
        const ::iceDEM::Body& b = bodies[i];
        const ::iceDEM::SurfaceMesh& m = surfaces_[b.shape];
        const ::iceDEM::Mat3 R = b.rotation();
        const ::iceDEM::Vec3 omega = b.omega();

        const int base = int(points.size()/3);
        for (const ::iceDEM::Vec3& p : m.points)
        {
            const ::iceDEM::Vec3 x = b.x + R*p;
            points.push_back(x.x());
            points.push_back(x.y());
            points.push_back(x.z());
        }
        for (size_t k = 0; k < m.polygons.size();)
        {
            const int n = m.polygons[k];
            polys.push_back(n);
            for (int j = 1; j <= n; ++j)
            {
                polys.push_back(base + m.polygons[k + j]);
            }
            k += n + 1;
        }
        nPolys += m.nPolygons;
        for (int c = 0; c < m.nPolygons; ++c)
        {
            ids.push_back(b.id);
            for (int d = 0; d < 3; ++d)
            {
                vel.push_back(b.v[d]);
                omg.push_back(omega[d]);
            }
        }
    }

    const word name("bodies_" + Foam::name(runTime.timeIndex()) + ".vtk");
    const fileName file(dir_/"VTK"/name);

    std::ofstream os(file, binary_ ? std::ios::binary : std::ios::out);
    os.precision(precision_);
    os  << "# vtk DataFile Version 3.0\n"
        << "iceDEM bodies, time " << runTime.timeName() << '\n'
        << (binary_ ? "BINARY\n" : "ASCII\n")
        << "DATASET POLYDATA\n"
        << "FIELD FieldData 1\nTimeValue 1 1 double\n";
    writeValues(os, std::vector<double>{runTime.value()}, binary_, 1);

    os  << "POINTS " << points.size()/3 << " double\n";
    writeValues(os, points, binary_, 3);

    os  << "POLYGONS " << nPolys << ' ' << polys.size() << '\n';
    writeValues(os, polys, binary_, 16);

    os  << "CELL_DATA " << nPolys << '\n'
        << "SCALARS id int 1\nLOOKUP_TABLE default\n";
    writeValues(os, ids, binary_, 16);
    os  << "VECTORS velocity double\n";
    writeValues(os, vel, binary_, 3);
    os  << "VECTORS omega double\n";
    writeValues(os, omg, binary_, 3);

    if (!os.good())
    {
        FatalErrorInFunction
            << "Cannot write " << file << exit(FatalError);
    }

    // The series file, rewritten
    series_.append(Tuple2<word, scalar>(name, runTime.value()));

    std::ostringstream json;
    json.precision(precision_);
    json<< "{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n";
    forAll(series_, k)
    {
        json<< "    { \"name\" : \"" << series_[k].first()
            << "\", \"time\" : " << series_[k].second() << " }"
            << (k + 1 < series_.size() ? ",\n" : "\n");
    }
    json<< "  ]\n}\n";

    std::ofstream ser(dir_/"VTK"/"bodies.vtk.series");
    ser << json.str();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void Foam::iceDEMOutput::write(bool force)
{
    if (!Pstream::master())
    {
        return;
    }

    const Time& runTime = case_.time();
    const scalar t = runTime.value();

    if (t != lastEnergyTime_)
    {
        writeEnergy();
        lastEnergyTime_ = t;
    }

    if ((force || runTime.writeTime()) && t != lastBodiesTime_)
    {
        writeBodies();
        if (vtk_)
        {
            writeVTK();
        }
        lastBodiesTime_ = t;
    }
}


// ************************************************************************* //
