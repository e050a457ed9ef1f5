#!/usr/bin/env python3
# iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
# Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
"""Random combinations of entries, which the bad-input battery (one entry at
a time, tests/cases/inputBattery) does not try. A tool, not a test: run it
after changing a reader, a generator or the restart, and look at what it
prints; it fixes its random draws by the case number, so a case it reports
can be made again.

  combinations.py field N [FIRST]      random system/createIceFieldDict
      files (regions of 1 m to 3 km up to 100 km from the origin, either
      count, concentrations up to 0.999999, the three thickness
      distributions, radii of 1 mm to 1 m, zones, corrections); each field
      createIceField writes is run on by iceDEMFoam (two steps)
  combinations.py dem N [FIRST]        random iceDEMFoam settings on a small
      field (step, skins, contact model, current, uniform or table wind,
      floe damping, bodyForceInterval, no domain, periodic, inflow, floor),
      2 s, run with 1 and 2 threads and restarted at 1 s: the three DEM
      states at 2 s must be identical (the 'step' line excepted)
  combinations.py structure N [FIRST]  random facetedHull profiles run on by
      iceFloatingFoam -noFlow

Every run must end with exit 0 or with a FOAM FATAL (IO) ERROR, within a
time bound, without NaN in the log. Cases that do not are printed and
left in the scratch directory (ICEDEM_FUZZ_DIR, default /tmp/iceDEMfuzz);
the others are removed. The last line counts the outcomes. Needs the
solvers built and etc/bashrc sourced.
"""

import hashlib
import math
import os
import random
import re
import shutil
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
BASES = os.path.join(ROOT, 'tests', 'cases', 'inputBattery', 'bases')
SCRATCH = os.environ.get('ICEDEM_FUZZ_DIR', '/tmp/iceDEMfuzz')
GRAVITY = os.path.join(ROOT, 'tests', 'cases', 'createIceField', 'case', 'constant', 'g')
TIMEOUT = 120   # seconds per run: the runs take well under 10 s


def run(cmd, case, env=None):
    try:
        q = subprocess.run(cmd, cwd=case, capture_output=True, text=True,
                           timeout=TIMEOUT, env=env)
        return q.returncode, q.stdout + q.stderr
    except subprocess.TimeoutExpired:
        return 'TIMEOUT', ''


def outcome(rc, out):
    if rc == 'TIMEOUT':
        return 'TIMEOUT'
    if re.search(r'(^|\s)nan(\s|$)', out.lower()):
        return 'NAN'
    if rc == 0:
        return 'ran'
    if 'FOAM FATAL' in out:
        return 'stopped'
    return 'CRASH(rc=%s)' % rc


def fatalText(out):
    lines = out.splitlines()
    at = [k for k, l in enumerate(lines) if 'FOAM FATAL' in l]
    if not at:
        return ''
    return ' | '.join(l.strip() for l in lines[at[0] + 1:at[0] + 4] if l.strip())[:300]


