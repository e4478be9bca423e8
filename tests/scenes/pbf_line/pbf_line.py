#!/usr/bin/env python3
"""CI variant of examples/pbf-line (Fuchs2022 §4.5, line melting), coupled
meltdemFoam + LAMMPS: 160 log-normal grains (16-32 um) on a 40 um substrate, 280 x 140 x 160 um
of 10 um cells (overlap), 312 W laser (eta 0.5, d_w = 140 um) on at x = 80 um, at rest 10 us,
then 2 m/s over 60 um, off at 40 us, end 45 us; recoil and evaporation on.

References: exact ones as in pbf_point (laser energy, grain mass, ledger); the melt-pool width
vs the Eagar-Tsai conduction solution (EagarTsai1983) for the same Gaussian source at 2 m/s on a half space
(20 %; the CI substrate is 40 um thick and 160 um wide and the beam moves only 60 um, so it
is neither a half space nor a quasi-steady pool). Grains ejected: the peak stays below boiling
in the CI run, so there is no recoil to throw them: XFAIL.
"""
import os
import sys
import tempfile

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.loader import load_module
from meltdem.paths import examples_dir, source_dir
from meltdem.testing.report import check_at_least, check_relative

SRC = paths.source_dir()

pbf = load_module(os.path.join(examples_dir(), "pbf-point", "pbf.py"))
_point = load_module(os.path.join(source_dir(), "tests", "scenes", "pbf_point", "pbf_point.py"))
common_checks, run_case, stopped = _point.common_checks, _point.run_case, _point.stopped

TEST = "scenes.pbf-line"
XFAIL_NO_BOILING = ("peak below T_v (2880 K) in the CI run: no recoil; since 53da1c5 no grain is kicked out "
                    "of freezing metal (the 13-44 grains counted before were that kick)")

# the CI track's depth sits at the 1-cell bound, inside the spread between poured beds
XFAIL_BED_DEPTH = ("bed realization: 9.65 um on the CI bed poured with the onset force of damping tsuji and the "
                   "three-contact-time hold of fix powder/dt, 8.99 um with the two-time hold (93008a3), 10.12 um "
                   "before it; the 10 um bound lies within the bed-to-bed spread")


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-pbf-line-")
    case = os.path.join(work, "case")
    s, stop = run_case(case, "line-ci")
    ok = common_checks(TEST, case, s, stop, short=XFAIL_BED_DEPTH)
    ok &= check_relative(TEST, "melt pool width while moving [um] vs Eagar-Tsai (2 m/s, conduction)",
                         s["melt_pool_width_moving_um"], s["eagar_tsai_width_um"], 0.2,
                         xfail=stopped(s, stop))
    ok &= check_at_least(TEST, "grains ejected (paper: ejected ahead of and around the pool)",
                         s["grains_ejected"], 1, xfail=stopped(s, stop) or XFAIL_NO_BOILING)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
