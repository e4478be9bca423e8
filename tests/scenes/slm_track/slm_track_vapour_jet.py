#!/usr/bin/env python3
"""scenes.slm-track.vapour-jet: the CI variant of examples/slm-track with `--vapour-jet`: evaporation
(Fuchs2022's steel data), recoil, and the evaporated metal's mass loss and vapour jet (the vapour as the
scene's argon). Checks the laser energy (exact), the particle ledger's per-step balances with the
evaporated metal booked, that metal did evaporate (booked by meltdemBalance), the 10 m/s speed cap, and the
thesis's ejection speed (XFAIL while the jet ejects no grain at this size); reports the rest.
"""
import os
import sys
import tempfile

from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.loader import load_module
from meltdem.testing.report import check_at_most, check_relative, report_info

SLM = load_module(os.path.join(os.path.dirname(os.path.abspath(__file__)), "slm_track.py"))
TEST = "scenes.slm-track.vapour-jet"


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-slm-jet-")
    case = os.path.join(work, "case")
    s, ok = SLM.run_exact(TEST, case, vapour_jet=True)
    booked, evaporated, metal = cc.check_evaporation_booked(TEST, case, 1e-12)
    ok &= booked
    ok &= check_at_most(TEST, "DEM updates capped by the 10 m/s speed limit (fix nve/limit; pop-corn watch)",
                        s["dem_updates_speed_limited"], 0)
    ok &= check_relative(TEST, "median speed of the ejected particles [m/s] vs thesis ~1 m/s",
                         s["ejection_speed_median_m_per_s"], 1.0, 0.5,
                         xfail="the vapour jet (argon, 30 um cells) ejects no grain in the CI run: the fastest "
                         "grain reaches 1.09 m/s (0.88 without the jet) but stays in the bed")
    ok &= report_info(TEST, "evaporated metal / continuum metal (info)", evaporated / metal)
    ok &= report_info(TEST, "largest particle speed [m/s] (info; 0.88 without the jet)",
                      s["particle_speed_max_m_per_s"])
    ok &= report_info(TEST, "melted track width [m] (info)", s["track_width_m"])
    ok &= report_info(TEST, "denudation width [m] (info)", s["denudation_width_m"])
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
