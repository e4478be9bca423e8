"""What a finished run left in its case folder, read once for the plots and the summary:
the coupling ledger (postProcessing/particleLedger/ledger.csv, columns from
ConservationLedger::csv_header), the per-step particle tally (particles.csv next to it), the
meltdemBalance rows (postProcessing/<name>/<startTime>/balance.csv, restarts concatenated),
the solver logs (wall time) and the case's laser dictionary (constant/meltdemProperties)."""
import glob
import os
import re

import numpy as np


def read_csv(path):
    """Structured array of a CSV with a header row (names kept as written), or None."""
    if not path or not os.path.exists(path) or os.path.getsize(path) == 0:
        return None
    with open(path) as f:
        header = f.readline().strip().split(",")
    try:
        d = np.genfromtxt(path, delimiter=",", skip_header=1, dtype=float, invalid_raise=False)
    except ValueError:
        return None
    if d.size == 0:
        return None
    d = np.atleast_2d(d)
    if d.shape[1] != len(header):
        return None
    out = np.zeros(len(d), dtype=[(h, float) for h in header])
    for k, h in enumerate(header):
        out[h] = d[:, k]
    return out


def ledger_path(case):
    p = os.path.join(case, "postProcessing", "particleLedger", "ledger.csv")
    return p if os.path.exists(p) else None


def ledger(case):
    return read_csv(ledger_path(case))


def particles_csv(case):
    return read_csv(os.path.join(case, "postProcessing", "particleLedger", "particles.csv"))


def balance_rows(case):
    """meltdemBalance rows: every postProcessing/*/<startTime>/balance.csv with a laserPower or
    metalMass column, start times in order, a restart's rows replacing the overlap. Returns
    (function object name, structured array) or (None, None)."""
    found = {}
    for p in glob.glob(os.path.join(case, "postProcessing", "*", "*", "balance.csv")):
        name, start = p.split(os.sep)[-3], p.split(os.sep)[-2]
        try:
            t0 = float(start)
        except ValueError:
            continue
        found.setdefault(name, []).append((t0, p))
    for name in sorted(found, key=lambda n: (n != "particleBalance", n)):
        parts = [read_csv(p) for _, p in sorted(found[name])]
        parts = [d for d in parts if d is not None and "time" in d.dtype.names]
        if not parts:
            continue
        rows = parts[0]
        for d in parts[1:]:
            if d.dtype.names != rows.dtype.names:
                continue
            t0 = d["time"][0]
            at = np.isclose(rows["time"], t0, rtol=1e-12, atol=0)
            if "deltaT" in d.dtype.names and d["deltaT"][0] == 0 and at.any():
                # a resumed segment's first row is its start state (no step): the row the run
                # it continues wrote at that time has the step's flows and sources
                rows = np.concatenate([rows[(rows["time"] < t0) | at][:np.argmax(at) + 1], d[1:]])
            else:
                rows = np.concatenate([rows[rows["time"] < t0], d])
        return name, rows
    return None, None


def foam_log(case):
    logs = sorted(glob.glob(os.path.join(case, "log.meltdemFoam*")), key=os.path.getmtime)
    return logs[-1] if logs else None


def wall_time(case):
    """(seconds, source) of the run: the solver's last ClockTime, else LAMMPS' 'Total wall time',
    else None. The wall_seconds file `meltdem run` and the scenes write comes first: it times the
    whole job, and LAMMPS truncates its own to whole seconds."""
    p = os.path.join(case, "wall_seconds")
    if os.path.exists(p):
        try:
            return float(open(p).read().split()[0]), "wall_seconds (the whole job)"
        except (ValueError, IndexError):
            pass
    log = foam_log(case)
    if log:
        m = re.findall(r"ClockTime = (\S+) s", open(log, errors="replace").read())
        if m:
            return float(m[-1]), os.path.basename(log) + " ClockTime"
    p = os.path.join(case, "log.lammps")
    if os.path.exists(p):
        m = re.findall(r"Total wall time: (\d+):(\d+):(\d+)", open(p, errors="replace").read())
        if m:
            h, mi, s = (int(v) for v in m[-1])
            return float(3600 * h + 60 * mi + s), "log.lammps Total wall time"
    return None, None


def _dict_block(text, name):
    """Text of the top-level OpenFOAM sub-dictionary 'name { ... }' (braces balanced)."""
    m = re.search(r"(^|\n)\s*" + re.escape(name) + r"\s*\{", text)
    if not m:
        return None
    i, depth = m.end(), 1
    while i < len(text) and depth:
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        i += 1
    return text[m.end():i - 1]


def _vector(block, key):
    m = re.search(r"(^|[\s;{])" + key + r"\s+\(\s*([^()]+?)\s*\)\s*;", block)
    return np.array([float(v) for v in m.group(2).split()]) if m else None


def _scalar(block, key):
    m = re.search(r"(^|[\s;{])" + key + r"\s+([0-9eE.+-]+)\s*;", block)
    return float(m.group(2)) if m else None


def laser(case):
    """The laser of constant/meltdemProperties as a dict (position, velocity, direction, tStart,
    tStop, tOn, tOff, path points, speed, power, absorptivity), or None."""
    p = os.path.join(case, "constant", "meltdemProperties")
    if not os.path.exists(p):
        return None
    text = re.sub(r"//[^\n]*", "", open(p, errors="replace").read())
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    b = _dict_block(text, "laser")
    if b is None:
        return None
    out = {k: _vector(b, k) for k in ("position", "velocity", "direction")}
    out.update({k: _scalar(b, k) for k in ("tStart", "tStop", "tOn", "tOff", "speed", "power", "absorptivity")})
    m = re.search(r"path\s*\(((?:\s*\([^()]*\))+)\s*\)\s*;", b)
    out["path"] = ([np.array([float(v) for v in q.split()]) for q in re.findall(r"\(([^()]*)\)", m.group(1))]
                   if m else None)
    return out


def track(case, t_end):
    """A moving laser: dict start, end (beam-axis points at the start of the motion and at t_end
    or when the motion / beam stopped), axis (unit, along the track), up (unit, against the
    beam), or None for a fixed beam."""
    las = laser(case)
    if not las:
        return None
    d = las["direction"] if las["direction"] is not None else np.array([0.0, 0.0, -1.0])
    up = -d / np.linalg.norm(d)
    t0 = las["tStart"] or 0.0
    stops = [t for t in (las["tStop"], las["tOff"], t_end) if t is not None]
    t1 = max(t0, min(stops))
    if las["path"] and len(las["path"]) >= 2 and las["speed"]:
        pts = las["path"]
        seg = [np.linalg.norm(b - a) for a, b in zip(pts[:-1], pts[1:])]
        walk = min(las["speed"] * (t1 - t0), sum(seg))
        start, end, left = pts[0], pts[0], walk
        for a, b, L in zip(pts[:-1], pts[1:], seg):
            if left <= L:
                end = a + (b - a) * (left / L if L else 0)
                break
            left -= L
            end = b
    elif las["velocity"] is not None and np.linalg.norm(las["velocity"]) > 0 and las["position"] is not None:
        start = las["position"]
        end = start + las["velocity"] * (t1 - t0)
    else:
        return None
    axis = end - start
    if np.linalg.norm(axis) == 0:
        return None
    axis = axis / np.linalg.norm(axis)
    return {"start": start, "end": end, "axis": axis, "up": up, "laser": las}
