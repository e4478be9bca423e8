#!/usr/bin/env python3
"""Adaptive refinement against the uniform finest mesh: examples/slm-track CI (0.3 x 0.3 mm floor,
153 grains, 0.2 mm of track at 0.5 m/s, 100 W, 0.1 mm spot), the same poured bed and fluid step
for every run. Each pair: the uniform mesh of cell h, and a base mesh of 2^L h refined to h by the
scene's refinement{} (--refine L: melt pool and metal within 300 K of melting, the beam's footprint
and its path over the next half spot, grains near either). Reported: track width and depth (on the
lattice of the finest cells), most cells, solver CPU (LAMMPS included), the width and depth change
against the uniform run and the CPU ratio uniform/AMR. Writes amr.md and amr.png next to this
script.

    /usr/bin/python3 bench/amr.py [--pairs 15e-6:1,10e-6:1] [--fluid-dt 1e-6] [--work DIR] [--out DIR]
                                  [--variant ci|full] [--track METRES] [--refine-interval N] [--courant CO]

--variant full (0.9 x 0.9 mm floor) with a shorter --track writes amr_full.md/png instead.

Run by hand (minutes per run).
"""
import argparse
import json
import os
import sys

import numpy as np

from meltdem import scene as scenes
from meltdem.case import foam as fc

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import amr_pairs  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
scene = scenes.module("slm-track")


def one(work, bed, h, levels, fluid_dt, variant="ci", track=None, interval=1, courant=None):
    case = os.path.join(work, f"h{h * 1e6:g}um_L{levels}" + (f"_i{interval}" if levels and interval > 1 else ""))
    scene.build(case, variant, cell=h, bed=bed, fluid_dt=fluid_dt, refine=levels, track=track,
                refine_interval=interval, courant=courant)
    scene.run(case)
    s = scene.analyse(case)
    meta = json.load(open(os.path.join(case, "scene.json")))
    return dict(cell_um=h * 1e6, levels=levels, base_um=meta["base_cell"] * 1e6,
                cells=fc.most_cells(case, np.prod(meta["n_cells"])),
                width_um=s["track_width_m"] * 1e6, depth_um=s["track_depth_m"] * 1e6, cpu_s=s["cpu_s"],
                wall_s=s["wall_s"])


def write(rows, fluid_dt, out, variant="ci", track=None, courant=None):
    v = scene.VARIANTS[variant]
    what = __doc__.split(chr(10) + chr(10))[0].split(': ', 1)[1]
    if variant != "ci":
        what += (f" Here the {variant} variant: {v['lx'] * 1e3:g} x {v['lz'] * 1e3:g} mm floor, "
                 f"{(track or v['x1'] - v['x0']) * 1e3:g} mm of track.")
    lines = [f"# Adaptive refinement vs the uniform finest mesh (slm-track {variant})", "",
             f"`bench/amr.py`: {what} Fluid step "
             + (f"the flow's own (Courant number <= {courant:g}, at most {fluid_dt * 1e6:g} us)" if courant else
                f"{fluid_dt * 1e6:g} us") + " for every run; one rank; CPU = the solver's ExecutionTime.", ""]
    lines += amr_pairs.table(rows, [("base_um", "base cell [um]", "{:g}", False),
                                    ("width_um", "width [um]", "{:.1f}", True),
                                    ("depth_um", "depth [um]", "{:.1f}", True)])
    name = "amr" if variant == "ci" else f"amr_{variant}"
    open(os.path.join(out, name + ".md"), "w").write("\n".join(lines) + "\n")
    amr_pairs.plot(rows, "width_um", "track width [um]", os.path.join(out, name + ".png"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", default="15e-6:1,10e-6:1", help="finest cell:levels, ...")
    ap.add_argument("--fluid-dt", type=float, default=1e-6)
    ap.add_argument("--work", default="/tmp/meltdem-amr")
    ap.add_argument("--out", default=HERE)
    ap.add_argument("--variant", default="ci", choices=sorted(scene.VARIANTS))
    ap.add_argument("--track", type=float, default=None, help="track length [m] (default: the variant's)")
    ap.add_argument("--refine-interval", type=int, default=1, help="fluid steps between mesh updates of the AMR runs")
    ap.add_argument("--courant", type=float, default=None,
                    help="the flow's own step (Courant number <= CO, at most --fluid-dt) instead of fixed steps")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    bed = os.path.join(a.work, "bed", "bed.dump")
    if not os.path.exists(bed):
        scene.pour_bed(a.work, dict(scene.VARIANTS[a.variant], np=1))
    rows = []
    for pair in a.pairs.split(","):
        h, levels = float(pair.split(":")[0]), int(pair.split(":")[1])
        rows.append(one(a.work, bed, h, 0, a.fluid_dt, a.variant, a.track, courant=a.courant))
        rows.append(one(a.work, bed, h, levels, a.fluid_dt, a.variant, a.track, a.refine_interval, a.courant))
        json.dump(rows, open(os.path.join(a.work, "results.json"), "w"), indent=1)
    write(rows, a.fluid_dt, a.out, a.variant, a.track, a.courant)
    return 0


if __name__ == "__main__":
    sys.exit(main())
