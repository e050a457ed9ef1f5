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

# 1. Per step: fluid = - floe, nothing lost
for name, st, n in (('serial', serial, 20), ('parallel', parallel, 10)):
    worst = max(s[2] for s in st.values()) if st else 1
    lost = max(mag(s[3]) for s in st.values()) if st else 1
    drag = min(mag(s[0]) for s in st.values()) if st else 0
    check(len(st) == n and worst < 1e-10 and lost == 0 and drag > 0,
          f'{name}: {len(st)} steps, fluid source impulse = - floe drag impulse'
          f' (largest relative imbalance {worst:.2e}, smallest impulse {drag:.3e} N s, lost {lost:g})')

# 2. The written source fields against the logged floe impulse
for name, case, times, procs, st in (
        ('serial', base/'serial', ['0.5', '1', '1.5', '2'], None, serial),
        ('parallel', base/'parallel', ['1.5', '2'], 2, parallel)):
    for t in times:
        f = fluidImpulse(case, t, procs)
        J = st[round(float(t), 9)][0]
        err = mag([a + b for a, b in zip(f, J)])/mag(J)
        check(err < 1e-10, f'{name}: t = {t}: sum of iceDragSource rho V deltaT '
              f'({f[0]:.6e} {f[1]:.3e} {f[2]:.3e}) = - floe drag impulse, relative {err:.2e}')

B = bodies(base/'serial'/'postProcessing'/'iceDEM'/'0'/'bodies.dat')
masses = []
for t0, t1 in ((0.0, 0.5), (0.5, 1.0), (1.0, 1.5), (1.5, 2.0)):
    Jx = sum(s[0][0] for t, s in serial.items() if t0 + 1e-9 < t <= t1 + 1e-9)
    dv = B[(t1, 0)][5] - B[(t0, 0)][5]
    masses.append(Jx/dv)
spread = (max(masses) - min(masses))/abs(masses[0])
check(spread < 1e-8 and masses[0] > 0,
      f'floe drag impulse / velocity change = {masses[0]:.10g} kg in every write interval '
      f'(relative spread {spread:.2e})')

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

sys.exit(0 if allPassed() else 1)
