# iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
# Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
"""The bad-input battery: walks every entry of src/iceDEM/foam/case/
caseEntriesList.H (the list the readers take their valid keywords from)
and tries on it what applies of: missing, wrong type, NaN, inf, zero,
negative, huge, a misspelt name; and for every file a truncated copy.

Every try must end, within a time bound, either with a FOAM FATAL IO ERROR
that names the file and the entry, or (a missing optional entry, or a value
inside the documented range) with a normal run: never a signal, a stack
trace, a hang, NaN in an output, and the case's input files unchanged.
Every listed entry must be documented in doc/caseFiles.md.

Usage: battery.py <root of the repository> <scratch directory>
"""

import ast
import concurrent.futures as cf
import hashlib
import math
import os
import re
import shutil
import subprocess
import sys
import time

import foamDictText as fd

TIMEOUT = 15            # seconds per run: the base runs take well under 1 s
WORKERS = 2

# Base cases (tests/cases/inputBattery/bases/<name>): the application and
# the files it reads. An entry is tried in the first base that has its
# file and its dictionary.
BASES = [
    ('dem', ['iceDEMFoam'],
     ['constant/iceDEMProperties', 'constant/iceField', 'system/controlDict']),
    ('noflow', ['iceFloatingFoam', '-noFlow'],
     ['constant/iceDEMProperties', 'constant/structureDict',
      'constant/dynamicMeshDict', 'system/controlDict', 'constant/iceField']),
    ('field', ['createIceField'], ['system/createIceFieldDict']),
    ('hull', ['createStructure'], ['constant/structureDict']),
    # Variants for the entries the bases above do not hold: the inflowOutflow
    # domain, a mooring of lines one by one, the constant and uniform
    # thickness distributions
    ('demInflow', ['iceDEMFoam'], ['constant/iceDEMProperties']),
    ('noflowLines', ['iceFloatingFoam', '-noFlow'],
     ['constant/dynamicMeshDict']),
    ('fieldConstant', ['createIceField'], ['system/createIceFieldDict']),
    ('fieldUniform', ['createIceField'], ['system/createIceFieldDict']),
    # The flow on a coarse mesh: the resolved drag, the rigid-lid solver
    ('flow', ['iceFloatingFoam'],
     ['constant/iceDEMProperties', 'constant/dynamicMeshDict']),
]

# A variant base holds only the files that differ from its parent's
# (a path with a '/' is relative to the repository)
PARENTS = {'demInflow': 'dem', 'noflowLines': 'noflow', 'fieldConstant': 'field',
           'fieldUniform': 'field',
           'flow': 'tutorials/iceFloatingFoam/floeApproach'}

# Set-up of a base before its first run
SETUP = {
    'noflow': [['createStructure']],
    'noflowLines': [['createStructure']],
    'flow': [['createStructure'], ['blockMesh'], ['topoSet'],
             ['subsetMesh', 'fluid', '-patch', 'hull', '-overwrite'],
             ['rm', '-rf', 'constant/polyMesh/sets', '0/cellLevel',
              '0/pointLevel']],
}

# Where the dictionary of a spreadMooring line is (an element of 'lines')
LINE_DICT = ('sixDoFRigidBodyMotionCoeffs/restraints/'
             '*(sixDoFRigidBodyMotionRestraint spreadMooring)/lines/*')

# Inputs whose right outcome is not a stop, and why (not faults; the rest
# of the battery's rules hold: no crash, no NaN, no input overwritten):
#   runs    a valid input of a run that does not end within the time bound:
#           it must still be running, without an error, after RUNS_TIMEOUT s
#   ok      must run to its end without an error
#   either  a run or an error that names the file and the entry
RUNS_TIMEOUT = 3
NOT_FAULTS = {
    # endTime 1e300 is finite and after the start: a valid (very long) run
    'system/controlDict /endTime huge: set -> 1e300': 'runs',
    # OpenFOAM's functionObjectList: an unknown type is a warning and the
    # object is skipped (the name may be another library's function object)
    'system/controlDict functions/loads/type unknownName: set -> bogusName':
        'either',
    # OpenFOAM's libs: the solvers link libiceDEM, so iceLoadStatistics is
    # found with an empty list too
    'system/controlDict functions/loads/libs empty: set -> ()': 'ok',
    'system/controlDict functions/clearance/type unknownName: set -> bogusName':
        'either',
    'system/controlDict functions/clearance/libs empty: set -> ()': 'ok',
}

