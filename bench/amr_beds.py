#!/usr/bin/env python3
"""The refined slm-track against the uniform mesh on several poured beds: examples/slm-track's full
floor (0.9 x 0.9 mm, 1375 grains poured by examples/powder-bed with each seed), 0.2 mm of track,
the flow's own step (Courant number <= 0.3, at most 0.5 us). Per bed: the uniform mesh of 15 um
cells, and a 60 um base mesh refined twice to 15 um by the scene's refinement{} (mesh updated every
10 fluid steps) with the grains criterion's reach of each --reach (grain diameters; the scene's is
1). Compared: the track's width (its widest span at the half-liquid temperature at any height,
grains above the plate included), its width on the substrate's top plane, and its depth (medians
over the track's slices). A single bed is one sample of the refined run's error; over several the
table gives its mean, spread and largest value, and the bed-to-bed spread of the uniform track
itself. Writes
amr_beds.md and amr_beds.png next to this script.

    /usr/bin/python3 bench/amr_beds.py [--seeds 4242,1,2,3,5,6] [--reach 1,0.5] [--work DIR] [--out DIR]
                                       [--jobs N] [--from-results]

Runs already in DIR/results.json are kept (a stopped sweep resumes); --from-results only rewrites the
table and plot. Run by hand: about 25 min of CPU per uniform run, 5 per refined run.
"""
import argparse
import json
import os
import sys
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from meltdem import scene as scenes
from meltdem.case import foam as fc

HERE = os.path.dirname(os.path.abspath(__file__))
scene = scenes.module("slm-track")
CELL, LEVELS, FLUID_DT, TRACK, INTERVAL, COURANT = 15e-6, 2, 5e-7, 2e-4, 10, 0.3
MEASURES = [("width_um", "width [um]", "{:.1f}"), ("width_surface_um", "top-plane width [um]", "{:.1f}"),
            ("depth_um", "depth [um]", "{:.2f}")]


def measure(case, bed, reach):
    """The full floor's track on the bed dump `bed` in `case`: reach 0 is the uniform mesh, else the
    refined one with that reach of the grains criterion; its row (reach, cells, MEASURES, CPU)."""
    scene.build(case, "full", cell=CELL, bed=bed, fluid_dt=FLUID_DT, refine=LEVELS if reach else 0, track=TRACK,
                refine_interval=INTERVAL, courant=COURANT, grain_reach=reach or 1.0)
    scene.run(case)
    s = scene.analyse(case)
    meta = json.load(open(os.path.join(case, "scene.json")))
    return dict(reach=reach, cells=fc.most_cells(case, np.prod(meta["n_cells"])),
                width_um=s["track_width_m"] * 1e6, width_surface_um=s["track_width_surface_m"] * 1e6,
                depth_um=s["track_depth_m"] * 1e6, cpu_s=s["cpu_s"], **slices_and_melt(s))


def slices_and_melt(s):
    """The width's mean over the track's slices, the slices' widths and the powder's melted volume,
    from a scene summary."""
    return dict(width_mean_um=s["track_width_mean_m"] * 1e6,
                width_slices_um=[w * 1e6 for w in s["track_width_slices_m"]],
                melted_um3=s["powder_melted_volume_m3"] * 1e18)


def one(work, seed, reach):
    """One run on the bed poured with `seed`: reach 0 is the uniform mesh, else the refined one."""
    bed = os.path.join(work, f"seed{seed}", "bed", "bed.dump")
    case = os.path.join(work, f"seed{seed}", "uniform" if reach == 0 else f"reach{reach:g}")
    return dict(seed=seed, **measure(case, bed, reach))


def pour(work, seed):
    if not os.path.exists(os.path.join(work, f"seed{seed}", "bed", "bed.dump")):
        scene.pour_bed(os.path.join(work, f"seed{seed}"), dict(scene.VARIANTS["full"], np=1, seed=seed))


def changes(rows, reach):
    """Per bed with both runs: (seed, {measure: refined vs uniform in %}, CPU ratio uniform / refined)."""
    out = []
    for u in (r for r in rows if r["reach"] == 0):
        for a in (r for r in rows if r["reach"] == reach and r["seed"] == u["seed"]):
            out.append((u["seed"], {k: (a[k] / u[k] - 1) * 100 for k, *_ in MEASURES if k in a and k in u},
                        u["cpu_s"] / a["cpu_s"]))
    return out


def spread(x):
    """mean +- sample standard deviation, and the largest magnitude."""
    x = np.asarray(x)
    sd = np.std(x, ddof=1) if len(x) > 1 else 0.0
    return f"{np.mean(x):+.1f} +- {sd:.1f} % (largest {x[np.argmax(abs(x))]:+.1f} %)"


