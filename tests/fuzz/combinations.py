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
      field (step, skins, contact model and its damping, current, uniform or table wind,
      floe damping, bodyForceInterval, no domain, periodic, inflow, floor),
      2 s, run with 1 and 2 threads and restarted at 1 s: the three DEM
      states at 2 s must be identical (the 'step' line excepted)
  combinations.py structure N [FIRST]  random facetedHull profiles run on by
      iceFloatingFoam -noFlow
  combinations.py coupled N [FIRST]    random iceFloatingFoam settings with
      the flow on a coarse mesh of tutorials/iceFloatingFoam/floeApproach
      (a few floes, resolved or empirical drag, sampling, interpolation,
      two-way, wind, floe damping, bodyForceInterval, periodic DEM domain,
      the flow every 1-3 steps, outer correctors, correctPhi;
      the box hull fixed, free on sixDoFRigidBodyMotion or on the rigid
      lid, with hydrostatics, a spread mooring and wind on it), 2 s, run
      with 1 and 2 threads and restarted at 1 s (binary writes): the DEM
      state, the structure's state, the flow's U and the ice load from 1 s
      on must be identical; a third of them also on 2 ranks, uninterrupted
      and restarted at 1 s, identical on each rank
  combinations.py noflow N [FIRST]     random DEM-only studies as kullukPack
      runs them (iceFloatingFoam -noFlow): a createIceField pack around the
      moored structure (concentration, thickness, floe size, velocity), the
      DEM's step, K, contact model and its damping, current, wind (uniform or table), floe
      damping, periodic in x and y, in x, none or inflow/outflow; the 2 m
      box or a random facetedHull inside it, free or held to the plane,
      moored by 3-12 lines of 1e3-1e8 N/m damped by 10-1e5 N s/m, with wind on it; the
      structure's step (0.01-0.5 s); the load statistics and clearance
      function objects.
      2 s with 1 and 2 threads and restarted at 1 s: the DEM state, the
      structure's state, the ice load and the statistics' samples after 1 s
      must be identical

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
# The fields here are small: every loop of the DEM on the threads anyway,
# so that 1 thread = 2 threads compares the threaded path (below the
# default cut-off of 256 bodies or pairs a world steps on one thread)
THREADED = '\nsingleThreadBelow 0;\n'


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
                  'contactModel    %s;\nnormalDamping   %s;'
                  % (rng.choice(['hertz', 'hertzSimplified']), rng.choice(['perContact', 'perPair'])))
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


def digest(data):
    return hashlib.md5(data).hexdigest()[:16]


def fileDigest(path):
    """The file's digest, None when it is missing"""
    return digest(open(path, 'rb').read()) if os.path.exists(path) else None


def stateOf(case, time):
    """The DEM state at time, its 'step' line (the run's own count) out"""
    f = os.path.join(case, time, 'uniform', 'iceDEMState')
    if not os.path.exists(f):
        return None
    lines = [l for l in open(f, 'rb').read().split(b'\n') if not l.startswith(b'step ')]
    return digest(b'\n'.join(lines))


def samplesAfter(case, function, name, time=1):
    """The digest of the rows after time of postProcessing/<function>/<start>/
    <name> (start 0, and 1 for a run restarted there), None without rows"""
    rows = []
    for d in ('0', '1'):
        p = os.path.join(case, 'postProcessing', function, d, name)
        if os.path.exists(p):
            rows += [l for l in open(p) if l.strip() and not l.startswith('#')
                     and float(l.split()[0]) > time + 1e-9]
    return digest(''.join(rows).encode()) if rows else None


def resultsAt(case, time, files, samples):
    """The DEM state at time, the digests of the time's files and those of
    the samples after 1 s ((function, file) pairs)"""
    return tuple([stateOf(case, time)]
                 + [fileDigest(os.path.join(case, time, f)) for f in files]
                 + [samplesAfter(case, fn, name) for fn, name in samples])


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


