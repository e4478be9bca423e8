#!/usr/bin/env python3
"""What the Marangoni force costs and changes on examples/lmd-track (Codina2019 §4.1, table 4.2):
the same case with Marangoni off, on spread over the interface cells (unscaled), and on
density-scaled (the scene's default: carried by the metal side of the interface). Reported: bead
(fused) width, height and penetration at the measured section, the capture (geometric for a bare
track, the deposition efficiency of a coupled one), fluid steps, solver CPU, and the largest speed
of the argon (alpha < 0.01) and of the liquid metal (alpha > 0.99, liquid fraction > 0.99) over the
written times. Writes marangoni_lmd.md and .png next to this script (marangoni_lmd_full.* for --variant full).

    /usr/bin/python3 bench/marangoni_lmd.py [--variant ci|full] [--refine L] [--coupled] [--jobs 2]
                                            [--work DIR] [--out DIR] [--from-results]
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

from meltdem import paths
from meltdem import scene as scenes
from meltdem.case import foam as fc

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(paths.source_dir(), "examples", "lmd-track", "scene.py")
scene = scenes.module("lmd-track")
CHOICES = [("off", "Marangoni off", ["--no-marangoni"]),
           ("unscaled", "Marangoni, unscaled", ["--marangoni-scaling", "none"]),
           ("density", "Marangoni, density-scaled (default)", [])]
EXPERIMENT = dict(width_mm=3.46, height_mm=0.82, penetration_mm=0.61, capture_pct=85.8)


def case_of(work, key):
    return os.path.join(work, key)


def start(work, a, key, flags):
    case = case_of(work, key)
    build = ["/usr/bin/python3", SCENE, "build", case, f"--{a.variant}", "--refine", str(a.refine)] + flags
    build += [] if a.coupled else ["--no-particles"]
    subprocess.run(build, check=True)
    return subprocess.Popen(["/usr/bin/python3", SCENE, "run", case])


def largest_speeds(case):
    """Largest |U| of the argon and of the liquid metal over the written times (every cell of the mesh
    written at each time, refined or not)."""
    gas = melt = 0.0
    for d in fc.time_dirs(case):
        if float(d) == 0:
            continue
        try:
            U = np.asarray(fc.read_internal(os.path.join(case, d, "U")), dtype=float).reshape(-1, 3)
            a = np.asarray(fc.read_internal(os.path.join(case, d, "alpha.metal")), dtype=float)
            f = np.asarray(fc.read_internal(os.path.join(case, d, "liquidFraction")), dtype=float)
        except (OSError, ValueError):
            continue
        if U.shape[0] != a.size:
            continue
        m = np.linalg.norm(U, axis=1)
        gas = max(gas, float(m[a < 0.01].max(initial=0.0)))
        melt = max(melt, float(m[(a > 0.99) & (f > 0.99)].max(initial=0.0)))
    return gas, melt


def result(work, key, label):
    case = case_of(work, key)
    s = scene.analyse(case, quiet=True)
    gas, melt = largest_speeds(case)
    steps = fc.fluid_steps(case)
    return dict(key=key, label=label, width_mm=s["bead_width_mm"], height_mm=s["bead_height_mm"],
                penetration_mm=s["penetration_mm"],
                capture_pct=s.get("deposition_efficiency_pct", s.get("geometric_capture_pct")),
                steps=steps, cpu_s=s["cpu_seconds"], gas_max=gas, melt_max=melt)


def write(rows, a, out):
    name = "marangoni_lmd" + ("" if a.variant == "ci" else f"_{a.variant}")
    what = "coupled (powder stream on)" if a.coupled else "bare track (no powder)"
    lines = ["# What the Marangoni force costs and changes (lmd-track)", "",
             f"`bench/marangoni_lmd.py`: examples/lmd-track, {a.variant} variant, {what}, "
             f"{a.refine} refinement level(s); one rank each; CPU = the solver's ExecutionTime. Largest "
             "speeds over the written times: argon (alpha < 0.01), liquid metal (alpha > 0.99, liquid "
             "fraction > 0.99). Experiment: Codina2019 table 4.2.", "",
             "| Marangoni | width [mm] | height [mm] | penetration [mm] | capture [%] | fluid steps | CPU [s] | "
             "CPU / off | largest argon speed [m/s] | largest melt speed [m/s] |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    off = next((r for r in rows if r["key"] == "off"), rows[0])
    for r in rows:
        lines.append(f"| {r['label']} | {r['width_mm']:.3f} | {r['height_mm']:.3f} | {r['penetration_mm']:.3f} | "
                     f"{r['capture_pct']:.1f} | {r['steps']} | {r['cpu_s']:.0f} | {r['cpu_s'] / off['cpu_s']:.2f} | "
                     f"{r['gas_max']:.3f} | {r['melt_max']:.3f} |")
    lines.append(f"| experiment | {EXPERIMENT['width_mm']} | {EXPERIMENT['height_mm']} | "
                 f"{EXPERIMENT['penetration_mm']} | {EXPERIMENT['capture_pct']} | | | | | |")
    open(os.path.join(out, name + ".md"), "w").write("\n".join(lines) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(11, 3.4))
    names = [r["key"] for r in rows]
    ax[0].bar(names, [r["cpu_s"] for r in rows])
    ax[0].set_ylabel("solver CPU [s]")
    x = np.arange(len(rows))
    for i, (k, lab) in enumerate((("width_mm", "width"), ("height_mm", "height"), ("penetration_mm", "penetration"))):
        ax[1].bar(x + (i - 1) * 0.27, [r[k] for r in rows], 0.27, label=lab)
        ax[1].axhline(EXPERIMENT[k], ls=":", color=f"C{i}")
    ax[1].set_xticks(x, names)
    ax[1].set_ylabel("bead [mm] (dotted: experiment)")
    ax[1].legend(fontsize=7)
    ax[2].bar(x - 0.2, [r["gas_max"] for r in rows], 0.4, label="argon")
    ax[2].bar(x + 0.2, [r["melt_max"] for r in rows], 0.4, label="liquid metal")
    ax[2].set_xticks(x, names)
    ax[2].set_yscale("log")
    ax[2].set_ylabel("largest speed [m/s]")
    ax[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, name + ".png"), dpi=120)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--variant", default="ci", choices=["ci", "full"])
    ap.add_argument("--refine", type=int, default=0)
    ap.add_argument("--coupled", action="store_true", help="with the powder stream (default: bare track)")
    ap.add_argument("--jobs", type=int, default=1, help="runs at once (CPU is per run)")
    ap.add_argument("--work", default="/tmp/meltdem-marangoni-lmd")
    ap.add_argument("--out", default=HERE)
    ap.add_argument("--from-results", action="store_true", help="only write the table from WORK/results.json")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    if a.from_results:
        write(json.load(open(os.path.join(a.work, "results.json"))), a, a.out)
        return 0
    running = []
    for key, _, flags in CHOICES:
        running.append((key, start(a.work, a, key, flags)))
        while len([p for _, p in running if p.poll() is None]) >= a.jobs:
            time.sleep(1)
    failed = [k for k, p in running if p.wait() != 0]
    if failed:
        raise SystemExit(f"runs failed: {', '.join(failed)} (cases in {a.work})")
    rows = [result(a.work, key, label) for key, label, _ in CHOICES]
    json.dump(rows, open(os.path.join(a.work, "results.json"), "w"), indent=1)
    write(rows, a, a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
