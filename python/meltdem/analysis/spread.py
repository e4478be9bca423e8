#!/usr/bin/python3
"""The layer a spreader left on the build plate (examples/powder-spread), from its final dump.

    python3 -m meltdem.analysis.spread CASE     (CASE holds spread.dump and the run's output)

The run prints its geometry in one line (``SPREAD spreader ... xplate0 .. xplate1 .. ybase ..
gap .. Lz ..``); the dump has the columns id type radius mass x y z (type 1: spread grains,
type 2: the frozen previous layer). Measured on the plate's inner part (2 d_max in from
each end, so the edges do not enter):

  packing     effective layer packing fraction: the spread grains' volume per plate area
              over the nominal layer thickness (the gap): phi = V / (A gap), the measure of
              the NIST/Penny experiments (mass deposited / (rho A layer thickness)).
  thickness   surface height map H(x, z) on a grid of d_max/4 columns: the highest sphere
              surface over the column's centre (the base height where no grain covers it);
              the profile is its mean per d_max-wide band along x, the thickness its mean,
              all above the base (the plate, or the previous layer's mean top).
  roughness   Sq = rms of H about its mean (ISO 25178 areal).
  uncovered   the fraction of the columns that no spread grain covers.
  segregation mean diameter of the spread grains per band along x; its slope (linear fit,
              um per mm) and the ratio of the last third's mean to the first third's, against
              the heap's mean diameter.
  carried     spread grains past the plate's end (the pit and the table after the plate): the
              powder the spreader dragged past the plate, as a count and a mass fraction.
Every spread grain is booked in one place: dosing area (behind the plate), plate, past it.
As a module: spread_stats(case) returns a dict; layer_bed(case, lx, out) writes the plate's
middle lx as a bed dump (floor at y = 0, x from 0) for the melt scenes' --bed.
"""
import argparse
import json
import os
import re

import numpy as np

from ..io import dumps


def run_geometry(case):
    """the SPREAD line the run printed into CASE/log.lammps"""
    path = os.path.join(case, "log.lammps")
    m = re.findall(r"^SPREAD (.*)$", open(path).read(), re.M) if os.path.exists(path) else []
    if m:
        kv = m[-1].split()
        return {k: (v if k in ("spreader", "base") else float(v)) for k, v in zip(kv[0::2], kv[1::2])}
    raise RuntimeError(f"{case}: no 'SPREAD' line in log.lammps: the spreading run did not finish")


def surface_map(x, y, z, r, xs, zs, lz, base, lx=None):
    """highest sphere surface over each column (xs[i], zs[j]), base where none covers it;
    periodic in z over lz, and in x over lx when given"""
    H = np.full((len(xs), len(zs)), base)
    for xi, yi, zi, ri in zip(x, y, z, r):
        dx = xs - xi if lx is None else (xs - xi + lx / 2) % lx - lx / 2
        ix = np.nonzero(np.abs(dx) < ri)[0]
        if not len(ix):
            continue
        dz = (zs - zi + lz / 2) % lz - lz / 2
        iz = np.nonzero(np.abs(dz) < ri)[0]
        if not len(iz):
            continue
        rho2 = dx[ix, None] ** 2 + dz[None, iz] ** 2
        top = np.where(rho2 < ri * ri, yi + np.sqrt(np.maximum(ri * ri - rho2, 0.0)), -np.inf)
        H[np.ix_(ix, iz)] = np.maximum(H[np.ix_(ix, iz)], top)
    return H