def invariantRuns(case, app, setEnd, results):
    """Run case with 1 thread to 2 s, a copy with 2 threads, and a copy
    stopped at 1 s and restarted (setEnd(copy, endTime, startFrom) edits its
    controlDict); results(case) of the three must agree. Returns (kind,
    note) and removes the copies when they agree"""
    two, split = case + '_2threads', case + '_restart'
    for c in (two, split):
        shutil.rmtree(c, ignore_errors=True)
        shutil.copytree(case, c)
    cmd = app if isinstance(app, list) else [app]
    one = dict(os.environ, OMP_NUM_THREADS='1')
    rc, out = run(cmd, case, one)
    kind, note = outcome(rc, out), fatalText(out)
    if kind != 'ran':
        return kind, note
    run(cmd, two, dict(os.environ, OMP_NUM_THREADS='2'))
    setEnd(split, 1, 'startTime')
    run(cmd, split, one)
    setEnd(split, 2, 'latestTime')
    run(cmd, split, one)
    found = [results(c) for c in (case, two, split)]
    if found[0] is None or (isinstance(found[0], tuple) and None in found[0]) \
            or len(set(found)) != 1:
        return 'INVARIANT', '1 thread %s, 2 threads %s, restarted %s' % tuple(found)
    for c in (two, split):
        shutil.rmtree(c, ignore_errors=True)
    return 'ran, 1 = 2 threads = restart', ''


def demCaseRun(i):
    rng = random.Random(i)
    case = newCase('dem%d' % i)
    text, L, W, x0, y0, h = fieldDict(rng, small=True)
    open(os.path.join(case, 'system', 'createIceFieldDict'), 'w').write(text)
    open(os.path.join(case, 'constant', 'iceDEMProperties'), 'w').write(
        demProperties(rng, L, W, x0, y0, h) + THREADED)
    shutil.copy(GRAVITY, os.path.join(case, 'constant', 'g'))
    demCase(case, 2, 1)
    rc, out = run(['createIceField'], case)
    if rc != 0:
        return case, 'field ' + outcome(rc, out), fatalText(out)
    kind, note = invariantRuns(case, 'iceDEMFoam',
                               lambda c, end, start: demCase(c, end, 1, start),
                               lambda c: stateOf(c, '2'))
    return case, kind, note


def facetedHullDict(rng, largestDiameter, offset):
    """A random facetedHull structureDict: 2-6 profile points up to 3 m high
    (a flat step now and then), diameters up to largestDiameter, the draft
    up to 1.2 times the height (a hull that would sink), the centre within
    offset of the origin"""
    n = rng.randint(2, 6)
    H = rng.uniform(0.2, 3)
    heights = [0.0] + sorted(rng.uniform(0, H) for _ in range(n - 2)) + [H]
    if rng.random() < 0.15:
        heights[1] = heights[0]
    diameters = [rng.uniform(0.05, largestDiameter) for _ in range(n)]
    return ('FoamFile { version 2.0; format ascii; class dictionary; object structureDict; }\n'
            'type facetedHull;\nwater { density 1025; level 0; }\n'
            'facetedHull { position (%r %r); nFacets %d; diameters %s; draft %r; profile (%s); }\n'
            % (rng.uniform(-offset, offset), rng.uniform(-offset, offset),
               rng.choice([3, 4, 5, 8, 24, 64, rng.randint(3, 40)]),
               rng.choice(['corners', 'flats']), rng.uniform(0.05, 1.2*H),
               ' '.join('(%r %r)' % p for p in zip(heights, diameters))))


def structureCase(i):
    rng = random.Random(i)
    case = os.path.join(SCRATCH, 'structure%d' % i)
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(os.path.join(BASES, 'noflow'), case)
    open(os.path.join(case, 'constant', 'structureDict'), 'w').write(
        facetedHullDict(rng, 4.5, 0.3))
    rc, out = run(['createStructure'], case)
    kind, note = outcome(rc, out), fatalText(out)
    if kind == 'ran':
        rc, out = run(['iceFloatingFoam', '-noFlow'], case)
        kind, note = 'structure ' + outcome(rc, out), fatalText(out)
    return case, kind, note


COUPLED_TUTORIAL = os.path.join(ROOT, 'tutorials', 'iceFloatingFoam', 'floeApproach')


