# iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
# Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
"""The table of every entry of caseEntriesList.H, as the section of
doc/caseFiles.md between the markers below.

    python3 entriesTable.py <root> --write   rewrites that section
    python3 entriesTable.py <root>           exits 1 when it is not current
"""

import os
import sys

BEGIN = '<!-- BEGIN caseEntriesList.H (generated: tests/cases/inputBattery/entriesTable.py --write) -->'
END = '<!-- END caseEntriesList.H -->'


def table(entries):
    lines = [BEGIN, '']
    current = None
    for e in entries:
        if e['file'] != current:
            current = e['file']
            lines += ['', '#### `%s`' % current, '',
                      '| dictionary | keyword | kind | allowed | default | meaning |',
                      '|---|---|---|---|---|---|']
        cells = [e['dict'] or '(top level)', '`%s`' % e['key'], e['kind'],
                 e['range'], e['default'], e['doc']]
        lines.append('| ' + ' | '.join(c.replace('|', '\\|') for c in cells) + ' |')
    lines += ['', END]
    return '\n'.join(lines)


def check(root, write=False):
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from battery import read_list
    path = os.path.join(root, 'doc/caseFiles.md')
    doc = open(path).read()
    new = table(read_list(root))
    if BEGIN in doc and END in doc:
        i = doc.index(BEGIN)
        j = doc.index(END) + len(END)
        current = doc[i:j]
        updated = doc[:i] + new + doc[j:]
    else:
        current = None
        updated = doc.rstrip('\n') + '\n\n## Every entry\n\n' + new + '\n'
    if write:
        open(path, 'w').write(updated)
        return True
    return current == new


if __name__ == '__main__':
    ok = check(sys.argv[1], '--write' in sys.argv)
    if not ok:
        print('doc/caseFiles.md: the table of entries is not that of '
              'caseEntriesList.H: run python3 tests/cases/inputBattery/'
              'entriesTable.py . --write')
        sys.exit(1)
