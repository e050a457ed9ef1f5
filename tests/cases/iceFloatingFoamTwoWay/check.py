#!/usr/bin/env python3
# Checks of tests/cases/iceFloatingFoamTwoWay/Alltest (see there).
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from caseCheck import allPassed, check, internal, mag, twoWaySteps  # noqa: E402

base = Path(sys.argv[1])
RHO = 1025.0        # water.density of the tutorial
DT = 0.1            # flow step of the tutorial


def steps(log):
    """twoWaySteps of a solver log file."""
    return twoWaySteps(open(log))


def fluidImpulse(case, time, procs=None):
    """sum_c iceDragSource_c rho V_c deltaT over the cells (and processors)."""
    dirs = [case/f'processor{p}' for p in range(procs)] if procs else [case]
    tot = [0.0, 0.0, 0.0]
    for d in dirs:
        kind, S = internal(d/time/'iceDragSource')
        _, V = internal(d/time/'V')
        if kind == 'uniform':
            continue
        for s, v in zip(S, V):
            for k in range(3):
                tot[k] += s[k]*RHO*v*DT
    return tot


def rows(p):
    return [list(map(float, l.split())) for l in open(p) if l.strip() and not l.startswith('#')]


def bodies(p):
    """bodies.dat by (time rounded to 1e-6, id)."""
    return {(round(r[0], 6), r[1]): r for r in rows(p)}


serial = steps(base/'serial'/'log.iceFloatingFoam')
parallel = steps(base/'parallel'/'log.iceFloatingFoam')
multi = steps(base/'multiRate'/'log.iceFloatingFoam')


# 1. Per step: fluid = - floe, nothing lost
def perStep(name, st, n):
    worst = max(s[2] for s in st.values()) if st else 1
    lost = max(mag(s[3]) for s in st.values()) if st else 1
    drag = min(mag(s[0]) for s in st.values()) if st else 0
    check(len(st) == n and worst < 1e-10 and lost == 0 and drag > 0,
          f'{name}: {len(st)} steps, fluid source impulse = - floe drag impulse'
          f' (largest relative imbalance {worst:.2e}, smallest impulse {drag:.3e} N s, lost {lost:g})')


# 2. The written source fields against the logged floe impulse
def writtenSource(name, case, times, procs, st):
    for t in times:
        f = fluidImpulse(case, t, procs)
        J = st[round(float(t), 9)][0]
        err = mag([a + b for a, b in zip(f, J)])/mag(J)
        check(err < 1e-10, f'{name}: t = {t}: sum of iceDragSource rho V deltaT '
              f'({f[0]:.6e} {f[1]:.3e} {f[2]:.3e}) = - floe drag impulse, relative {err:.2e}')


#    and the floe's drag impulse between write times over its velocity
#    change: the floe's mass in every interval (the logged impulse is the
#    one the integrator applied)
def masses(name, st, B):
    m = []
    for t0, t1 in ((0.0, 0.5), (0.5, 1.0), (1.0, 1.5), (1.5, 2.0)):
        Jx = sum(s[0][0] for t, s in st.items() if t0 + 1e-9 < t <= t1 + 1e-9)
        dv = B[(t1, 0)][5] - B[(t0, 0)][5]
        m.append(Jx/dv)
    spread = (max(m) - min(m))/abs(m[0])
    check(spread < 1e-8 and m[0] > 0,
          f'{name}: floe drag impulse / velocity change = {m[0]:.10g} kg in every write interval '
          f'(relative spread {spread:.2e})')
    return m[0]


perStep('serial', serial, 20)
perStep('parallel', parallel, 10)
writtenSource('serial', base/'serial', ['0.5', '1', '1.5', '2'], None, serial)
writtenSource('parallel', base/'parallel', ['1.5', '2'], 2, parallel)
B = bodies(base/'serial'/'postProcessing'/'iceDEM'/'0'/'bodies.dat')
mass = masses('serial', serial, B)

