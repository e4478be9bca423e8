"""Particles for ParaView: LAMMPS custom dumps -> one .vtp (PolyData points) per frame and a .pvd
series with the simulated time as timestep.

Sources, in order: CASE/particles/*.dump (the coupled solver's one frame per OpenFOAM write
time), else every custom dump in the case folder itself (*.dump, dump.*). Columns come from the
'ITEM: ATOMS' header line; every column becomes a point array, plus 'velocity' (vx vy vz),
'radius' and 'diameter', and for fix powder/melt's per-atom array (f_ID[1], f_ID[2]; ID from the
LAMMPS input, any id) 'temperature' [K] and 'melted_fraction'.
Time of a frame: ITEM: TIME when the dump has it (dump_modify time yes), else the step mapped
through log.lammps' Step/Time thermo columns, else step x the input's fixed timestep, else the
step itself (the .pvd then counts steps; reported as time_source)."""
import glob
import os
import re

import numpy as np

from . import vtkxml
from .dumps import read_frames

POSITION = (("x", "y", "z"), ("xu", "yu", "zu"), ("xs", "ys", "zs"))


def is_particle_dump(path):
    """A LAMMPS text dump whose ATOMS header names positions (x y z, xu.., xs..)."""
    try:
        with open(path, errors="replace") as f:
            head = [f.readline() for _ in range(12)]
    except OSError:
        return False
    for line in head:
        if line.startswith("ITEM: ATOMS"):
            cols = line.split()[2:]
            return any(all(c in cols for c in p) for p in POSITION)
    return False


def find_dumps(case):
    """(kind, [paths]): 'series' for CASE/particles/*.dump (one frame each, ordered by their time
    name), else 'files' for the dumps in the case folder (each its own series)."""
    pdir = os.path.join(case, "particles")
    if os.path.isdir(pdir):
        files = [p for p in glob.glob(os.path.join(pdir, "*.dump")) if is_particle_dump(p)]

        def key(p):
            stem = os.path.basename(p)[:-5]
            try:
                return (0, float(stem), stem)
            except ValueError:
                return (1, 0.0, stem)
        if files:
            return "series", sorted(files, key=key)
    files = sorted(set(glob.glob(os.path.join(case, "*.dump")) + glob.glob(os.path.join(case, "dump.*"))))
    return "files", [p for p in files if os.path.isfile(p) and is_particle_dump(p)]


def lammps_inputs(case):
    """Text of the LAMMPS inputs in the case folder (in.*), concatenated."""
    txt = ""
    for p in sorted(glob.glob(os.path.join(case, "in.*"))):
        try:
            txt += open(p, errors="replace").read() + "\n"
        except OSError:
            pass
    return txt


def melt_fix_ids(case):
    """Fix ids of powder/melt in the case's LAMMPS input (default ['melt'])."""
    ids = re.findall(r"^\s*fix\s+(\S+)\s+\S+\s+powder/melt\b", lammps_inputs(case), re.M)
    return ids or ["melt"]


def run_logs(case):
    """log.lammps and, after resumes, the logs of the runs it continues (log.lammps.1, .2, ...:
    meltdem run's keep_log), oldest first."""
    kept = glob.glob(os.path.join(case, "log.lammps.[0-9]*"))
    kept = sorted((p for p in kept if p.rsplit(".", 1)[1].isdigit()), key=lambda p: int(p.rsplit(".", 1)[1]))
    path = os.path.join(case, "log.lammps")
    return kept + ([path] if os.path.exists(path) else [])


def step_time_map(case):
    """(steps, times) from the thermo tables with Step and Time columns of log.lammps and the
    logs of the runs it resumed (a step in several: the latest log's time)."""
    at = {}
    for path in run_logs(case):
        cols = None
        for line in open(path, errors="replace"):
            w = line.split()
            if "Step" in w and "Time" in w:
                cols = (w.index("Step"), w.index("Time"), len(w))
                continue
            # a thermo row: as many numbers as the header has columns (warnings in between are skipped)
            if cols and len(w) == cols[2] and w[0].isdigit():
                try:
                    at[int(w[cols[0]])] = float(w[cols[1]])
                except ValueError:
                    continue
    if len(at) < 2:
        return None
    s = np.array(sorted(at))
    return s, np.array([at[k] for k in s])


