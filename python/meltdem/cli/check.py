"""`meltdem check CASE`: validates a case before launch. Every problem names the file and the entry
(`system/controlDict: endTime missing`); what was checked is listed when all is fine.

Checks: files present (system/, constant/ dictionaries meltdemFoam reads, the initial fields, the
LAMMPS input named by particles.lammpsInput and the data files it reads), SI units (LAMMPS `units
si`, OpenFOAM dimensions of the known fields), domains consistent (the LAMMPS box contains the mesh
box), materials complete (constant/meltdemProperties metal{}/gas{}/darcy{}/surfaceTension{}/
evaporation{} entries the switched-on terms read, transportProperties, the fix powder/melt
keywords) and the laser path inside the mesh (as laserHeatSource::checkInBounds does).
"""
import os

from .. import paths
from ..io import foamdict as fd
from ..io.lammps_input import LammpsInput

# entries the solver reads (foam-src/meltdemModels/*, foam-src/meltdemFoam)
CONTROL = ("startTime", "endTime", "deltaT", "writeInterval")
SCHEMES = ("ddtSchemes", "gradSchemes", "divSchemes", "laplacianSchemes")
MELT_KEYWORDS = ("cp", "Tmelt", "latent", "temp")
# SI dimensions [kg m s K mol A cd] of the fields meltdemFoam reads
DIMENSIONS = {"T": "0 0 0 1 0 0 0", "U": "0 1 -1 0 0 0 0", "p_rgh": "1 -1 -2 0 0 0 0",
              "alpha.metal": "0 0 0 0 0 0 0", "p": "1 -1 -2 0 0 0 0"}
G_DIMENSIONS = "0 1 -2 0 0 0 0"
GREAT = 1e300
# the values a field may take (meltdemFoam stops before the first step otherwise)
# (alpha: 1e-6 beyond the bounds, what MULES's bounded solution may leave, as the solver allows)
FIELD_RANGE = {"alpha.metal": (0.0, 1.0, 1e-6, "a volume fraction"), "T": (0.0, None, 0.0, "an absolute temperature")}


class Report:
    def __init__(self):
        self.problems, self.checked, self.notes = [], [], []

    def bad(self, where, msg):
        self.problems.append(f"{where}: {msg}")

    def ok(self, what):
        self.checked.append(what)

    def note(self, msg):
        self.notes.append(msg)


def case_kind(case):
    """'foam' (system/controlDict), 'dem' (a LAMMPS in.* input and no controlDict) or None."""
    if os.path.isfile(os.path.join(case, "system", "controlDict")):
        return "foam"
    if dem_input(case):
        return "dem"
    return None


def dem_input(case):
    """The LAMMPS input of a DEM-only case: in.* in the case folder (one, or the one named like
    the folder / in.pour); None when there is none."""
    if not os.path.isdir(case):
        return None
    ins = sorted(f for f in os.listdir(case) if f.startswith("in.") and os.path.isfile(os.path.join(case, f)))
    if not ins:
        return None
    if len(ins) == 1:
        return ins[0]
    base = os.path.basename(os.path.abspath(case))
    for f in ins:
        if f == f"in.{base}":
            return f
    return ins[0]


def scene_vars(case):
    """-var overrides a scene recorded for its DEM input (CASE/scene.json 'vars'), {} otherwise."""
    import json
    p = os.path.join(case, "scene.json")
    try:
        v = json.load(open(p)).get("vars", {})
        return {str(k): str(x) for k, x in v.items()} if isinstance(v, dict) else {}
    except (OSError, ValueError, AttributeError):
        return {}


