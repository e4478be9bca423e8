"""A small reader of OpenFOAM dictionaries (no PyFoam): enough for what `meltdem check` and
`meltdem run` read (controlDict, blockMeshDict, meltdemProperties, transportProperties, field
headers). Values are kept as token lists; lists in parentheses become Python lists.

    d = read("case/system/controlDict")      # FoamDict; d.get("endTime") -> ['2e-05']
    number(d, "endTime")                     # 2e-05, or None when missing / not a number

Not handled (reported as unreadable by the caller, never guessed): #include, #calc, $macros
other than plain top-level $name substitutions.
"""
import math
import os
import re

_TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|[(){};\[\]]|[^\s(){};\[\]"]+')


class FoamDictError(ValueError):
    pass


def _strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def tokenize(text):
    return _TOKEN.findall(_strip_comments(text))


def _parse_item(tokens, i):
    """(item, next index) at tokens[i]: a nested list or dictionary, or one plain token."""
    t = tokens[i]
    if t in ("(", "["):
        return _parse_list(tokens, i + 1, ")" if t == "(" else "]")
    if t == "{":
        return _parse_dict(tokens, i + 1, "}")
    return t, i + 1


def _parse_list(tokens, i, close):
    out = []
    while i < len(tokens):
        if tokens[i] == close:
            return out, i + 1
        item, i = _parse_item(tokens, i)
        out.append(item)
    raise FoamDictError(f"unclosed '{'(' if close == ')' else '['}'")


def _parse_dict(tokens, i, close):
    d = {}
    while i < len(tokens):
        t = tokens[i]
        if t == close:
            return d, i + 1
        if t in ("}", ")", "]"):
            raise FoamDictError(f"unexpected '{t}' (unbalanced brackets)")
        if t == ";":
            i += 1
            continue
        if t.startswith("#"):          # directive: #include "x", #inputMode merge, ...
            i += 2 if i + 1 < len(tokens) and tokens[i + 1].startswith('"') else 1
            continue
        key = t.strip('"')
        i += 1
        if i < len(tokens) and tokens[i] == "{":
            sub, i = _parse_dict(tokens, i + 1, "}")
            d[key] = sub
            continue
        value = []
        while i < len(tokens) and tokens[i] not in (";", close):
            item, i = _parse_item(tokens, i)
            value.append(item)
        if i < len(tokens) and tokens[i] == ";":
            i += 1
        d[key] = value
    if close is None:
        return d, i
    raise FoamDictError("unclosed '{'")


def parse(text):
    d, _ = _parse_dict(tokenize(text), 0, None)
    return d


def read(path):
    """The dictionary of a file (FoamFile header kept as d['FoamFile']); raises OSError when
    missing, FoamDictError when unbalanced."""
    with open(path, errors="replace") as f:
        return parse(f.read())


def to_float(tok):
    """The finite number of a token, None otherwise (nan and inf are not numbers a case may hold)."""
    try:
        v = float(tok)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


NON_FINITE = {"nan", "+nan", "-nan", "inf", "+inf", "-inf", "infinity", "+infinity", "-infinity"}


def non_finite(d, prefix=""):
    """[(entry path, token)] of the nan/inf tokens anywhere in a parsed dictionary."""
    out = []

    def walk(v, where):
        if isinstance(v, dict):
            for k, x in v.items():
                walk(x, f"{where}{k}" if not where else f"{where}.{k}")
        elif isinstance(v, list):
            for x in v:
                walk(x, where)
        elif isinstance(v, str) and v.lower() in NON_FINITE:
            out.append((where, v))
    walk(d, prefix)
    return out


def value(d, key):
    """The value tokens of key (None when missing or when key is a sub-dictionary)."""
    v = d.get(key) if isinstance(d, dict) else None
    return v if isinstance(v, list) else None


def number(d, key):
    """The scalar of 'key value;', also 'key [dims] value;' and 'key name [dims] value;'; None when
    missing or not one finite number (e.g. 'endTime 1e-5 writeInterval 1e-6;', a missing ';')."""
    v = value(d, key)
    if not v or isinstance(v[-1], list):
        return None
    head = v[:-1]
    if head and isinstance(head[-1], list):
        head = head[:-1]
    if len(head) > 1 or (head and isinstance(head[0], list)) or (head and to_float(head[0]) is not None):
        return None
    return to_float(v[-1])


def vector(tok):
    """(x y z) token list -> tuple of 3 floats, None otherwise."""
    if isinstance(tok, list) and len(tok) == 3:
        vals = [to_float(t) for t in tok]
        if all(v is not None for v in vals):
            return tuple(vals)
    return None


def word(d, key):
    v = value(d, key)
    return v[0].strip('"') if v and isinstance(v[0], str) else None


def switch(d, key, default=False):
    w = word(d, key)
    if w is None:
        return default
    return w.lower() in ("on", "yes", "true", "1", "y")


def set_entries(path, entries):
    """Set top-level 'key value;' entries of a dictionary file in place, keeping everything else
    (used when foamDictionary is not available)."""
    with open(path) as f:
        text = f.read()
    for key, val in entries.items():
        pat = re.compile(rf"^(\s*){re.escape(key)}\s+[^;{{]*;", re.M)
        if pat.search(text):
            text = pat.sub(lambda m: f"{m.group(1)}{key} {val};", text, count=1)
        else:
            text = text.rstrip("\n") + f"\n{key} {val};\n"
    with open(path, "w") as f:
        f.write(text)


def read_points(path):
    """Bounding box ((xmin ymin zmin), (xmax ymax zmax)) of an ASCII constant/polyMesh/points file,
    None when it is binary or unreadable."""
    try:
        with open(path, errors="replace") as f:
            text = f.read()
    except OSError:
        return None
    if re.search(r"format\s+binary", text):
        return None
    body = text.split("FoamFile", 1)[-1]
    body = body[body.find("}") + 1:]
    pts = re.findall(r"\(\s*(\S+)\s+(\S+)\s+(\S+)\s*\)", body)
    try:
        xyz = [(float(a), float(b), float(c)) for a, b, c in pts]
    except ValueError:
        return None
    if not xyz:
        return None
    return tuple(min(p[k] for p in xyz) for k in range(3)), tuple(max(p[k] for p in xyz) for k in range(3))


def time_dirs(case):
    """Numeric time folder names of a case (or a processor folder), sorted by value."""
    out = []
    if not os.path.isdir(case):
        return out
    for name in os.listdir(case):
        if to_float(name) is not None and os.path.isdir(os.path.join(case, name)):
            out.append(name)
    return sorted(out, key=float)
