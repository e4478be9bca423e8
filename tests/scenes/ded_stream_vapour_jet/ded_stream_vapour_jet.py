#!/usr/bin/env python3
"""CI variant of examples/ded-stream (laser on, to 0.020 ms) with `--vapour-jet` (evaporation
`massLoss on; vapourJet on;`): five steel grains into the melt pool while the metal evaporates and its
vapour streams off through the open top.

The metal that evaporates leaves the continuum, so the coupled ledger closes only if it books it:
continuum + particles absorb eta P on every lit step (1e-9), the per-step continuum balances
(meltdem.case.coupled.check_balances) and the system enthalpy (1e-6), and the evaporated mass booked
by meltdemBalance is above 1e-7 of the continuum's metal (far above the ledger's 1e-10). The pool
diameter at 0.018 ms and the peak temperature are printed against the default run's README values.
usage: ded_stream_vapour_jet.py [--keep]
"""
import os
import sys
import tempfile

from meltdem import paths
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.loader import load_module
from meltdem.testing.report import check_at_most, report_info

SRC = paths.source_dir()
DED = load_module(os.path.join(SRC, "tests", "scenes", "ded_stream", "ded_stream.py"))
TEST = "scenes.ded-stream.vapour-jet"


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-ded-vapour-")
    case, s = DED.run_variant(work, "jet", ["--vapour-jet"])
    ok, *_ = DED.laser_checks(case, s, "vapour jet", TEST)
    ok &= cc.check_balances(TEST, cc.ledger(case))
    ok &= check_at_most(TEST, "vapour jet: worst per-step system enthalpy error (particles + continuum)",
                        s["worst_enthalpy_system_error"], 1e-6)
    booked, evaporated, metal = cc.check_evaporation_booked(TEST, case, 1e-10)
    ok &= booked
    ok &= report_info(TEST, "evaporated metal / continuum metal at the start (info)", evaporated / metal)
    ok &= report_info(TEST, "pool diameter at 0.018 ms [um] (info; paper ~130)", s["pool_diameter_at_0.018ms_um"])
    ok &= report_info(TEST, "peak temperature [K] (info; T_v 3000 K)", max(s["peak_T_K"]))
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
