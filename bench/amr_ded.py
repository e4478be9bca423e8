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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import amr_pairs  # noqa: E402

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
             "solver's ExecutionTime.", ""]
    lines += amr_pairs.table(rows, [("diameter_um", "pool diameter [um]", "{:.1f}", True),
                                    ("depth_um", "pool depth [um]", "{:.1f}", True)])
    open(os.path.join(out, "amr_ded.md"), "w").write("\n".join(lines) + "\n")
    amr_pairs.plot(rows, "diameter_um", "pool diameter at 0.018 ms [um]", os.path.join(out, "amr_ded.png"),
                   (scene.PAPER["pool_diameter_um"], "Fuchs2022 ~130 um"))


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