def _read(case, rel, rep, required=True):
    """The parsed dictionary, or None with the problem reported: missing, unreadable, a syntax
    error (OpenFOAM's own parser, foamDictionary, names the line), nan/inf values."""
    p = os.path.join(case, rel)
    if not os.path.isfile(p):
        if required:
            rep.bad(rel, "file missing")
        return None
    try:
        d = fd.read(p)
    except OSError as e:
        rep.bad(rel, f"cannot be read ({e.strerror})")
        return None
    except fd.FoamDictError as e:
        rep.bad(rel, f"cannot be parsed ({e})")
        return None
    syntax = foam_syntax_error(p)
    if syntax:
        rep.bad(rel, f"cannot be parsed by OpenFOAM: {syntax}")
        return None
    for where, tok in fd.non_finite(d):
        rep.bad(rel, f"{where}: {tok} is not a number")
    return d


def foam_syntax_error(path):
    """OpenFOAM's parser on a dictionary file (foamDictionary): its error with the line, '' when
    the file parses (or foamDictionary is not installed)."""
    import shutil
    import subprocess
    exe = shutil.which("foamDictionary")
    if not exe or any(c.isspace() for c in path):   # (a case path with spaces is reported as such)
        return ""
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    try:
        r = subprocess.run([exe, "-keywords", path], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           stdin=subprocess.DEVNULL, text=True, env=env, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return ""
    if r.returncode == 0:
        return ""
    lines = [x.strip() for x in r.stderr.splitlines() if x.strip()]
    msg = next((x for i, x in enumerate(lines) if i and "FOAM FATAL" in lines[i - 1]), "")
    at = next((x for x in lines if x.startswith("file:")), "")
    line = at.rsplit(" at line ", 1)[-1].rstrip(".") if " at line " in at else ""
    return f"{msg}{' (line ' + line + ')' if line else ''}" or "syntax error"


NON_NEGATIVE = {"L", "beta", "power"}   # may be 0 (meltdemProperties::readPositive allowZero)


def _need(d, keys, rel, rep, prefix="", positive=False):
    """Number entries (positive ones as meltdemProperties::readPositive); returns those present."""
    got = {}
    for k in keys:
        v = fd.number(d, k)
        if fd.value(d, k) is None:
            rep.bad(rel, f"{prefix}{k} missing")
        elif v is None and fd.non_finite({k: fd.value(d, k)}):
            continue   # reported when the file was read
        elif v is None:
            toks = [t for t in fd.value(d, k) if not isinstance(t, list)]
            rep.bad(rel, f"{prefix}{k} is not a number ({' '.join(map(str, d[k]))})"
                    + ("; a missing ';' after it?" if len(toks) > 2 else ""))
        elif positive and (v < 0 or (v == 0 and k not in NON_NEGATIVE)):
            rep.bad(rel, f"{prefix}{k} = {v:g} must be {'non-negative' if k in NON_NEGATIVE else 'positive'}")
        else:
            got[k] = v
    return got


RANGE_WORDS = {"> 0": "positive", ">= 0": "non-negative"}


def _need_spec(d, entries, rel, rep, prefix=""):
    """The entries of a sub-dictionary as the solver's table gives them ({key: range}, range '> 0',
    '>= 0', '' for any number, other: a word); returns the numbers present."""
    got = {}
    for k, rng in entries.items():
        raw = fd.value(d, k)
        if raw is None:
            rep.bad(rel, f"{prefix}{k} missing")
            continue
        if rng not in RANGE_WORDS and rng != "":
            continue   # a word entry
        v = fd.number(d, k)
        if v is None and fd.non_finite({k: raw}):
            continue   # reported when the file was read
        if v is None:
            toks = [t for t in raw if not isinstance(t, list)]
            rep.bad(rel, f"{prefix}{k} is not a number ({' '.join(map(str, d[k]))})"
                    + ("; a missing ';' after it?" if len(toks) > 2 else ""))
        elif (rng == "> 0" and not v > 0) or (rng == ">= 0" and v < 0):
            rep.bad(rel, f"{prefix}{k} = {v:g} must be {RANGE_WORDS[rng]}")
        else:
            got[k] = v
    return got


_SOLVER_TERMS = []


def solver_terms():
    """The physics switches of meltdemFoam and what each reads (`meltdemFoam -listTerms`, the
    solver's own table), or None when meltdemFoam is not built."""
    import json
    import subprocess
    if _SOLVER_TERMS:
        return _SOLVER_TERMS[0]
    exe = paths.binary("meltdemFoam")
    try:
        env = dict(os.environ)
        env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
        out = subprocess.run([exe, "-listTerms"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                             timeout=60, check=True, env=env).stdout
        _SOLVER_TERMS.append(json.loads(out))
    except (OSError, subprocess.SubprocessError, ValueError):
        return None
    return _SOLVER_TERMS[0]


def mesh_box(case, rep):
    """Mesh bounding box: constant/polyMesh/points when present, else blockMeshDict vertices x scale."""
    pts = os.path.join(case, "constant", "polyMesh", "points")
    if os.path.isfile(pts):
        b = fd.read_points(pts)
        if b:
            return b, "constant/polyMesh/points"
    rel = "system/blockMeshDict"
    if (not os.path.isfile(os.path.join(case, rel))
            and os.path.isdir(os.path.join(case, "processor0", "constant", "polyMesh"))):
        rep.note("decomposed mesh only (processor*/constant/polyMesh): mesh box not checked")
        return None, None
    d = _read(case, rel, rep, required=not os.path.isfile(pts))
    if d is None:
        return None, None
    scale = fd.number(d, "scale") if "scale" in d else fd.number(d, "convertToMeters")
    scale = 1.0 if scale is None else scale
    verts = fd.value(d, "vertices")
    xyz = [fd.vector(v) for v in (verts[0] if verts and isinstance(verts[0], list) else [])]
    if not xyz or any(v is None for v in xyz):
        rep.note(f"{rel}: vertices not plain numbers; mesh box taken after blockMesh only")
        return None, None
    lo = tuple(min(v[k] for v in xyz) * scale for k in range(3))
    hi = tuple(max(v[k] for v in xyz) * scale for k in range(3))
    return (lo, hi), f"{rel} vertices x {scale:g}"


def _fmt(b):
    return "(" + " ".join(f"{x:.6g}" for x in b[0]) + ") - (" + " ".join(f"{x:.6g}" for x in b[1]) + ")"


def check_gravity(lmp, rel, g, rep):
    """The particles' fix gravity equals constant/g (meltdemFoam stops otherwise, checkGravity)."""
    from ..io.lammps_input import _eval
    gl = [0.0, 0.0, 0.0]
    for n, w in lmp.fixes("gravity"):
        mag = _eval(w[4]) if len(w) > 4 else None
        if len(w) < 9 or w[5] != "vector" or mag is None:
            rep.note(f"{rel}: line {n}: fix gravity style not checked ({' '.join(w[4:])})")
            return
        d = [_eval(x) for x in w[6:9]]
        if None in d:
            return
        norm = sum(x * x for x in d) ** 0.5 or 1.0
        gl = [gl[k] + mag * d[k] / norm for k in range(3)]
    diff = sum((a - b) ** 2 for a, b in zip(gl, g)) ** 0.5
    scale = max(sum(x * x for x in gl) ** 0.5, sum(x * x for x in g) ** 0.5)
    if diff > 1e-9 * scale:
        rep.bad(rel, f"fix gravity gives ({' '.join(f'{x:.6g}' for x in gl)}) m/s2 but constant/g is "
                     f"({' '.join(f'{x:.6g}' for x in g)}): particles and continuum must feel the same gravity")
    else:
        rep.ok(f"{rel}: fix gravity = constant/g")


def check_lammps(case, rel, rep, mesh=None, coupled=False, overrides=None, g=None):
    p = os.path.join(case, rel)
    if not os.path.isfile(p):
        rep.bad(rel, "file missing (LAMMPS input)")
        return None
    try:
        lmp = LammpsInput(p, overrides)
    except OSError as e:
        rep.bad(rel, f"cannot be read ({e.strerror}{': ' + e.filename if e.filename and e.filename != p else ''})")
        return None
    for inc, problem in lmp.includes:
        if problem:
            rep.bad(rel, problem)
        else:
            rep.ok(f"{rel}: include {inc} read in place")
    u = lmp.units()
    if u != "si":
        rep.bad(rel, f"units {u or '(none: LAMMPS default lj)'}: MeltDEM styles and the coupling need 'units si'")
    else:
        rep.ok(f"{rel}: units si")
    for f in lmp.read_data_files():
        if not os.path.isfile(os.path.join(case, f)):
            rep.bad(rel, f"read_data {f}: file missing")
        else:
            rep.ok(f"{rel}: read_data {f} present")
    for _, w in lmp.find("read_restart"):
        if len(w) > 1 and not os.path.isfile(os.path.join(case, w[1].replace("*", ""))) and "*" not in w[1]:
            rep.bad(rel, f"read_restart {w[1]}: file missing")
    melts = lmp.fixes("powder/melt")
    for n, w in melts:
        missing = [k for k in MELT_KEYWORDS if k not in w[4:]]
        if missing:
            rep.bad(rel, f"line {n}: fix {w[1]} powder/melt: keyword(s) {' '.join(missing)} missing")
        else:
            rep.ok(f"{rel}: fix powder/melt has cp Tmelt latent temp")
    if coupled and not melts:
        rep.bad(rel, "no fix powder/melt (the coupling exchanges through it)")
    if coupled and g is not None:
        check_gravity(lmp, rel, g, rep)
    if mesh is not None:
        box, src = lmp.box()
        if box is None:
            rep.note(f"{rel}: LAMMPS box not known before the run ({src}); domain check skipped")
        else:
            span = max(high - low for low, high in zip(*mesh))
            tol = 1e-9 * span
            out = [a for k, a in enumerate("xyz")
                   if mesh[0][k] < box[0][k] - tol or mesh[1][k] > box[1][k] + tol]
            if out:
                rep.bad(rel, f"LAMMPS box {_fmt(box)} ({src}) does not contain the mesh box {_fmt(mesh)} "
                             f"in {','.join(out)}")
            else:
                rep.ok(f"{rel}: LAMMPS box {_fmt(box)} contains the mesh {_fmt(mesh)}")
    if coupled and mesh is not None:
        check_insertion_regions(lmp, rel, mesh, rep)
    if lmp.unresolved:
        rep.note(f"{rel}: variables without a value here: {' '.join(sorted(set(lmp.unresolved)))}")
    return lmp


def check_insertion_regions(lmp, rel, mesh, rep):
    """A fix powder/insert region (a block) outside the mesh: its grains would be booked lost the
    moment they are inserted (the coupling removes particles outside the mesh)."""
    from ..io.lammps_input import _eval
    blocks = {w[1]: w[3:9] for _, w in lmp.find("region") if len(w) >= 9 and w[2] == "block"}
    for n, w in lmp.fixes("powder/insert"):
        rid = w[w.index("region") + 1] if "region" in w[4:-1] else None
        if rid not in blocks:
            continue
        b = blocks[rid]
        lo, hi = [], []
        for k in range(3):
            a, c = b[2 * k], b[2 * k + 1]
            lo.append(mesh[0][k] if a in ("INF", "EDGE") else _eval(a))
            hi.append(mesh[1][k] if c in ("INF", "EDGE") else _eval(c))
        if None in lo or None in hi:
            continue
        inside = [max(lo[k], mesh[0][k]) < min(hi[k], mesh[1][k]) for k in range(3)]
        if not all(inside):
            axes = ",".join("xyz"[k] for k in range(3) if not inside[k])
            rep.bad(rel, f"line {n}: fix {w[1]} powder/insert: region {rid} {_fmt((lo, hi))} lies outside the "
                         f"mesh {_fmt(mesh)} in {axes}: every grain it inserts would leave the coupled domain at "
                         f"once and be booked lost")
        elif any(lo[k] < mesh[0][k] or hi[k] > mesh[1][k] for k in range(3)):
            rep.note(f"{rel}: line {n}: part of region {rid} lies outside the mesh: grains inserted there are "
                     f"booked lost at once")


def check_laser(d, mesh, rep, rel, entries):
    las = d.get("laser")
    if not isinstance(las, dict):
        rep.bad(rel, "laser: sub-dictionary missing (physics laser on)")
        return
    got = _need_spec(las, entries, rel, rep, "laser.")
    if got.get("absorptivity", 0) > 1:
        rep.bad(rel, f"laser.absorptivity = {got['absorptivity']:g} must be in [0, 1]")
    if mesh is None:
        return
    lo, hi = mesh
    tol = 1e-9 * max(high - low for low, high in zip(lo, hi))

    def inside(p):
        return all(lo[k] - tol <= p[k] <= hi[k] + tol for k in range(3))

    num = lambda k, default: fd.number(las, k) if fd.number(las, k) is not None else default  # noqa: E731
    t_end = min(num("tStop", GREAT), num("tOff", GREAT))
    t0 = num("tStart", 0.0)
    pts = []
    if "path" in las:
        path = fd.value(las, "path")
        raw = path[0] if path and isinstance(path[0], list) else []
        pts = [("path", fd.vector(v)) for v in raw]
        if not pts or any(p is None for _, p in pts):
            rep.bad(rel, "laser.path: not a list of (x y z) points")
            return
        if fd.number(las, "speed") is None:
            rep.bad(rel, "laser.speed missing (path given)")
    else:
        pos = fd.vector((fd.value(las, "position") or [None])[0])
        if pos is None:
            rep.bad(rel, "laser.position missing or not (x y z)")
            return
        pts.append(("position", pos))
        vel = fd.vector((fd.value(las, "velocity") or [None])[0]) or (0.0, 0.0, 0.0)
        if any(vel):
            if t_end >= 0.5 * GREAT:
                rep.bad(rel, "laser.velocity non-zero but neither tStop nor tOff given: the path would leave the mesh")
            else:
                tau = max(t_end - t0, 0.0)
                pts.append((f"end of the path (position + velocity x {tau:.4g} s)",
                            tuple(pos[k] + vel[k] * tau for k in range(3))))
    bad = [(what, p) for what, p in pts if not inside(p)]
    for what, p in bad:
        rep.bad(rel, f"laser.{what}: point ({' '.join(f'{x:.6g}' for x in p)}) lies outside the mesh {_fmt(mesh)}")
    if not bad:
        rep.ok(f"{rel}: laser path ({len(pts)} point(s)) inside the mesh")


def field_text(path, size=-1):
    """A field file's text (its first SIZE characters), gzipped (writeCompression on) or not."""
    if path.endswith(".gz"):
        import gzip
        with gzip.open(path, "rt", errors="replace") as f:
            return f.read(size)
    with open(path, errors="replace") as f:
        return f.read(size)


START_FROM = ("startTime", "firstTime", "latestTime")


def start_time_folder(case, ctl):
    """The time folder a run starts from by controlDict's startFrom (one of START_FROM), as
    meltdemFoam finds it: a name relative to the case (processor0/<time> when the case folder
    has none), or None."""
    how = fd.word(ctl, "startFrom") or "startTime"
    for where in ("", "processor0"):
        times = fd.time_dirs(os.path.join(case, where))
        if how == "startTime":
            start = fd.number(ctl, "startTime")
            times = [t for t in times if start is not None and float(t) == start]
        if times:
            return os.path.join(where, times[-1] if how == "latestTime" else times[0])
    return None


def start_folder(case, ctl, rep):
    """start_time_folder, with what is wrong reported."""
    how = fd.word(ctl, "startFrom") or "startTime"
    if how not in START_FROM:
        rep.bad("system/controlDict", f"startFrom {how} unknown (startTime, firstTime or latestTime)")
        return None
    folder = start_time_folder(case, ctl)
    if folder is not None:
        return folder
    start = fd.number(ctl, "startTime")
    rep.bad("system/controlDict", f"startFrom {how}" + (f"; startTime {start:g}" if how == "startTime" else "")
            + f": no such time folder in {case} (the start fields)")
    return None


def field_values(path):
    """(internal and boundary values) of an ASCII field file as one list of floats, 'binary' for a
    binary one, or a text naming what is not a number."""
    import re
    text = field_text(path)
    if re.search(r"format\s+binary", text[:4096]):
        return "binary"
    vals = []
    for m in re.finditer(r"\b(internalField|value)\s+"
                         r"(uniform\s+([^;]+);|nonuniform\s+List<scalar>\s*\d*\s*\(([^)]*)\))", text):
        toks = (m.group(3) or m.group(4) or "").split()
        for t in toks:
            try:
                vals.append(float(t))
            except ValueError:
                return f"{m.group(1)}: '{t}' is not a number"
    return vals


def check_field_range(case, rel, rng, rep):
    lo, hi, tol, what = rng
    try:
        vals = field_values(os.path.join(case, rel))
    except OSError as e:
        rep.bad(rel, f"cannot be read ({e.strerror})")
        return
    if vals == "binary":
        rep.note(f"{rel}: binary field, values not checked (meltdemFoam checks them at start)")
        return
    if isinstance(vals, str):
        rep.bad(rel, vals)
        return
    import math
    bad = [v for v in vals if not math.isfinite(v) or v < lo - tol or (hi is not None and v > hi + tol)]
    if bad:
        rng_txt = f"[{lo:g}, {hi:g}]" if hi is not None else f">= {lo:g}"
        rep.bad(rel, f"{len(bad)} value(s) outside {rng_txt} ({what}), e.g. {bad[0]:g}")


def check_foam(case, rep):
    ctl = _read(case, "system/controlDict", rep)
    if ctl is not None:
        for k in CONTROL:
            if fd.value(ctl, k) is None:
                rep.bad("system/controlDict", f"{k} missing")
            elif fd.number(ctl, k) is None and not fd.non_finite({k: fd.value(ctl, k)}):
                rep.bad("system/controlDict", f"{k} is not a number ({' '.join(map(str, fd.value(ctl, k)))})"
                        + ("; a missing ';' after it?" if len(fd.value(ctl, k)) > 1 else ""))
        e, s = fd.number(ctl, "endTime"), fd.number(ctl, "startTime")
        how = fd.word(ctl, "startFrom") or "startTime"
        if e is not None and s is not None and e <= s and how == "startTime":
            rep.bad("system/controlDict", f"endTime {e:g} is not after startTime {s:g}")
        rep.ok("system/controlDict: " + ", ".join(CONTROL))
    sch = _read(case, "system/fvSchemes", rep)
    if sch is not None:
        for k in SCHEMES:
            if not isinstance(sch.get(k), dict):
                rep.bad("system/fvSchemes", f"{k} missing")
        rep.ok("system/fvSchemes: " + ", ".join(SCHEMES))
    sol = _read(case, "system/fvSolution", rep)
    if sol is not None:
        for k in ("solvers", "PIMPLE"):
            if not isinstance(sol.get(k), dict):
                rep.bad("system/fvSolution", f"{k} missing")
        rep.ok("system/fvSolution: solvers, PIMPLE")
    mesh, src = mesh_box(case, rep)
    if mesh:
        rep.ok(f"mesh box {_fmt(mesh)} from {src}")

    tp = _read(case, "constant/transportProperties", rep)
    if tp is not None:
        phases = fd.value(tp, "phases")
        names = phases[0] if phases and isinstance(phases[0], list) else []
        if len(names) != 2:
            rep.bad("constant/transportProperties", "phases missing (phases (metal gas);)")
        for ph in names:
            sub = tp.get(ph)
            if not isinstance(sub, dict):
                rep.bad("constant/transportProperties", f"{ph}: sub-dictionary missing")
                continue
            _need(sub, ("nu", "rho"), "constant/transportProperties", rep, f"{ph}.", positive=True)
        if fd.value(tp, "sigma") is None:
            rep.bad("constant/transportProperties", "sigma missing")
        elif fd.number(tp, "sigma") is not None and fd.number(tp, "sigma") < 0:
            rep.bad("constant/transportProperties", f"sigma = {fd.number(tp, 'sigma'):g} must be non-negative")
        rep.ok("constant/transportProperties: phases, nu, rho, sigma")
    turb = _read(case, "constant/turbulenceProperties", rep)
    if turb is not None:
        if fd.word(turb, "simulationType") is None:
            rep.bad("constant/turbulenceProperties", "simulationType missing (laminar)")
        rep.ok("constant/turbulenceProperties: simulationType")
    g = _read(case, "constant/g", rep)
    gvec = None
    if g is not None:
        dims = fd.value(g, "dimensions")
        if dims and isinstance(dims[0], list) and " ".join(dims[0][:7]) != G_DIMENSIONS:
            rep.bad("constant/g", f"dimensions [{' '.join(dims[0])}] are not m/s^2 [{G_DIMENSIONS}]")
        gvec = fd.vector((fd.value(g, "value") or [None])[0])
        if gvec is None:
            rep.bad("constant/g", "value missing or not (x y z)")
        rep.ok("constant/g: dimensions, value")

    rel = "constant/meltdemProperties"
    md = _read(case, rel, rep)
    physics = {}
    if md is not None:
        ph = md.get("physics")
        if not isinstance(ph, dict):
            rep.bad(rel, "physics missing (the per-term switches)")
            ph = {}
        table = solver_terms()
        if table is None:
            rep.note(f"{rel}: meltdemFoam not found (build MeltDEM): the physics switches and their entries "
                     f"are not checked")
            return
        switches = dict(table["core"], **table["terms"])
        # the top level holds the solver's own entries and the terms' sub-dictionaries only (a
        # misspelt block, refinment or energyControl, would switch its part off: the solver stops)
        blocks = set(table.get("topLevel", [])) | {s for t in switches.values() for s in t["entries"]}
        if table.get("topLevel"):
            for k in md:
                if k not in blocks:
                    rep.bad(rel, f"{k}: unknown entry; known entries: {' '.join(sorted(blocks))}")
        for k in ph:
            if k not in switches:
                rep.bad(rel, f"physics.{k}: unknown switch; known switches: {' '.join(sorted(switches))}")
        physics = {k: fd.switch(ph, k, k == "flow") for k in switches}
        on = [k for k, v in physics.items() if v]
        rep.ok(f"{rel}: physics on: {' '.join(on) or '(none)'}")
        for name in sorted(on, key=lambda k: (k not in table["core"], switches[k]["order"], k)):
            info = switches[name]
            for n in info["needs"]:
                if not physics.get(n):
                    rep.bad(rel, f"physics.{name} needs {n} on")
            for sub, entries in info["entries"].items():
                if name in ("particles", "laser"):
                    continue   # their own checks below
                if not isinstance(md.get(sub), dict):
                    rep.bad(rel, f"{sub}: sub-dictionary missing (physics {name} on)")
                    continue
                got = _need_spec(md[sub], entries, rel, rep, f"{sub}.")
                if sub == "metal" and "Tsolidus" in got and "Tliquidus" in got \
                        and not got["Tliquidus"] > got["Tsolidus"]:
                    rep.bad(rel, f"metal.Tsolidus ({got['Tsolidus']:g}) must be below Tliquidus ({got['Tliquidus']:g})")
                rep.ok(f"{rel}: {sub} {{{' '.join(entries)}}} (physics {name})")
        if physics.get("laser"):
            check_laser(md, mesh, rep, rel, table["terms"]["laser"]["entries"]["laser"])

    fields = ["alpha.metal", "U", "p_rgh"] + (["T"] if physics.get("energy") else [])
    start = start_folder(case, ctl, rep) if ctl is not None else "0"
    for f in fields if start is not None else []:
        rel0 = os.path.join(start, f)
        if not os.path.isfile(os.path.join(case, rel0)) and os.path.isfile(os.path.join(case, rel0 + ".gz")):
            rel0 += ".gz"
        if not os.path.isfile(os.path.join(case, rel0)):
            rep.bad(rel0, "file missing")
            continue
        if start.startswith("processor"):
            continue
        # the header only: a field's values can be millions of numbers
        head = field_text(os.path.join(case, rel0), 1 << 16).split("internalField")[0]
        try:
            d = fd.parse(head)
        except fd.FoamDictError as e:
            rep.bad(rel0, f"cannot be parsed ({e})")
            continue
        dims = fd.value(d, "dimensions")
        got = " ".join(dims[0][:7]) if dims and isinstance(dims[0], list) else None
        if got is None:
            rep.bad(rel0, "dimensions missing")
        elif [fd.to_float(x) for x in got.split()] != [float(x) for x in DIMENSIONS[f].split()]:
            rep.bad(rel0, f"dimensions [{got}] are not the SI dimensions of {f} [{DIMENSIONS[f]}]")
        if f in FIELD_RANGE:
            check_field_range(case, rel0, FIELD_RANGE[f], rep)
    if start is not None:
        rep.ok(f"{start}/: " + ", ".join(fields) + " (SI dimensions)")

    if physics.get("particles") and md is not None:
        pd = md.get("particles")
        if not isinstance(pd, dict):
            rep.bad(rel, "particles: sub-dictionary missing (physics particles on)")
            return
        for k in ("lammpsInput", "distribution"):
            if fd.word(pd, k) is None:
                rep.bad(rel, f"particles.{k} missing")
        dist = fd.word(pd, "distribution")
        models = solver_terms()["core"]["particles"]["entries"]["particles"]["distribution"].split()
        if dist and dist not in models:
            rep.bad(rel, f"particles.distribution {dist} unknown ({', '.join(models)})")
        inp = fd.word(pd, "lammpsInput")
        if inp:
            check_lammps(case, inp, rep, mesh, coupled=True, g=gvec)


def check(case):
    """Report of a case folder."""
    rep = Report()
    case = os.path.abspath(case)
    kind = case_kind(case)
    if any(c.isspace() for c in case):
        rep.bad(case, "the case path has white space, which OpenFOAM's file names cannot hold (meltdemFoam "
                      "would stop): move or rename the case folder")
    if not os.path.isdir(case):
        rep.bad(case, "no such folder")
    elif kind == "foam":
        check_foam(case, rep)
    elif kind == "dem":
        check_lammps(case, dem_input(case), rep, overrides=scene_vars(case))
    else:
        rep.bad(os.path.basename(case) or case,
                "not a case: no system/controlDict (coupled or continuum case) and no in.* LAMMPS input "
                "(DEM-only case)")
    return rep, kind


def print_report(case, rep, kind, out=None):
    import sys
    out = out or sys.stdout
    label = {"foam": "OpenFOAM/coupled case", "dem": "DEM-only case"}.get(kind, "case")
    if rep.problems:
        print(f"meltdem check: {case} ({label}): {len(rep.problems)} problem(s)", file=out)
        for p in rep.problems:
            print(f"  ERROR {p}", file=out)
    else:
        print(f"meltdem check: {case} ({label}): OK", file=out)
        for c in rep.checked:
            print(f"  ok    {c}", file=out)
    for n in rep.notes:
        print(f"  note  {n}", file=out)
    return 0 if not rep.problems else 1
