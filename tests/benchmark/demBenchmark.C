/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

Application
    demBenchmark

Description
    Speed benchmark of the DEM core alone (no flow solver), issues 7 and 16.
    Built and run by tests/benchmark/Allrun; see tests/benchmark/README.md.

    Fields (same seed every run):
      drifting    N Voronoi prism floes (Lloyd-relaxed), mean equivalent
                  diameter 10 m, thickness 1 m, r = 0.1 m, 70 % coverage,
                  random in-plane velocity 0.5 m/s and spin |w_z| <= 0.05
                  rad/s, four fixed walls, gravity off;
      compacting  2000 floes at 90 % pushed along +x by a constant force per
                  unit area against a fixed 48-sided vertical cylinder and
                  the walls. A compaction phase (not timed) brings the field
                  to persistent contact; its end state is cached on disk and
                  every repetition restarts from it;
      floating    the drifting field of -floatN floes (the real workload,
                  issue 16) at its draft with gravity, buoyancy, empirical
                  drag and floe damping at the tutorials' defaults (water
                  1025 kg/m3 at z = 0, C_f = 1, C_s = 0.004, subdivision 2,
                  a 0.3 m/s current along x; damping 0.1 of critical in
                  heave, roll and pitch; no wind, as the tutorials but
                  kullukPack; -wind U adds kullukPack's, U m/s along x;
                  -dragIntegration and -windIntegration choose the
                  quadratures).
    Material: ice, density 920 kg/m3, E = 1 GPa, nu = 0.33; friction 0.2,
    restitution 0.3; DEM step 1 ms.

    Per configuration (field, N, threads) it prints
      N=<floes> threads=<t> steps=<s> wall_s=<w> floe_steps_per_s=<x> contacts_per_step=<c>
    with the median wall time of the repetitions (only the world.step()
    calls are timed), and comment lines (#) with the repetitions, memory
    and the thread-invariance check:
      threads_identical=yes|no   (final states of all thread counts equal
                                  bit for bit)

Usage
    demBenchmark [options]
      -fields drift,compact,float  fields to run (default all three)
      -N 500,2000,8000,20000  drifting field sizes
      -compactN 2000          compacting field size
      -floatN 2000            floating field size
      -dragIntegration I      floating: drag integration exact | sampled
                              (default: the core's default)
      -wind U                 floating: wind U m/s along x at the defaults
                              of doc/caseFiles.md (kullukPack: 15.28;
                              default 0: no wind, the tutorials' default)
      -windIntegration I      floating: wind integration exact | sampled
                              (default: the core's default)
      -floeDamping on|off     floating: floe damping (default on, as in
                              both solvers wherever there is water)
      -bodyForceInterval k    floating: the multi-rate step, body forces
                              every k-th step (default 1; doc/caseFiles.md)
      -hydroAccuracy          floating: instead of timing, each floe's drag,
                              buoyancy and (with -wind) wind by every
                              shortcut against its reference (after
                              -warmup T), rms and max
      -threads 1,2            thread counts
      -steps S                steps per repetition, every field (default:
                              drifting and floating -duration,
                              compacting -compactSteps)
      -duration T             drifting and floating: simulated seconds per
                              repetition (default 15, the open peer's run)
      -compactSteps S         compacting steps per repetition (default 300)
      -reps R                 repetitions, median reported (default 3)
      -warmup T               drifting: simulated seconds run before the
                              timed window (not timed; default 0)
      -compactTime T          compacting: simulated seconds of the
                              compaction phase (default 30)
      -push P                 compacting: push per unit area [Pa] (default 50)
      -skin S                 neighbour-list skin [m] (default: the core's,
                              the dilation radius)
      -featureSkin S          skin of the feature-pair lists [m] (default:
                              the core's, r/2; 0: no lists)
      -lloyd K                Lloyd iterations (default 5)
      -seed K                 field and velocity seed (default 2026)
      -cache DIR              where the compacted state is kept (default .)
      -callgrind              collect callgrind costs of the stepping loop
                              only (run under valgrind --collect-atstart=no)
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "contact/NeighbourList.H"
#include "field/VoronoiField.H"
#include "field/IceFloe.H"
#include "geometry/DilatedShape.H"
#include "hydro/Buoyancy.H"
#include "hydro/Drag.H"
#include "hydro/FloeDamping.H"
#include "hydro/WaterFrame.H"
#include "hydro/Wind.H"
#include "hydro/FlowVelocity.H"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <limits>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <malloc.h>
#include <omp.h>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define HAVE_CALLGRIND 1
#else
#define HAVE_CALLGRIND 0
#endif

using namespace iceDEM;

namespace
{

// * * * * * * * * * * * * * * * Small helpers * * * * * * * * * * * * * * //

//- The benchmark's own deterministic random numbers (splitmix64)
class SplitMix
{
    std::uint64_t s_;

public:

    explicit SplitMix(std::uint64_t seed) : s_(seed) {}

    std::uint64_t next()
    {
        std::uint64_t z = (s_ += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30))*0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27))*0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }

    //- Uniform in [0, 1)
    double uniform01() { return double(next() >> 11)*0x1.0p-53; }

    double uniform(double a, double b) { return a + (b - a)*uniform01(); }
};


//- CPU time of the process (all threads) [s]
double processCpuSeconds()
{
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9*ts.tv_nsec;
}


//- A field of /proc/self/status in kB (VmRSS, VmHWM)
long procStatusKB(const char* key)
{
    std::ifstream in("/proc/self/status");
    std::string line;
    const std::size_t n = std::strlen(key);
    while (std::getline(in, line))
    {
        if (line.compare(0, n, key) == 0 && line.size() > n && line[n] == ':')
        {
            return std::atol(line.c_str() + n + 1);
        }
    }
    return -1;
}


//- Resident memory after returning the allocator's free pages [kB]
long residentKB()
{
    malloc_trim(0);
    return procStatusKB("VmRSS");
}


//- FNV-1a over the bytes of n doubles
void mixHash(std::uint64_t& h, const double* p, int n)
{
    const unsigned char* b = reinterpret_cast<const unsigned char*>(p);
    for (std::size_t k = 0; k < n*sizeof(double); ++k)
    {
        h ^= b[k];
        h *= 1099511628211ULL;
    }
}

constexpr std::uint64_t hashSeed = 1469598103934665603ULL;

//- FNV-1a over the bytes of the bodies' state (x, q, v, L)
std::uint64_t stateHash(const World& w)
{
    std::uint64_t h = hashSeed;
    for (const Body& b : w.bodies())
    {
        mixHash(h, b.x.data(), 3);
        mixHash(h, b.q.coeffs().data(), 4);
        mixHash(h, b.v.data(), 3);
        mixHash(h, b.L.data(), 3);
    }
    return h;
}


//- The floes' outlines in their order: a cached compaction belongs to one
//  field, numbering included
std::uint64_t fieldHash(const std::vector<Floe>& floes)
{
    std::uint64_t h = hashSeed;
    for (const Floe& f : floes)
    {
        for (const Vec2& p : f.outline) mixHash(h, p.data(), 2);
    }
    return h;
}


[[noreturn]] void usage(const char* msg);


//- The option's value as a whole integer >= least, else the usage line
//  naming the option (atoi took '0' and 'abc' alike, as 0)
int intOption(const std::string& opt, const std::string& text, long least)
{
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0 || v < least
     || v > std::numeric_limits<int>::max())
    {
        usage((opt + " '" + text + "': an integer >= " + std::to_string(least)
            + " is needed").c_str());
    }
    return int(v);
}


//- The option's value as a finite number >= least (> least: above; least
//  -infinity: any finite number)
double realOption
(
    const std::string& opt,
    const std::string& text,
    double least,
    bool above = false
)
{
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if
    (
        text.empty() || *end != '\0' || errno != 0 || !std::isfinite(v)
     || v < least || (above && !(v > least))
    )
    {
        std::ostringstream msg;
        msg << opt << " '" << text << "': a finite number";
        if (std::isfinite(least))
        {
            msg << (above ? " > " : " >= ") << least;
        }
        msg << " is needed";
        usage(msg.str().c_str());
    }
    return v;
}


//- A comma-separated list of integers >= least, at least one
std::vector<int> intListOption
(
    const std::string& opt,
    const std::string& s,
    long least
)
{
    std::vector<int> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ','))
    {
        out.push_back(intOption(opt, item, least));
    }
    if (out.empty()) usage((opt + ": an empty list").c_str());
    return out;
}


double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n/2] : 0.5*(v[n/2 - 1] + v[n/2]);
}


