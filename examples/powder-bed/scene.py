#!/usr/bin/python3
"""Powder bed (Codina2019 table 4.3/4.4), DEM only: the scene interface of examples/.

    scene.py build CASE [--ci | --full]   write CASE/ (the input and its variables)
    scene.py run CASE [--np N]            meltdem-lmp (mpirun -np N for N > 1)
    scene.py analyse CASE                 bed thickness, packing (meltdem.analysis.beds) -> CASE/summary.json
    scene.py all CASE [--ci | --full] [--np N]

--ci is what tests/dem/powder_bed checks (0.30 x 0.30 mm floor, periodic sideways, 153
particles, ~30 s serial); --full (default) the Codina2019 box 0.90 x 0.21 x 0.90 mm with walls,
1375 particles (~7 min on 2 cores). README.md explains both.
"""
import argparse
import json
import os
import shutil
import subprocess

from meltdem import paths
from meltdem.analysis.beds import bed_stats
from meltdem.scene import Scene

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
BIN = paths.bin_dir()

VARIANTS = {
    "ci": {"Lx": "3e-4", "Lz": "3e-4", "sides": "periodic", "every": "100"},
    "full": {},
}


def build(case, variant):
    os.makedirs(case, exist_ok=True)
    shutil.copy(os.path.join(HERE, "in.powder-bed"), case)
    with open(os.path.join(case, "scene.json"), "w") as f:
        json.dump({"scene": "powder-bed", "variant": variant, "vars": VARIANTS[variant]}, f, indent=1)


def run(case, np_):
    spec = json.load(open(os.path.join(case, "scene.json")))
    cmd = [os.path.join(BIN, "meltdem-lmp"), "-in", "in.powder-bed", "-log", "log.lammps", "-screen", "none"]
    for k, v in spec["vars"].items():
        cmd += ["-var", k, v]
    if np_ > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_)] + cmd
    subprocess.run(cmd, cwd=case, check=True)


def analyse(case):
    spec = json.load(open(os.path.join(case, "scene.json")))
    s = bed_stats(os.path.join(case, "bed.dump"), walls=spec["vars"].get("sides", "wall") == "wall")
    summary = {"particles": s["particles"], "bed_thickness_m": s["thickness"],
               "packing_fraction": s["packing_layer"], "slab_packing_fraction": s["packing_slab"],
               "top_thickness_m": s["top_thickness"], "rms_speed_m_per_s": s["rms_speed"],
               "reference_bed_thickness_m": 60e-6, "reference_packing_fraction": 0.5}
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print(f"powder-bed: {s['particles']} particles, bed thickness {s['thickness'] * 1e6:.1f} um "
          f"(thesis ~60), packing {s['packing_layer']:.3f} (thesis 0.5), top {s['top_thickness'] * 1e6:.1f} um")
    return summary


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=["build", "run", "analyse", "all"])
    ap.add_argument("case")
    size = ap.add_mutually_exclusive_group()
    size.add_argument("--ci", action="store_const", dest="variant", const="ci")
    size.add_argument("--full", action="store_const", dest="variant", const="full")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args(argv)
    case = os.path.abspath(a.case)
    if a.action in ("build", "all"):
        build(case, a.variant or "full")
    if a.action in ("run", "all"):
        run(case, a.np)
    if a.action in ("analyse", "all"):
        analyse(case)


SCENE = Scene(name="powder-bed", kind="dem",
              title="Powder bed (Codina2019 table 4.3 / 4.4)",
              ci_time='~30 s serial', full_time='~7 min on 2 ranks',
              build=lambda case, size: main(["build", case, f"--{size}"]),
              analyse=lambda case: main(["analyse", case]),
              summary=analyse)


if __name__ == "__main__":
    main()