def fieldDict(rng, small):
    """A createIceFieldDict; small: a field for a DEM run of seconds"""
    if small:
        L, W = rng.uniform(15, 80), rng.uniform(15, 80)
        x0, y0 = rng.choice([0, -L/2, 1000.5]), rng.choice([0, -W/2, -333.25])
        area = 'meanFloeArea %r;' % rng.uniform(5, 60)
        c = rng.choice([0.3, 0.6, 0.8, 0.9, 0.95])
        r = rng.choice([0.02, 0.05])
        h = rng.uniform(0.3, 1.5)
    else:
        L = 10**rng.uniform(0, 3.5)
        W = L*10**rng.uniform(-1.5, 1.5)
        x0 = rng.choice([0, -L/2, rng.uniform(-1e5, 1e5)])
        y0 = rng.choice([0, -W/2, rng.uniform(-1e5, 1e5)])
        if rng.random() < 0.5:
            area = 'nFloes %d;' % rng.choice([1, 2, 5, 100, 1000, rng.randint(1, 3000)])
        else:   # at most 2e4 floes: the DEM run after it stays short
            area = 'meanFloeArea %r;' % max(10**rng.uniform(-1, 5), L*W/2e4)
        c = rng.choice([0.999999, 0.9999, 0.999, 0.99, 0.9, 0.5, 0.1, 1e-3,
                        rng.uniform(0.01, 1)])
        r = 10**rng.uniform(-3, 0)
        h = 2*r*10**rng.uniform(0.01, 1.5)
    t = rng.random()
    if t < 0.5:
        thickness = '%r' % h
    elif t < 0.75:
        thickness = '{ distribution uniform; min %r; max %r; }' % (h, h*rng.uniform(1, 3))
    else:
        thickness = ('{ distribution normal; mean %r; standardDeviation %r; '
                     'min %r; max %r; }' % (1.5*h, h*rng.uniform(0, 1), h, h*rng.uniform(1.5, 3)))
    d = ['FoamFile { version 2.0; format ascii; class dictionary; object createIceFieldDict; }',
         'region { min (%r %r); max (%r %r); }' % (x0, y0, x0 + L, y0 + W), area,
         'concentration %r;' % c, 'thickness %s;' % thickness, 'radius %r;' % r,
         'seed %d;' % rng.randint(0, 1000), 'lloydIterations %d;' % rng.choice([0, 0, 1, 5]),
         'writeVTK no;', 'image { write no; }']
    if small:
        d.append('velocity (%g %g 0);' % (rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)))
    else:
        if rng.random() < 0.5:
            s = min(L, W)
            zones = ['z1 { type circle; centre (%r %r); radius %r; }'
                     % (x0 + L*rng.uniform(-0.2, 1.2), y0 + W*rng.uniform(-0.2, 1.2),
                        s*10**rng.uniform(-2, 0.5))]
            if rng.random() < 0.5:
                px, py, e = x0 + L*rng.random(), y0 + W*rng.random(), s*rng.uniform(0.01, 0.3)
                zones.append('z2 { type polygon; points ((%r %r) (%r %r) (%r %r) (%r %r)); }'
                             % (px, py, px + e, py, px + e, py + e*rng.uniform(0.1, 2), px, py + e))
            d.append('exclusionZones { %s }' % ' '.join(zones))
        if rng.random() < 0.2:
            d.append('minCoreEdgeRatio %r;' % rng.uniform(0, 10))
        if rng.random() < 0.2:
            d.append('minCoreWidthRatio %r;' % rng.uniform(2, 20))
        if rng.random() < 0.2:
            d.append('correctConcentration no;')
        if rng.random() < 0.3:
            d.append('maxCorrections %d;' % rng.choice([0, 1, 50, 200]))
    return '\n'.join(d) + '\n', L, W, x0, y0, h


def demCase(case, endTime, writeInterval, startFrom='startTime'):
    """The DEM base's controlDict with these times, a 0.02 s solver step"""
    c = open(os.path.join(BASES, 'dem', 'system', 'controlDict')).read()
    for key, value in (('endTime', endTime), ('deltaT', 0.02),
                       ('writeControl', 'runTime'), ('writeInterval', writeInterval),
                       ('startFrom', startFrom)):
        c = re.sub(r'\n%s\s+[^;]+;' % key, '\n%-16s%s;' % (key, value), c)
    open(os.path.join(case, 'system', 'controlDict'), 'w').write(c)