def write(rows, reaches, out):
    what = " ".join(__doc__.split("\n\n")[0].split(": ", 1)[1].split(" A single")[0].split())
    names = [h.split(" [")[0] for _, h, _ in MEASURES]
    lines = ["# Refined vs uniform slm-track on several poured beds", "",
             f"`bench/amr_beds.py`: {what} One rank; CPU = the solver's ExecutionTime.", "",
             "| bed seed | mesh | most cells | " + " | ".join(h for _, h, _ in MEASURES) + " | CPU [s] | "
             + " | ".join(f"{n} vs uniform" for n in names) + " | CPU uniform / AMR |",
             "|" + "---|" * (4 + 2 * len(MEASURES) + 1)]
    for seed in dict.fromkeys(r["seed"] for r in rows):
        u = next((r for r in rows if r["seed"] == seed and r["reach"] == 0), None)
        for r in sorted((r for r in rows if r["seed"] == seed), key=lambda r: (r["reach"] != 0, -r["reach"])):
            mesh = "uniform 15 um" if r["reach"] == 0 else f"60 -> 15 um, grains `diameters {r['reach']:g}`"
            cells = [str(seed), mesh, str(r["cells"])] + [f.format(r[k]) if k in r else "" for k, _, f in MEASURES]
            cells.append(f"{r['cpu_s']:.0f}")
            if r["reach"] == 0 or u is None:
                cells += [""] * (len(MEASURES) + 1)
            else:
                cells += [f"{(r[k] / u[k] - 1) * 100:+.1f} %" if k in r and k in u else "" for k, *_ in MEASURES]
                cells.append(f"{u['cpu_s'] / r['cpu_s']:.1f}")
            lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "Over the beds (mean +- sample standard deviation; issue 15's limit: 2 % of the uniform result):", "",
              "| mesh | beds | " + " | ".join(f"{n} vs uniform" for n in names)
              + " | beds with all within 2 % | CPU uniform / AMR |", "|" + "---|" * (len(MEASURES) + 4)]
    for reach in reaches:
        c = changes(rows, reach)
        if not c:
            continue
        inside = sum(all(abs(v) <= 2 for v in pct.values()) for _, pct, _ in c)
        ratios = [x[2] for x in c]
        cols = [spread([pct[k] for _, pct, _ in c if k in pct]) for k, *_ in MEASURES]
        lines.append(f"| refined, grains `diameters {reach:g}` | {len(c)} | " + " | ".join(cols)
                     + f" | {inside} of {len(c)} | {np.mean(ratios):.1f} ({min(ratios):.1f}-{max(ratios):.1f}) |")
    uni = [r for r in rows if r["reach"] == 0]
    if len(uni) > 1:
        parts = []
        for (k, h, f), n in zip(MEASURES, names):
            v = [r[k] for r in uni if k in r]
            sd = np.std(v, ddof=1)
            parts.append(f"{n} {f.format(np.mean(v))} +- {f.format(sd)} um ({sd / np.mean(v) * 100:.1f} %)")
        lines += ["", f"The uniform track itself, bed to bed ({len(uni)} beds): " + ", ".join(parts) + "."]
    open(os.path.join(out, "amr_beds.md"), "w").write("\n".join(lines) + "\n")
    plot(rows, reaches, os.path.join(out, "amr_beds.png"))


def plot(rows, reaches, png):
    """Each measure's change of each bed's refined run against its uniform run, the 2 % band shaded."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, len(MEASURES), figsize=(4.3 * len(MEASURES), 3.6), sharey=True)
    seeds = list(dict.fromkeys(r["seed"] for r in rows if r["reach"] == 0))
    for k, (key, head, _) in enumerate(MEASURES):
        ax[k].axhspan(-2, 2, color="0.9", label="2 % of uniform")
        ax[k].axhline(0, color="k", lw=0.6)
        for j, (reach, mk) in enumerate(zip(reaches, "os^v")):
            c = [(s, pct[key]) for s, pct, _ in changes(rows, reach) if key in pct]
            x = [seeds.index(s) + 0.12 * (j - (len(reaches) - 1) / 2) for s, _ in c]
            y = [v for _, v in c]
            ax[k].plot(x, y, mk, label=f"refined, diameters {reach:g}")
            if y:
                ax[k].axhline(np.mean(y), color=f"C{j}", lw=0.8, ls="--")
        ax[k].set_xticks(range(len(seeds)))
        ax[k].set_xticklabels([str(s) for s in seeds])
        ax[k].set_xlabel("bed seed")
        ax[k].set_title("track " + head.split(" [")[0], fontsize=10)
    ax[0].set_ylabel("refined vs uniform [%] (dashed: mean)")
    save_figure(fig, ax, png)


def save_figure(fig, ax, png):
    """The legend on the last panel, then the PNG, readable by all."""
    ax[-1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    os.chmod(png, 0o644)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", default="4242,1,2,3,5,6", help="powder-bed seeds, one bed each")
    ap.add_argument("--reach", default="1,0.5", help="the grains criterion's diameters of the refined runs")
    ap.add_argument("--work", default="/tmp/meltdem-amr-beds")
    ap.add_argument("--out", default=HERE)
    ap.add_argument("--jobs", type=int, default=1, help="runs at once")
    ap.add_argument("--from-results", action="store_true", help="rewrite the table and plot from DIR/results.json")
    a = ap.parse_args()
    seeds = [int(s) for s in a.seeds.split(",")]
    reaches = [float(r) for r in a.reach.split(",")]
    if any(r <= 0 for r in reaches):
        ap.error("--reach: grain diameters must be > 0")
    os.makedirs(a.work, exist_ok=True)
    store = os.path.join(a.work, "results.json")
    rows = json.load(open(store)) if os.path.exists(store) else []
    if not a.from_results:
        todo = [(s, r) for s in seeds for r in [0.0] + reaches
                if not any(x["seed"] == s and x["reach"] == r for x in rows)]
        with ProcessPoolExecutor(a.jobs) as pool:
            list(pool.map(pour, [a.work] * len(seeds), seeds))
            for row in pool.map(one, [a.work] * len(todo), *zip(*todo)) if todo else []:
                rows.append(row)
                json.dump(rows, open(store, "w"), indent=1)
    rows = [r for r in rows if r["seed"] in seeds and (r["reach"] == 0 or r["reach"] in reaches)]
    write(rows, reaches, a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
