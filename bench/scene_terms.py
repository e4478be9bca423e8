#!/usr/bin/env python3
"""What each physics term costs and changes on the melt-pool scenes: every scene's CI variant with
all its terms on (the default), then Marangoni, surface tension (with Marangoni, which needs it),
evaporation with recoil, and all of them off; each run's melt-pool result, fluid steps and solver
CPU. The switches are set in the built case's physics{} (meltdem.case.foam.set_physics), so the
mesh, the bed and the steps' limits are the default's. Terms the scenes leave off by default are
switched on by their build option (--vapour-jet: evaporation's mass loss and vapour jet).
single-track has its own table (bench/single_track.py terms). Writes scene_terms.md and .png next
to this script.

    /usr/bin/python3 bench/scene_terms.py [--scenes ded-stream,pbf-point,...] [--jobs 2] [--work DIR]
                                          [--out DIR] [--from-results] [--keep-done]
    /usr/bin/python3 bench/scene_terms.py one SCENE KEY WORK     (one run; what the above starts)
"""
import argparse
import json
import os
import subprocess
import sys
import time

from meltdem import paths
from meltdem.case import foam as fc

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = paths.source_dir()

# term sets switched off per row; a row whose terms the scene does not use is skipped
ROWS = [("all", "all on (default)", {}),
        ("no-marangoni", "Marangoni off", {"marangoni": "off"}),
        ("no-surface", "surface tension and Marangoni off", {"surfaceTension": "off", "marangoni": "off"}),
        ("no-evaporation", "evaporation and recoil off", {"evaporation": "off", "recoil": "off"}),
        ("none", "all four off", {"surfaceTension": "off", "marangoni": "off", "evaporation": "off",
                                  "recoil": "off"})]
# terms off by default, switched on by a build option (rows only for scenes that take it)
ON_ROWS = [("vapour-jet", "+ mass loss and vapour jet (--vapour-jet)", "--vapour-jet")]


def _um(key, scale=1.0):
    return lambda s: None if s.get(key) is None else s[key] * scale


# per scene: terms it has on, its result columns (label, from summary.json)
SCENES = {
    "ded-stream": dict(terms={"surfaceTension", "marangoni", "evaporation", "recoil"}, options={"--vapour-jet"},
                       columns=[("pool diameter 0.018 ms [µm]", _um("pool_diameter_at_0.018ms_um")),
                                ("pool depth, end [µm]", lambda s: s["pool_depth_um"][-1]),
                                ("peak T [K]", lambda s: max(s["peak_T_K"]))]),
    "pbf-point": dict(terms={"surfaceTension", "marangoni", "evaporation", "recoil"}, options={"--vapour-jet"},
                      columns=[("pool width max [µm]", _um("melt_pool_width_max_um")),
                               ("pool depth max [µm]", _um("melt_pool_depth_max_um")),
                               ("peak T [K]", _um("peak_metal_T_K"))]),
    "pbf-line": dict(terms={"surfaceTension", "marangoni", "evaporation", "recoil"}, options={"--vapour-jet"},
                     columns=[("moving pool width [µm]", _um("melt_pool_width_moving_um")),
                              ("moving pool depth [µm]", _um("melt_pool_depth_moving_um")),
                              ("peak T [K]", _um("peak_metal_T_K"))]),
    "slm-track": dict(terms={"surfaceTension", "marangoni"}, options={"--vapour-jet"},
                      columns=[("track width [µm]", _um("track_width_m", 1e6)),
                               ("track depth [µm]", _um("track_depth_m", 1e6)),
                               ("bead height [µm]", _um("bead_height_m", 1e6))]),
    "lmd-track": dict(terms={"surfaceTension", "marangoni"},
                      columns=[("bead width [mm]", _um("bead_width_mm")),
                               ("bead height [mm]", _um("bead_height_mm")),
                               ("penetration [mm]", _um("penetration_mm"))]),
}


def rows_of(scene):
    """(key, label, terms off, build options) of SCENE's rows"""
    have = SCENES[scene]["terms"]
    out, seen = [], set()
    for key, label, off in ROWS:
        off = {k: v for k, v in off.items() if k in have}
        if (off or key == "all") and frozenset(off) not in seen:
            seen.add(frozenset(off))
            out.append((key, label, off, []))
    for key, label, option in ON_ROWS:
        if option in SCENES[scene].get("options", ()):
            out.append((key, label, {}, [option]))
    return out


def one(scene, key, work):
    """Build SCENE's CI case (with KEY's build options), switch KEY's terms off, run it and analyse it;
    WORK/SCENE/KEY/summary.json gets the wall time and fluid steps too."""
    off, options = dict((k, (o, b)) for k, _, o, b in rows_of(scene))[key]
    script = os.path.join(SRC, "examples", scene, "scene.py")
    case = os.path.join(work, scene, key)
    subprocess.run(["/usr/bin/python3", script, "build", case, "--ci", *options], check=True)
    if off:
        fc.set_physics(case, **off)
    t0 = time.time()
    subprocess.run(["/usr/bin/python3", script, "run", case], check=True)
    wall = time.time() - t0
    subprocess.run(["/usr/bin/python3", script, "analyse", case], check=True)
    s = json.load(open(os.path.join(case, "summary.json")))
    s.update(bench_wall_s=wall, bench_cpu_s=fc.execution_time(case), bench_fluid_steps=fc.fluid_steps(case))
    json.dump(s, open(os.path.join(case, "summary.json"), "w"), indent=1)