def demProperties(rng, L, W, x0, y0, h):
    p = open(os.path.join(BASES, 'dem', 'constant', 'iceDEMProperties')).read()
    p = re.sub(r'\nwalls\s*\{(?:[^{}]|\{[^{}]*\})*\}', '\n', p)
    for block in ('water', 'drag', 'wind', 'floeDamping', 'output'):
        p = re.sub(r'\n%s\s*\{[^{}]*\}' % block, '\n', p)
    p = p.replace('deltaT          5e-4;', 'deltaT          %g;' % rng.choice([2e-4, 5e-4, 1e-3]))
    p = p.replace('neighbourSkin   0.02;', 'neighbourSkin   %g;' % rng.choice([0.01, 0.05, 0.3]))
    p = p.replace('featureSkin     0.01;', 'featureSkin     %g;' % rng.choice([0, 0.005, 0.02]))
    p = p.replace('contactModel    hertz;',
                  'contactModel    %s;' % rng.choice(['hertz', 'hertzSimplified']))
    add = ['water { density 1025; level 0; }']
    if rng.random() < 0.8:
        a, u = rng.uniform(0, 2*math.pi), rng.choice([0, 0.1, 0.5, 1.5])
        add.append('drag { type empirical; current (%g %g 0); integration %s; subdivision %d; }'
                   % (u*math.cos(a), u*math.sin(a), rng.choice(['exact', 'exact', 'sampled']),
                      rng.randint(0, 2)))
    if rng.random() < 0.6:
        a, u = rng.uniform(0, 2*math.pi), rng.choice([5, 15, 30])
        if rng.random() < 0.5:
            add.append('wind { type uniform; velocity (%g %g 0); }' % (u*math.cos(a), u*math.sin(a)))
        else:
            add.append('wind { type table; table ((0 (%g %g 0)) (1 (%g %g 0)) (2.5 (0 %g 0))); }'
                       % (u*math.cos(a), u*math.sin(a), -u, 0.3*u, u))
    if rng.random() < 0.3:
        add.append('floeDamping { heave %g; rollPitch %g; }'
                   % (rng.choice([0, 0.1, 1]), rng.choice([0, 0.1, 1])))
    add.append('bodyForceInterval %d;' % rng.choice([1, 1, 2, 3, 5]))
    domain = rng.choice(['none', 'periodic', 'periodicX', 'inflow'])
    if domain == 'periodic':
        add.append('domain { type periodic; x (%r %r); y (%r %r); }' % (x0, x0 + L, y0, y0 + W))
    elif domain == 'periodicX':
        add.append('domain { type periodic; x (%r %r); }' % (x0, x0 + L))
    elif domain == 'inflow':
        add.append('domain { type inflowOutflow; direction x; upstream %r; downstream %r; '
                   'stripWidth %r; interval %g; material ice; fieldDict "system/createIceFieldDict"; '
                   'sides %s; }' % (x0, x0 + L, L/rng.choice([3, 5, 8]), rng.choice([0.2, 1]),
                                    rng.choice(['open', 'periodic'])))
    if rng.random() < 0.3:
        add.append('walls { floor { point (0 0 %g); normal (0 0 1); material steel; } }'
                   % (-h - rng.uniform(0.5, 3)))
    add.append('output { precision 12; vtk false; }')
    return p + '\n' + '\n'.join(add) + '\n'


def stateOf(case, time):
    """The DEM state at time, its 'step' line (the run's own count) out"""
    f = os.path.join(case, time, 'uniform', 'iceDEMState')
    if not os.path.exists(f):
        return None
    lines = [l for l in open(f, 'rb').read().split(b'\n') if not l.startswith(b'step ')]
    return hashlib.md5(b'\n'.join(lines)).hexdigest()[:16]


def newCase(name):
    case = os.path.join(SCRATCH, name)
    shutil.rmtree(case, ignore_errors=True)
    os.makedirs(os.path.join(case, 'system'))
    os.makedirs(os.path.join(case, 'constant'))
    return case


def fieldCase(i):
    rng = random.Random(i)
    case = newCase('field%d' % i)
    text = fieldDict(rng, small=False)[0]
    open(os.path.join(case, 'system', 'createIceFieldDict'), 'w').write(text)
    for f in ('constant/iceDEMProperties', 'system/controlDict'):
        shutil.copy(os.path.join(BASES, 'dem', f), os.path.join(case, f))
    shutil.copy(GRAVITY, os.path.join(case, 'constant', 'g'))
    rc, out = run(['createIceField'], case)
    kind, note = outcome(rc, out), fatalText(out)
    if kind == 'ran':
        rc, out = run(['iceDEMFoam'], case)
        kind, note = 'field ' + outcome(rc, out), fatalText(out)
    return case, kind, note


