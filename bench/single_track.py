#!/usr/bin/env python3
"""Speed and accuracy of examples/single-track (AM Bench 2018 AMB2018-02, bare IN625 plates):
width and depth of the fused track against the measured mean and scatter, fluid steps and solver
CPU, for one of three studies. Writes single_track_<study>.md and .png next to this script.

    mesh     AMMT-B on 20 um cells, 20 -> 10 um (one level) and 20 -> 5 um (two levels)
    terms    AMMT-B on the CI mesh with all terms on, then Marangoni, surface tension, evaporation
             and recoil off (surface tension with Marangoni, which needs it), all off, and Marangoni
             reversed (inward flow)
    absorptivity  AMMT-B at 0.26 / 0.30 / 0.36, CBM-A at 0.36 / 0.70 (CI mesh)
    tracks   the six tracks on the CI mesh (CBM-A on 0.4 mm of track)

    /usr/bin/python3 bench/single_track.py mesh|terms|absorptivity|tracks [--jobs 2] [--work DIR] [--out DIR]
                                           [--from-results] [--keep-done] [--absorptivity ETA]
"""
import argparse
import json
import os
import subprocess
import time

from meltdem import paths
from meltdem import scene as scenes

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(paths.source_dir(), "examples", "single-track", "scene.py")
scene = scenes.module("single-track")

STUDIES = {
    "mesh": [("20um", "AMMT-B", "20 um (uniform)", ["--dx", "20", "--refine", "0"]),
             ("10um", "AMMT-B", "10 um (20 um base, one level)", ["--dx", "10", "--refine", "1"]),
             ("5um", "AMMT-B", "5 um (20 um base, two levels)", ["--dx", "5", "--refine", "2"])],
    "terms": [("all", "AMMT-B", "all on (default)", []),
              ("no-marangoni", "AMMT-B", "Marangoni off", ["--no-marangoni"]),
              ("no-surface", "AMMT-B", "surface tension and Marangoni off", ["--no-surface-tension", "--no-marangoni"]),
              ("no-recoil", "AMMT-B", "evaporation and recoil off", ["--no-recoil"]),
              ("none", "AMMT-B", "all three off", ["--no-marangoni", "--no-surface-tension", "--no-recoil"]),
              ("inward", "AMMT-B", "dsigma/dT +1.1e-4 (inward Marangoni)", ["--dsigma-dt", "1.1e-4"])],
    "absorptivity": [("B-0.26", "AMMT-B", "absorptivity 0.26", ["--absorptivity", "0.26"]),
                     ("B-0.30", "AMMT-B", "absorptivity 0.30", ["--absorptivity", "0.30"]),
                     ("B-0.36", "AMMT-B", "absorptivity 0.36 (default)", []),
                     ("A-0.36", "CBM-A", "absorptivity 0.36 (default), 0.4 mm track", ["--track", "0.4"]),
                     ("A-0.70", "CBM-A", "absorptivity 0.70, 0.4 mm track",
                      ["--track", "0.4", "--absorptivity", "0.7"])],
    "tracks": [(t, t, t, ["--track", "0.4"] if t == "CBM-A" else []) for t in sorted(scene.TRACKS)],
}


def start(work, key, track, flags, a):
    case = os.path.join(work, key)
    cmd = ["/usr/bin/python3", SCENE, "all", case, "--ci", "--track-case", track] + flags
    if a.absorptivity is not None and "--absorptivity" not in flags:
        cmd += ["--absorptivity", repr(a.absorptivity)]
    return subprocess.Popen(cmd, stdout=open(case + ".log", "w"), stderr=subprocess.STDOUT)


def result(work, key, label):
    s = scene.analyse(os.path.join(work, key), quiet=True)
    return dict(s, key=key, label=label)


def write(study, rows, out):
    name = f"single_track_{study}"
    ref = rows[0]
    lines = [f"# single-track: {study}", "",
             f"`bench/single_track.py {study}`: examples/single-track, CI box and track unless the row says "
             "otherwise, one rank per run; CPU = the solver's ExecutionTime (runs two at a time on the "
             "2-core machine). Measured: AMB2018-02 class mean ± the scatter between tracks; tolerance "
             "max(scatter, 10 %) (README).", "",
             "| run | track | cells | width [µm] | measured | depth [µm] | measured | fluid steps | most cells | "
             "CPU [s] | CPU / first row |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['label']} | {r['track_case']} | {r['dx_um']:g} µm | {r['width_um']:.1f} | "
                     f"{r['measured_width_um']:g} ± {r['measured_width_sd_um']:g} | {r['depth_um']:.1f} | "
                     f"{r['measured_depth_um']:g} ± {r['measured_depth_sd_um']:g} | {r['fluid_steps']} | "
                     f"{r['most_cells']} | {r['cpu_seconds']:.0f} | {r['cpu_seconds'] / ref['cpu_seconds']:.2f} |")
    open(os.path.join(out, name + ".md"), "w").write("\n".join(lines) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, ax = plt.subplots(1, 2, figsize=(11, 3.6))
    x = np.arange(len(rows))
    for i, q in enumerate(("width", "depth")):
        ax[0].bar(x + (i - 0.5) * 0.4, [r[f"{q}_um"] / r[f"measured_{q}_um"] for r in rows], 0.4, label=q)
        ax[0].errorbar(x + (i - 0.5) * 0.4, [1.0] * len(rows),
                       yerr=[scene.tolerance(r[f"measured_{q}_um"], r[f"measured_{q}_sd_um"]) / r[f"measured_{q}_um"]
                             for r in rows], fmt="none", color="k", capsize=3)
    ax[0].set_xticks(x, [r["key"] for r in rows], rotation=20, fontsize=8)
    ax[0].set_ylabel("simulated / measured (bars: tolerance)")
    ax[0].legend(fontsize=8)
    ax[1].bar(x, [r["cpu_seconds"] for r in rows])
    ax[1].set_xticks(x, [r["key"] for r in rows], rotation=20, fontsize=8)
    ax[1].set_ylabel("solver CPU [s]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, name + ".png"), dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study", choices=sorted(STUDIES))
    ap.add_argument("--jobs", type=int, default=2, help="runs at once")
    ap.add_argument("--work", default="/tmp/meltdem-single-track")
    ap.add_argument("--out", default=HERE)
    ap.add_argument("--absorptivity", type=float)
    ap.add_argument("--from-results", action="store_true", help="only write the table from WORK/STUDY.json")
    ap.add_argument("--keep-done", action="store_true", help="do not rerun a case that has a summary.json")
    a = ap.parse_args()
    work = os.path.join(a.work, a.study)
    os.makedirs(work, exist_ok=True)
    saved = os.path.join(work, "results.json")
    if not a.from_results:
        running = []
        for key, track, _, flags in STUDIES[a.study]:
            if a.keep_done and os.path.exists(os.path.join(work, key, "summary.json")):
                continue
            while len([p for _, p in running if p.poll() is None]) >= a.jobs:
                time.sleep(2)
            running.append((key, start(work, key, track, flags, a)))
        failed = [k for k, p in running if p.wait() != 0]
        if failed:
            raise SystemExit(f"runs failed: {', '.join(failed)} (cases and logs in {work})")
        json.dump([result(work, key, label) for key, _, label, _ in STUDIES[a.study]], open(saved, "w"), indent=1)
    write(a.study, json.load(open(saved)), a.out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
