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
import json
import os

from meltdem.analysis.beds import bed_stats
from meltdem.case.dem import run_actions, run_input, scene_parser, write_case
from meltdem.scene import Scene

HERE = os.path.dirname(os.path.abspath(__file__))

VARIANTS = {
    "ci": {"Lx": "3e-4", "Lz": "3e-4", "sides": "periodic", "every": "100"},
    "full": {},
}


def build(case, variant):
    write_case(case, "powder-bed", variant, os.path.join(HERE, "in.powder-bed"), VARIANTS[variant])


def run(case, np_):
    run_input(case, "in.powder-bed", np_)


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
    a = scene_parser(__doc__).parse_args(argv)
    run_actions(a, lambda case: build(case, a.variant or "full"), run, analyse)


SCENE = Scene(name="powder-bed", kind="dem",
              title="Powder bed (Codina2019 table 4.3 / 4.4)",
              ci_time='~30 s serial', full_time='~7 min on 2 ranks',
              build=lambda case, size: main(["build", case, f"--{size}"]),
              analyse=lambda case: main(["analyse", case]),
              summary=analyse)


if __name__ == "__main__":
    main()