// * * * * * * * * * * * * * * * * Options * * * * * * * * * * * * * * * * //

struct Options
{
    bool drift = true;
    bool compact = true;
    bool floating = true;
    int floatN = 2000;
    std::string dragIntegration;    //!< empty: the core's default
    double wind = 0;                //!< floating: wind along x [m/s]; 0: none
    std::string windIntegration;    //!< empty: the core's default
    bool floeDamping = true;        //!< floating: floe damping on
    int bodyForceInterval = 1;      //!< floating: the multi-rate step's k
    bool hydroAccuracy = false;     //!< floating: accuracy of the shortcuts
    std::vector<int> sizes{500, 2000, 8000, 20000};
    int compactN = 2000;
    std::vector<int> threads{1, 2};
    int steps = 0;                  //!< 0: from the work per repetition
    double duration = 15;           //!< drifting, floating: simulated s
    int compactSteps = 300;
    int reps = 3;
    double warmup = 0;
    double compactTime = 30;
    double push = 50;
    double skin = -1;
    double featureSkin = -1;
    int lloyd = 5;
    std::uint64_t seed = 2026;
    std::string cache = ".";
    bool callgrind = false;
};


[[noreturn]] void usage(const char* msg)
{
    std::cerr << "demBenchmark: " << msg << "\n"
        "usage: demBenchmark [-fields drift,compact,float] [-N 500,2000,...]"
        " [-compactN n] [-floatN n] [-dragIntegration exact|sampled] [-wind U] [-windIntegration exact|sampled] [-floeDamping on|off] [-bodyForceInterval k] [-hydroAccuracy] [-threads 1,2] [-steps s] [-compactSteps s] [-reps r] [-warmup T]"
        " [-duration T] [-compactTime T] [-push P] [-skin S] [-lloyd K] [-seed K]"
        " [-cache DIR] [-callgrind]\n";
    std::exit(2);
}