def coupledBase():
    """The tutorial floeApproach on a coarse mesh (24 x 12 x 4 cells before
    the hull is cut out), set up once per invocation"""
    base = os.path.join(SCRATCH, 'coupledBase')
    if os.path.exists(os.path.join(base, 'constant', 'polyMesh', 'owner')):
        return base
    shutil.rmtree(base, ignore_errors=True)
    shutil.copytree(COUPLED_TUTORIAL, base)
    for f in ('Allrun', 'Allclean'):
        os.remove(os.path.join(base, f))
    shutil.copytree(os.path.join(base, '0.orig'), os.path.join(base, '0'))
    mesh = os.path.join(base, 'system', 'blockMeshDict')
    text = open(mesh).read()
    assert '(48 24 6)' in text
    open(mesh, 'w').write(text.replace('(48 24 6)', '(24 12 4)'))
    for cmd in (['createStructure'], ['blockMesh'], ['topoSet'],
                ['subsetMesh', 'fluid', '-patch', 'hull', '-overwrite']):
        rc, out = run(cmd, base)
        if rc != 0:
            sys.exit('the coupled base does not set up (%s):\n%s' % (cmd[0], out[-2000:]))
    for d in ('constant/polyMesh/sets', '0/cellLevel', '0/pointLevel'):
        p = os.path.join(base, d)
        shutil.rmtree(p) if os.path.isdir(p) else (os.path.exists(p) and os.remove(p))
    return base


def coupledIceField(rng):
    """1 to 10 prisms on a grid of cells upstream of and beside the hull
    (the box [-1, 1] x [-1, 1]; the nearest 0.2 m from it); the hull's 2 cm
    radius"""
    h = rng.choice([0.15, 0.25, 0.4])
    cells = [(x, y) for x in (-4.6, -3.6, -2.6, -1.65) for y in (-2.2, -1.1, 0.0, 1.1, 2.2)]
    cells += [(x, y) for x in (-0.6, 0.6, 1.8, 3.0) for y in (-2.2, 2.2)]
    rng.shuffle(cells)
    bodies = []
    for k, (x, y) in enumerate(cells[:rng.randint(1, 10)]):
        n = rng.choice([3, 4, 5, 6])
        a0, R = rng.uniform(0, 2*math.pi), rng.uniform(0.2, 0.45)
        outline = ' '.join('(%r %r)' % (x + R*math.cos(a0 + 2*math.pi*j/n),
                                         y + R*math.sin(a0 + 2*math.pi*j/n)) for j in range(n))
        bodies.append('floe%d { type prism; outline (%s); zBottom %r; thickness %r; '
                      'radius 0.02; material ice; velocity (%r %r 0); }'
                      % (k, outline, -h*900/1025*rng.uniform(0.8, 1.2), h,
                         rng.uniform(0, 0.6), rng.uniform(-0.2, 0.2)))
    return ('FoamFile { version 2.0; format ascii; class dictionary; object iceField; }\n'
            'bodies\n{\n    %s\n}\n' % '\n    '.join(bodies))


def coupledProperties(rng, base):
    p = open(os.path.join(base, 'constant', 'iceDEMProperties')).read()
    p = re.sub(r'\ndrag\s*\{[^{}]*\}', '\n', p)
    p = re.sub(r'\noutput\s*\{[^{}]*\}', '\n', p)
    p = re.sub(r'\ndeltaT\s+[^;]+;', '\ndeltaT %g;' % rng.choice([2.5e-4, 5e-4, 5e-4, 1e-3]), p)
    p = p.replace('iceSteel {', 'iceIce { materials (ice ice); friction 0.2; restitution 0.3; }\n'
                  '    iceSteel {')
    u = rng.choice([0, 0.1, 0.3, 0.6])
    if rng.random() < 0.7:
        drag = ('drag { type resolved; U U; current (%g 0 0); sampling %s; interpolation %s; '
                'twoWay %s; subdivision %d; }'
                % (u, rng.choice(['flowStep', 'demStep']), rng.choice(['cellGradient', 'cellPoint']),
                   rng.choice(['true', 'false']), rng.randint(0, 2)))
    else:
        drag = 'drag { type empirical; current (%g 0 0); subdivision %d; }' % (u, rng.randint(0, 2))
    add = [drag]
    if rng.random() < 0.5:
        a, w = rng.uniform(0, 2*math.pi), rng.choice([5, 15, 30])
        add.append('wind { type uniform; velocity (%g %g 0); }' % (w*math.cos(a), w*math.sin(a)))
    if rng.random() < 0.3:
        add.append('floeDamping { heave %g; rollPitch %g; }'
                   % (rng.choice([0, 0.1, 1]), rng.choice([0, 0.1, 1])))
    add.append('bodyForceInterval %d;' % rng.choice([1, 1, 2, 3]))
    if rng.random() < 0.25:
        add.append('domain { type periodic; x (-6 6); }')
    add.append('output { precision 12; vtk false; }')
    return p + '\n' + '\n'.join(add) + '\n'


