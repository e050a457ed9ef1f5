#------------------------------------------------------------------------------
# iceDEM case tests: what the Python checks of the case tests share (import it
# from a case's check.py with tests/cases on sys.path).
# Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
#------------------------------------------------------------------------------
"""Checks printed as ok/FAIL, ascii OpenFOAM fields, the two-way log lines."""
import re

VEC = r'\(([^()]*)\)'

_allPassed = [True]


def check(cond, msg):
    """Print 'ok:' or 'FAIL:' with msg; a failure is remembered for allPassed()."""
    print(("ok:   " if cond else "FAIL: ") + msg)
    _allPassed[0] = _allPassed[0] and bool(cond)


def allPassed():
    return _allPassed[0]


def mag(a):
    return sum(x*x for x in a)**0.5


def internal(path):
    """The internalField of an ascii OpenFOAM field: ('uniform', text) or
    ('nonuniform', list of floats or of tuples)."""
    txt = open(path).read()
    m = re.search(r'internalField\s+(uniform|nonuniform)', txt)
    rest = txt[m.end():]
    if m.group(1) == 'uniform':
        return 'uniform', rest.split(';')[0].strip()
    m2 = re.search(r'(\d+)\s*\(', rest)
    n = int(m2.group(1))
    body = rest[m2.end():]
    if body.lstrip().startswith('('):
        return 'nonuniform', [tuple(map(float, x.split())) for x in re.findall(VEC, body)[:n]]
    return 'nonuniform', [float(x) for x in body.split(')')[0].split()][:n]


def twoWaySteps(lines):
    """Per time step of an iceFloatingFoam log (lines) with two-way drag:
    (floes' drag impulse, fluid source impulse, relative imbalance, lost)."""
    out = {}
    t = None
    for line in lines:
        m = re.match(r'^Time = (\S+)', line)
        if m:
            t = round(float(m.group(1)), 9)
        if 'relative imbalance' in line:
            v = re.findall(VEC, line)
            imb = float(re.search(r'relative imbalance (\S+),', line).group(1))
            out[t] = ([float(x) for x in v[0].split()],
                      [float(x) for x in v[1].split()], imb,
                      [float(x) for x in v[-1].split()])
    return out
