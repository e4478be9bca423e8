#!/usr/bin/env python3
"""Adaptive refinement vs the uniform finest mesh on examples/lmd-track (Codina2019 §4.1, table 4.2):
for each finest cell h, the uniform graded mesh of h and the base mesh of 2^L h refined to h by the
scene's refinement{} (--refine L: the melt pool and the metal within 300 K of melting, the beam's
footprint and its path over the next half beam radius, the grains near either). Reported: bead
(fused) width, height and penetration at the measured section (on the lattice of the finest cells),
the geometric capture of the bare track or the deposition efficiency of the coupled one, most cells,
solver CPU (LAMMPS included), the change against the uniform run and the CPU ratio uniform/AMR.
Writes amr_lmd.md and amr_lmd.png next to this script.

    /usr/bin/python3 bench/amr_lmd.py [--pairs 0.25:1] [--variant full] [--track MM] [--coupled]
                                      [--refine-interval N] [--jobs 2] [--work DIR] [--out DIR]
                                      [--from-results]

Run by hand (the thesis's 0.25 mm cells: the uniform bare track takes about 25 min of CPU).
"""
import argparse
import json
import os
import subprocess
import sys

from meltdem import paths
from meltdem import scene as scenes

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import amr_pairs  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(paths.source_dir(), "examples", "lmd-track", "scene.py")
scene = scenes.module("lmd-track")


def case_of(work, a, h_mm, levels):
    return os.path.join(work, f"h{h_mm:g}mm_L{levels}{'_coupled' if a.coupled else ''}")


def start(work, a, h_mm, levels):
    """Build the case and start its run (returns the running process)."""
    case = case_of(work, a, h_mm, levels)
    build = ["/usr/bin/python3", SCENE, "build", case, f"--{a.variant}", "--dx", repr(h_mm),
             "--refine", str(levels), "--refine-interval", str(a.refine_interval)]
    build += ["--track", repr(a.track)] if a.track else []
    build += [] if a.coupled else ["--no-particles"]
    subprocess.run(build, check=True)
    return subprocess.Popen(["/usr/bin/python3", SCENE, "run", case])


def result(work, a, h_mm, levels):
    case = case_of(work, a, h_mm, levels)
    s = scene.analyse(case, quiet=True)
    capture = s.get("deposition_efficiency_pct", s.get("geometric_capture_pct"))
    return dict(cell_um=h_mm * 1e3, levels=levels, cells=s["most_cells"], width_mm=s["bead_width_mm"],
                height_mm=s["bead_height_mm"], penetration_mm=s["penetration_mm"], capture_pct=capture,
                cpu_s=s["cpu_seconds"])


def write(rows, a, out):
    what = "coupled (powder stream on)" if a.coupled else "bare track (no powder)"
    lines = ["# Adaptive refinement vs the uniform finest mesh (lmd-track)", "",
             "`bench/amr_lmd.py`: examples/lmd-track (Codina2019 §4.1), for each finest cell h the uniform "
             "graded mesh of h and the base mesh of 2^L h refined to h by the scene's refinement{} (the melt "
             "pool and the metal within 300 K of melting, the beam's footprint and its path over the next "
             "half beam radius, the grains near either). Reported: bead (fused) width, height and "
             "penetration at the measured section (on the lattice of the finest cells), the capture, most "
             "cells, solver CPU (LAMMPS included), the change against the uniform run and the CPU ratio "
             f"uniform/AMR. Here: {a.variant} variant, {what}, mesh updated every {a.refine_interval} fluid "
             "step(s); one rank; CPU = the solver's ExecutionTime. Finest cell in um (250 um = the thesis's "
             "0.25 mm). Capture: the deposition efficiency of a coupled run, the geometric capture (share of "
             "the powder spot on the pool surface) of a bare track. Width and penetration are read where the "
             "liquid fraction crosses 1/2 between cell centres, so they move in steps of a cell.", ""]
    lines += amr_pairs.table(rows, [("width_mm", "width [mm]", "{:.3f}", True),
                                    ("height_mm", "height [mm]", "{:.3f}", False),
                                    ("penetration_mm", "penetration [mm]", "{:.3f}", True),
                                    ("capture_pct", "capture [%]", "{:.1f}", True)])
    open(os.path.join(out, "amr_lmd.md"), "w").write("\n".join(lines) + "\n")
    amr_pairs.plot(rows, "width_mm", "bead (fused) width [mm]", os.path.join(out, "amr_lmd.png"),
                   (scene.EXPERIMENT["width_mm"], "experiment (table 4.2)"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", default="0.25:1", help="finest cell [mm]:levels, ...")
    ap.add_argument("--variant", default="full", choices=["ci", "full"])
    ap.add_argument("--track", type=float, help="track length [mm] (default: the variant's)")
    ap.add_argument("--coupled", action="store_true", help="with the powder stream (default: bare track)")
    ap.add_argument("--refine-interval", type=int, default=20)
    ap.add_argument("--jobs", type=int, default=1, help="2: the two runs of a pair at once (CPU is per run)")
    ap.add_argument("--work", default="/tmp/meltdem-amr-lmd")
    ap.add_argument("--out", default=HERE)
    ap.add_argument("--from-results", action="store_true", help="only write the table from WORK/results.json")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    if a.from_results:
        write(json.load(open(os.path.join(a.work, "results.json"))), a, a.out)
        return 0
    rows = []
    for pair in a.pairs.split(","):
        h, levels = float(pair.split(":")[0]), int(pair.split(":")[1])
        runs = []
        for lv in (0, levels):             # --jobs 2: the uniform and the AMR run side by side
            runs.append(start(a.work, a, h, lv))
            if a.jobs < 2 and runs[-1].wait() != 0:
                raise SystemExit(f"run failed: {case_of(a.work, a, h, lv)}")
        if any(p.wait() != 0 for p in runs):
            raise SystemExit(f"a run of the {h:g} mm pair failed (cases in {a.work})")
        rows += [result(a.work, a, h, lv) for lv in (0, levels)]
        json.dump(rows, open(os.path.join(a.work, "results.json"), "w"), indent=1)
        write(rows, a, a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
