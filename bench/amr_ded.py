#!/usr/bin/env python3
"""Adaptive refinement vs the uniform finest mesh on examples/ded-stream (Fuchs2022 §4.4, laser on
to 0.020 ms): for each finest cell h, the uniform mesh of h and a base mesh of 2^L h refined to h by
the scene's refinement{} (--refine L: the pool and the metal within 300 K of melting, the beam's
footprint, every grain). Reported: pool diameter and depth at 0.018 ms (on the lattice of the
finest cells), most cells, solver CPU (LAMMPS included), the change against the uniform run and the
CPU ratio uniform/AMR. Writes amr_ded.md and amr_ded.png next to this script.

    /usr/bin/python3 bench/amr_ded.py [--pairs 10e-6:1,5e-6:1] [--work DIR] [--out DIR]

Run by hand (the 5 um uniform run takes about 25 min).
"""
import argparse
import json
import os
import subprocess
import sys

from meltdem import paths
from meltdem import scene as scenes
from meltdem.case import foam as fc

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(paths.source_dir(), "examples", "ded-stream", "scene.py")
scene = scenes.module("ded-stream")


def one(work, h, levels):
    case = os.path.join(work, f"h{h * 1e6:g}um_L{levels}")
    subprocess.run(["/usr/bin/python3", SCENE, "build", case, "--ci", "--dx", repr(h), "--refine", str(levels)],
                   check=True)
    subprocess.run(["/usr/bin/python3", SCENE, "run", case], check=True)
    s = scene.analyse(case)
    at = s["pool_time_ms"].index(min(s["pool_time_ms"], key=lambda t: abs(t - 0.018)))
    cells = int(fc.refinement_ledger(case)[0]["cellsAfter"].max()) if levels else s["cells"]
    return dict(cell_um=h * 1e6, levels=levels, cells=cells, diameter_um=s["pool_diameter_um"][at],
                depth_um=s["pool_depth_um"][at], cpu_s=s["solver_cpu_s"])


def write(rows, out):
    lines = ["# Adaptive refinement vs the uniform finest mesh (ded-stream)", "",
             f"`bench/amr_ded.py`: {__doc__.split(chr(10) + chr(10))[0].split(': ', 1)[1]} One rank; CPU = the "
             "solver's ExecutionTime.", "",
             "| finest cell [um] | mesh | most cells | pool diameter [um] | pool depth [um] | CPU [s] | "
             "diameter vs uniform | depth vs uniform | CPU uniform / AMR |", "|---|---|---|---|---|---|---|---|---|"]
    for u in (r for r in rows if r["levels"] == 0):
        lines.append(f"| {u['cell_um']:g} | uniform | {u['cells']} | {u['diameter_um']:.1f} | {u['depth_um']:.1f} | "
                     f"{u['cpu_s']:.0f} | | | |")
        for r in (r for r in rows if r["levels"] > 0 and r["cell_um"] == u["cell_um"]):
            lines.append(f"| {r['cell_um']:g} | AMR, {r['levels']} level(s) | {r['cells']} | {r['diameter_um']:.1f} | "
                         f"{r['depth_um']:.1f} | {r['cpu_s']:.0f} | "
                         f"{(r['diameter_um'] / u['diameter_um'] - 1) * 100:+.1f} % | "
                         f"{(r['depth_um'] / u['depth_um'] - 1) * 100:+.1f} % | {u['cpu_s'] / r['cpu_s']:.2f} |")
    open(os.path.join(out, "amr_ded.md"), "w").write("\n".join(lines) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
    for lv, mk in ((0, "o-"), (1, "s--"), (2, "^:")):
        sel = sorted((r for r in rows if r["levels"] == lv), key=lambda r: r["cell_um"])
        if sel:
            lab = "uniform" if lv == 0 else f"AMR {lv} level(s)"
            ax[0].plot([r["cell_um"] for r in sel], [r["diameter_um"] for r in sel], mk, label=lab)
            ax[1].plot([r["cell_um"] for r in sel], [r["cpu_s"] for r in sel], mk, label=lab)
    ax[0].axhline(scene.PAPER["pool_diameter_um"], color="k", lw=0.8, ls=":", label="Fuchs2022 ~130 um")
    ax[0].set_xlabel("finest cell [um]")
    ax[0].set_ylabel("pool diameter at 0.018 ms [um]")
    ax[1].set_xlabel("finest cell [um]")
    ax[1].set_ylabel("solver CPU [s]")
    ax[0].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "amr_ded.png"), dpi=110)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", default="10e-6:1,5e-6:1", help="finest cell:levels, ...")
    ap.add_argument("--work", default="/tmp/meltdem-amr-ded")
    ap.add_argument("--out", default=HERE)
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    rows = []
    for pair in a.pairs.split(","):
        h, levels = float(pair.split(":")[0]), int(pair.split(":")[1])
        rows.append(one(a.work, h, 0))
        rows.append(one(a.work, h, levels))
        json.dump(rows, open(os.path.join(a.work, "results.json"), "w"), indent=1)
        write(rows, a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