def coupledMotion(rng):
    """The hull fixed (the tutorial), free on sixDoFRigidBodyMotion or free
    on the rigid lid, with a random set of restraints"""
    motion = rng.choice(['fixed', 'sixDoF', 'rigidLid'])
    restraints = ['ice { sixDoFRigidBodyMotionRestraint iceLoad; }']
    constraints = ''
    if motion == 'fixed':
        constraints = ('fixedPoint { sixDoFRigidBodyMotionConstraint point; } '
                       'fixedOrientation { sixDoFRigidBodyMotionConstraint orientation; }')
        solver = 'symplectic'
    else:
        solver = ('rigidLidSymplectic; heave { addedMass %g; linearDamping %g; } '
                  'roll { addedMass %g; linearDamping %g; } pitch { addedMass %g; linearDamping %g; }'
                  % tuple(rng.choice([0, 1, 100]) for _ in range(6)))
        restraints.append('hydrostatics { sixDoFRigidBodyMotionRestraint hullHydrostatics; }')
        if motion == 'sixDoF' and rng.random() < 0.7:
            # held in the plane (the stock solver under the lid must be)
            constraints = ('horizontal { sixDoFRigidBodyMotionConstraint plane; normal (0 0 1); } '
                           'yawOnly { sixDoFRigidBodyMotionConstraint axis; axis (0 0 1); }')
        if rng.random() < 0.7:
            restraints.append(
                'mooring { sixDoFRigidBodyMotionRestraint spreadMooring; spread { nLines %d; '
                'startAngle %g; anchorRadius %g; anchorZ %g; fairleadRadius 1; fairleadZ -0.25; '
                'stiffness %g; damping %g; pretension %g; } }'
                % (rng.choice([3, 4, 8, 12]), rng.uniform(0, 90), rng.uniform(3, 30),
                   rng.uniform(-1.5, 0), rng.choice([1e2, 1e3, 1e4, 1e5]),
                   rng.choice([0, 10, 1e3]), rng.choice([0, 10, 200])))
        if rng.random() < 0.5:
            restraints.append(
                'wind { sixDoFRigidBodyMotionRestraint windLoad; type uniform; velocity (%g %g 0); '
                'rhoAir 1.3; Cd 1; area 2; centreOfPressure (0 0 0.5); }'
                % (rng.uniform(-20, 20), rng.uniform(-20, 20)))
    name = 'rigidLidSixDoFRigidBodyMotion' if motion == 'rigidLid' else 'sixDoFRigidBodyMotion'
    return motion, (
        'FoamFile { version 2.0; format ascii; class dictionary; object dynamicMeshDict; }\n'
        'dynamicFvMesh dynamicMotionSolverFvMesh;\nmotionSolverLibs (sixDoFRigidBodyMotion);\n'
        'motionSolver %s;\n%sCoeffs\n{\n    patches (hull);\n    innerDistance 0.3;\n'
        '    outerDistance 1.0;\n    #include "hullMassProperties"\n    rho rhoInf;\n'
        '    rhoInf 1025;\n    report off;\n    solver { type %s; }\n'
        '    constraints { %s }\n    restraints { %s }\n}\n'
        % (name, name, solver, constraints, ' '.join(restraints)))


def coupledControl(case, endTime, startFrom, flowStep):
    c = open(os.path.join(COUPLED_TUTORIAL, 'system', 'controlDict')).read()
    for key, value in (('endTime', endTime), ('deltaT', flowStep), ('writeInterval', 1),
                       ('startFrom', startFrom), ('writeFormat', 'binary')):
        c = re.sub(r'\n%s\s+[^;]+;' % key, '\n%-16s%s;' % (key, value), c)
    open(os.path.join(case, 'system', 'controlDict'), 'w').write(c)


