"""Reads what `meltdem check` / `meltdem run` need from a LAMMPS input script: the commands with
simple variables substituted (index/equal/string/constant variables with numeric arithmetic, and
-var overrides), units, the simulation box (region + create_box, or the read_data file header),
the fix powder/melt keywords, the run lengths and the time step. Not a LAMMPS interpreter:
anything it cannot evaluate is reported as unknown, never guessed."""
import math
import os
import re

_SAFE_EXPR = re.compile(r"^[0-9eE+\-*/^(). \t]*$")


def _eval(expr):
    expr = expr.strip().strip('"').strip("'")
    if not _SAFE_EXPR.match(expr) or not expr:
        return None
    try:
        return float(eval(expr.replace("^", "**"), {"__builtins__": {}}, {"math": math}))  # noqa: S307
    except Exception:
        return None


class LammpsInput:
    def __init__(self, path, overrides=None):
        self.path = path
        self.dir = os.path.dirname(os.path.abspath(path))
        self.vars = dict(overrides or {})
        self.commands = []   # (line number, [words]) after substitution
        self.unresolved = []
        self.includes = []   # include files read in place (path, or the problem)
        self._read(path)

    def _subst(self, line):
        def rep(m):
            name = m.group(1) or m.group(2)
            if name in self.vars:
                return str(self.vars[name])
            self.unresolved.append(name)
            return m.group(0)
        line = re.sub(r"\$\{(\w+)\}|\$(\w)", rep, line)
        # immediate $(expr): numeric arithmetic only
        return re.sub(r"\$\(([^)]*)\)", lambda m: repr(_eval(m.group(1))) if _eval(m.group(1)) is not None
                      else m.group(0), line)

    def _read(self, path, depth=0):
        with open(path, errors="replace") as f:
            raw = f.read().splitlines()
        buf, start = "", 0
        for n, line in enumerate(raw, 1):
            s = line.split("#", 1)[0] if '"' not in line else line
            s = s.rstrip()
            if not buf:
                start = n
            if s.endswith("&"):
                buf += s[:-1] + " "
                continue
            buf += s
            text, buf = buf.strip(), ""
            if not text:
                continue
            words = text.split()
            if words[0] == "variable" and len(words) >= 4:
                name, style = words[1], words[2]
                # index/string/equal/constant: a -var override (index) wins, as in LAMMPS
                if style in ("index", "string", "constant", "equal", "internal") and name not in self.vars:
                    v = self._subst(" ".join(words[3:]))
                    if style in ("equal", "constant"):
                        ev = _eval(re.sub(r"v_(\w+)", lambda m: str(self.vars.get(m.group(1), m.group(0))), v))
                        if ev is not None:
                            self.vars[name] = repr(ev)
                    else:
                        self.vars[name] = words[3]
                continue
            words = self._subst(text).split()
            if words[0] == "include" and len(words) > 1:
                # read in place, as LAMMPS does (relative to the case folder, where it runs)
                inc = os.path.join(self.dir, words[1])
                if "$" in words[1] or not os.path.isfile(inc) or depth > 16:
                    self.includes.append((words[1], f"line {start}: include {words[1]}: file not found"
                                          if "$" not in words[1] else f"line {start}: include {words[1]}: "
                                          "a file name with variables is not read ahead"))
                else:
                    self.includes.append((words[1], None))
                    self._read(inc, depth + 1)
                continue
            self.commands.append((start, words))

    def find(self, cmd):
        return [(n, w) for n, w in self.commands if w[0] == cmd]

    def units(self):
        u = self.find("units")
        return u[-1][1][1] if u and len(u[-1][1]) > 1 else None

    def read_data_files(self):
        return [w[1] for _, w in self.find("read_data") if len(w) > 1]

    def box(self):
        """((lo), (hi)) of the simulation box and where it came from, or (None, reason)."""
        boxes = self.find("create_box")
        if boxes:
            rname = boxes[-1][1][2] if len(boxes[-1][1]) > 2 else None
            for _, w in self.find("region"):
                if len(w) >= 9 and w[1] == rname and w[2] == "block":
                    vals = [_eval(x) if x not in ("INF", "EDGE") else None for x in w[3:9]]
                    if any(v is None for v in vals):
                        return None, f"region {rname} bounds not numeric ({' '.join(w[3:9])})"
                    # region units default to lattice; under units si with no lattice command
                    # the lattice spacing is 1 m, i.e. box units
                    return ((vals[0], vals[2], vals[4]), (vals[1], vals[3], vals[5])), f"region {rname} (create_box)"
            return None, f"create_box region '{rname}' is not a block region"
        for f in self.read_data_files():
            p = os.path.join(self.dir, f)
            if not os.path.isfile(p):
                return None, f"{f} missing"
            b = data_box(p)
            if b:
                return b, f"{f} header"
            return None, f"{f} has no xlo xhi / ylo yhi / zlo zhi header"
        return None, "no create_box and no read_data"

    def fixes(self, style):
        return [(n, w) for n, w in self.find("fix") if len(w) > 3 and w[3] == style]

    def timestep(self):
        t = self.find("timestep")
        return _eval(t[-1][1][1]) if t else None

    def run_timesteps(self):
        """The timestep in effect at each run command, in order (None where not known)."""
        out, dt = [], None
        for _, w in self.commands:
            if w[0] == "timestep" and len(w) > 1:
                dt = _eval(w[1])
            elif w[0] == "run" and len(w) > 1 and _eval(w[1]) is not None:
                out.append(dt)
        return out

    def runs(self):
        """Step counts of the run commands in order; a 'run N upto' is given as -N (up to step N)."""
        return [int(_eval(w[1])) * (-1 if "upto" in w[2:] else 1)
                for _, w in self.find("run") if len(w) > 1 and _eval(w[1]) is not None]


def data_box(path):
    """Box of a LAMMPS data file header, None when missing."""
    lo, hi = [None] * 3, [None] * 3
    try:
        with open(path, errors="replace") as f:
            for k, line in enumerate(f):
                w = line.split()
                for i, (a, b) in enumerate((("xlo", "xhi"), ("ylo", "yhi"), ("zlo", "zhi"))):
                    if len(w) >= 4 and w[2] == a and w[3] == b:
                        lo[i], hi[i] = float(w[0]), float(w[1])
                if w and w[0] in ("Atoms", "Velocities", "Masses") or k > 200:
                    break
    except (OSError, ValueError):
        return None
    if None in lo:
        return None
    return tuple(lo), tuple(hi)
