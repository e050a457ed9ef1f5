#!/usr/bin/env python3
# Checks of tests/cases/kullukPackFlow/Alltest (see there).
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from caseCheck import allPassed, check, internal, mag, twoWaySteps  # noqa: E402

case = Path(sys.argv[1])
restart = Path(sys.argv[2])
RHO = 1025.0        # water.density of the tutorial
UBAR = 0.3          # system/fvOptions
TIMES = ['1', '1.5', '2', '2.5', '3', '3.5', '4']


log = open(case/'log.iceFloatingFoam').read().splitlines()

# 1. The run ended
check(any(l.strip() == 'End' for l in log), 'the run ends ("End" in log.iceFloatingFoam)')

# 2. The cyclic pairs match; the hull translated without yaw
cm = open(case/'log.checkMesh').read()
m = re.search(r'Coupled point location match \(average (\S+)\) OK', cm)
check(m is not None and float(m.group(1)) < 1e-9 and 'Mesh OK' in cm,
      f'checkMesh: cyclic pairs match (average {m.group(1) if m else "?"} m), Mesh OK')
npatch = len(re.findall(r'^\s+(back|front|left|right)\s+\d+', cm, re.M))
check(npatch == 4, f'checkMesh: the four cyclic patches back/front/left/right ({npatch})')
sep = sum('differs from computed separation vector' in l for l in log)
check(sep == 0, f'solver log: no cyclic separation mismatch warning ({sep})')
rows = [list(map(float, l.split())) for l in open(case/'postProcessing/hullMotion/0/motion.dat')
        if l.strip() and not l.startswith('#')]
dx = max(abs(r[1] - rows[0][1]) + abs(r[2] - rows[0][2]) for r in rows)
yaw = max(abs(r[6]) for r in rows)
check(dx > 1e-4 and yaw == 0,
      f'the hull moved {dx:.3e} m in surge and sway and did not yaw (max |yaw| {yaw:g} deg)')

# Drag sample points outside the mesh: none, every one found in the mesh or
# at its periodic image (the mesh follows the hull's drift; floes straddle
# the periodic sides), and the images are used
samp = [re.search(r'resolved drag: \d+ points per sampling \(\d+ samplings\), (\d+) of (\d+) outside'
                  r' the mesh \(far-field current\)(?:, (\d+) at a periodic image)?', l)
        for l in log if 'resolved drag:' in l]
outside = max(int(m.group(1)) for m in samp) if samp else 1
images = max(int(m.group(3) or 0) for m in samp) if samp else 0
check(len(samp) == 8 and outside == 0 and images > 0,
      f'{len(samp)} samplings: no drag point outside the mesh (largest count {outside}); '
      f'up to {images} points per step sampled at a periodic image')

# 3. meanVelocityForce holds Ubar
Vk, V = internal(case/'1'/'V')
for t in TIMES:
    _, U = internal(case/t/'U')
    _, V = internal(case/t/'V')
    mean = sum(u[0]*v for u, v in zip(U, V))/sum(V)
    check(abs(mean - UBAR) < 1e-10,
          f't = {t}: volume mean of U_x = {mean:.15f} m/s (Ubar {UBAR}, difference {mean - UBAR:.1e})')
unc = [float(re.search(r'uncorrected Ubar = (\S+),', l).group(1)) for l in log
       if 'uncorrected Ubar' in l]
worst = max(abs(u - UBAR) for u in unc) if unc else 1
check(len(unc) >= 4*2 and worst < 1e-3*UBAR,
      f'{len(unc)} corrections, uncorrected mean within {worst/UBAR:.1e} of Ubar (limit 1e-3)')

# 4. Two-way momentum balance
steps = twoWaySteps(log)
worstImb = max(s[2] for s in steps.values()) if steps else 1
lost = max(mag(s[3]) for s in steps.values()) if steps else 1
smallest = min(mag(s[0]) for s in steps.values()) if steps else 0
check(len(steps) == 8 and worstImb < 1e-10 and lost == 0 and smallest > 0,
      f'{len(steps)} steps: fluid source impulse = - floes\' drag impulse (largest relative '
      f'imbalance {worstImb:.2e}, smallest impulse {smallest:.3e} N s, lost {lost:g})')
held = sum('the source holds the impulse of the last 1 s' in l for l in log)
check(held == 3, f'{held} steps without a flow solve after the first: the source holds the '
      f'impulse of the last 1 s')
for t in TIMES:
    kind, S = internal(case/t/'iceDragSource')
    _, V = internal(case/t/'V')
    tf = float(t)
    # the intervals the flow has not taken: after a flow step (integer t)
    # the one just run, else the two since the last flow step
    held = [tf] if tf == int(tf) else [tf - 0.5, tf]
    T = 0.5*len(held)
    f = [sum(s[k]*RHO*v*T for s, v in zip(S, V)) for k in range(3)] if kind != 'uniform' else [0, 0, 0]
    J = [sum(steps[round(h, 9)][0][k] for h in held) for k in range(3)]
    err = mag([a + b for a, b in zip(f, J)])/mag(J)
    check(err < 1e-10, f't = {t}: sum of iceDragSource rho V {T} s ({f[0]:.6e} {f[1]:.3e} {f[2]:.3e}) '
          f'= - floes\' drag impulse of {len(held)} interval(s), relative {err:.2e}')

# 5. Restart from t = 1 = uninterrupted at t = 4
for field in ('U', 'iceDragSource'):
    _, a = internal(case/'4'/field)
    _, b = internal(restart/'4'/field)
    d = max(abs(x - y) for u, w in zip(a, b) for x, y in zip(u, w))
    m = max(abs(x) for u in a for x in u)
    check(len(a) == len(b) and d <= 1e-12*m,
          f'restart from 1: {field} at t = 4 as uninterrupted (max difference {d:.2e}, largest {m:.3e})')

sys.exit(0 if allPassed() else 1)
