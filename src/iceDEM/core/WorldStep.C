/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "World.H"
#include "worldDetail.H"
#include "contact/NarrowPhase.H"
#include "contact/NeighbourList.H"
#include "domain/InflowOutflow.H"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace iceDEM
{

using namespace worldDetail;

/*  The step's schedule: a multi-rate step for the body forces (issue 16)

    The contact forces change within a few steps (a Hertz contact lasts
    some 10-30 of them); the body forces (buoyancy, water drag, wind, floe
    damping: every BodyForceModel) follow the floes' heave and roll, whose
    periods are hundreds of steps, and cost as much as the contacts (the
    study point: 46 % of a step, tests/benchmark/README.md). So the models
    are evaluated every k-th step only (WorldSettings::bodyForceInterval,
    entry bodyForceInterval of constant/iceDEMProperties), the contacts at
    every step.

    Scheme: impulse multiple time stepping (Verlet-I / r-RESPA; Grubmueller
    et al. 1991, Tuckerman, Berne & Martyna 1992). Over an outer step of
    k steps, H = k dt, with the slow force S = models + gravity of a free
    body (gravity goes with buoyancy, which nearly cancels it: a floe at
    rest gets no kick; with the contacts it would sag by g H^2/8 within
    every outer step) and the fast force C = contacts:
        v += H/2 S(x_0)                      slow half kick
        k times velocity Verlet with C alone (dt)
        v += H/2 S(x_k)                      slow half kick
    The two slow kicks of consecutive outer steps meet at the boundary, so
    in the code a boundary step's kick force is C + k S and an inner
    step's C: the same half kicks as the single-rate step, the models not
    called in between. With k = 1 it is velocity Verlet unchanged (the
    same sums in the same order: results bit for bit).

    Why not the models' force held for k steps (zero-order hold): holding
    an old force is not time-reversible and not symplectic, so the floes'
    hydrostatic energy drifts (a heaving floe gains or loses amplitude
    every period). The impulse scheme is a composition of exact flows of
    the split Hamiltonian (kick, Verlet, kick): symplectic and reversible
    for the conservative part (buoyancy, gravity, contacts), second order,
    and its energy error stays bounded.

    Stability and resonance:
    - The slow part alone is velocity Verlet with step H on the floes'
      hydrostatic modes: stable for omega H < 2, i.e. H < T/pi, T the
      shortest heave, roll or pitch period; the period's relative error is
      (omega H)^2/24 (the test's scaling). The case reader stops above
      H = T_min/pi (BodyForceModel::shortestPeriod of the start poses:
      the buoyancy's shortestHydrostaticPeriod).
    - Resonance with the fast modes: impulses every H excite a contact's
      oscillation (period 2 t_c, t_c the Hertz contact time) when H is near
      a multiple of its half period; linear resonance first at H = t_c,
      nonlinear at a third of the period (Ma, Izaguirre & Skeel 2003, SIAM
      J. Sci. Comput. 24:1951). The reader stops above H = 2 t_c/3, below
      every resonance of the contacts, whose own step dt is unchanged.
    - Both bounds (bodyForceLimits) hold for the bodies a case starts
      with; a body inserted in the run (inflow: a new floe, possibly
      smaller than any before, so a shorter contact time) is checked when
      it joins, and the run stops there (checkInsertedBodyForceLimits):
      every floe that ever runs is inside them.
    - Velocity-dependent forces (drag, wind, floe damping) are evaluated
      explicitly with the velocity of the boundary's first half kick, as
      the single-rate step does; an explicit kick is stable for H below
      twice the relaxation time m/c (drag: hundreds of seconds; floe
      damping at a fraction zeta of critical: 1/(zeta omega), well above
      T/pi for zeta <= 1).

    The schedule is the world's state: bodyForcePhase_ counts the steps
    since the last evaluation and is written with a restart state, so a
    restart in the middle of an outer step continues it (the bodies' kick
    forces of the last step are saved as before). A body inserted during a
    run (inflow) starts with the kick of the rest of the outer step. A step
    shorter than dt (the last of an interval that is not a multiple of dt)
    counts as a step of the schedule. modelForceOnFreeBodies gives the
    force the kicks applied (k times the models' at a boundary, zero in
    between), so a force balance summing it over the steps sees the
    impulses the floes received.
*/

double BodyForceModel::shortestPeriod(const World&, int, int) const
{
    return std::numeric_limits<double>::infinity();
}


BodyForceLimits World::bodyForceLimits(int begin, int end) const
{
    BodyForceLimits limits;
    limits.contactTime = estimatedContactTime(begin, end);
    for (const auto& m : forceModels_)
    {
        limits.period = std::min(limits.period, m->shortestPeriod(*this, begin, end));
    }
    return limits;
}


void World::checkInsertedBodyForceLimits(int first) const
{
    const int k = bodyForceInterval();
    if (k <= 1) return;
    const double H = k*settings_.timeStep;
    const int N = static_cast<int>(bodies_.size());
    for (int i = first; i < N; ++i)
    {
        const BodyForceLimits limits = bodyForceLimits(i, i + 1);
        const bool contact = H > limits.contactLimit();
        if (!contact && !(H > limits.periodLimit())) continue;
        std::ostringstream msg;
        msg << "inserted body " << bodies_[i].id << ": the multi-rate step's outer step "
            << H << " s (bodyForceInterval " << k << ", deltaT " << settings_.timeStep
            << " s) exceeds ";
        if (contact)
        {
            msg << "2/3 of its estimated Hertz contact time " << limits.contactTime
                << " s (resonance with the contacts)";
        }
        else
        {
            msg << "1/pi of its shortest heave, roll or pitch period " << limits.period
                << " s (stability of the hydrostatic modes)";
        }
        msg << "; an inserted floe is a new shape, checked as it joins: for this one at"
            << " most bodyForceInterval "
            << std::max(1, int(std::floor(std::min(limits.contactLimit(), limits.periodLimit())
                                          /settings_.timeStep)));
        throw Error(msg.str(), "bodyForceInterval");
    }
}


void World::setBodyForcePhase(int phase)
{
    bodyForcePhase_ = std::max(0, phase);
}


void World::setRestartSchedule(int interval, int phase)
{
    restartInterval_ = std::max(1, interval);
    restartPhase_ = std::max(0, phase);
}


void World::applyRestartSchedule()
{
    const int k = bodyForceInterval();
    const int kOld = restartInterval_;
    const int phase = restartPhase_;
    restartInterval_ = 0;
    if (kOld == k)
    {
        bodyForcePhase_ = phase;
        return;
    }
    // The slow force of the restart pose (computeForces above) times what
    // the saved kick force lacks of it
    const double add = k - (phase == 0 ? kOld : 0);
    const bool models = modelForce_.size() == bodies_.size();
    for (std::size_t i = 0; i < bodies_.size(); ++i)
    {
        Body& b = bodies_[i];
        if (!b.isFree()) continue;
        Vec3 f = b.mass*settings_.gravity;
        if (models)
        {
            f += modelForce_[i];
            b.torque += add*modelTorque_[i];
        }
        b.force += add*f;
    }
    bodyForcePhase_ = 0;
    std::ostringstream msg;
    msg << "bodyForceInterval " << k << " differs from the restart state's ("
        << kOld << ", " << phase << " steps into an outer step): the kick"
        << " forces are corrected to the new interval and a new outer step"
        << " starts";
    if (phase != 0)
    {
        msg << "; the state was written inside an outer step, whose closing"
            << " kick is lost once (write at an outer step's end for an"
            << " exact change)";
    }
    warnings_.push_back(msg.str());
}


void World::stepBy(double dt)
{
    if (!initialised_)
    {
        initialise();
    }
    if (firstInserted_ >= 0)
    {
        joinInserted();
    }
    // A prescribed structure was posed for this step: it must still fit
    // the periodic domain (Domain::checkStructure)
    if (domain_ && domain_->structureMoves())
    {
        domain_->checkStructure(*this);
    }
    resizeBodyFrames();
    ++evaluation_;
    preparePairs();
    const int N = static_cast<int>(bodies_.size());

    // The multi-rate schedule: this step ends an outer step (evaluates the
    // body forces) or is an inner one (contacts only)
    const int interval = bodyForceInterval();
    const bool slowStep = bodyForcePhase_ + 1 >= interval;

    // Without body-force models to evaluate the whole step is one parallel
    // region; models prepare serially (flow sampling), between two regions
    const bool oneRegion = forceModels_.empty() || !slowStep;
    const bool listCoversBodies = nlist_->coversBodies(bodies_.size());
    bool rebuild = !listCoversBodies;
    if (listCoversBodies) nlist_->advanceDrift(dt);
    const bool periodic = domain_ != nullptr;
    bool wrappedAny = false;

    // One team for the first half step, the world frames, the neighbour
    // list and the contacts (fewer fork-joins and barriers: on a loaded
    // machine each waits for the slowest thread)
    parallelRegion(N >= settings_.singleThreadBelow, [&]
    {
        // First half kick, drift, rotation; then the neighbour list's
        // check (some body moved more than skin/2) and the body's motion
        // bound (the world frames follow in the pair loop, where needed).
        // The bodies go in blocks of bodyLanes whose rotations advance side
        // by side (rotateFreeLanes: the drifting field's step 1.19x faster,
        // the same results to the bit)
        const int nBlocks = (N + bodyLanes - 1)/bodyLanes;
        #pragma omp for schedule(static) reduction(||: rebuild, wrappedAny)
        for (int block = 0; block < nBlocks; ++block)
        {
            const int first = block*bodyLanes;
            const int last = std::min(N, first + bodyLanes);
            Quat* q[bodyLanes];
            const Vec3* L[bodyLanes];
            const Vec3* invI[bodyLanes];
            int nFree = 0;
            for (int i = first; i < last; ++i)
            {
                Body& b = bodies_[i];
                if (!b.isFree()) continue;
                halfKick(b, dt);
                b.x += dt*b.v;
                q[nFree] = &b.q;
                L[nFree] = &b.L;
                invI[nFree] = &b.invInertia;
                ++nFree;
            }
            if (nFree == bodyLanes)
            {
                rotateFreeLanes<bodyLanes>(q, L, invI, dt);
            }
            else
            {
                for (int a = 0; a < nFree; ++a) rotateFree(*q[a], *L[a], *invI[a], dt);
            }
            for (int i = first; i < last; ++i)
            {
                Body& b = bodies_[i];
                if (listCoversBodies && nlist_->track(i, b.x, b.q))
                {
                    rebuild = true;
                }
                // Migration: a free body leaving through a periodic side
                // re-enters at the other (after track: its motion bound is
                // that of the unwrapped path)
                if (periodic && b.isFree())
                {
                    const int w = domain_->wrap(b.x);
                    if (w != Domain::noImage)
                    {
                        wrapped_[i] = w;
                        wrappedAny = true;
                    }
                }
            }
        }

        if (rebuild || wrappedAny)
        {
            #pragma omp single
            {
                // The pairs of bodies that only crossed a periodic side
                // follow them (NeighbourList::applyWraps; a serial build
                // for every crossing was 14 of the 81 builds of 1000 steps
                // of the study's closed pack at 90 %); a build takes the
                // crossings with it
                if (rebuild || !nlist_->applyWraps(wrapped_, *domain_))
                {
                    nlist_->build(*this);
                    preparePairs();
                }
                if (periodic) std::fill(wrapped_.begin(), wrapped_.end(), int(Domain::noImage));
            }
        }

        pairForces(dt);

        if (oneRegion) sumBodyForces(dt, slowStep ? interval : 0);
    });
    checkOverlapRange();

    // Body-force models: their serial preparation, then the body sums and
    // the second half kick
    if (!oneRegion) bodyForces(dt, interval);
    bodyForcePhase_ = slowStep ? 0 : bodyForcePhase_ + 1;
    time_ += dt;
    ++step_;

    // Bodies leave and enter between steps
    if (inflowOutflow_) inflowOutflow_->update(*this);
}


void World::step()
{
    stepBy(settings_.timeStep);
}


void World::advanceTo(double t)
{
    const double dt = settings_.timeStep;
    // Steps shorter than this fraction of dt are merged into the last one
    constexpr double mergeFraction = 1e-6;
    while (t - time_ > mergeFraction*dt)
    {
        const double remaining = t - time_;
        if (remaining < (1 + mergeFraction)*dt)
        {
            // The last step: a full one when only round-off separates them,
            // so the trajectory does not depend on how t was summed (a
            // restart reads t from a directory name)
            stepBy(remaining > (1 - mergeFraction)*dt ? dt : remaining);
            time_ = t;
        }
        else
        {
            stepBy(dt);
        }
    }
}


void World::setPrescribedState
(
    int i,
    const Vec3& x,
    const Quat& q,
    const Vec3& v,
    const Vec3& omega
)
{
    Body& b = bodies_.at(i);
    if (b.motion != BodyMotion::prescribed)
    {
        throw Error("setPrescribedState on a body whose motion is not prescribed");
    }
    b.x = x;
    b.q = q.normalized();
    b.v = v;
    b.setOmega(omega);
}

} // namespace iceDEM
