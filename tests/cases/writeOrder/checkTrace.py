#!/usr/bin/env python3
# iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
# Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
"""Check the order of a solver's file system calls, as strace recorded them
(strace -y -e trace=openat,mkdir,fsync,rename,unlink,rmdir -o TRACE), against
what a restart needs from a time directory whatever moment the run stops,
a kill or a power failure:

  1. the mark (<time>/uniform/iceDEMComplete, renamed into place) comes
     after every write into the time directory: nothing is written into a
     marked time until its mark is removed (and the removal synced);
  2. when the mark is renamed into place, every file of the time written
     before it has been flushed (fsync) after its last write, and every
     directory of the time after its last change of entries;
  3. after the mark, the mark's directory and the time's entry in its
     parent are flushed before any other time directory loses a file
     (purgeWrite), and a time directory that loses files has lost its mark
     first;
  4. every time directory the run wrote (its uniform/) was marked.

Usage: checkTrace.py CASE TRACE   (prints what it checked; exit 1 on a
failure, naming the call)
"""

import os
import re
import sys

caseDir = os.path.realpath(sys.argv[1])
lines = open(sys.argv[2]).read().splitlines()

MARK = 'iceDEMComplete'
failures = []


def fail(i, what):
    failures.append('call %d: %s\n    %s' % (i + 1, what, lines[i][:200]))


def timeDirOf(path):
    """The time directory (case/<t> or case/processorN/<t>) a path lies in,
    or None"""
    rel = os.path.relpath(path, caseDir)
    if rel.startswith('..'):
        return None
    parts = rel.split(os.sep)
    base = caseDir
    if parts[0].startswith('processor'):
        base = os.path.join(base, parts[0])
        parts = parts[1:]
    if not parts or not re.fullmatch(r'[-+0-9.eE]+', parts[0]):
        return None
    return os.path.join(base, parts[0])


def quoted(s):
    return re.findall(r'"((?:[^"\\]|\\.)*)"', s)


modified = {}      # path -> call of its last write (open for writing, rename onto, create)
dirChanged = {}    # directory -> call of its last change of entries
synced = {}        # path -> call of its last fsync
exists = set()     # files written and not removed since
marked = {}        # time directory -> call of its mark
unmarkedAt = {}    # time directory -> call of its last removed mark
pendingSync = {}   # time directory -> (call of the mark) until its dir and parent are synced
written = set()    # time directories written into
everMarked = set() # time directories marked at some call

for i, line in enumerate(lines):
    m = re.match(r'^(\w+)\((.*)\)\s+=\s+(-?\d+)', line)
    if not m:
        continue
    call, args, ret = m.group(1), m.group(2), int(m.group(3))
    if ret < 0:
        continue
    if call == 'fsync':
        p = re.search(r'<([^>]*)>', args).group(1)
        synced[p] = i
        for t, mk in list(pendingSync.items()):
            if synced.get(os.path.join(t, 'uniform'), -1) > mk \
               and synced.get(os.path.dirname(t), -1) > mk:
                del pendingSync[t]
        continue
    q = quoted(args)
    if call == 'openat':
        if not re.search(r'O_WRONLY|O_RDWR', args):
            continue
        p = os.path.realpath(q[0])
        targets = [p]
    elif call == 'mkdir':
        targets = [os.path.realpath(q[0])]
    elif call == 'rename':
        src, dst = (os.path.realpath(x) for x in q[:2])
        exists.discard(src)
        dirChanged[os.path.dirname(src)] = i
        targets = [dst]
    elif call in ('unlink', 'rmdir'):
        p = os.path.realpath(q[0])
        t = timeDirOf(p)
        exists.discard(p)
        dirChanged[os.path.dirname(p)] = i
        if t is None:
            continue
        if os.path.basename(p) == MARK:
            unmarkedAt[t] = i
            marked.pop(t, None)
            continue
        if t in marked:
            fail(i, 'a file of the marked time %s removed before its mark'
                 % os.path.relpath(t, caseDir))
        for u in pendingSync:
            if u != t:
                fail(i, '%s loses a file before the mark of %s and its'
                     ' directories are on the disk'
                     % (os.path.relpath(t, caseDir), os.path.relpath(u, caseDir)))
        continue
    else:
        continue

    for p in targets:
        t = timeDirOf(p)
        if t is None:
            continue
        is_mark = os.path.basename(p) == MARK
        if p.startswith(os.path.join(t, 'uniform') + os.sep) and not is_mark:
            # A time the solver wrote (it writes uniform/time first); an
            # initial time directory (0/: the sixDoF solver writes its
            # motionScale there at the start) is not marked
            written.add(t)
        if t in marked and not (p.endswith(MARK + '.writing')):
            fail(i, 'written into %s after its mark' % os.path.relpath(t, caseDir))
        if t in unmarkedAt and t not in marked \
           and synced.get(os.path.join(t, 'uniform'), -1) < unmarkedAt[t] \
           and not p.endswith('.writing') and not is_mark:
            fail(i, 'written into %s before the removal of its mark was'
                 ' flushed' % os.path.relpath(t, caseDir))
        modified[p] = i
        exists.add(p)
        dirChanged[os.path.dirname(p)] = i
        if is_mark and call == 'rename':
            # 2: every file and directory of the time flushed since its
            # last write
            for f in sorted(exists):
                if timeDirOf(f) != t or f == p:
                    continue
                if synced.get(f, -1) < modified[f]:
                    fail(i, 'marked before %s was flushed'
                         % os.path.relpath(f, caseDir))
            for d, c in dirChanged.items():
                if timeDirOf(d) != t or d == os.path.dirname(p):
                    continue
                if synced.get(d, -1) < c:
                    fail(i, 'marked before directory %s was flushed'
                         % os.path.relpath(d, caseDir))
            marked[t] = i
            everMarked.add(t)
            pendingSync[t] = i

unmarkedWritten = sorted(t for t in written if t not in marked)
for t in unmarkedWritten:
    if os.path.isdir(t):
        failures.append('time %s written and never marked'
                        % os.path.relpath(t, caseDir))

if not everMarked:
    # Paths the trace names otherwise than CASE (a symbolic link): nothing
    # would be checked
    failures.append('no time directory of %s marked in the trace' % caseDir)

print('checkTrace: %d calls, %d time directories written, %d marked, '
      '%d paths flushed' % (len(lines), len(written), len(everMarked),
                            len(synced)))
if failures:
    print('checkTrace: FAIL (%d):' % len(failures))
    for f in failures[:20]:
        print('  ' + f)
    sys.exit(1)
print('checkTrace: every mark after the writes and flushes of its time')