Options parseOptions(int argc, char* argv[])
{
    Options o;
    for (int a = 1; a < argc; ++a)
    {
        const std::string opt = argv[a];
        auto value = [&]() -> std::string
        {
            if (a + 1 >= argc) usage(("missing value of " + opt).c_str());
            return argv[++a];
        };
        if (opt == "-fields")
        {
            const std::string v = value();
            o.drift = v.find("drift") != std::string::npos;
            o.compact = v.find("compact") != std::string::npos;
            o.floating = v.find("float") != std::string::npos;
            if (!o.drift && !o.compact && !o.floating)
            {
                usage("-fields: drift, compact and/or float");
            }
        }
        else if (opt == "-N") o.sizes = intListOption(opt, value(), 1);
        else if (opt == "-compactN") o.compactN = intOption(opt, value(), 1);
        else if (opt == "-floatN") o.floatN = intOption(opt, value(), 1);
        else if (opt == "-dragIntegration") o.dragIntegration = value();
        else if (opt == "-wind") o.wind = realOption(opt, value(), -std::numeric_limits<double>::infinity());
        else if (opt == "-windIntegration") o.windIntegration = value();
        else if (opt == "-floeDamping")
        {
            const std::string v = value();
            if (v != "on" && v != "off") usage("-floeDamping: on or off");
            o.floeDamping = v == "on";
        }
        else if (opt == "-bodyForceInterval") o.bodyForceInterval = intOption(opt, value(), 1);
        else if (opt == "-threads") o.threads = intListOption(opt, value(), 1);
        else if (opt == "-steps") o.steps = intOption(opt, value(), 0);
        else if (opt == "-duration") o.duration = realOption(opt, value(), 0, true);
        else if (opt == "-compactSteps") o.compactSteps = intOption(opt, value(), 1);
        else if (opt == "-h" || opt == "-help") usage("help");
        else if (opt == "-reps") o.reps = intOption(opt, value(), 1);
        else if (opt == "-warmup") o.warmup = realOption(opt, value(), 0);
        else if (opt == "-compactTime") o.compactTime = realOption(opt, value(), 0, true);
        else if (opt == "-push") o.push = realOption(opt, value(), 0);
        else if (opt == "-skin") o.skin = realOption(opt, value(), -std::numeric_limits<double>::infinity());
        else if (opt == "-featureSkin") o.featureSkin = realOption(opt, value(), -std::numeric_limits<double>::infinity());
        else if (opt == "-lloyd") o.lloyd = intOption(opt, value(), 0);
        else if (opt == "-seed")
        {
            const std::string v = value();
            char* end = nullptr;
            errno = 0;
            o.seed = std::strtoull(v.c_str(), &end, 10);
            if (v.empty() || v[0] == '-' || *end != '\0' || errno != 0)
            {
                usage(("-seed '" + v + "': an integer >= 0 is needed").c_str());
            }
        }
        else if (opt == "-cache") o.cache = value();
        else if (opt == "-callgrind") o.callgrind = true;
        else if (opt == "-hydroAccuracy") o.hydroAccuracy = true;
        else usage(("unknown option " + opt).c_str());
    }
    return o;
}


// * * * * * * * * * * * * * * * * * Fields * * * * * * * * * * * * * * * * //

constexpr double kDiameter = 10;        //!< mean equivalent diameter [m]
constexpr double kThickness = 1;        //!< [m]
constexpr double kRadius = 0.1;         //!< dilation radius [m]
constexpr double kDensity = 920;        //!< [kg/m3]
constexpr double kSpeed = 0.5;          //!< drifting speed [m/s]
constexpr double kSpin = 0.05;          //!< largest spin [rad/s]
constexpr int kCylinderSides = 48;
constexpr double kTimeStep = 1e-3;      //!< DEM step [s]
constexpr double kGravity = 9.81;       //!< floating field [m/s2]
constexpr double kWaterDensity = 1025;  //!< floating field [kg/m3]
constexpr double kCurrent = 0.3;        //!< floating field, along x [m/s]

//- A generated field: floes (true outlines) + initial velocities + box
struct Field
{
    std::string name;
    std::vector<Floe> floes;
    std::vector<Vec3> velocity, omega;
    double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
    bool cylinder = false;
    Vec2 cylinderCentre = Vec2::Zero();
    double cylinderRadius = 0;
    double push = 0;                    //!< Pa, along +x
    bool floating = false;              //!< gravity, buoyancy and drag
    int nCells = 0;
};


Field makeField
(
    const std::string& name,
    int n,
    double concentration,
    bool cylinder,
    const Options& o
)
{
    Field f;
    f.name = name;
    const double area = M_PI*0.25*kDiameter*kDiameter;
    const double L = std::sqrt(n*area/concentration);
    f.xmin = 0; f.xmax = L; f.ymin = 0; f.ymax = L;

    VoronoiFieldSettings s;
    s.xmin = f.xmin; s.xmax = f.xmax; s.ymin = f.ymin; s.ymax = f.ymax;
    s.nFloes = n;
    s.concentration = concentration;
    s.thickness.distribution = ThicknessSettings::Distribution::constant;
    s.thickness.value = kThickness;
    s.radius = kRadius;
    s.seed = o.seed;
    s.lloydIterations = o.lloyd;
    s.iceDensity = kDensity;

    if (cylinder)
    {
        // A structure about five floes across, two thirds down the push
        f.cylinder = true;
        f.cylinderRadius = 25;
        f.cylinderCentre = Vec2(f.xmin + 0.67*L, 0.5*(f.ymin + f.ymax));
        f.push = o.push;
        ExclusionZone z;
        z.name = "cylinder";
        z.type = ExclusionZone::Type::circle;
        z.centre = f.cylinderCentre;
        z.radius = f.cylinderRadius + 0.5;
        s.exclusionZones.push_back(z);
    }

    VoronoiFieldReport report;
    f.floes = generateVoronoiField(s, report);
    f.nCells = report.nCells;

    // Initial velocities: the benchmark's own generator, in floe order
    SplitMix rng(o.seed ^ 0x5eedf00dULL);
    for (std::size_t i = 0; i < f.floes.size(); ++i)
    {
        const double angle = rng.uniform(0, 2*M_PI);
        const double spin = rng.uniform(-kSpin, kSpin);
        if (cylinder)
        {
            // Drift with the push, a little scatter across it
            f.velocity.emplace_back(kSpeed, 0.1*kSpeed*std::sin(angle), 0);
        }
        else
        {
            f.velocity.emplace_back(kSpeed*std::cos(angle), kSpeed*std::sin(angle), 0);
        }
        f.omega.emplace_back(0, 0, spin);
    }
    return f;
}


//- Constant force per unit floe area along +x (free bodies only)
class PushModel : public BodyForceModel
{
    std::vector<Vec3> force_;

public:

    PushModel(const World& w, double pressure)
    {
        for (const Body& b : w.bodies())
        {
            const double footprint =
                w.shapes()[b.shape].volume()/kThickness;
            force_.push_back
            (
                b.isFree() ? Vec3(pressure*footprint, 0, 0) : Vec3::Zero()
            );
        }
    }