# Files the application writes (not inputs: may change)
OUTPUTS = re.compile(
    r'^(constant/(iceField|hullMassProperties|hullPieces|triSurface/.*)'
    r'|postProcessing/.*|VTK/.*|iceField\.png|[0-9.e+-]+/.*|log\..*)$')


def read_list(root):
    path = os.path.join(root, 'src/iceDEM/foam/case/caseEntriesList.H')
    entries = []
    for line in open(path):
        line = line.strip()
        if line.startswith('ICEDEM_ENTRY("'):
            args = ast.literal_eval('(' + line[len('ICEDEM_ENTRY('):])
            if len(args) != 7:
                sys.exit('caseEntriesList.H: 7 columns expected: ' + line)
            entries.append(dict(zip(
                ('file', 'dict', 'key', 'kind', 'range', 'default', 'doc'),
                args)))
    return entries


# ---- what a value may be ------------------------------------------------

def allowed(rng, values):
    """True/False when the documented range decides for these numbers,
    None when it depends on other entries"""
    if any(not math.isfinite(v) for v in values):
        return False
    rng = rng.strip()
    if rng in ('finite', '-'):
        return True
    if rng == 'non-zero':
        return any(v != 0 for v in values)
    m = re.match(r'^(>=|>)\s*(-?[0-9.e+-]+)$', rng)
    if m:
        lo = float(m.group(2))
        return all(v >= lo if m.group(1) == '>=' else v > lo for v in values)
    # An interval; a bound may be another entry's name ("(min, 1e6]"),
    # which decides nothing here (as in caseEntries.H's checkListedRange)
    m = re.match(r'^([\[(])\s*([^,\s]+),\s*([^,\s]+)\s*([\])])$', rng)
    if m:
        def num(t):
            try:
                return float(t)
            except ValueError:
                return None
        lo, hi = num(m.group(2)), num(m.group(3))
        ok = True
        for v in values:
            if lo is not None:
                ok &= (v >= lo if m.group(1) == '[' else v > lo)
            if hi is not None:
                ok &= (v <= hi if m.group(4) == ']' else v < hi)
        if not ok:
            return False
        return True if lo is not None and hi is not None else None
    if rng.startswith('>') and all(v <= 0 for v in values) \
            and not re.search(r'\bmin\b|start', rng):
        return False        # > radius, > draft, > iceDensity: all positive
    return None


def numbers(text):
    return [float(x) for x in re.findall(r'[-+]?(?:nan|inf|[0-9.]+(?:e[-+]?[0-9]+)?)', text)]