def fixed_timestep(case):
    """The input's 'timestep X' when the input has no variable-step fix (dt/reset, powder/dt) and
    one step for all its runs."""
    txt = lammps_inputs(case)
    if re.search(r"^\s*fix\s+\S+\s+\S+\s+(dt/reset|powder/dt)\b", txt, re.M):
        return None
    m = re.findall(r"^\s*timestep\s+(\S+)\s*$", txt, re.M)
    try:
        steps = {float(x) for x in m}
    except ValueError:
        return None
    return steps.pop() if len(steps) == 1 else None


def run_segments(case):
    """[(first step, its time, dt)] of the runs of a one-file LAMMPS input that changes its
    'timestep X' between 'run N' commands, from step 0 (no include, loop, restart, step reset or
    variable-step fix; numbers as written), else None."""
    inputs = glob.glob(os.path.join(case, "in.*"))
    txt = lammps_inputs(case)
    if len(inputs) != 1 or re.search(r"^\s*(include|jump|label|next|reset_timestep|read_restart)\b|"
                                     r"^\s*fix\s+\S+\s+\S+\s+(dt/reset|powder/dt)\b", txt, re.M):
        return None
    segments, dt, step, t = [], None, 0, 0.0
    for line in txt.splitlines():
        w = line.split("#", 1)[0].split()
        try:
            if w and w[0] == "timestep" and len(w) == 2:
                dt = float(w[1])
            elif w and w[0] == "run" and len(w) >= 2:
                n = int(w[1])
                n = n - step if "upto" in w[2:] else n
                if dt is None or any(k in w[2:] for k in ("start", "stop", "every")):
                    return None
                segments.append((step, t, dt))
                step, t = step + n, t + n * dt
        except ValueError:
            return None
    return segments or None


def frame_times(case, frames):
    """Simulated time of each frame and where it came from."""
    if frames and all(f["time"] is not None for f in frames):
        return [f["time"] for f in frames], "ITEM: TIME"
    m = step_time_map(case)
    steps = [f["step"] for f in frames]
    if m is not None and min(steps) >= m[0][0] and max(steps) <= m[0][-1]:
        return [float(np.interp(s, m[0], m[1])) for s in steps], "log.lammps Step/Time"
    dt = fixed_timestep(case)
    if dt:
        return [s * dt for s in steps], "step x timestep"
    seg = run_segments(case)
    if seg:
        starts = [a for a, _, _ in seg]
        out = []
        for s in steps:
            a, t0, d = seg[max(0, int(np.searchsorted(starts, s, side="right")) - 1)]
            out.append(t0 + (s - a) * d)
        return out, "step x the timestep of each run"
    return [float(s) for s in steps], "step"


def frame_arrays(frame, melt_ids):
    """(positions (n, 3), {name: (array, components)}) of one frame."""
    cols = frame["columns"]
    d = frame["data"]
    c = {name: d[:, k] for k, name in enumerate(cols)}
    pos = None
    for p in POSITION:
        if all(k in c for k in p):
            pos = np.column_stack([c[k] for k in p])
            if p[0] == "xs":
                box = frame["box"]
                pos = box[:, 0] + pos * (box[:, 1] - box[:, 0])
            break
    arrays = {}
    for name in cols:
        if name in ("x", "y", "z", "xs", "ys", "zs", "xu", "yu", "zu"):
            continue
        a = c[name]
        if name in ("id", "type", "mol", "proc"):
            a = a.astype(np.int64)
        arrays[name] = (a, 1)
    if all(k in c for k in ("vx", "vy", "vz")):
        arrays["velocity"] = (np.column_stack([c["vx"], c["vy"], c["vz"]]), 3)
        arrays["speed"] = (np.sqrt(c["vx"] ** 2 + c["vy"] ** 2 + c["vz"] ** 2), 1)
    if "radius" in c:
        arrays["diameter"] = (2.0 * c["radius"], 1)
    elif "diameter" in c:
        arrays["radius"] = (0.5 * c["diameter"], 1)
    for fid in melt_ids:
        for k, alias in ((1, "temperature"), (2, "melted_fraction")):
            col = f"f_{fid}[{k}]"
            if col in c and alias not in arrays:
                arrays[alias] = (c[col], 1)
    return pos, arrays


