# iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
# Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
"""Find and edit entries of an OpenFOAM dictionary file as text (keeps
comments, #include and $macros as they are): enough of the syntax for the
case files of iceDEM (keywords, sub-dictionaries, values up to ';', lists
that may hold dictionaries: the dictionaries of a list are the list
entry's children '0', '1', ...)."""

import re

_token = re.compile(r'''
    (?P<ws>\s+)
  | (?P<lcomment>//[^\n]*)
  | (?P<bcomment>/\*.*?\*/)
  | (?P<string>"(?:[^"\\]|\\.)*")
  | (?P<punct>[{}();\[\]])
  | (?P<word>[^\s{}();\[\]"]+)
''', re.S | re.X)


def tokens(text):
    """(kind, value, start, end) without white space and comments"""
    out = []
    for m in _token.finditer(text):
        kind = m.lastgroup
        if kind in ('ws', 'lcomment', 'bcomment'):
            continue
        out.append((kind, m.group(), m.start(), m.end()))
    return out


class Entry:
    def __init__(self, key, kstart, vstart, end, children=None, close=None):
        self.key = key
        self.kstart = kstart        # start of the keyword
        self.vstart = vstart        # start of the value
        self.end = end              # after ';' or '}'
        self.children = children    # list of Entry for a dictionary
        self.close = close          # position of the closing '}'
        self.value = None           # text of a primitive value


def parse(text):
    """Top-level list of Entry (sub-dictionaries nested)"""
    toks = tokens(text)
    pos = [0]

    def parse_dict(until_brace):
        entries = []
        while pos[0] < len(toks):
            kind, val, s, e = toks[pos[0]]
            if kind == 'punct' and val == '}':
                if until_brace:
                    return entries, s
                pos[0] += 1
                continue
            if kind == 'punct':
                pos[0] += 1
                continue
            if val.startswith('#'):
                pos[0] += 2          # directive and its argument
                continue
            key = val.strip('"')
            pos[0] += 1
            if pos[0] >= len(toks):
                break
            kind2, val2, s2, e2 = toks[pos[0]]
            if val.startswith('$') and kind2 == 'punct' and val2 == ';':
                pos[0] += 1
                continue
            if kind2 == 'punct' and val2 == '{':
                pos[0] += 1
                children, close = parse_dict(True)
                end = toks[pos[0]][3] if pos[0] < len(toks) else len(text)
                pos[0] += 1
                entries.append(Entry(key, s, s2, end, children, close))
                continue
            depth = 0
            vstart = s2
            elements = []           # dictionaries of a list: keys '0', '1' ...
            while pos[0] < len(toks):
                kind3, val3, s3, e3 = toks[pos[0]]
                pos[0] += 1
                if kind3 == 'punct' and val3 == '{' and depth == 1:
                    children, close = parse_dict(True)
                    end = toks[pos[0]][3] if pos[0] < len(toks) else len(text)
                    pos[0] += 1
                    elements.append(Entry(str(len(elements)), s3, s3, end,
                                          children, close))
                    continue
                if kind3 == 'punct' and val3 in '({[':
                    depth += 1
                elif kind3 == 'punct' and val3 in ')}]':
                    depth -= 1
                elif kind3 == 'punct' and val3 == ';' and depth <= 0:
                    ent = Entry(key, s, vstart, e3,
                                elements if elements else None)
                    ent.value = text[vstart:s3].strip()
                    entries.append(ent)
                    break
        return entries, len(text)

    entries, _ = parse_dict(False)
    return entries


def find(entries, key):
    for e in entries:
        if e.key == key:
            return e
    return None


def resolve(text, path):
    """Concrete key paths for a dictionary string of caseEntriesList.H:
    "" top, "a/b", "*" any sub-dictionary, "*(k v)" one whose entry k is v.
    Returns a list of key lists (possibly empty)."""
    top = parse(text)
    if path == '':
        return [[]]
    results = []

    def walk(entries, parts, prefix):
        if not parts:
            results.append(prefix)
            return
        part = parts[0]
        m = re.match(r'^(\*|[^(]+)(?:\((\S+) (\S+)\))?$', part)
        name, fk, fv = m.group(1), m.group(2), m.group(3)
        for e in entries:
            if e.children is None or e.key == 'FoamFile':
                continue
            if name != '*' and e.key != name:
                continue
            if fk:
                f = find(e.children, fk)
                if f is None or f.value != fv:
                    continue
            walk(e.children, parts[1:], prefix + [e.key])

    walk(top, path.split('/'), [])
    return results


def locate(text, keys):
    """The Entry at the key path, or None"""
    entries = parse(text)
    ent = None
    for k in keys:
        ent = find(entries, k) if entries is not None else None
        if ent is None:
            return None
        entries = ent.children
    return ent


def dict_insert_pos(text, keys):
    """Where to add an entry to the dictionary at keys (before its '}')"""
    if not keys:
        return len(text)
    return locate(text, keys).close


def set_value(text, keys, key, value):
    """Set (or add) keys/key to value (text)"""
    ent = locate(text, keys + [key])
    if ent is None:
        p = dict_insert_pos(text, keys)
        return text[:p] + '\n    %s %s;\n' % (key, value) + text[p:]
    return text[:ent.kstart] + '%s %s;' % (key, value) + text[ent.end:]


def remove(text, keys, key):
    ent = locate(text, keys + [key])
    if ent is None:
        return text
    return text[:ent.kstart] + text[ent.end:]


def rename(text, keys, key, newkey):
    ent = locate(text, keys + [key])
    if ent is None:
        return None
    return text[:ent.kstart] + newkey + text[ent.kstart + len(key):]