    const char* name() const override { return "push"; }

    void addForces
    (
        const World&,
        int begin,
        int end,
        Vec3* force,
        Vec3*
    ) const override
    {
        for (int i = begin; i < end; ++i)
        {
            force[i] += force_[i];
        }
    }
};


//- Saved state of a world (restart)
struct Snapshot
{
    bool valid = false;
    double time = 0;
    std::vector<Body> bodies;
    std::vector<ContactRecord> records;
};


std::unique_ptr<World> buildWorld
(
    const Field& f,
    const Options& o,
    const Snapshot* snap
)
{
    WorldSettings ws;
    ws.timeStep = kTimeStep;
    ws.gravity = f.floating ? Vec3(0, 0, -kGravity) : Vec3::Zero();
    ws.skin = o.skin;
    ws.featureSkin = o.featureSkin;
    ws.bodyForceInterval = o.bodyForceInterval;
    auto world = std::make_unique<World>(ws);

    Material ice;
    ice.name = "ice";
    ice.density = kDensity;
    ice.youngsModulus = 1e9;
    ice.poissonsRatio = 0.33;
    const int mat = world->addMaterial(ice);
    PairProperties pp;
    pp.friction = 0.2;
    pp.restitution = 0.3;
    world->setPairProperties(mat, mat, pp);

    for (std::size_t i = 0; i < f.floes.size(); ++i)
    {
        const int shape = world->addShape(DilatedShape(f.floes[i].core(), kRadius));
        world->addBody
        (
            shape, mat, Vec3::Zero(), Quat::Identity(),
            f.velocity[i], f.omega[i], BodyMotion::free
        );
    }

    if (f.cylinder)
    {
        std::vector<Vec2> polygon;
        const double rc = f.cylinderRadius - kRadius;
        for (int k = 0; k < kCylinderSides; ++k)
        {
            const double a = 2*M_PI*k/kCylinderSides;
            polygon.push_back(f.cylinderCentre + rc*Vec2(std::cos(a), std::sin(a)));
        }
        const ConvexPolyhedron core = ConvexPolyhedron::prism(polygon, -5 + kRadius, 10 - 2*kRadius);
        const int shape = world->addShape(DilatedShape(core, kRadius));
        world->addBody
        (
            shape, mat, Vec3::Zero(), Quat::Identity(),
            Vec3::Zero(), Vec3::Zero(), BodyMotion::fixed
        );
    }

    auto wall = [&](const char* name, const Vec3& p, const Vec3& n)
    {
        Wall w;
        w.name = name;
        w.point = p;
        w.normal = n;
        w.material = mat;
        world->addWall(w);
    };
    wall("xmin", Vec3(f.xmin, 0, 0), Vec3::UnitX());
    wall("xmax", Vec3(f.xmax, 0, 0), -Vec3::UnitX());
    wall("ymin", Vec3(0, f.ymin, 0), Vec3::UnitY());
    wall("ymax", Vec3(0, f.ymax, 0), -Vec3::UnitY());

    if (f.push != 0)
    {
        world->addForceModel(std::make_shared<PushModel>(*world, f.push));
    }

    if (f.floating)
    {
        // The water of the tutorials (doc/caseFiles.md defaults): buoyancy,
        // empirical drag in a uniform current, floe damping (on wherever
        // there is water) and, on request, a uniform wind (kullukPack's)
        const WaterSettings water{kWaterDensity, 0};
        DragSettings drag;
        if (!o.dragIntegration.empty())
        {
            drag.integration = dragIntegrationFromName(o.dragIntegration);
        }
        world->addForceModel(std::make_shared<Buoyancy>(water));
        world->addForceModel
        (
            std::make_shared<Drag>
            (
                water, drag,
                std::make_shared<UniformCurrent>(Vec3(kCurrent, 0, 0))
            )
        );
        if (o.floeDamping)
        {
            world->addForceModel
            (
                std::make_shared<FloeDamping>(water, FloeDampingSettings())
            );
        }
        if (o.wind != 0)
        {
            WindSettings ws;
            if (!o.windIntegration.empty())
            {
                ws.integration = dragIntegrationFromName(o.windIntegration);
            }
            world->addForceModel
            (
                std::make_shared<Wind>
                (
                    water, ws, WindHistory(Vec3(o.wind, 0, 0))
                )
            );
        }
    }

    if (snap && snap->valid)
    {
        if (snap->bodies.size() != world->bodies().size())
        {
            throw Error("the saved state does not match the field");
        }
        world->bodies() = snap->bodies;
        world->setTime(snap->time);
        world->setContactRecords(snap->records);
        world->initialise(true);
    }
    else
    {
        world->initialise();
    }
    return world;
}


Snapshot takeSnapshot(const World& w)
{
    Snapshot s;
    s.valid = true;
    s.time = w.time();
    s.bodies = w.bodies();
    s.records = w.contactRecords();
    return s;
}


// Binary cache of a snapshot (the compacting field's compacted state)

bool writeSnapshot(const std::string& file, const Snapshot& s)
{
    std::ofstream out(file, std::ios::binary);
    if (!out) return false;
    const std::uint64_t nb = s.bodies.size(), nr = s.records.size();
    out.write(reinterpret_cast<const char*>(&s.time), sizeof(s.time));
    out.write(reinterpret_cast<const char*>(&nb), sizeof(nb));
    out.write(reinterpret_cast<const char*>(s.bodies.data()), nb*sizeof(Body));
    out.write(reinterpret_cast<const char*>(&nr), sizeof(nr));
    out.write(reinterpret_cast<const char*>(s.records.data()), nr*sizeof(ContactRecord));
    return bool(out);
}


