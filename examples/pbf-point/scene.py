#!/usr/bin/python3
"""Powder bed fusion, point melting (Fuchs2022 §4.5): a fixed 312 W laser (d_w = 140 um)
on a 500-grain log-normal (16-32 um) bed on an 80 um steel substrate, 320 x 320 x 240 um,
on until 0.1 ms, off until 0.25 ms; meltdemFoam (melt pool, recoil, evaporation) hosting
LAMMPS (the grains). See README.md.

    scene.py build CASE [--ci | --full] [--dx 10e-6] [--dist overlap] [--grains N] [--absorptivity ETA]
                   [--dabsorptivity-dt PER_K [--absorptivity-min ETA] [--absorptivity-max ETA]] [--vapour-jet]
    scene.py run CASE [--np N]
    scene.py analyse CASE          (prints the table, writes CASE/summary.json)
    scene.py all CASE [--ci | --full] [--np N]
"""
import argparse
import os

from meltdem.case import evaporation
from meltdem.case import laser
from meltdem.scene import Scene

import pbf


VARIANT = "point"


def main(scene=VARIANT, doc=__doc__, argv=None):
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=["build", "run", "analyse", "all"])
    ap.add_argument("case")
    size = ap.add_mutually_exclusive_group()
    size.add_argument("--ci", action="store_true", help="CI size (default)")
    size.add_argument("--full", action="store_true", help="the paper's size")
    ap.add_argument("--dx", type=float, default=None, help="cell size [m]")
    ap.add_argument("--dist", choices=["centre", "neighbours", "overlap"], default=None,
                    help="particle-to-cell distribution model")
    ap.add_argument("--grains", type=int, default=None, help="number of grains")
    ap.add_argument("--bed", default=None, help="folder of the poured bed (reused when present)")
    ap.add_argument("--bed-process", choices=["pour", "spread"], default="pour",
                    help="pour the bed (the paper's) or spread it with examples/powder-spread's blade")
    ap.add_argument("--no-shadow", action="store_true",
                    help="grains cast no shadow and absorb no light (the beam reaches the continuum)")
    ap.add_argument("--gas-cp", type=float, default=pbf.G["cp"],
                    help="gas heat capacity [J/kg/K] (paper: 10; see pbf.py GAS_CP_STABLE)")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks")
    ap.add_argument("--timeout", type=float, default=None, help="wall-clock limit of the solver [s]")
    ap.add_argument("--refine", type=int, default=0, metavar="L",
                    help="adaptive refinement: base cells 2^L x --dx, refined to --dx in the pool, under the beam "
                    "and its path ahead and around the grains near them (refinement{})")
    ap.add_argument("--refine-interval", type=int, default=1, metavar="N", help="fluid steps between mesh updates")
    ap.add_argument("--vapour-jet", action="store_true", help=evaporation.VAPOUR_JET_HELP)
    laser.add_absorptivity_arguments(ap, pbf.ETA)
    args = ap.parse_args(argv)
    laser.check_absorptivity_arguments(ap, args, pbf.ETA)
    case = os.path.abspath(args.case)
    variant = f"{scene}-{'full' if args.full else 'ci'}"
    if args.action in ("build", "all"):
        pbf.build(case, variant, dx=args.dx, dist=args.dist, n=args.grains, bed_dir=args.bed,
                  gas_cp=args.gas_cp, shadow=not args.no_shadow, bed_process=args.bed_process,
                  refine=args.refine, refine_interval=args.refine_interval, laser_args=args,
                  vapour_jet=args.vapour_jet)
    if args.action in ("run", "all"):
        pbf.run(case, args.np, args.timeout)
    if args.action in ("analyse", "all"):
        pbf.print_summary(pbf.summary(case))


SCENE = Scene(name="pbf-point", kind="coupled",
              title="Powder bed fusion, point melting (Fuchs2022 §4.5, tables 1–3)",
              ci_time='88 s wall', full_time='16 min on 2 ranks',
              build=lambda case, size: main(argv=["build", case, f"--{size}"]),
              analyse=lambda case: main(argv=["analyse", case]),
              summary=pbf.summary)


if __name__ == "__main__":
    main()