def spread_stats(case):
    geo = run_geometry(case)
    d = dumps.columns(dumps.read_frames(os.path.join(case, "spread.dump"))[-1])
    typ, x, y, z, r, m = d["type"], d["x"], d["y"], d["z"], d["radius"], d["mass"]
    dmax, lz, base, gap = geo["dhi"], geo["Lz"], geo["ybase"], geo["gap"]
    x0, x1 = geo["xplate0"], geo["xplate1"]
    spread = typ == 1
    a, b = x0 + 2 * dmax, x1 - 2 * dmax                    # the plate's inner part
    on = spread & (x >= a) & (x < b) & (y > 0.0)
    behind = spread & (x < x0)
    carried = spread & (x >= x1)
    plate = spread & (x >= x0) & (x < x1)
    area = (b - a) * lz
    vol = 4.0 / 3.0 * np.pi * r ** 3
    packing = vol[on].sum() / (area * gap)

    # surface height map and its profile along x (only the spread grains and the frozen base)
    h = dmax / 4
    xs = np.arange(a + h / 2, b, h)
    zs = np.arange(h / 2, lz, h)
    sel = (x > a - dmax) & (x < b + dmax) & (y > -dmax)
    H = surface_map(x[sel], y[sel], z[sel], r[sel], xs, zs, lz, 0.0) - base
    H = np.maximum(H, 0.0)
    mine = sel & spread                                     # columns no spread grain covers
    uncovered = float(np.mean(np.isinf(surface_map(x[mine], y[mine], z[mine], r[mine], xs, zs, lz, -np.inf))))
    band = max(1, int(round(dmax / h)))
    nb = len(xs) // band
    prof_x = xs[:nb * band].reshape(nb, band).mean(axis=1)
    prof_h = H[:nb * band].reshape(nb, band, -1).mean(axis=(1, 2))
    # segregation: mean diameter per band, its slope, last third / first third
    in_band = [on & (x >= xc - dmax / 2) & (x < xc + dmax / 2) for xc in prof_x]
    dm = np.array([2 * r[k].mean() if k.any() else np.nan for k in in_band])
    ok = np.isfinite(dm)
    slope = float(np.polyfit(prof_x[ok], dm[ok], 1)[0]) if ok.sum() > 2 else float("nan")
    third = (b - a) / 3
    first = on & (x < a + third)
    last = on & (x >= b - third)
    ratio = float(r[last].mean() / r[first].mean()) if first.any() and last.any() else float("nan")
    return {
        "spreader": geo["spreader"], "speed_m_per_s": geo["V"], "gap_m": gap, "base": geo["base"],
        "grains": int(spread.sum()), "grains_behind_plate": int(behind.sum()),
        "grains_on_plate": int(plate.sum()), "grains_carried_past_plate": int(carried.sum()),
        "mass_fraction_carried_past_plate": float(m[carried].sum() / m[spread].sum()),
        "packing_fraction": float(packing),
        "solid_thickness_m": float(vol[on].sum() / area),
        "thickness_m": float(H.mean()), "roughness_Sq_m": float(H.std()),
        "uncovered_fraction": uncovered,
        "profile_x_m": [float(v - x0) for v in prof_x], "profile_thickness_m": [float(v) for v in prof_h],
        "profile_mean_diameter_m": [float(v) for v in dm],
        "mean_diameter_layer_m": float(2 * r[on].mean()) if on.any() else float("nan"),
        "mean_diameter_heap_m": float(2 * r[spread].mean()),
        "segregation_slope_um_per_mm": slope * 1e3,
        "segregation_last_over_first_third": ratio,
    }


def layer_bed(case, lx, out):
    """the spread layer over the plate's middle lx (x shifted to start at 0, y so the plate is
    at 0) as a bed dump (id type radius mass x y z vx vy vz) for the melt scenes' --bed: the
    grains that lie wholly inside lx and the run's width Lz (the melt scenes have side walls)"""
    geo = run_geometry(case)
    d = dumps.columns(dumps.read_frames(os.path.join(case, "spread.dump"))[-1])
    x0, x1, lz = geo["xplate0"], geo["xplate1"], geo["Lz"]
    if lx > x1 - x0:
        raise ValueError(f"a bed {lx:g} m long needs a plate at least as long (this one is {x1 - x0:g} m)")
    xa = 0.5 * (x0 + x1) - lx / 2
    x, y, z, r = d["x"] - xa, d["y"], d["z"], d["radius"]
    keep = (d["type"] == 1) & (x >= r) & (x <= lx - r) & (z >= r) & (z <= lz - r) & (y > 0.0)
    idx = np.nonzero(keep)[0]
    with open(out, "w") as f:
        f.write(f"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n{len(idx)}\nITEM: BOX BOUNDS ff ff ff\n"
                f"0 {lx!r}\n0 {float((y[idx] + r[idx]).max()) if len(idx) else 0.0!r}\n0 {lz!r}\n"
                "ITEM: ATOMS id type radius mass x y z vx vy vz\n")
        for i, k in enumerate(idx, 1):
            values = " ".join(repr(float(v)) for v in (r[k], d["mass"][k], x[k], y[k], z[k]))
            f.write(f"{i} 1 {values} 0 0 0\n")
    return len(idx)


def layer_packing(case):
    """{k: (bed packing, packing below the newest layer)} after each layer k of a run with layers > 1
    (spread.dump is layer 1, spread_layerK.dump the others), in the plate's inner part: the grain
    volume over plate area x k gaps (the cavity floor at -(k - 1) gap up to the spreader's lowest
    point), and the volume below the previous layers' top (y < 0) over plate area x (k - 1) gaps
    (nan for k = 1)"""
    geo = run_geometry(case)
    gap, lz = geo["gap"], geo["Lz"]
    a, b = geo["xplate0"] + 2 * geo["dhi"], geo["xplate1"] - 2 * geo["dhi"]
    area = (b - a) * lz
    paths = {1: os.path.join(case, "spread.dump")}
    for name in os.listdir(case):
        m = re.fullmatch(r"spread_layer(\d+)\.dump", name)
        if m:
            paths[int(m.group(1))] = os.path.join(case, name)
    out = {}
    for k in sorted(paths):
        d = dumps.columns(dumps.read_frames(paths[k])[-1])
        vol = 4.0 / 3.0 * np.pi * d["radius"] ** 3
        inner = (d["x"] > a) & (d["x"] < b) & (d["y"] < gap)
        below = inner & (d["y"] < 0.0)
        out[k] = (float(vol[inner].sum()) / (area * k * gap),
                  float(vol[below].sum()) / (area * (k - 1) * gap) if k > 1 else float("nan"))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case")
    a = ap.parse_args(argv)
    s = spread_stats(a.case)
    print(json.dumps({k: v for k, v in s.items() if not k.startswith("profile")}, indent=1))


if __name__ == "__main__":
    main()