def coupledPimple(rng, case):
    """PIMPLE: the flow solved every 1-3 steps, 1-2 outer correctors, the
    mesh moved in each of them or not, correctPhi on or off"""
    p = os.path.join(case, 'system', 'fvSolution')
    s = open(p).read()
    entries = ('nOuterCorrectors %d; moveMeshOuterCorrectors %s; flowSolveInterval %d; '
               'correctPhi %s;' % (rng.choice([1, 1, 2]), rng.choice(['no', 'no', 'yes']),
                                  rng.choice([1, 1, 2, 3]), rng.choice(['yes', 'yes', 'no'])))
    s = re.sub(r'\n\s*(nOuterCorrectors|correctPhi|moveMeshOuterCorrectors|flowSolveInterval)'
               r'\s+[^;]+;', '', s)
    s, n = re.subn(r'\nPIMPLE\s*\{', '\nPIMPLE\n{\n    ' + entries, s)
    assert n == 1
    open(p, 'w').write(s)


def coupledResults(case):
    """The states at 2 s (DEM without its 'step' line, the structure, U)
    and the ice load's rows after 1 s"""
    return resultsAt(case, '2', ('uniform/sixDoFRigidBodyMotionState', 'U'),
                     (('iceLoad', 'iceLoad.dat'),))


def parallelRestart(case, endTime):
    """The case on 2 ranks (its decomposeParDict), 0 -> endTime and
    restarted at half of it: (kind, note), every processor's DEM state,
    structure state and U at endTime identical"""
    env = dict(os.environ, OMP_NUM_THREADS='1', OMPI_ALLOW_RUN_AS_ROOT='1',
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM='1')
    par = ['mpirun', '-np', '2', 'iceFloatingFoam', '-parallel']
    found = []
    for name, stops in (('_par', [endTime]), ('_parRestart', [endTime/2, endTime])):
        c = case + name
        shutil.rmtree(c, ignore_errors=True)
        os.makedirs(c)
        for d in ('0', 'constant', 'system'):
            shutil.copytree(os.path.join(case, d), os.path.join(c, d))
        run(['decomposePar'], c, env)
        for k, stop in enumerate(stops):
            text = open(os.path.join(c, 'system', 'controlDict')).read()
            text = re.sub(r'\nendTime\s+[^;]+;', '\nendTime %g;' % stop, text)
            text = re.sub(r'\nstartFrom\s+[^;]+;', '\nstartFrom %s;'
                          % ('latestTime' if k else 'startTime'), text)
            open(os.path.join(c, 'system', 'controlDict'), 'w').write(text)
            rc, out = run(par, c, env)
            kind = outcome(rc, out)
            if kind != 'ran':
                return '2 ranks ' + kind, fatalText(out)
        found.append(sum((resultsAt(os.path.join(c, proc), '%g' % endTime,
                                    ('uniform/sixDoFRigidBodyMotionState', 'U'), ())
                          for proc in ('processor0', 'processor1')), ()))
    if None in found[0] or found[0] != found[1]:
        return 'INVARIANT 2 ranks', 'uninterrupted %s, restarted %s' % tuple(found)
    for name in ('_par', '_parRestart'):
        shutil.rmtree(case + name, ignore_errors=True)
    return 'ran, 2 ranks = 2 ranks restarted', ''


def coupledCase(i):
    rng = random.Random(i)
    base = coupledBase()
    case = os.path.join(SCRATCH, 'coupled%d' % i)
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(base, case)
    open(os.path.join(case, 'constant', 'iceField'), 'w').write(coupledIceField(rng))
    open(os.path.join(case, 'constant', 'iceDEMProperties'), 'w').write(
        coupledProperties(rng, base) + THREADED)
    motion, text = coupledMotion(rng)
    open(os.path.join(case, 'constant', 'dynamicMeshDict'), 'w').write(text)
    flowStep = rng.choice([0.05, 0.1, 0.2])
    coupledControl(case, 2, 'startTime', flowStep)
    coupledPimple(rng, case)
    kind, note = invariantRuns(case, 'iceFloatingFoam',
                               lambda c, end, start: coupledControl(c, end, start, flowStep),
                               coupledResults)
    if kind.startswith('ran') and rng.random() < 0.3:
        kind2, note2 = parallelRestart(case, 2)
        if not kind2.startswith('ran'):
            kind, note = kind2, note2
        else:
            kind += '; ' + kind2
    return case, '%s (%s)' % (kind, motion), note or structureContactNote(case)


