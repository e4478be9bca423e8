#!/usr/bin/env python3
"""scenes.single-track: the CI variant of examples/single-track (AM Bench 2018 AMB2018-02, bare IN625
plates), meltdemFoam alone, 20 um base cells refined once to 10 um, surface tension, Marangoni,
evaporation and recoil on.

- AMMT-B and AMMT-C (conduction mode, NIST's testbed, 170 um spot, 0.8 and 1.2 m/s), with the
  literature absorptivity 0.36 (not fitted): width and depth vs the measured mean with the
  tolerance of issue 19 (the measured scatter or 10 %, whichever is larger). The depths pass; the
  widths are booked XFAIL (WIDE: the simulated pools are as wide as conduction from this beam
  makes them, the measured ones narrower; no absorptivity fits both, README).
- CBM-A (keyhole, 100 um spot, 150 W, 0.4 m/s; 0.4 mm of track): width and depth vs the
  measurement, both booked XFAIL (KEYHOLE: one absorption at a constant absorptivity, no
  multiple reflections in the vapour depression).
- Each run: reaches its end, laser energy = absorptivity x P/2 x time to 1e-9, metal mass error
  <= 1e-13 per step (and 1e-13 x steps in all), enthalpy error <= 1e-6 of what was exchanged
  (meltdemBalance, the energy bound of the coupled scenes), every mesh change conserving metal and
  enthalpy to 1e-12.
"""
import json
import os
import sys
import tempfile

import numpy as np

from meltdem import scene as scenes
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_most, check_relative

scene = scenes.module("single-track")
TEST = "scenes.single-track"
KEYHOLE = ("one absorption at a constant absorptivity: no multiple reflections in the vapour depression, "
           "which raise a keyhole's absorptance above a flat surface's (at 0.70 the depth is 180 um, README)")
WIDE = ("the pool is as wide as conduction from the 170 um beam makes it (Eagar-Tsai 159 / 145 um at 0.36); "
        "an absorptivity low enough for the measured width leaves the depth 25 % short (README)")


def run_track(work, name, extra=(), xfail=None):
    """xfail: quantity -> (the reason of its known miss, the bound of that miss [um])"""
    case = os.path.join(work, name)
    scene.main(["all", case, "--ci", "--track-case", name] + list(extra))
    s = json.load(open(os.path.join(case, "summary.json")))
    ok = True
    for q in ("width", "depth"):
        m, sd = s[f"measured_{q}_um"], s[f"measured_{q}_sd_um"]
        reason, bound = (xfail or {}).get(q, (None, None))
        ok &= check_absolute(TEST, f"{name}: {q} vs AMB2018-02 mean (tolerance max(sd, 10 %)) [um]", s[f"{q}_um"], m,
                             scene.tolerance(m, sd), xfail=reason, miss_within=bound)
    ok &= check_absolute(TEST, f"{name}: run reaches the end of the track [s]", s["time_s"], s["end_s"], 1e-12)
    b = np.atleast_1d(np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"),
                                    delimiter=",", names=True))
    power = 0.5 * scene.TRACKS[name]["power"] * s["absorptivity"]
    ok &= check_relative(TEST, f"{name}: absorbed laser energy vs absorptivity x P/2 x t [J]",
                         float(b["laserEnergy_cum"][-1]), power * float(b["time"][-1]), 1e-9)
    steps = len(b) - 1
    per_step = np.abs(np.diff(b["massError"])) / float(b["metalMass"][0])
    ok &= check_at_most(TEST, f"{name}: worst per-step metal mass error (relative)", float(per_step.max()), 1e-13)
    ok &= check_at_most(TEST, f"{name}: cumulative metal mass error (relative) over {steps} steps",
                        abs(float(b["massErrorRel"][-1])), 1e-13 * steps)
    ok &= check_at_most(TEST, f"{name}: cumulative enthalpy error / exchanged",
                        abs(float(b["enthalpyErrorRelExchanged"][-1])), 1e-6)
    _, worst = fc.refinement_ledger(case)
    ok &= check_at_most(TEST, f"{name}: worst metal/enthalpy change over a mesh change (relative)", worst, 1e-12)
    print(f"{TEST}: {name}: {s['fluid_steps']} steps, at most {s['most_cells']} cells, CPU {s['cpu_seconds']:.0f} s")
    return ok


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-single-track-")
    ok = run_track(work, "AMMT-B", xfail={"width": (WIDE, 45.0)})
    ok &= run_track(work, "AMMT-C", xfail={"width": (WIDE, 60.0)})
    ok &= run_track(work, "CBM-A", ["--track", "0.4"], xfail={"width": (KEYHOLE, 80.0), "depth": (KEYHOLE, 100.0)})
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