bool readSnapshot(const std::string& file, Snapshot& s)
{
    std::ifstream in(file, std::ios::binary);
    if (!in) return false;
    std::uint64_t nb = 0, nr = 0;
    in.read(reinterpret_cast<char*>(&s.time), sizeof(s.time));
    in.read(reinterpret_cast<char*>(&nb), sizeof(nb));
    if (!in || nb > 10000000) return false;
    s.bodies.resize(nb);
    in.read(reinterpret_cast<char*>(s.bodies.data()), nb*sizeof(Body));
    in.read(reinterpret_cast<char*>(&nr), sizeof(nr));
    if (!in || nr > 100000000) return false;
    s.records.resize(nr);
    in.read(reinterpret_cast<char*>(s.records.data()), nr*sizeof(ContactRecord));
    s.valid = bool(in);
    return s.valid;
}


// * * * * * * * * * * * * * * * * Measuring * * * * * * * * * * * * * * * //

struct RunResult
{
    double wall = 0;                //!< seconds in world.step()
    //- CPU seconds of the process in world.step() (all threads; with
    //  OMP_WAIT_POLICY=PASSIVE waiting threads sleep): on a loaded machine
    //  a steadier measure of the work than the wall time
    double cpu = 0;
    double contactsPerStep = 0;     //!< mean contactPairCount()
    double searchedPerStep = 0;     //!< mean searchedPairCount()
    double candidatePairs = 0;      //!< neighbour-list pairs at the end
    std::uint64_t hash = 0;
    long rebuilds = 0;
    double rssPerFloe = 0;          //!< bytes, world built and stepped
    long peakKB = 0;
};


RunResult runOnce
(
    const Field& f,
    const Options& o,
    const Snapshot* snap,
    int steps,
    bool measureMemory
)
{
    RunResult r;
    const long before = measureMemory ? residentKB() : 0;

    std::unique_ptr<World> world = buildWorld(f, o, snap);
    const long buildsBefore = world->neighbourListBuilds();

    long contactSum = 0, searchedSum = 0;
    double wall = 0;
    double cpu = 0;
#if HAVE_CALLGRIND
    if (o.callgrind)
    {
        CALLGRIND_START_INSTRUMENTATION;
        CALLGRIND_TOGGLE_COLLECT;
    }
#endif
    for (int s = 0; s < steps; ++s)
    {
        const double c0 = processCpuSeconds();
        const auto t0 = std::chrono::steady_clock::now();
        world->step();
        const auto t1 = std::chrono::steady_clock::now();
        wall += std::chrono::duration<double>(t1 - t0).count();
        cpu += processCpuSeconds() - c0;
        contactSum += world->contactPairCount();
        searchedSum += world->searchedPairCount();
    }
#if HAVE_CALLGRIND
    if (o.callgrind)
    {
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_STOP_INSTRUMENTATION;
    }
#endif
    world->checkFinite();

    r.wall = wall;
    r.cpu = cpu;
    r.contactsPerStep = steps > 0 ? double(contactSum)/steps : 0;
    r.searchedPerStep = steps > 0 ? double(searchedSum)/steps : 0;
    r.candidatePairs = world->neighbourList().pairs().size();
    r.hash = stateHash(*world);
    r.rebuilds = world->neighbourListBuilds() - buildsBefore;
    if (measureMemory)
    {
        const long after = residentKB();
        r.rssPerFloe = 1024.0*(after - before)/double(f.floes.size());
        r.peakKB = procStatusKB("VmHWM");

        // Breakdown: what the core stores per body and per candidate pair
        // (vector capacities as the core reports them; allocator overhead,
        // about 16 B per heap block, excluded)
        const double pairs = r.candidatePairs;
        // Per shape: the object, its own heap (the core's vertices and face
        // planes, edge lengths, a stored outer polyhedron); the topologies
        // are shared between shapes: each distinct one counted once
        double shapeBytes = 0;
        std::set<const PolyhedronTopology*> topologies;
        double topologyBytes = 0;
        for (const DilatedShape& S : world->shapes())
        {
            shapeBytes += sizeof(DilatedShape) + S.heapBytes();
            PolyhedronBuffer buffer;
            for (const PolyhedronTopology* T : {&S.core().topology(), &S.outer(buffer).topology()})
            {
                if (topologies.insert(T).second)
                {
                    topologyBytes += T->heapBytes();
                }
            }
        }
        const double n = world->bodies().size();
        const double nF = f.floes.size();
        const double nv = world->shapes()[0].core().vertices().size();
        std::printf
        (
            "# memory N=%zu rss_per_floe_B=%.0f peak_rss_MB=%.1f"
            " | per floe: Body %zu B, shape %.0f B (sizeof %zu + heap: core"
            " vertices and face planes, edge lengths, stored outer polyhedra;"
            " + %zu shared"
            " topologies %.0f B), world vertices"
            " and omega %.0f B; contact state %.0f B per floe"
            " (%.2f candidate pairs per floe x ContactPair %zu B + pools:"
            " StoredContact %zu B per contact, feature lists %zu B + %zu B per entry)\n",
            f.floes.size(), r.rssPerFloe, r.peakKB/1024.0,
            sizeof(Body), (shapeBytes + topologyBytes)/n, sizeof(DilatedShape),
            topologies.size(), topologyBytes/n,
            24.0*nv + sizeof(Vec3),
            world->contactStateBytes()/nF,
            pairs/nF, sizeof(ContactPair),
            sizeof(StoredContact), sizeof(StoredFeatureList), sizeof(FeaturePairEntry)
        );
    }
    return r;
}


int stepsFor(int n, bool compacting, const Options& o)
{
    if (o.steps > 0) return o.steps;
    if (compacting) return o.compactSteps;
    (void)n;
    return std::max(1, int(std::lround(o.duration/kTimeStep)));
}


//- Runs one field at every thread count; returns false if the final
//  states differ between thread counts
// * * * * * * * * * * * *  Accuracy of the hydro shortcuts * * * * * * * * //