NOFLOW_BASE = os.path.join(BASES, 'noflow')


def noflowField(rng, half):
    """A createIceFieldDict for the periodic box [-half, half]^2 around the
    2 m box structure at the origin"""
    c = rng.choice([0.6, 0.8, 0.9])
    h = rng.choice([0.2, 0.3, 0.5])
    u = rng.uniform(0.3, 0.8)
    return '\n'.join([
        'FoamFile { version 2.0; format ascii; class dictionary; object createIceFieldDict; }',
        'region { min (%r %r); max (%r %r); }' % (-half, -half, half, half),
        'meanFloeArea %r;' % rng.choice([1.0, 2.0, 4.0]),
        'concentration %r;' % c, 'thickness %r;' % h, 'radius 0.02;',
        'seed %d;' % rng.randint(0, 1000), 'lloydIterations 1;', 'writeVTK no;',
        'image { write no; }', 'velocity (%r 0 0);' % u,
        'exclusionZones { hull { type polygon; points ((-1.3 -1.3) (1.3 -1.3) (1.3 1.3) (-1.3 1.3)); } }'
    ]) + '\n'


def noflowProperties(rng, half):
    p = open(os.path.join(NOFLOW_BASE, 'constant', 'iceDEMProperties')).read()
    for block in ('drag', 'wind', 'domain'):
        p = re.sub(r'\n%s\s*\{(?:[^{}]|\{[^{}]*\})*\}' % block, '\n', p)
    p = re.sub(r'\ndeltaT\s+[^;]+;', '\ndeltaT %g;' % rng.choice([5e-4, 1e-3]), p)
    p = re.sub(r'\ncontactModel\s+[^;]+;',
               '\ncontactModel %s;\nnormalDamping %s;'
               % (rng.choice(['hertz', 'hertzSimplified']), rng.choice(['perContact', 'perPair'])), p)
    p = p.replace('iceSteel {', 'iceIce { materials (ice ice); friction 0.2; restitution 0.3; }\n'
                  '    iceSteel {')
    add = ['drag { type empirical; current (%g %g 0); }'
           % (rng.choice([0, 0.3, 0.6]), rng.uniform(-0.1, 0.1))]
    w = rng.random()
    if w < 0.4:
        add.append('wind { type uniform; velocity (%g %g 0); }'
                   % (rng.uniform(0, 20), rng.uniform(-5, 5)))
    elif w < 0.7:
        add.append('wind { type table; table ((0 (10 0 0)) (1 (5 5 0)) (2 (15 -5 0))); }')
    if rng.random() < 0.3:
        add.append('floeDamping { heave 0.1; rollPitch 0.1; }')
    add.append('bodyForceInterval %d;' % rng.choice([1, 1, 2, 3]))
    d = rng.choice(['xy', 'x', 'none', 'inflow'])
    if d == 'xy':
        add.append('domain { type periodic; x (%r %r); y (%r %r); }' % (-half, half, -half, half))
    elif d == 'x':
        add.append('domain { type periodic; x (%r %r); }' % (-half, half))
    elif d == 'inflow':
        add.append('domain { type inflowOutflow; direction x; upstream %r; downstream %r; '
                   'stripWidth %r; interval %g; material ice; '
                   'fieldDict "system/createIceFieldDict"; sides %s; }'
                   % (-half, half, half/rng.choice([2, 3]), rng.choice([0.2, 1]),
                      rng.choice(['open', 'periodic'])))
    return p + '\n' + '\n'.join(add) + '\n'


def noflowMotion(rng):
    p = open(os.path.join(NOFLOW_BASE, 'constant', 'dynamicMeshDict')).read()
    p = re.sub(r'nLines\s+[^;]+;', 'nLines %d;' % rng.choice([3, 4, 8, 12]), p)
    p = re.sub(r'stiffness\s+[^;]+;', 'stiffness %g;' % rng.choice([1e3, 1e4, 1e5, 1e8]), p)
    p = re.sub(r'startAngle\s+[^;]+;', 'startAngle %g;' % rng.uniform(0, 90), p)
    p = re.sub(r'\n(\s+)damping\s+[^;]+;', r'\n\1damping %g;' % rng.choice([10, 1e3, 1e5]), p)
    p = re.sub(r'(windLoad;\s*type\s+uniform;\s*)velocity\s+[^;]+;',
               r'\1velocity (%g %g 0);' % (rng.uniform(-20, 20), rng.uniform(-20, 20)), p)
    if rng.random() < 0.5:
        p = p.replace('    restraints\n', '    constraints\n    {\n'
                      '        horizontal { sixDoFRigidBodyMotionConstraint plane; normal (0 0 1); }\n'
                      '        yawOnly { sixDoFRigidBodyMotionConstraint axis; axis (0 0 1); }\n'
                      '    }\n    restraints\n', 1)
    return p