# 3. Restart = uninterrupted, bit for bit (writePrecision 17: the ascii
# entries of the uniform dictionaries, e.g. the sixDoF state, exact too)
def maxdiff(a, b):
    if isinstance(a, str) or isinstance(b, str):
        return (0.0 if a == b else float('inf')), 1.0
    fa = [x for u in a for x in (u if isinstance(u, tuple) else (u,))]
    fb = [x for u in b for x in (u if isinstance(u, tuple) else (u,))]
    if len(fa) != len(fb):
        return float('inf'), 1.0
    return max(abs(x - y) for x, y in zip(fa, fb)), max(abs(x) for x in fa)


for field in ('U', 'iceDragSource', 'iceDragCoefficient'):
    d, m = maxdiff(internal(base/'serial'/'2'/field)[1], internal(base/'restart'/'2'/field)[1])
    check(d == 0, f'restart: {field} at t = 2 bit for bit (max difference {d:.2e}, largest {m:.3e})')
R = bodies(base/'restart'/'postProcessing'/'iceDEM'/'1'/'bodies.dat')
dB = max(abs(x - y) for x, y in zip(R[(2.0, 0)][2:8], B[(2.0, 0)][2:8]))
check(dB == 0, f'restart: floe position and velocity at t = 2 bit for bit (max difference {dB:.2e})')
rs = steps(base/'restart'/'log.iceFloatingFoam')
dR = max(mag([a - b for a, b in zip(rs[t][0], serial[t][0])])/mag(serial[t][0]) for t in rs)
check(len(rs) == 10 and dR == 0,
      f'restart: floe drag impulse of every step identical in the log (max relative difference {dR:.2e})')

# 4. Serial = parallel
P = bodies(base/'parallel'/'postProcessing'/'iceDEM'/'1'/'bodies.dat')
dX = max(abs(P[(t, 0)][k] - B[(t, 0)][k]) for t in (1.5, 2.0) for k in range(2, 8))
check(dX < 1e-6, f'parallel: floe position and velocity within 1e-6 of serial (max {dX:.2e})')
dJ = max(mag([a - b for a, b in zip(parallel[t][0], serial[t][0])])/mag(serial[t][0]) for t in parallel)
check(dJ < 1e-4, f'parallel: floe drag impulse per step within 1e-4 of serial (max relative {dJ:.2e})')

# 5. The multi-rate step (bodyForceInterval 3): the same exchange, the
# impulse the kicks gave the floe (outer steps straddle the flow steps and
# the write times), restart = uninterrupted from inside an outer step
perStep('multi-rate', multi, 20)
writtenSource('multi-rate', base/'multiRate', ['0.5', '1', '1.5', '2'], None, multi)
M = bodies(base/'multiRate'/'postProcessing'/'iceDEM'/'0'/'bodies.dat')
mMulti = masses('multi-rate', multi, M)
check(abs(mMulti - mass) < 1e-8*mass,
      f'multi-rate: the same floe mass as the single rate ({mMulti:.10g} against {mass:.10g} kg)')
for field in ('U', 'iceDragSource', 'iceDragCoefficient'):
    d, m = maxdiff(internal(base/'multiRate'/'2'/field)[1],
                   internal(base/'multiRateRestart'/'2'/field)[1])
    check(d == 0, f'multi-rate restart: {field} at t = 2 bit for bit (max difference {d:.2e}, largest {m:.3e})')
MR = bodies(base/'multiRateRestart'/'postProcessing'/'iceDEM'/'1'/'bodies.dat')
dM = max(abs(x - y) for x, y in zip(MR[(2.0, 0)][2:8], M[(2.0, 0)][2:8]))
check(dM == 0, f'multi-rate restart: floe position and velocity at t = 2 bit for bit (max difference {dM:.2e})')
#    Against the single rate: the floe's drift velocity at t = 2 s
du = abs(M[(2.0, 0)][5] - B[(2.0, 0)][5])
print(f'      multi-rate - single rate: floe u_x at t = 2 s {M[(2.0, 0)][5]:.12g} against '
      f'{B[(2.0, 0)][5]:.12g} m/s (difference {du:.2e})')

sys.exit(0 if allPassed() else 1)
