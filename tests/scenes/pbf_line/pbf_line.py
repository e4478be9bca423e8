#!/usr/bin/env python3
"""CI variant of examples/pbf-line (SPH paper section 4.5, line melting), coupled
meltdemFoam + LAMMPS: 160 log-normal grains (16-32 um) on a 40 um substrate, 280 x 140 x 160 um
of 10 um cells (overlap), 312 W laser (eta 0.5, d_w = 140 um) on at x = 80 um, at rest 10 us,
then 2 m/s over 60 um, off at 40 us, end 45 us; recoil and evaporation on.

References: exact ones as in pbf_point (laser energy, grain mass, ledger); the melt-pool width
vs the Eagar-Tsai conduction solution for the same Gaussian source at 2 m/s on a half space
(20 %; the CI substrate is 40 um thick and 160 um wide and the beam moves only 60 um, so it
is neither a half space nor a quasi-steady pool). Measured 120 um (-14 %); 110 um (-21 %, one
10 um cell below the tolerance) with 4ffedb5 alone, while grains were still kicked out of
freezing metal (53da1c5 removed that). Grains ejected: 0 since 53da1c5 (13-44 before, that kick);
the peak stays below boiling in the CI run, so there is no recoil to throw them: XFAIL.
"""
import os
import sys
import tempfile

SRC = os.environ["MELTDEM_SOURCE_DIR"]
sys.path.insert(0, os.path.join(SRC, "tests", "support"))
sys.path.insert(0, os.path.join(SRC, "tests", "scenes", "pbf_point"))
sys.path.insert(0, os.path.join(SRC, "examples", "pbf-point"))
from meltdem_report import check_at_least, check_relative  # noqa: E402
import pbf  # noqa: E402
import foamcase as fc  # noqa: E402
from pbf_point import common_checks, run_case, stopped  # noqa: E402

TEST = "scenes.pbf-line"
XFAIL_NO_BOILING = ("peak below T_v (2880 K) in the CI run: no recoil; since 53da1c5 no grain is kicked out "
                    "of freezing metal (the 13-44 grains counted before were that kick)")


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-pbf-line-")
    case = os.path.join(work, "case")
    s, stop = run_case(case, "line-ci")
    ok = common_checks(TEST, case, s, stop)
    ok &= check_relative(TEST, "melt pool width while moving [um] vs Eagar-Tsai (2 m/s, conduction)",
                         s["melt_pool_width_moving_um"], s["eagar_tsai_width_um"], 0.2,
                         xfail=stopped(s, stop))
    ok &= check_at_least(TEST, "grains ejected (paper: ejected ahead of and around the pool)",
                         s["grains_ejected"], 1, xfail=stopped(s, stop) or XFAIL_NO_BOILING)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