def noflowControl(case, endTime, startFrom, step, transient, batches):
    c = open(os.path.join(NOFLOW_BASE, 'system', 'controlDict')).read()
    c = re.sub(r'\n\s*stopAtHalfWidth\s+[^;]+;', '', c)   # the base's stops at once
    for key, value in (('endTime', endTime), ('deltaT', step), ('writeControl', 'runTime'),
                       ('writeInterval', 1), ('startFrom', startFrom), ('timeEnd', 10),
                       ('transient', transient), ('batches', batches)):
        c, n = re.subn(r'\n(\s*)%s\s+[^;]+;' % key, r'\n\g<1>%-16s%s;' % (key, value), c)
        if n == 0:
            c = c.replace('\nstopAt', '\n%s %s;\nstopAt' % (key, value), 1)
    open(os.path.join(case, 'system', 'controlDict'), 'w').write(c)


def noflowResults(case):
    """The states at 2 s (DEM without its 'step' line, the structure), the ice
    load's and the statistics' samples after 1 s"""
    return resultsAt(case, '2', ('uniform/sixDoFRigidBodyMotionState',),
                     (('iceLoad', 'iceLoad.dat'), ('loads', 'series.dat')))


def structureContactNote(case):
    """How many steps of the uninterrupted run had ice on the structure"""
    f = os.path.join(case, 'postProcessing', 'iceLoad', '0', 'iceLoad.dat')
    if not os.path.exists(f):
        return ''
    rows = [l.split() for l in open(f) if l.strip() and not l.startswith('#')]
    return '(ice on the structure in %d of %d steps)' % (sum(int(r[7]) > 0 for r in rows),
                                                         len(rows))


def noflowCase(i):
    rng = random.Random(i)
    case = os.path.join(SCRATCH, 'noflow%d' % i)
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(NOFLOW_BASE, case)
    os.remove(os.path.join(case, 'constant', 'iceField'))   # createIceField's
    half = rng.choice([6.0, 10.0])
    open(os.path.join(case, 'system', 'createIceFieldDict'), 'w').write(noflowField(rng, half))
    open(os.path.join(case, 'constant', 'iceDEMProperties'), 'w').write(
        noflowProperties(rng, half) + THREADED)
    open(os.path.join(case, 'constant', 'dynamicMeshDict'), 'w').write(noflowMotion(rng))
    if rng.random() < 0.5:
        # a faceted hull (a cone, a column, a cone on a column ...) instead
        # of the box, inside the field's exclusion square at +-1.3 m
        open(os.path.join(case, 'constant', 'structureDict'), 'w').write(
            facetedHullDict(rng, 2.4, 0.05))
    # the structure's step: a few long enough for the vertical modes' check
    step, transient, batches = rng.choice([0.01, 0.02, 0.05, 0.5]), rng.choice([0, 0.5]), \
        rng.choice([2, 5])
    setEnd = lambda c, end, start: noflowControl(c, end, start, step, transient, batches)
    setEnd(case, 2, 'startTime')
    for cmd in (['createStructure'], ['createIceField']):
        rc, out = run(cmd, case)
        if rc != 0:
            return case, '%s %s' % (cmd[0], outcome(rc, out)), fatalText(out)
    kind, note = invariantRuns(case, ['iceFloatingFoam', '-noFlow'], setEnd, noflowResults)
    return case, kind, note or structureContactNote(case)


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in ('field', 'dem', 'structure', 'coupled', 'noflow'):
        print(__doc__)
        sys.exit(1)
    what, n = sys.argv[1], int(sys.argv[2])
    first = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    one = {'field': fieldCase, 'dem': demCaseRun, 'structure': structureCase,
           'coupled': coupledCase, 'noflow': noflowCase}[what]
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