def mutations(e):
    """(name, action, value, expect) for an entry; action: set | remove |
    misspell; expect: error | ok | either"""
    kind, rng = e['kind'], e['range']
    required = e['default'] == 'required'
    # 'required by drag', 'one of a, b': the outcome depends on the others
    optional = not required and 'required' not in e['default'] \
        and not e['default'].startswith('one of')
    out = [('missing', 'remove', None,
            'error' if required else 'ok' if optional else 'either'),
           ('misspelt', 'misspell', None, 'error')]

    def numeric(name, text):
        a = allowed(rng, numbers(text))
        out.append((name, 'set', text,
                    'error' if a is False else 'either'))

    if kind in ('scalar', 'scalarOrDict'):
        out.append(('wrongType', 'set', 'abc', 'error'))
        for name, text in (('nan', 'nan'), ('inf', 'inf'), ('zero', '0'),
                           ('negative', '-1'), ('huge', '1e300')):
            numeric(name, text)
    elif kind == 'label':
        out.append(('wrongType', 'set', 'abc', 'error'))
        out.append(('fraction', 'set', '1.5', 'error'))
        for name, text in (('zero', '0'), ('negative', '-1'),
                           ('huge', '2000000000')):
            numeric(name, text)
    elif kind in ('vector', 'vector2D', 'diagTensor', 'tensor'):
        n = {'vector': 3, 'vector2D': 2, 'diagTensor': 3, 'tensor': 9}[kind]
        out.append(('wrongType', 'set', 'abc', 'error'))
        out.append(('wrongSize', 'set', '(1)', 'error'))
        for name, x in (('nan', 'nan'), ('inf', 'inf'), ('zero', '0'),
                        ('negative', '-1'), ('huge', '1e300')):
            text = '(' + ' '.join([x]*n) + ')'
            if kind == 'tensor':
                out.append((name, 'set', text, 'error'))   # not a rotation
            else:
                numeric(name, text)
    elif kind == 'word':
        out.append(('wrongType', 'set', '(1 2)', 'error'))
        out.append(('unknownName', 'set', 'bogusName',
                    'either' if rng == '-' else 'error'))
    elif kind == 'bool':
        out.append(('wrongType', 'set', 'maybe', 'error'))
    elif kind == 'fileName':
        out.append(('wrongType', 'set', '(1 2)', 'error'))
    elif kind == 'list':
        out.append(('wrongType', 'set', 'abc', 'error'))
        out.append(('empty', 'set', '()', 'error'))
    elif kind == 'dict':
        out.append(('wrongType', 'set', '1', 'error'))
    return out


# ---- running ------------------------------------------------------------

def snapshot(case):
    h = {}
    for d, _, files in os.walk(case):
        for f in files:
            p = os.path.join(d, f)
            rel = os.path.relpath(p, case)
            if not OUTPUTS.match(rel):
                h[rel] = hashlib.md5(open(p, 'rb').read()).hexdigest()
    return h


CRASH = re.compile(r'sigFpe::|sigSegv::|Segmentation fault|^#[0-9]+ |'
                   r'terminate called|core dumped|Aborted', re.M)
NAN = re.compile(r'(?<![A-Za-z])-?nan(?![A-Za-z])', re.I)


def outputs_have_nan(case):
    for d, _, files in os.walk(os.path.join(case, 'postProcessing')):
        for f in files:
            if f.endswith(('.dat', '.csv')):
                if NAN.search(open(os.path.join(d, f), errors='replace').read()):
                    return os.path.join(d, f)
    return None


def run_case(job):
    (label, case, base, app, fileRel, newText, keys, expect, env) = job
    shutil.copytree(base, case, symlinks=True)
    with open(os.path.join(case, fileRel), 'w') as f:
        f.write(newText)
    before = snapshot(case)
    start = time.time()
    try:
        p = subprocess.run(app, cwd=case, env=env, stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT,
                           timeout=RUNS_TIMEOUT if expect == 'runs' else TIMEOUT)
        rc, log = p.returncode, p.stdout.decode(errors='replace')
    except subprocess.TimeoutExpired as ex:
        rc, log = 'timeout', (ex.stdout or b'').decode(errors='replace')
    elapsed = time.time() - start
    problems = []
    if expect == 'runs':
        if rc == 'timeout' or rc == 0:
            rc, expect = 0, 'ok'    # still running, or done: no error
        else:
            problems.append('stopped where a valid run was expected')
    if rc == 'timeout':
        problems.append('no end within %d s (hang)' % TIMEOUT)
    elif rc < 0 or rc > 128:
        problems.append('killed by a signal (%s)' % rc)
    if CRASH.search(log):
        problems.append('crash in the log: ' + CRASH.search(log).group())
    fatal = log.find('FOAM FATAL')
    msg = log[fatal:] if fatal >= 0 else ''
    fileName = os.path.basename(fileRel)
    if rc == 0:
        if expect == 'error':
            problems.append('ran without error (silently accepted)')
        bad = outputs_have_nan(case)
        if bad:
            problems.append('NaN in ' + os.path.relpath(bad, case))
    elif rc != 'timeout' and not problems:
        if expect == 'ok':
            problems.append('failed where a normal run was expected')
        if 'FOAM FATAL IO ERROR' not in msg:
            problems.append('no FOAM FATAL IO ERROR')
        if fileName not in msg:
            problems.append("the message does not name the file '%s'" % fileName)
        # A value inside its range may clash with another entry: the file
        # named is enough then; outside the range the entry must be named
        if keys and expect == 'error' and not any(k in msg for k in keys):
            problems.append("the message does not name the entry (%s)" % ' or '.join(keys))
    after = snapshot(case)
    changed = sorted(k for k in before if after.get(k) != before[k])
    if changed:
        problems.append('input overwritten: ' + ' '.join(changed))
    summary = msg.split('\n')[1:3] if msg else ['(ran)']
    if not problems:
        shutil.rmtree(case, ignore_errors=True)
    return label, problems, elapsed, ' '.join(s.strip() for s in summary)[:160], log


