#!/usr/bin/python3
"""Bed thickness and packing fraction of a settled powder bed from a LAMMPS dump.

    bed_stats.py bed.dump [--up y] [--column 60e-6]

Reads the last snapshot of a custom dump with columns radius x y z (and vx vy vz) and
prints, with 'up' the vertical axis (y as in thesis table 4.3):
  thickness H  mean over a grid of vertical columns (about 2 mean diameters wide, 60 um)
               of the highest particle top (centre + radius) in the column;
  packing      total sphere volume / (floor area x H): the thesis's "compaction factor"
               of a thin bed, surface roughness included;
  core packing sphere volume inside the slab 0.25 H .. 0.75 H (exact sphere slices) /
               slab volume: the packing inside the bed, comparable with random packings.
As a module: bed_stats(path, up, column) returns a dict.
"""
import argparse
import math

import numpy as np


def read_last_snapshot(path):
    with open(path) as f:
        lines = f.read().splitlines()
    starts = [k for k, l in enumerate(lines) if l.startswith("ITEM: TIMESTEP")]
    lines = lines[starts[-1]:]
    n = int(lines[3])
    box = np.array([[float(v) for v in lines[5 + k].split()[:2]] for k in range(3)])
    cols = lines[8].split()[2:]
    data = np.array([[float(v) for v in l.split()] for l in lines[9:9 + n]]).reshape(n, len(cols))
    return box, {c: data[:, k] for k, c in enumerate(cols)}


def slice_volume(y0, r, a, b):
    """volume of the spheres (centres y0, radii r) between the planes y = a and y = b"""
    lo = np.clip(a - y0, -r, r)
    hi = np.clip(b - y0, -r, r)
    F = lambda t: math.pi * (r * r * t - t ** 3 / 3.0)  # noqa: E731
    return F(hi) - F(lo)


def bed_stats(path, up="y", column=60e-6):
    box, a = read_last_snapshot(path)
    axes = "xyz"
    iu = axes.index(up)
    h1, h2 = [k for k in range(3) if k != iu]
    r = a["radius"]
    pos = np.stack([a["x"], a["y"], a["z"]], axis=1)
    L1, L2 = box[h1, 1] - box[h1, 0], box[h2, 1] - box[h2, 0]
    floor = box[iu, 0]
    n1, n2 = max(1, round(L1 / column)), max(1, round(L2 / column))
    c1 = np.minimum(((pos[:, h1] - box[h1, 0]) / L1 * n1).astype(int), n1 - 1)
    c2 = np.minimum(((pos[:, h2] - box[h2, 0]) / L2 * n2).astype(int), n2 - 1)
    tops = np.zeros((n1, n2))
    np.maximum.at(tops, (c1, c2), pos[:, iu] + r - floor)
    H = tops.mean()
    V = (4.0 / 3.0 * math.pi * r ** 3).sum()
    A = L1 * L2
    y = pos[:, iu] - floor
    core = slice_volume(y, r, 0.25 * H, 0.75 * H).sum() / (A * 0.5 * H)
    speed = np.sqrt(a["vx"] ** 2 + a["vy"] ** 2 + a["vz"] ** 2) if "vx" in a else np.zeros(1)
    m = a["mass"] if "mass" in a else r ** 3
    rms = math.sqrt((m * speed ** 2).sum() / m.sum())
    return {"particles": len(r), "thickness": H, "packing": V / (A * H), "core_packing": core,
            "solid_layer": V / A, "d_mean": 2 * r.mean(), "d_min": 2 * r.min(), "d_max": 2 * r.max(),
            "max_speed": speed.max(), "rms_speed": rms, "columns": n1 * n2, "empty_columns": int((tops == 0).sum())}


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("dump")
    p.add_argument("--up", default="y", choices=list("xyz"))
    p.add_argument("--column", type=float, default=60e-6)
    args = p.parse_args()
    s = bed_stats(args.dump, args.up, args.column)
    print(f"particles            {s['particles']}")
    print(f"diameter min/mean/max {s['d_min'] * 1e6:.1f} / {s['d_mean'] * 1e6:.1f} / {s['d_max'] * 1e6:.1f} um")
    print(f"solid layer V/A      {s['solid_layer'] * 1e6:.2f} um")
    print(f"bed thickness H      {s['thickness'] * 1e6:.2f} um   (thesis table 4.4: ~60 um)")
    print(f"packing V/(A H)      {s['packing']:.3f}      (thesis table 4.4: 0.5)")
    print(f"core packing         {s['core_packing']:.3f}      (random poured beds: 0.55-0.64)")
    print(f"speed rms / largest  {s['rms_speed']:.3g} / {s['max_speed']:.3g} m/s")
