#!/usr/bin/python3
"""Material jetting (Fuchs2022 §4.3), continuum only: the scene interface of examples/.

    scene.py build CASE [--ci | --full] [--Tsub K]   write CASE/ (mjt_case.py build)
    scene.py run CASE [--np N]                       blockMesh + meltdemFoam (serial: N ignored,
                                                     said so; the axisymmetric mesh is 2D)
    scene.py analyse CASE                            remelt depth -> CASE/summary.json
    scene.py all CASE [--ci | --full] [--Tsub K]

--ci is what tests/foam/mjt runs (2 um cells, radius 60 um, height 100 um, to 0.1 ms);
--full (default) the Fuchs2022 box as a cylinder of radius 80 um, 1 um cells (~40 min serial).
"""
import argparse
import json
import os

from meltdem import paths
from meltdem.scene import Scene

import mjt_case

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = paths.source_dir()
paths.set_tool_environment()

VARIANTS = {"ci": dict(dx=2e-6, radius=60e-6, height=100e-6, end=1e-4),
            "full": dict(dx=1e-6, radius=80e-6, height=260e-6, end=1.5e-4)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=["build", "run", "analyse", "all"])
    ap.add_argument("case")
    size = ap.add_mutually_exclusive_group()
    size.add_argument("--ci", action="store_const", dest="variant", const="ci")
    size.add_argument("--full", action="store_const", dest="variant", const="full")
    ap.add_argument("--Tsub", type=float, default=1500.0, help="substrate temperature [K] (paper: 500, 1500)")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args(argv)
    case = os.path.abspath(a.case)
    if a.action in ("build", "all"):
        v = dict(VARIANTS[a.variant or "full"], Tsub=a.Tsub, write=2.5e-6, nsmooth=2, base="Tsub", solver=None)
        mjt_case.build(argparse.Namespace(case=case, **v))
        with open(os.path.join(case, "scene.json"), "w") as f:
            json.dump({"scene": "mjt-droplets", "variant": a.variant or "full"}, f)
    if a.action in ("run", "all"):
        if a.np > 1:
            print(f"mjt-droplets: runs serial (2D axisymmetric mesh); --np {a.np} not used")
        mjt_case.run(case)
    if a.action in ("analyse", "all"):
        dep, t, r = mjt_case.depth(case)
        peak = mjt_case.surface_peak(case)
        args = eval(open(os.path.join(case, "mjt.args")).read())
        summary = {"substrate_temperature_K": args["Tsub"], "remelt_depth_m": dep, "remelt_depth_time_s": t,
                   "remelt_depth_radius_m": r, "surface_peak_temperature_K": peak,
                   "reference_remelt_depth_m": 16e-6 if args["Tsub"] >= 1500 else 0.0,
                   "reference_remelt_depth_time_s": 7.5e-5 if args["Tsub"] >= 1500 else None}
        with open(os.path.join(case, "summary.json"), "w") as f:
            json.dump(summary, f, indent=1)
        print(f"mjt-droplets: remelt depth {dep * 1e6:.2f} um at {t * 1e3:.4f} ms (paper: ~16 um at 0.075 ms "
              f"for 1500 K, none for 500 K); surface peak {peak:.0f} K")


SCENE = Scene(name="mjt-droplets", kind="continuum",
              title="Material jetting: molten droplet onto a substrate (Fuchs2022 §4.3, tables 1–3)",
              ci_time='85 s (ctest foam.mjt, two substrates)', full_time='~40 min serial',
              build=lambda case, size: main(["build", case, f"--{size}"]),
              analyse=lambda case: main(["analyse", case]))


if __name__ == "__main__":
    main()
