"""pbf-layer: hatched tracks over a powder layer (examples/pbf-point's physics, bed, case writer
and analysis in ../pbf-point/pbf.py), and the layer's own analysis: per-track melt-pool width and
depth, the remelted overlap between neighbouring tracks, denudation and ejected grains.

Axes as in pbf.py: x along the tracks, y up (laser -y), z across (the hatch direction).
"""
import json
import math
import os

import numpy as np

from meltdem.case import foam as fc
from meltdem.io import dumps
from meltdem.loader import load_module

HERE = os.path.dirname(os.path.abspath(__file__))
pbf = load_module(os.path.join(HERE, "..", "pbf-point", "pbf.py"))

# grains per floor area of examples/pbf-line's beds (CI 160 on 280 x 160 um, full 1500 on 960 x 320 um)
GRAINS_PER_AREA = {"ci": 160 / (280e-6 * 160e-6), "full": 1500 / (960e-6 * 320e-6)}

VARIANTS = {
    # CI: three 120 um tracks 80 um apart, serpentine, the beam off for 50 us between one track's end
    # and the next one's start, on 10 um cells; 10 us of cooling after the last
    "ci": dict(lx=240e-6, ly=160e-6, lz=340e-6, sub=60e-6, dx=10e-6, power=312.0, rw=70e-6, v=2.0,
               tracks_n=3, hatch=80e-6, length=120e-6, x_start=60e-6, return_time=50e-6, order="serpentine",
               t_start=0.0, cool=10e-6, write=2.5e-6, dist="overlap"),
    # full: four 400 um tracks 100 um apart over 560 x 560 um of the paper's bed density
    "full": dict(lx=560e-6, ly=200e-6, lz=560e-6, sub=80e-6, dx=10e-6, power=312.0, rw=70e-6, v=2.0,
                 tracks_n=4, hatch=100e-6, length=400e-6, x_start=80e-6, return_time=50e-6, order="serpentine",
                 t_start=0.0, cool=30e-6, write=5e-6, dist="overlap"),
}
ORDERS = ("serpentine", "unidirectional")


def hatch_tracks(cfg):
    """[((x0, z0), (x1, z1))] of the tracks, centred across the floor, cfg['hatch'] apart, scanned
    alternately +x and -x (serpentine) or all +x (unidirectional)."""
    if cfg["order"] not in ORDERS:
        raise ValueError(f"order {cfg['order']!r} is not one of {', '.join(ORDERS)}")
    z0 = 0.5 * (cfg["lz"] - (cfg["tracks_n"] - 1) * cfg["hatch"])
    a, b = cfg["x_start"], cfg["x_start"] + cfg["length"]
    out = []
    for i in range(cfg["tracks_n"]):
        z = z0 + i * cfg["hatch"]
        forward = cfg["order"] == "unidirectional" or i % 2 == 0
        out.append(((a, z), (b, z)) if forward else ((b, z), (a, z)))
    return out


def config(size="ci", **entries):
    """The layer's configuration: the variant with the given entries replaced (hatch, tracks_n,
    order, return_time, v, length, dx, n, balance ...), its tracks, end time and grain count."""
    cfg = dict(VARIANTS[size])
    unknown = set(entries) - set(cfg) - {"n", "balance"}
    if unknown:
        raise ValueError(f"unknown layer entries: {', '.join(sorted(unknown))}")
    cfg.update({k: v for k, v in entries.items() if v is not None})
    for key in ("hatch", "length", "v"):
        if not cfg[key] > 0:
            raise ValueError(f"{key} must be > 0 (got {cfg[key]!r})")
    if cfg["return_time"] < 0 or cfg["tracks_n"] < 1:
        raise ValueError("return_time must be >= 0 and tracks_n >= 1")
    cfg["tracks"] = hatch_tracks(cfg)
    zs = [a[1] for a, _ in cfg["tracks"]]
    tol = 1e-3 * cfg["dx"]
    if (min(zs) < cfg["rw"] - tol or max(zs) > cfg["lz"] - cfg["rw"] + tol
            or cfg["x_start"] + cfg["length"] > cfg["lx"] + tol):
        raise ValueError("the tracks (and a beam radius around them) must lie on the floor: "
                         f"z {min(zs):.3g}..{max(zs):.3g} m on lz {cfg['lz']:.3g} m, "
                         f"x up to {cfg['x_start'] + cfg['length']:.3g} m on lx {cfg['lx']:.3g} m")
    last = pbf.track_intervals(cfg)[-1]
    cfg["t_end"] = last[1] + cfg["cool"]
    cfg.setdefault("n", None)
    if not cfg["n"]:
        cfg["n"] = int(round(GRAINS_PER_AREA[size] * cfg["lx"] * cfg["lz"]))
    cfg["variant"], cfg["scene"] = f"layer-{size}", "pbf-layer"
    return cfg


