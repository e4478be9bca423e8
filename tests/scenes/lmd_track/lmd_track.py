#!/usr/bin/env python3
"""scenes.lmd-track: the CI variant of examples/lmd-track (Codina2019 §4.1, table 4.1 conditions).

Half model, 0.5 mm cells, 1.2 mm of track (0.72 s) from the quasi-steady plate temperature: a
1 kW Gaussian beam (2.5 mm) at 100 mm/min on an AISI 304 plate. Two runs:

1. bare track (laser only): fused width and penetration vs table 4.2 (3.46 / 0.61 mm),
   within one cell of this mesh (0.5 mm; Codina2019 states its own accuracy as limited by its
   0.25 mm cells), and the share of the powder spot falling on the pool surface vs the
   deposition efficiency 85.8 % (within 5 points: the Codina2019 simulation is 0.7 points off).
2. coupled meltdemFoam + LAMMPS with the powder stream (fix powder/insert, 1.6 g/min, 40-200 um)
   inserted during the run: the run must reach the end of the track; then bead width, height,
   penetration and deposition efficiency (deposited / (deposited + lost)) vs table 4.2 with the
   same tolerances; the powder bookkeeping (fed = deposited + lost + aloft + pending to 1e-12;
   ledger deposit = fix powder/melt's molten mass (1e-9); fed = 0.8 g/min x run
   time within 1 %); the
   particle ledger (per-step continuum mass/energy errors, system mass error per step and
   cumulative, with the feed and pending store booked).

The coupled bead height is booked XFAIL (the CI section lies at the track start and misses part
of its powder). A coupled run that stops is a FAIL (a defect, not a miss).
"""
import json
import os
import sys
import tempfile

from meltdem import paths
from meltdem import scene as scenes
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_most, check_relative

SRC = paths.source_dir()

scene = scenes.module("lmd-track")

TEST = "scenes.lmd-track"
CELL_MM = scene.VARIANTS["ci"]["dx"] * 1e3
# the measured section (1.25-1.75 mm behind the final beam) lies at the start of the 1.2 mm CI
# track: it has not received the powder the beam would bring before the start
SHORT = "CI: the 1.2 mm track's measured section lies at its start and misses part of its powder"
# the 1.2 mm CI track from a cold powder start is shorter than the bead's own length (2.5 mm
# spot), so neither the coupled width nor the efficiency is at its steady value yet
SHORT_COUPLED = "CI: 1.2 mm of track at 0.5 mm cells is shorter than the 2.5 mm spot: no steady bead yet"


def bare_track(work):
    """The CI mesh and track without powder (laser only): the fused zone and the geometric
    capture of the powder spot by the pool surface."""
    case = os.path.join(work, "bare")
    scene.main(["all", case, "--ci", "--no-particles"])
    s = json.load(open(os.path.join(case, "summary.json")))
    ex = scene.EXPERIMENT
    ok = check_absolute(TEST, "bare track: fused width vs experiment bead width [mm]", s["bead_width_mm"],
                        ex["width_mm"], CELL_MM)
    ok &= check_absolute(TEST, "bare track: penetration vs experiment [mm]", s["penetration_mm"],
                         ex["penetration_mm"], CELL_MM)
    ok &= check_absolute(TEST, "bare track: powder spot share on the pool surface vs experiment deposition "
                         "efficiency [%]", s["geometric_capture_pct"], ex["efficiency_pct"], 5.0)
    return ok


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-lmd-")
    ok = bare_track(work)
    case = os.path.join(work, "case")
    scene.main(["build", case, "--ci"])
    t_end = json.load(open(os.path.join(case, "scene.json")))["end"]
    try:
        scene.main(["run", case])
    except RuntimeError as e:
        # the coupling stopped (e.g. its bounded-temperature guard): a defect, not a miss
        print(str(e)[-1500:])
        led = cc.ledger(case)
        check_absolute(TEST, "coupled run reaches the end of the track [s]", float(led["time"][-1]), t_end, 1e-9)
        cc.check_balances(TEST, led)
        return fc.finish(False, work, keep)
    ok_bare = ok
    scene.main(["analyse", case])
    s = json.load(open(os.path.join(case, "summary.json")))
    led = cc.ledger(case)
    ex = scene.EXPERIMENT
    ok = ok_bare & check_absolute(TEST, "coupled run reaches the end of the track [s]", s["time_s"], t_end, 1e-9)
    print(f"{TEST}: {s['particles_inserted']} grains inserted, wall {s['wall_seconds']:.0f} s")
    ok &= check_absolute(TEST, "bead width vs experiment (table 4.2) [mm]", s["bead_width_mm"], ex["width_mm"],
                         CELL_MM, xfail=SHORT_COUPLED, miss_within=1.2)
    ok &= check_absolute(TEST, "bead height vs experiment (table 4.2) [mm]", s["bead_height_mm"], ex["height_mm"],
                         CELL_MM, xfail=SHORT, miss_within=0.8)
    ok &= check_absolute(TEST, "penetration vs experiment (table 4.2) [mm]", s["penetration_mm"],
                         ex["penetration_mm"], CELL_MM)
    ok &= check_absolute(TEST, "powder deposition efficiency vs experiment (table 4.2) [%]",
                         s["deposition_efficiency_pct"], ex["efficiency_pct"], 5.0, xfail=SHORT_COUPLED,
                         miss_within=15.0)
    # powder bookkeeping
    fed = s["powder_fed_kg"]
    ok &= check_relative(TEST, "fed = deposited + lost + aloft + pending [kg]",
                         s["powder_deposited_kg"] + s["powder_lost_kg"] + s["powder_aloft_kg"] + s["powder_pending_kg"],
                         fed, 1e-12)
    ok &= check_relative(TEST, "deposited (ledger) vs molten mass fix powder/melt reports [kg]",
                         s["powder_deposited_kg"], s["powder_melted_lammps_kg"], 1e-9)
    ok &= check_relative(TEST, "fed powder vs 1.6 g/min / 2 (half model) x run time [kg]", fed,
                         0.5 * scene.PROCESS["feed"] * s["time_s"], 0.01)
    # ledger balances
    ok &= cc.check_balances(TEST, led)
    steps = led[1:]
    import numpy as np
    ok &= check_at_most(TEST, "worst per-step system mass error (particles + continuum + pending)",
                        float(np.max(np.abs(steps["mass_system_error"]))), 1e-12)
    ok &= check_at_most(TEST, "cumulative system mass error", abs(float(led["mass_cumulative_system_error"][-1])),
                        1e-12)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
