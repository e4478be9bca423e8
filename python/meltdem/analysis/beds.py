#!/usr/bin/python3
"""Bed thickness and packing fraction of a settled powder bed from a LAMMPS dump.

    python3 -m meltdem.analysis.beds bed.dump [--up y] [--walls] [--column 60e-6] [--profile FILE]

Reads the last snapshot of a custom dump with columns radius x y z (and vx vy vz, mass)
and prints, with 'up' the vertical axis (y as in Codina2019 table 4.3), floor at the box's
lower bound:

  solid fraction profile phi(y)  the solid area fraction of the horizontal plane at
               height y (exact sphere cross-sections). With --walls (closed box) only
               spheres whose centres lie at least d_max from the side walls count, over
               that inner area, so the wall layering does not enter.
  slab packing phi_b  mean of phi(y) over the slab 0.25 H .. 0.75 H (the bulk value;
               in a bed under two diameters thick this slab still holds the dense
               floor layer, where the sphere centres line up at one radius, so phi_b
               is above the packing of the layer as a whole).
  thickness H  the height where phi(y) falls to phi_b / 2 (last crossing from below),
               i.e. the mean level of the rough top surface. H and phi_b are found
               together by fixed-point iteration from the column-top thickness.
  packing      total sphere volume / (floor area x H) = solid layer / H: the packing
               of the whole layer (Codina2019's "compaction factor": it turns the bed
               thickness into the solid thickness, 60 um x 0.5 = 30 um); compare with
               random poured packings (0.55-0.64).
  top thickness  mean over a grid of vertical columns (about 2 mean diameters wide,
               60 um) of the highest particle top in the column (for information: the
               peaks of the top layer; always above H).
As a module: bed_stats(path, up, column, walls) returns a dict.
"""
import argparse
import math

import numpy as np

from ..io import dumps


def slice_volume(y0, r, a, b):
    """volume of the spheres (centres y0, radii r) between the planes y = a and y = b"""
    lo = np.clip(a - y0, -r, r)
    hi = np.clip(b - y0, -r, r)
    F = lambda t: math.pi * (r * r * t - t ** 3 / 3.0)  # noqa: E731
    return F(hi) - F(lo)


def solid_profile(y0, r, area, ys):
    """solid area fraction of the planes at heights ys (spheres: centre heights y0, radii r)"""
    phi = np.empty(len(ys))
    for k, y in enumerate(ys):
        c = r * r - (y - y0) ** 2
        phi[k] = math.pi * c[c > 0].sum() / area
    return phi


def thickness_and_packing(y0, r, area, H0, dy=0.1e-6):
    """fixed point H = height where phi falls to phi_b/2, phi_b = mean phi in 0.25-0.75 H"""
    ys = np.arange(0.0, (y0 + r).max() + dy, dy)
    phi = solid_profile(y0, r, area, ys)
    H = H0
    for _ in range(50):
        sel = (ys >= 0.25 * H) & (ys <= 0.75 * H)
        phib = phi[sel].mean()
        above = np.nonzero(phi >= 0.5 * phib)[0]
        k = above[-1]  # last plane still at half the bulk fraction; interpolate to the next
        Hn = ys[k] + dy * (phi[k] - 0.5 * phib) / max(phi[k] - phi[k + 1], 1e-300) if k + 1 < len(ys) else ys[k]
        if abs(Hn - H) < 1e-3 * dy:
            H = Hn
            break
        H = Hn
    return H, phib, ys, phi


def bed_stats(path, up="y", column=60e-6, walls=False):
    last = dumps.read_frames(path)[-1]
    box, a = last["box"], dumps.columns(last)
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
    # profile over the inner area (closed box: centres at least d_max from the side walls)
    inner = np.ones(len(r), bool)
    Ain = A
    if walls:
        m = 2 * r.max()
        inner = ((pos[:, h1] > box[h1, 0] + m) & (pos[:, h1] < box[h1, 1] - m)
                 & (pos[:, h2] > box[h2, 0] + m) & (pos[:, h2] < box[h2, 1] - m))
        Ain = (L1 - 2 * m) * (L2 - 2 * m)
    Hh, phib, ys, phi = thickness_and_packing(y[inner], r[inner], Ain, H)
    speed = np.sqrt(a["vx"] ** 2 + a["vy"] ** 2 + a["vz"] ** 2) if "vx" in a else np.zeros(1)
    m = a["mass"] if "mass" in a else r ** 3
    rms = math.sqrt((m * speed ** 2).sum() / m.sum())
    return {"particles": len(r), "thickness": Hh,
            "packing_layer": (4.0 / 3.0 * math.pi * r[inner] ** 3).sum() / (Ain * Hh), "packing_slab": phib,
            "top_thickness": H, "profile": (ys, phi),
            "solid_layer": V / A, "d_mean": 2 * r.mean(), "d_min": 2 * r.min(), "d_max": 2 * r.max(),
            "max_speed": speed.max(), "rms_speed": rms, "columns": n1 * n2, "empty_columns": int((tops == 0).sum())}


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("dump")
    p.add_argument("--up", default="y", choices=list("xyz"))
    p.add_argument("--column", type=float, default=60e-6)
    p.add_argument("--walls", action="store_true", help="closed box: leave out d_max next to the side walls")
    p.add_argument("--profile", help="write the solid fraction profile (height [m], phi) to this file")
    args = p.parse_args()
    s = bed_stats(args.dump, args.up, args.column, args.walls)
    if args.profile:
        np.savetxt(args.profile, np.column_stack(s["profile"]), header="height_m solid_fraction")
    print(f"particles            {s['particles']}")
    print(f"diameter min/mean/max {s['d_min'] * 1e6:.1f} / {s['d_mean'] * 1e6:.1f} / {s['d_max'] * 1e6:.1f} um")
    print(f"solid layer V/A      {s['solid_layer'] * 1e6:.2f} um")
    print(f"bed thickness H      {s['thickness'] * 1e6:.2f} um   (phi = phi_b/2; thesis table 4.4: ~60 um)")
    print(f"packing V/(A H)      {s['packing_layer']:.3f}      (poured beds 0.55-0.64; thesis table 4.4: 0.5)")
    print(f"slab packing phi_b   {s['packing_slab']:.3f}      (0.25-0.75 H, floor layer included)")
    print(f"top thickness        {s['top_thickness'] * 1e6:.2f} um   (mean column top)")
    print(f"speed rms / largest  {s['rms_speed']:.3g} / {s['max_speed']:.3g} m/s")
