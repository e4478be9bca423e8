#!/usr/bin/python3
"""Powder bed fusion, a layer: hatched tracks over a powder layer (examples/pbf-point's
physics: Fuchs2022's steel, gas, 312 W laser of d_w = 140 um; meltdemFoam hosting LAMMPS). The
beam scans the tracks in order at the given speed and is off while it returns to the next one.
See README.md.

    scene.py build CASE [--ci | --full] [--hatch 80e-6] [--tracks 3] [--order serpentine]
                        [--return-time 30e-6] [--speed 2] [--length 80e-6] [--dx 10e-6]
                        [--grains N] [--bed-process pour|spread] [--balance N] [--absorptivity ETA]
                        [--dabsorptivity-dt PER_K [--absorptivity-min ETA] [--absorptivity-max ETA]]
    scene.py run CASE [--np N] [--timeout S]
    scene.py analyse CASE          (prints the table, writes CASE/summary.json)
    scene.py all CASE [--ci | --full] [--np N] ...
"""
import argparse
import os

from meltdem.case import laser
from meltdem.scene import Scene

import layer


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=["build", "run", "analyse", "all"])
    ap.add_argument("case")
    size = ap.add_mutually_exclusive_group()
    size.add_argument("--ci", action="store_true", help="CI size (default)")
    size.add_argument("--full", action="store_true", help="four 400 um tracks over 560 x 560 um")
    ap.add_argument("--hatch", type=float, default=None, help="hatch spacing between track centres [m]")
    ap.add_argument("--tracks", type=int, default=None, help="number of tracks")
    ap.add_argument("--order", choices=layer.ORDERS, default=None,
                    help="serpentine (alternating direction) or unidirectional (all +x)")
    ap.add_argument("--return-time", type=float, default=None,
                    help="beam off between one track's end and the next one's start [s]")
    ap.add_argument("--speed", type=float, default=None, help="scan speed [m/s]")
    ap.add_argument("--length", type=float, default=None, help="track length [m]")
    ap.add_argument("--dx", type=float, default=None, help="cell size [m]")
    ap.add_argument("--grains", type=int, default=None, help="number of grains (default: the bed density)")
    ap.add_argument("--bed", default=None, help="folder of the poured bed (reused when present)")
    ap.add_argument("--bed-process", choices=["pour", "spread"], default="pour",
                    help="pour the bed or spread it with examples/powder-spread's blade")
    ap.add_argument("--balance", type=int, default=None, metavar="N",
                    help="LAMMPS fix balance by particle count every N DEM steps (shift x z)")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks")
    ap.add_argument("--timeout", type=float, default=None, help="wall-clock limit of the solver [s]")
    laser.add_absorptivity_arguments(ap, layer.pbf.ETA)
    args = ap.parse_args(argv)
    laser.check_absorptivity_arguments(ap, args, layer.pbf.ETA)
    case = os.path.abspath(args.case)
    if args.action in ("build", "all"):
        try:
            cfg = layer.config("full" if args.full else "ci", hatch=args.hatch, tracks_n=args.tracks,
                               order=args.order, return_time=args.return_time, v=args.speed, length=args.length,
                               dx=args.dx, n=args.grains, balance=args.balance)
        except ValueError as e:
            ap.error(str(e))
        layer.pbf.build(case, cfg, bed_dir=args.bed, bed_process=args.bed_process, laser_args=args)
    if args.action in ("run", "all"):
        layer.pbf.run(case, args.np, args.timeout)
    if args.action in ("analyse", "all"):
        layer.print_summary(layer.summary(case))


SCENE = Scene(name="pbf-layer", kind="coupled",
              title="Powder bed fusion, a layer of hatched tracks (Fuchs2022's material and laser)",
              ci_time="about 5 min wall", full_time="estimated in README.md",
              build=lambda case, size: main(["build", case, f"--{size}"]),
              analyse=lambda case: main(["analyse", case]),
              summary=layer.summary)


if __name__ == "__main__":
    main()