def main():
    root, scratch = sys.argv[1], sys.argv[2]
    here = os.path.dirname(os.path.abspath(__file__))
    entries = read_list(root)

    # Every listed entry documented: doc/caseFiles.md holds the table made
    # from the list (entriesTable.py)
    import entriesTable
    undocumented = [] if entriesTable.check(root) else entries

    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    env = dict(os.environ, OMP_NUM_THREADS='1', FOAM_SIGFPE='true')

    # Base cases, set up and run once (must run cleanly)
    texts = {}
    for name, app, files in BASES:
        base = os.path.join(scratch, 'base.' + name)
        if name in PARENTS:
            parent = PARENTS[name]
            parent = os.path.join(root, parent) if '/' in parent \
                else os.path.join(here, 'bases', parent)
            shutil.copytree(parent, base, symlinks=True)
            for f in ('Allrun', 'Allclean'):
                if os.path.exists(os.path.join(base, f)):
                    os.remove(os.path.join(base, f))
            if os.path.isdir(os.path.join(base, '0.orig')):
                shutil.copytree(os.path.join(base, '0.orig'),
                                os.path.join(base, '0'))
            shutil.copytree(os.path.join(here, 'bases', name), base,
                            dirs_exist_ok=True)
        else:
            shutil.copytree(os.path.join(here, 'bases', name), base)
        for cmd in SETUP.get(name, []):
            subprocess.run(cmd, cwd=base, env=env, stdout=subprocess.DEVNULL,
                           stderr=subprocess.STDOUT, check=True)
        p = subprocess.run(app, cwd=base, env=env, stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, timeout=TIMEOUT)
        if p.returncode != 0:
            print(p.stdout.decode(errors='replace')[-3000:])
            sys.exit('FAIL: the base case %s does not run' % name)
        for d in ('postProcessing', 'VTK'):
            shutil.rmtree(os.path.join(base, d), ignore_errors=True)
        for f in os.listdir(base):
            if re.match(r'^[0-9.e+-]+$', f) and f != '0':
                shutil.rmtree(os.path.join(base, f))
        for f in ('constant/iceField',) if name.startswith('field') else ():
            os.remove(os.path.join(base, f))
        for f in files:
            texts[(name, f)] = open(os.path.join(base, f)).read()

    jobs = []
    uncovered = []
    n = 0

    def newCase(base):
        nonlocal n
        n += 1
        return os.path.join(scratch, '%04d' % n), \
            os.path.join(scratch, 'base.' + base)

    for e in entries:
        # The first base and path that hold the entry, else the first that
        # hold its dictionary
        where = fallback = None
        for name, app, files in BASES:
            if e['file'] not in files:
                continue
            text = texts[(name, e['file'])]
            d = LINE_DICT if e['dict'] == 'spreadMooring line' else e['dict']
            for path in fd.resolve(text, d):
                if fd.locate(text, path + [e['key']]) is not None:
                    where = (name, app, path)
                    break
                if fallback is None:
                    fallback = (name, app, path)
            if where:
                break
        where = where or fallback
        if where is None:
            uncovered.append(e)
            continue
        name, app, keys = where
        text = texts[(name, e['file'])]
        for mname, action, value, expect in mutations(e):
            if action == 'remove':
                if fd.locate(text, keys + [e['key']]) is None:
                    continue        # not in the base: the default ran there
                new = fd.remove(text, keys, e['key'])
                named = [e['key']]
            elif action == 'misspell':
                bad = e['key'][:-1] if len(e['key']) > 3 else e['key'] + 'x'
                new = fd.rename(text, keys, e['key'], bad)
                if new is None:
                    new = fd.set_value(text, keys, bad, '1')
                named = [bad, e['key']]    # required: 'missing' is named
            else:
                new = fd.set_value(text, keys, e['key'], value)
                named = [e['key']]
            if e['dict'].endswith(')') and e['key'] == e['dict'].split('(')[1].split()[0]:
                named.append(keys[-1])   # the selecting entry: named by its dictionary
            label = '%s %s/%s %s: %s' % (e['file'], '/'.join(keys), e['key'], mname,
                                         '%s -> %s' % (action, value) if value else action)
            expect = NOT_FAULTS.get(label, expect)
            if expect == 'either':
                named.append(keys[-1] if keys else e['key'])
            case, base = newCase(name)
            jobs.append((label, case, base, app, e['file'], new, named,
                         expect, env))

    # Truncated copies of every file
    for (name, f), text in texts.items():
        app = [b for b in BASES if b[0] == name][0][1]
        case, base = newCase(name)
        jobs.append(('%s truncated (%s)' % (f, name), case, base, app, f,
                     text[:int(0.6*len(text))], [], 'error', env))

    # Known gaps (knownGaps, one label per line): reported, not failed; a
    # known gap that passes fails the test, so that the list stays true
    known = set()
    for line in open(os.path.join(here, 'knownGaps')):
        line = line.split('#')[0].strip()
        if line:
            known.add(line)
    knownSeen = set()

    failures = 0
    slowest = 0
    t0 = time.time()
    with cf.ThreadPoolExecutor(WORKERS) as pool:
        for label, problems, elapsed, summary, log in pool.map(run_case, jobs):
            slowest = max(slowest, elapsed)
            if label in known:
                knownSeen.add(label)
                if problems:
                    print('KNOWN %s: %s' % (label, '; '.join(problems)))
                else:
                    failures += 1
                    print('FAIL %s: passes now, remove it from knownGaps' % label)
                continue
            if problems:
                failures += 1
                print('FAIL %s\n     %s' % (label, '; '.join(problems)))
                tail = log[log.find('FOAM FATAL'):] if 'FOAM FATAL' in log else log[-1500:]
                print('     ' + '\n     '.join(tail.strip().split('\n')[:8]))
            else:
                print('ok   %s | %s' % (label, summary))

    files = sorted(set(e['file'] for e in entries))
    print()
    print('Entries listed: %d in %d files; tried: %d; not covered by a base'
          ' case: %d' % (len(entries), len(files),
                         len(entries) - len(uncovered), len(uncovered)))
    for e in uncovered:
        print('    not covered: %s %s %s' % (e['file'], e['dict'], e['key']))
    if undocumented:
        print('FAIL doc/caseFiles.md: its table of entries is not that of'
              ' caseEntriesList.H (python3 tests/cases/inputBattery/'
              'entriesTable.py . --write)')
    for k in sorted(known - knownSeen):
        print('FAIL knownGaps names an input that was not tried: ' + k)
        failures += 1
    print('Inputs tried: %d (%d failed, %d known gaps) in %.0f s, slowest'
          ' run %.1f s' % (len(jobs), failures, len(knownSeen),
                           time.time() - t0, slowest))
    if failures or undocumented:
        print('FAIL')
        sys.exit(1)
    print('PASS')


if __name__ == '__main__':
    main()
