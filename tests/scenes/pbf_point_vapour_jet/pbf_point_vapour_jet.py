#!/usr/bin/env python3
"""CI variant of examples/pbf-point with `--vapour-jet` (evaporation `massLoss on; vapourJet on;`) on the
kept CI bed (tests/scenes/pbf_point/bed-ci): coupled meltdemFoam + LAMMPS, 100 grains, laser on 30 us.

The metal that evaporates leaves the continuum, so the particle ledger (grains + continuum + boundaries)
closes only if it books it: the checks of scenes.pbf-point's common part (laser energy exact, grain
mass, per-step mass and energy balances, cumulative system mass), the evaporated mass booked by
meltdemBalance (> 1e-7 of the continuum's metal, 2.9e-6 measured; far above the 1e-10 the ledger holds).
usage: pbf_point_vapour_jet.py [--keep]
"""
import os
import shutil
import sys
import tempfile

from meltdem import paths
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.loader import load_module
from meltdem.testing.report import report_info

SRC = paths.source_dir()
PP = load_module(os.path.join(SRC, "tests", "scenes", "pbf_point", "pbf_point.py"))
TEST = "scenes.pbf-point.vapour-jet"


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-pbf-vapour-")
    bed = os.path.join(work, "bed")
    shutil.copytree(PP.KEPT_BED, bed)
    case = os.path.join(work, "jet")
    s, stop = PP.run_case(case, "point-ci", bed_dir=bed, vapour_jet=True)
    ok = PP.common_checks(TEST, case, s, stop)
    booked, evaporated, metal = cc.check_evaporation_booked(TEST, case, 1e-10)
    ok &= booked
    ok &= report_info(TEST, "evaporated metal / continuum metal at the start (info)", evaporated / metal)
    ok &= report_info(TEST, "peak metal temperature [K] (info; T_v 3000 K)", s["peak_metal_T_K"])
    ok &= report_info(TEST, "grains ejected (info)", s["grains_ejected"])
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