# ----------------------------------------------------------------------------------------------
# analysis


def molten_series(case, cfg):
    """[(t, molten mask (nz, ny, nx))] of the written times: metal (alpha >= 0.5) at or above the
    melting point."""
    n = pbf.ncells(cfg)
    out = []
    for d in fc.time_dirs(case):
        if float(d) == 0.0 or not os.path.exists(os.path.join(case, d, "T")):
            continue
        T = fc.lattice_field(case, d, "T", n, cfg["dx"])
        a = fc.lattice_field(case, d, "alpha.metal", n, cfg["dx"])
        out.append((float(d), (a >= 0.5) & (T >= pbf.T_MELT)))
    return out


def track_pools(cfg, series):
    """Per track: the cells it melted (a solid-to-molten transition between written times within
    its window, from its start to the next one's start) and the cells still molten from the track
    before when it started (a merged pool: the return time was too short to separate them)."""
    windows = pbf.track_intervals(cfg)
    starts = [w[0] for w in windows] + [math.inf]
    pools = []
    for i in range(len(windows)):
        melted = np.zeros_like(series[0][1]) if series else None
        carried = None
        prev = None
        for t, molten in series:
            if t < starts[i]:
                prev = molten
                continue
            if t >= starts[i + 1]:
                break
            if carried is None:
                carried = prev if prev is not None else np.zeros_like(molten)
            melted |= molten & ~prev if prev is not None else molten
            prev = molten
        pools.append(dict(melted=melted, carried=carried if carried is not None else np.zeros_like(melted)))
    return pools


def middle_columns(cfg, track, nx):
    """x indices of the middle half of a track (away from where it starts and stops)."""
    (xa, _), (xb, _) = track
    lo, hi = min(xa, xb), max(xa, xb)
    xc = (np.arange(nx) + 0.5) * cfg["dx"]
    return np.nonzero((xc >= lo + 0.25 * (hi - lo)) & (xc <= hi - 0.25 * (hi - lo)))[0]


def z_run(mask, cols, z, h):
    """Per column of cols: the contiguous run of z cells of mask (nz, ny, nx), projected on z,
    that contains z (0 when z's cell is not in mask); (mean length, mean low face, mean high face)."""
    k = min(max(int(z / h), 0), mask.shape[0] - 1)
    runs = []
    for i in cols:
        on = mask[:, :, i].any(axis=1)
        if not on[k]:
            runs.append((0.0, z, z))
            continue
        lo, hi = k, k
        while lo > 0 and on[lo - 1]:
            lo -= 1
        while hi + 1 < len(on) and on[hi + 1]:
            hi += 1
        runs.append(((hi - lo + 1) * h, lo * h, (hi + 1) * h))
    return tuple(float(np.mean(c)) for c in zip(*runs)) if runs else (0.0, z, z)


def depth_below(mask, cols, cfg):
    """Deepest cell-face depth of mask below the initial substrate surface over the columns cols."""
    h = cfg["dx"]
    js = np.nonzero(mask[:, :, cols].any(axis=(0, 2)))[0] if len(cols) else []
    return max(cfg["sub"] - js.min() * h, 0.0) if len(js) else 0.0