def write(results, out):
    lines = ["# Physics terms: cost and effect per scene", "",
             "`bench/scene_terms.py`: each scene's CI variant, one rank per run (two runs at a time on the "
             "2-core machine), the terms switched off in the built case's physics{} (or on by the scene's build "
             "option, where the row names one: `--vapour-jet` is evaporation's mass loss and vapour jet, and in "
             "slm-track evaporation and recoil with them); CPU = the solver's "
             "ExecutionTime (LAMMPS included), relative to the scene's default run. The fluid step of these "
             "scenes is set by their build (DEM sub-cycles, Courant number, the capillary limit of the built "
             "cells) and the same in every row, so a row's CPU is the terms' cost per step; where the "
             "capillary limit sets an adaptive step (single-track: `single_track_terms.md`), switching surface "
             "tension off also lengthens the step.", ""]
    for scene, rows in results.items():
        cols = SCENES[scene]["columns"]
        ref = rows[0]
        lines += [f"## {scene}", "", "| run | " + " | ".join(c for c, _ in cols) + " | fluid steps | CPU [s] | "
                  "CPU / default |", "|---" * (len(cols) + 4) + "|"]
        for r in rows:
            vals = [f(r["summary"]) for _, f in cols]
            cells = " | ".join("—" if v is None else f"{v:.0f}" if abs(v) >= 100 else f"{v:.3g}" for v in vals)
            lines.append(f"| {r['label']} | {cells} | {r['summary']['bench_fluid_steps']} | "
                         f"{r['summary']['bench_cpu_s']:.0f} | "
                         f"{r['summary']['bench_cpu_s'] / ref['summary']['bench_cpu_s']:.2f} |")
        lines.append("")
    os.makedirs(out, exist_ok=True)
    open(os.path.join(out, "scene_terms.md"), "w").write("\n".join(lines))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, axes = plt.subplots(1, len(results), figsize=(3.2 * len(results), 3.6), squeeze=False)
    for ax, (scene, rows) in zip(axes[0], results.items()):
        x = np.arange(len(rows))
        cpu = [r["summary"]["bench_cpu_s"] / rows[0]["summary"]["bench_cpu_s"] for r in rows]
        first = SCENES[scene]["columns"][0]
        res = [(first[1](r["summary"]) or 0.0) / (first[1](rows[0]["summary"]) or 1.0) for r in rows]
        ax.bar(x - 0.2, cpu, 0.4, label="CPU / default")
        ax.bar(x + 0.2, res, 0.4, label=f"{first[0].split(' [')[0]} / default")
        ax.set_xticks(x, [r["key"] for r in rows], rotation=30, fontsize=7)
        ax.set_title(scene, fontsize=9)
        ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "scene_terms.png"), dpi=120)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["one"]:
        one(*argv[1:4])
        return 0
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default=",".join(SCENES), help="comma-separated scenes (default all)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at once")
    ap.add_argument("--work", default="/tmp/meltdem-scene-terms")
    ap.add_argument("--out", default=HERE)
    ap.add_argument("--from-results", action="store_true", help="only write the table from WORK/results.json")
    ap.add_argument("--keep-done", action="store_true", help="do not rerun a case that has a summary.json")
    a = ap.parse_args(argv)
    scenes = a.scenes.split(",")
    unknown = [s for s in scenes if s not in SCENES]
    if unknown:
        ap.error(f"--scenes: unknown {', '.join(unknown)} (one of {', '.join(SCENES)})")
    saved = os.path.join(a.work, "results.json")
    if not a.from_results:
        running = []
        for scene in scenes:
            for key, _, _, _ in rows_of(scene):
                case = os.path.join(a.work, scene, key)
                if a.keep_done and os.path.exists(os.path.join(case, "summary.json")):
                    continue
                while len([p for _, p in running if p.poll() is None]) >= a.jobs:
                    time.sleep(2)
                # a session folder per run: Open MPI singletons started together collide in a shared one
                os.makedirs(case + ".tmp", exist_ok=True)
                p = subprocess.Popen(["/usr/bin/python3", __file__, "one", scene, key, a.work],
                                     stdout=open(case + ".log", "w"), stderr=subprocess.STDOUT,
                                     env=dict(os.environ, TMPDIR=case + ".tmp"))
                running.append((f"{scene}/{key}", p))
        failed = [k for k, p in running if p.wait() != 0]
        if failed:
            print(f"runs failed: {', '.join(failed)} (cases and logs in {a.work})", file=sys.stderr)
        results = {}
        for scene in scenes:
            rows = []
            for key, label, _, _ in rows_of(scene):
                path = os.path.join(a.work, scene, key, "summary.json")
                if os.path.exists(path) and "bench_cpu_s" in json.load(open(path)):
                    rows.append(dict(key=key, label=label, summary=json.load(open(path))))
            if rows and rows[0]["key"] == "all":
                results[scene] = rows
        json.dump(results, open(saved, "w"), indent=1)
    write(json.load(open(saved)), a.out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