//- Relative error of (F, M) against (Fr, Mr), the moment over the size L
double relError
(
    const Vec3& F, const Vec3& M, const Vec3& Fr, const Vec3& Mr, double L
)
{
    const double scale = Fr.norm() + Mr.norm()/L;
    return scale > 0 ? ((F - Fr).norm() + (M - Mr).norm()/L)/scale : 0;
}

//- rms and largest of a set of errors
struct ErrorStats
{
    double sq = 0, max = 0;
    int n = 0;
    void add(double e) { sq += e*e; max = std::max(max, e); ++n; }
    void print(const char* what) const
    {
        std::printf("accuracy %-58s rms %.3g max %.3g (%d floes)\n", what,
            n ? std::sqrt(sq/n) : 0.0, max, n);
    }
};

//- -hydroAccuracy: the floating field after the -warmup time (default 0),
//  every floe's buoyancy and drag by each shortcut against its reference
void hydroAccuracy(const Field& f, const Options& o)
{
    std::unique_ptr<World> world = buildWorld(f, o, nullptr);
    world->initialise();
    while (world->time() < o.warmup - 0.5e-3) world->step();
    const std::vector<Body>& bodies = world->bodies();
    const WaterSettings water{kWaterDensity, 0};
    const auto current = std::make_shared<UniformCurrent>(Vec3(kCurrent, 0, 0));
    auto drag = [&](DragIntegration integration, int sub, double Cf, double Cs)
    {
        DragSettings s;
        s.integration = integration;
        s.subdivision = sub;
        s.formCoefficient = Cf;
        s.skinCoefficient = Cs;
        return Drag(water, s, current);
    };
    const DragSettings defaults;
    const double Cf = defaults.formCoefficient, Cs = defaults.skinCoefficient;
    const Drag exactForm = drag(DragIntegration::exact, 0, Cf, 0);
    const Drag exactSkin = drag(DragIntegration::exact, 0, 0, Cs);
    ErrorStats form2, skin2, skinRule, skinClosed, skinForced, skinSwitch, skinExpansion, volume;
    // Wet bottom polygons whose centre of rotation lies beyond
    // skinUniformRatio radii (skinIntegral takes the expansion there)
    long bottoms = 0, farBottoms = 0;
    // The wind (with -wind U): sampled at subdivision 1 (the default until
    // issue 16's third round) and 0, and the exact integration, against the
    // closed form (form drag) and the Richardson limit (skin drag)
    const Vec3 Ua(o.wind, 0, 0);
    auto wind = [&](DragIntegration integration, int sub, double Cf, double Cs)
    {
        WindSettings s;
        s.integration = integration;
        s.subdivision = sub;
        s.formCoefficient = Cf;
        s.skinCoefficient = Cs;
        return Wind(water, s, WindHistory(Ua));
    };
    const WindSettings windDefaults;
    const double CfA = windDefaults.formCoefficient, CsA = windDefaults.skinCoefficient;
    const Wind exactWindForm = wind(DragIntegration::exact, 0, CfA, 0);
    const Wind exactWindSkin = wind(DragIntegration::exact, 0, 0, CsA);
    ErrorStats windForm0, windForm1, windSkin0, windSkin1, windSkinExact, windTotal1;
    PolyhedronBuffer buf;
    for (int i = 0; i < static_cast<int>(bodies.size()); ++i)
    {
        const double L = world->shapeOf(i).boundingRadius();
        // Sampled sums and their Richardson limit (subdivisions 3 and 4)
        Vec3 F[5], M[5], S[5], SM[5];
        for (int sub = 2; sub <= 4; ++sub)
        {
            drag(DragIntegration::sampled, sub, Cf, 0).bodyDrag(*world, i, F[sub], M[sub]);
            drag(DragIntegration::sampled, sub, 0, Cs).bodyDrag(*world, i, S[sub], SM[sub]);
        }
        const Vec3 Sr = (4*S[4] - S[3])/3, SMr = (4*SM[4] - SM[3])/3;
        Vec3 Fe, Me, Se, SMe;
        exactForm.bodyDrag(*world, i, Fe, Me);
        exactSkin.bodyDrag(*world, i, Se, SMe);
        form2.add(relError(F[2], M[2], Fe, Me, L));
        skin2.add(relError(S[2], SM[2], Sr, SMr, L));
        skinClosed.add(relError(Se, SMe, Sr, SMr, L));

        // The skin of the wet bottom facets by the 6-point rule (the last
        // round's), the closed form everywhere and skinIntegral's choice
        // between them (the drag's), against the Richardson limit
        const WaterFrame& frame = waterFrame(*world, i, water.level);
        const PolyhedronView P = world->shapeOf(i).outer(buf);
        const Body& b = bodies[i];
        const Vec3 omega = b.omega();
        const Vec3 w = b.v - Vec3(kCurrent, 0, 0);
        Vec3 Ic = Vec3::Zero(), Irc = Vec3::Zero(), Iq = Vec3::Zero(),
            Irq = Vec3::Zero(), Is = Vec3::Zero(), Irs = Vec3::Zero(),
            Ix = Vec3::Zero(), Irx = Vec3::Zero();
        for (int k = 0; k < frame.nWet; ++k)
        {
            const Vec3 n = frame.R*P.faces()[frame.wetFace[k]].normal;
            if (std::abs(n.z()) < defaults.bottomCosine) continue;
            const Vec3* q = frame.wetVertex + frame.wetBegin[k];
            const int m = frame.wetBegin[k + 1] - frame.wetBegin[k];
            Vec3 I, Ir;
            if (skinIntegralClosedForm(q, m, n, w, omega, I, Ir)) { Ic += I; Irc += Ir; }
            if (skinIntegralConical(q, m, n, w, omega, I, Ir)) { Iq += I; Irq += Ir; }
            if (skinIntegral(q, m, n, w, omega, I, Ir)) { Is += I; Irs += Ir; }
            if (skinIntegralExpansion(q, m, n, w, omega, I, Ir)) { Ix += I; Irx += Ir; }
            // Where skinIntegral switches (its criterion, Drag.C)
            Vec3 cq = Vec3::Zero();
            for (int j = 0; j < m; ++j) cq += q[j];
            cq /= m;
            double a2 = 0;
            for (int j = 0; j < m; ++j) a2 = std::max(a2, (q[j] - cq).squaredNorm());
            const Vec3 Uc = w + omega.cross(cq);
            const Vec3 Ut = Uc - Uc.dot(n)*n;
            const double Om = omega.dot(n);
            ++bottoms;
            farBottoms += !(Om*Om*a2*skinUniformRatio*skinUniformRatio > Ut.squaredNorm());
        }
        // As forces: F = -1/2 rho C_s I
        const double c = -0.5*kWaterDensity*Cs;
        skinRule.add(relError(c*Iq, c*Irq, Sr, SMr, L));
        skinForced.add(relError(c*Ic, c*Irc, Sr, SMr, L));
        skinSwitch.add(relError(c*Is, c*Irs, Sr, SMr, L));
        skinExpansion.add(relError(c*Ix, c*Irx, Sr, SMr, L));

        if (o.wind != 0)
        {
            Vec3 WF[5], WM[5], WS[5], WSM[5];
            for (int sub : {0, 1, 3, 4})
            {
                wind(DragIntegration::sampled, sub, CfA, 0).bodyWind(*world, i, Ua, WF[sub], WM[sub]);
                wind(DragIntegration::sampled, sub, 0, CsA).bodyWind(*world, i, Ua, WS[sub], WSM[sub]);
            }
            const Vec3 WSr = (4*WS[4] - WS[3])/3, WSMr = (4*WSM[4] - WSM[3])/3;
            Vec3 WFe, WMe, WSe, WSMe;
            exactWindForm.bodyWind(*world, i, Ua, WFe, WMe);
            exactWindSkin.bodyWind(*world, i, Ua, WSe, WSMe);
            windForm0.add(relError(WF[0], WM[0], WFe, WMe, L));
            windForm1.add(relError(WF[1], WM[1], WFe, WMe, L));
            windSkin0.add(relError(WS[0], WSM[0], WSr, WSMr, L));
            windSkin1.add(relError(WS[1], WSM[1], WSr, WSMr, L));
            windSkinExact.add(relError(WSe, WSMe, WSr, WSMr, L));
            // Both together, as the model acts: subdivision 1 against the
            // exact form drag + the Richardson limit of the skin
            windTotal1.add(relError(WF[1] + WS[1], WM[1] + WSM[1], WFe + WSr, WMe + WSMr, L));
        }

        // Buoyancy: the frame's (truncated prism) against the tetrahedra
        const SubmergedVolume& sv = frameVolume(P, frame);
        const SubmergedVolume ref =
            submergedVolumeByTetrahedra(P, frame.R, b.x, water.level);
        volume.add
        (
            std::abs(sv.volume - ref.volume)/ref.volume
          + (sv.centroid - ref.centroid).norm()/L
        );
    }
    std::printf("# hydro accuracy, floating field at t = %g s, %zu floes"
        " (relative error of force + moment/R, R the bounding radius)\n",
        world->time(), bodies.size());
    form2.print("form drag, sampled subdivision 2 vs closed form");
    skin2.print("skin drag, sampled subdivision 2 vs Richardson(3, 4)");
    skinClosed.print("skin drag, exact integration (bodyDrag) vs Richardson");
    skinRule.print("skin drag, 6-point rule everywhere vs Richardson(3, 4)");
    skinForced.print("skin drag, closed form everywhere vs Richardson(3, 4)");
    skinSwitch.print("skin drag, skinIntegral (the drag's choice) vs Richardson");
    skinExpansion.print("skin drag, expansion everywhere vs Richardson(3, 4)");
    std::printf("#   wet bottoms beyond %g radii (the expansion's part): %ld of %ld"
        " (centroid's vertex mean as the centre: an estimate)\n",
        skinUniformRatio, farBottoms, bottoms);
    volume.print("buoyancy: volume + centre/R, frame vs tetrahedra");
    if (o.wind != 0)
    {
        std::printf("# wind %g m/s along x\n", o.wind);
        windForm0.print("wind form drag, sampled subdivision 0 vs closed form");
        windForm1.print("wind form drag, sampled subdivision 1 vs closed form");
        windSkin0.print("wind skin drag, sampled subdivision 0 vs Richardson");
        windSkin1.print("wind skin drag, sampled subdivision 1 vs Richardson");
        windSkinExact.print("wind skin drag, exact integration vs Richardson");
        windTotal1.print("wind, sampled subdivision 1 vs exact form + Richardson skin");
    }
}