def demCaseRun(i):
    rng = random.Random(i)
    case = newCase('dem%d' % i)
    text, L, W, x0, y0, h = fieldDict(rng, small=True)
    open(os.path.join(case, 'system', 'createIceFieldDict'), 'w').write(text)
    open(os.path.join(case, 'constant', 'iceDEMProperties'), 'w').write(
        demProperties(rng, L, W, x0, y0, h))
    shutil.copy(GRAVITY, os.path.join(case, 'constant', 'g'))
    demCase(case, 2, 1)
    rc, out = run(['createIceField'], case)
    if rc != 0:
        return case, 'field ' + outcome(rc, out), fatalText(out)
    two, split = case + '_2threads', case + '_restart'
    for c in (two, split):
        shutil.rmtree(c, ignore_errors=True)
        shutil.copytree(case, c)
    one = dict(os.environ, OMP_NUM_THREADS='1')
    rc, out = run(['iceDEMFoam'], case, one)
    kind, note = outcome(rc, out), fatalText(out)
    if kind != 'ran':
        return case, kind, note
    run(['iceDEMFoam'], two, dict(os.environ, OMP_NUM_THREADS='2'))
    demCase(split, 1, 1)
    run(['iceDEMFoam'], split, one)
    demCase(split, 2, 1, 'latestTime')
    run(['iceDEMFoam'], split, one)
    states = [stateOf(c, '2') for c in (case, two, split)]
    if states[0] is None or len(set(states)) != 1:
        return case, 'INVARIANT', '1 thread %s, 2 threads %s, restarted %s' % tuple(states)
    for c in (two, split):
        shutil.rmtree(c, ignore_errors=True)
    return case, 'ran, 1 = 2 threads = restart', ''


def structureCase(i):
    rng = random.Random(i)
    case = os.path.join(SCRATCH, 'structure%d' % i)
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(os.path.join(BASES, 'noflow'), case)
    n = rng.randint(2, 6)
    H = rng.uniform(0.2, 3)
    heights = [0.0] + sorted(rng.uniform(0, H) for _ in range(n - 2)) + [H]
    if rng.random() < 0.15:
        heights[1] = heights[0]
    diameters = [rng.uniform(0.05, 4.5) for _ in range(n)]
    text = ('FoamFile { version 2.0; format ascii; class dictionary; object structureDict; }\n'
            'type facetedHull;\nwater { density 1025; level 0; }\n'
            'facetedHull { position (%r %r); nFacets %d; diameters %s; draft %r; profile (%s); }\n'
            % (rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3),
               rng.choice([3, 4, 5, 8, 24, 64, rng.randint(3, 40)]),
               rng.choice(['corners', 'flats']), rng.uniform(0.05, 1.2*H),
               ' '.join('(%r %r)' % p for p in zip(heights, diameters))))
    open(os.path.join(case, 'constant', 'structureDict'), 'w').write(text)
    rc, out = run(['createStructure'], case)
    kind, note = outcome(rc, out), fatalText(out)
    if kind == 'ran':
        rc, out = run(['iceFloatingFoam', '-noFlow'], case)
        kind, note = 'structure ' + outcome(rc, out), fatalText(out)
    return case, kind, note


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in ('field', 'dem', 'structure'):
        print(__doc__)
        sys.exit(1)
    what, n = sys.argv[1], int(sys.argv[2])
    first = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    one = {'field': fieldCase, 'dem': demCaseRun, 'structure': structureCase}[what]
    counts = {}
    for i in range(first, first + n):
        case, kind, note = one(i)
        counts[kind] = counts.get(kind, 0) + 1
        bad = any(k in kind for k in ('TIMEOUT', 'NAN', 'CRASH', 'INVARIANT'))
        if bad:
            print('%s %d: %s %s (left in %s)' % (what, i, kind, note, case))
        else:
            print('%s %d: %s %s' % (what, i, kind, note))
            for c in (case, case + '_2threads', case + '_restart'):
                shutil.rmtree(c, ignore_errors=True)
        sys.stdout.flush()
    print('outcomes: ' + ', '.join('%s %d' % kv for kv in sorted(counts.items())))


if __name__ == '__main__':
    main()
