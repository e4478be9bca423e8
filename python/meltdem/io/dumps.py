"""LAMMPS text dumps (custom and atom style): frames with their step, time, box, column names
and data, the columns of a frame by name, and the path of each particle through a dump."""
import numpy as np


def read_frames(path):
    """Frames of a LAMMPS text dump: list of dicts step, time (None when absent), box (3, 2),
    columns (names), data (n, ncol float array). Only 'custom'/'atom' style dumps with an
    ATOMS header; raises ValueError on a truncated frame except the last (a run still writing)."""
    frames = []
    with open(path) as f:
        lines = f.read().splitlines()
    i, n = 0, len(lines)
    cur = {}
    while i < n:
        line = lines[i].strip()
        if not line.startswith("ITEM:"):
            i += 1
            continue
        item = line[5:].strip()
        if item.startswith("TIMESTEP"):
            step = int(lines[i + 1].split()[0])
            t = cur.get("time") if cur.get("step") is None else None
            cur = {"step": step, "time": t}
            i += 2
        elif item.startswith("TIME"):
            t = float(lines[i + 1].split()[0])
            if cur.get("step") is not None and "data" in cur:
                cur = {}
            cur["time"] = t
            i += 2
        elif item.startswith("UNITS"):
            i += 2
        elif item.startswith("NUMBER OF ATOMS"):
            cur["natoms"] = int(lines[i + 1].split()[0])
            i += 2
        elif item.startswith("BOX BOUNDS"):
            cur["box"] = np.array([[float(v) for v in lines[i + 1 + k].split()[:2]] for k in range(3)])
            i += 4
        elif item.startswith("ATOMS"):
            cols = item.split()[1:]
            na = cur.get("natoms", 0)
            rows = lines[i + 1:i + 1 + na]
            if len(rows) < na:
                if frames:   # the last frame of a dump being written: skip it
                    break
                raise ValueError(f"{path}: frame at step {cur.get('step')} has {len(rows)} of {na} atoms")
            data = np.array(" ".join(rows).split(), dtype=float).reshape(na, len(cols))
            cur.update(columns=cols, data=data)
            frames.append(cur)
            cur = {"step": None}
            i += 1 + na
        else:
            i += 1
    for fr in frames:
        fr.setdefault("time", None)
    return frames


def columns(frame):
    """{column name: array} of one frame."""
    return {c: frame["data"][:, k] for k, c in enumerate(frame["columns"])}


def tracks(path, dt):
    """{particle id: array of rows (time, the frame's other columns)} through all frames of a dump
    whose first column is id; a frame's time is its step x dt."""
    out = {}
    for fr in read_frames(path):
        t = fr["step"] * dt
        for row in fr["data"]:
            out.setdefault(int(row[0]), []).append([t] + list(row[1:]))
    return {k: np.array(v) for k, v in out.items()}