bool benchmarkField(const Field& f, const Options& o, const Snapshot* snap, bool memory)
{
    const int n = static_cast<int>(f.floes.size());
    const int steps = stepsFor(n, f.push != 0, o);
    std::uint64_t firstHash = 0;
    bool identical = true;
    bool first = true;

    for (int t : o.threads)
    {
        omp_set_num_threads(t);
        std::vector<double> walls, cpus, contacts;
        std::uint64_t hash = 0;
        long rebuilds = 0;
        double searched = 0, candidates = 0;
        for (int rep = 0; rep < o.reps; ++rep)
        {
            const RunResult r = runOnce(f, o, snap, steps, memory && first && rep == 0);
            walls.push_back(r.wall);
            cpus.push_back(r.cpu);
            contacts.push_back(r.contactsPerStep);
            if (rep == 0)
            {
                hash = r.hash;
                rebuilds = r.rebuilds;
                searched = r.searchedPerStep;
                candidates = r.candidatePairs;
            }
            else if (r.hash != hash)
            {
                identical = false;
                std::printf("# WARNING: repetition %d differs from repetition 0\n", rep);
            }
        }
        if (first)
        {
            firstHash = hash;
            first = false;
        }
        else if (hash != firstHash)
        {
            identical = false;
        }

        const double w = median(walls);
        std::printf
        (
            "N=%d threads=%d steps=%d wall_s=%.4g floe_steps_per_s=%.4g"
            " contacts_per_step=%.1f\n",
            n, t, steps, w, double(n)*steps/w, median(contacts)
        );
        std::printf("#   field=%s reps wall_s:", f.name.c_str());
        for (double x : walls) std::printf(" %.4g", x);
        std::printf("  cpu_s:");
        for (double x : cpus) std::printf(" %.4g", x);
        std::printf("  neighbour_list_builds=%ld  state_hash=%016llx\n",
            rebuilds, static_cast<unsigned long long>(hash));
        std::printf("#   searched_pairs_per_step=%.1f of %.0f candidate pairs (the"
            " others certified apart)\n", searched, candidates);
        std::fflush(stdout);
    }
    if (o.threads.size() > 1)
    {
        std::printf("# field=%s N=%d threads_identical=%s\n",
            f.name.c_str(), n, identical ? "yes" : "no");
    }
    std::fflush(stdout);
    return identical;
}