def denudation(case, cfg, pools, nx):
    """Powder cleared beside the layer's two outer tracks: over the track's x range, the gap between
    the edge of the track's melted band and the nearest grain surface outside it (grains whose centre
    lies beyond the edge), at the start and when the track's window ends (the next track starts,
    or the run ends); the growth of the gap is the denudation of that side (first track: its low-z
    side, last track: its high-z side)."""
    path = os.path.join(case, "traj.dump")
    if not os.path.exists(path) or not pools:
        return {}
    frames = [fr for fr in dumps.read_frames(path) if len(fr["data"])]
    windows = pbf.track_intervals(cfg)
    h = cfg["dx"]
    out = {}
    for side, i in (("low_z", 0), ("high_z", len(pools) - 1)):
        cols = middle_columns(cfg, cfg["tracks"][i], nx)
        width, lo, hi = z_run(pools[i]["melted"], cols, cfg["tracks"][i][0][1], h)
        if not width:
            continue
        edge = lo if side == "low_z" else hi
        x_lo, x_hi = sorted((cfg["tracks"][i][0][0], cfg["tracks"][i][1][0]))
        t_stop = windows[i + 1][0] if i + 1 < len(windows) else math.inf
        last = [fr for fr in frames if fr["time"] <= t_stop][-1]

        def gap(a):
            x, z, r = a[:, 1], a[:, 3], a[:, 7]
            near = (x >= x_lo) & (x <= x_hi)
            if side == "low_z":
                beyond = near & (z < edge)
                return edge - (np.max(z[beyond] + r[beyond]) if beyond.any() else 0.0)
            beyond = near & (z > edge)
            return (np.min(z[beyond] - r[beyond]) if beyond.any() else cfg["lz"]) - edge

        g0, g1 = gap(frames[0]["data"]), gap(last["data"])
        out[f"powder_gap_{side}_initial_um"] = g0 * 1e6
        out[f"powder_gap_{side}_final_um"] = g1 * 1e6
        out[f"denudation_{side}_um"] = (g1 - g0) * 1e6
    return out


def summary(case):
    """pbf.summary (balances, laser energy, grains, whole-run pool maxima) plus the layer's numbers."""
    cfg = json.load(open(os.path.join(case, "pbf.json")))
    cfg["tracks"] = [tuple(tuple(p) for p in tr) for tr in cfg["tracks"]]
    s = pbf.summary(case)
    s.update({"tracks": cfg["tracks_n"], "hatch_um": cfg["hatch"] * 1e6, "order": cfg["order"],
              "return_time_s": cfg["return_time"], "speed_m_per_s": cfg["v"], "track_length_um": cfg["length"] * 1e6})
    series = molten_series(case, cfg)
    if not series:
        return s
    h = cfg["dx"]
    nx = series[0][1].shape[2]
    pools = track_pools(cfg, series)
    per = []
    for i, (track, pool) in enumerate(zip(cfg["tracks"], pools)):
        cols = middle_columns(cfg, track, nx)
        z = track[0][1]
        width, _, _ = z_run(pool["melted"], cols, z, h)
        row = {"track": i + 1, "width_um": width * 1e6,
               "depth_um": depth_below(pool["melted"], cols, cfg) * 1e6,
               "melted_um3": float(pool["melted"].sum()) * h ** 3 * 1e18,
               "still_molten_at_start_um3": float((pool["carried"][:, :, cols]).sum()) * h ** 3 * 1e18}
        if i:
            both = pools[i - 1]["melted"] & pool["melted"]
            # remelted: melted by the track before, solidified, melted again (cells still molten when
            # this track started are its merged pool, not remelt)
            row["remelted_overlap_width_um"] = float(np.mean(both[:, :, cols].any(axis=1).sum(axis=0))) * h * 1e6
            row["remelted_share"] = float(both.sum()) / max(float(pool["melted"].sum()), 1.0)
            row["overlap_from_widths_um"] = 0.5 * (per[-1]["width_um"] + row["width_um"]) - cfg["hatch"] * 1e6
        per.append(row)
    s["per_track"] = per
    s["eagar_tsai_width_um"] = pbf.eagar_tsai_width(pbf.ETA * cfg["power"], cfg["v"], cfg["rw"] / 2) * 1e6
    s.update(denudation(case, cfg, pools, nx))
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(s, f, indent=1)
    return s


def print_summary(s):
    per = s.pop("per_track", [])
    pbf.print_summary(s)
    if per:
        keys = list(per[-1])
        print("  " + " | ".join(keys))
        for row in per:
            print("  " + " | ".join(f"{row[k]:.4g}" if isinstance(row.get(k), float) else str(row.get(k, "-"))
                                    for k in keys))
    s["per_track"] = per