def write_vtp(path, pos, arrays, time=None):
    n = len(pos)
    pd = "".join(vtkxml.data_array(name, a, comps) for name, (a, comps) in arrays.items())
    fd = (f"<FieldData>\n{vtkxml.data_array('TimeValue', np.array([time], float))}</FieldData>\n"
          if time is not None else "")
    text = ("<?xml version='1.0'?>\n"
            "<VTKFile type='PolyData' version='1.0' byte_order='LittleEndian' header_type='UInt64'>\n"
            f"<PolyData>\n{fd}<Piece NumberOfPoints='{n}' NumberOfVerts='{n}' NumberOfLines='0' "
            "NumberOfStrips='0' NumberOfPolys='0'>\n"
            f"<Points>\n{vtkxml.data_array('Points', np.asarray(pos, float).reshape(n, 3), 3)}</Points>\n"
            f"<Verts>\n{vtkxml.data_array('connectivity', np.arange(n, dtype=np.int64))}"
            f"{vtkxml.data_array('offsets', np.arange(1, n + 1, dtype=np.int64))}</Verts>\n"
            f"<PointData Scalars='{'radius' if 'radius' in arrays else ''}'>\n{pd}</PointData>\n"
            "</Piece>\n</PolyData>\n</VTKFile>\n")
    with open(path, "w") as f:
        f.write(text)


def write_series(case, out_dir, pvd_name, frames, times, subdir):
    """One .vtp per frame under out_dir/subdir and out_dir/pvd_name; returns the entries."""
    d = os.path.join(out_dir, subdir)
    os.makedirs(d, exist_ok=True)
    for old in glob.glob(os.path.join(d, "*.vtp")):
        os.remove(old)
    melt_ids = melt_fix_ids(case)
    entries = []
    for k, (fr, t) in enumerate(zip(frames, times)):
        pos, arrays = frame_arrays(fr, melt_ids)
        if pos is None:
            continue
        name = f"{subdir}_{k:05d}.vtp"
        write_vtp(os.path.join(d, name), pos, arrays, t)
        entries.append((t, f"{subdir}/{name}"))
    vtkxml.write_pvd(os.path.join(out_dir, pvd_name), entries)
    return entries


def convert(case, out_dir=None):
    """Write the particle series of a case; returns a list of dicts (pvd, source, frames,
    first_frame_particles, time_source). The series with the most frames is VTK/particles.pvd,
    further dumps VTK/particles-<name>.pvd."""
    case = os.path.abspath(case)
    out_dir = out_dir or os.path.join(case, "VTK")
    kind, paths = find_dumps(case)
    if not paths:
        return []
    os.makedirs(out_dir, exist_ok=True)
    if kind == "series":
        frames = []
        for p in paths:
            fr = read_frames(p)
            if fr:
                frames.append(fr[-1])
        sources = [(os.path.relpath(os.path.join(case, "particles"), case), frames)]
    else:
        sources = [(os.path.relpath(p, case), read_frames(p)) for p in paths]
        sources = [s for s in sources if s[1]]
        sources.sort(key=lambda s: -len(s[1]))
    out = []
    for k, (src, frames) in enumerate(sources):
        times, how = frame_times(case, frames)
        if k == 0:
            pvd, sub = "particles.pvd", "particles"
        else:
            tag = re.sub(r"[^A-Za-z0-9_.-]", "_", os.path.basename(src))
            pvd, sub = f"particles-{tag}.pvd", f"particles-{tag}"
        entries = write_series(case, out_dir, pvd, frames, times, sub)
        out.append({"pvd": os.path.join(out_dir, pvd), "source": src, "frames": len(entries),
                    "first_frame_particles": int(len(frames[0]["data"])) if frames else 0,
                    "time_source": how, "times": times})
    return out