std::string loadAverage()
{
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    in >> a >> b >> c;
    return a + " " + b + " " + c;
}

} // anonymous namespace


int main(int argc, char* argv[])
{
    const Options o = parseOptions(argc, argv);
    bool identical = true;

    try
    {
        std::printf("# demBenchmark: load average %s, %d processors, reps=%d\n",
            loadAverage().c_str(), omp_get_num_procs(), o.reps);
        // Waiting threads spin (default, ACTIVE) or sleep (PASSIVE): a step
        // has a few barriers, and with PASSIVE each costs a wake-up
        const char* wait = std::getenv("OMP_WAIT_POLICY");
        std::printf("# OMP_WAIT_POLICY=%s\n", wait ? wait : "(unset: spin, then sleep)");

        if (o.drift)
        {
            for (int n : o.sizes)
            {
                const auto g0 = std::chrono::steady_clock::now();
                const Field f = makeField("drifting", n, 0.7, false, o);
                const double gen = std::chrono::duration<double>
                    (std::chrono::steady_clock::now() - g0).count();
                std::printf("# field=drifting nominal_N=%d floes=%zu box=%.1f m"
                    " (generated in %.2f s)\n", n, f.floes.size(), f.xmax - f.xmin, gen);

                Snapshot snap;
                if (o.warmup > 0)
                {
                    omp_set_num_threads(o.threads.back());
                    auto w = buildWorld(f, o, nullptr);
                    while (w->time() < o.warmup - 0.5e-3) w->step();
                    snap = takeSnapshot(*w);
                    std::printf("# warm-up %.3g s: %d pairs in contact\n",
                        o.warmup, w->contactPairCount());
                }
                identical = benchmarkField(f, o, snap.valid ? &snap : nullptr, !o.callgrind)
                    && identical;
            }
        }

        if (o.compact)
        {
            const Field f = makeField("compacting", o.compactN, 0.9, true, o);
            std::printf("# field=compacting floes=%zu box=%.1f m push=%g Pa"
                " cylinder r=%g m\n", f.floes.size(), f.xmax - f.xmin, f.push,
                f.cylinderRadius);

            std::ostringstream file;
            file << o.cache << "/compacted_N" << o.compactN << "_seed" << o.seed
                 << "_lloyd" << o.lloyd << "_push" << o.push << "_T" << o.compactTime
                 << "_skin" << o.skin << "_field" << std::hex << fieldHash(f.floes)
                 << ".state";
            Snapshot snap;
            if (readSnapshot(file.str(), snap) && snap.bodies.size() == f.floes.size() + 1)
            {
                std::printf("# compacted state read from %s (t = %g s)\n",
                    file.str().c_str(), snap.time);
            }
            else
            {
                omp_set_num_threads(o.threads.back());
                const auto c0 = std::chrono::steady_clock::now();
                auto w = buildWorld(f, o, nullptr);
                while (w->time() < o.compactTime - 0.5e-3) w->step();
                snap = takeSnapshot(*w);
                std::printf("# compaction %g s simulated in %.1f s wall: %d pairs in"
                    " contact\n", o.compactTime, std::chrono::duration<double>
                    (std::chrono::steady_clock::now() - c0).count(),
                    w->contactPairCount());
                if (writeSnapshot(file.str(), snap))
                {
                    std::printf("# compacted state written to %s\n", file.str().c_str());
                }
            }
            identical = benchmarkField(f, o, &snap, !o.callgrind) && identical;
        }

        if (o.floating)
        {
            Field f = makeField("floating", o.floatN, 0.7, false, o);
            f.floating = true;
            std::printf("# field=floating floes=%zu box=%.1f m: gravity, buoyancy,"
                " empirical drag (current %g m/s along x), floe damping %s,"
                " wind %g m/s along x, body forces every %d steps\n", f.floes.size(),
                f.xmax - f.xmin, kCurrent, o.floeDamping ? "on" : "off", o.wind,
                o.bodyForceInterval);
            if (o.hydroAccuracy)
            {
                hydroAccuracy(f, o);
            }
            else
            {
                identical = benchmarkField(f, o, nullptr, !o.callgrind) && identical;
            }
        }
    }
    catch (const Error& e)
    {
        std::fprintf(stderr, "demBenchmark: %s\n", e.what());
        return 1;
    }

    if (o.threads.size() > 1)
    {
        std::printf("threads_identical=%s\n", identical ? "yes" : "no");
    }
    return identical ? 0 : 3;
}
