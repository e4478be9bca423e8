#!/usr/bin/env python3
"""CI variant of examples/pbf-line (SPH paper section 4.5, line melting), coupled
meltdemFoam + LAMMPS: 400 log-normal grains (16-32 um) on a 40 um substrate, 400 x 160 x 200 um
of 10 um cells (overlap), 312 W laser (eta 0.5, d_w = 140 um) on at x = 100 um, at rest 20 us,
then 2 m/s over 160 um, off at 100 us, end 110 us; recoil and evaporation on.

References: exact ones as in pbf_point (laser energy, grain mass, ledger); the melt-pool width
vs the Eagar-Tsai conduction solution for the same Gaussian source at 2 m/s on a half space
(20 %; the CI substrate is 40 um thick and 200 um wide, so it is not a half space).
"""
import os
import sys
import tempfile

SRC = os.environ["MELTDEM_SOURCE_DIR"]
sys.path.insert(0, os.path.join(SRC, "tests", "support"))
sys.path.insert(0, os.path.join(SRC, "tests", "scenes", "pbf_point"))
sys.path.insert(0, os.path.join(SRC, "examples", "pbf-point"))
from meltdem_report import check_relative  # noqa: E402
import pbf  # noqa: E402
import foamcase as fc  # noqa: E402
from pbf_point import common_checks  # noqa: E402

TEST = "scenes.pbf_line"


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-pbf-line-")
    case = os.path.join(work, "case")
    cfg = pbf.build(case, "line-ci")
    pbf.run(case, 1)
    s = pbf.summary(case)
    pbf.print_summary(s)
    ok = common_checks(TEST, case, s)
    ref = pbf.eagar_tsai_width(pbf.ETA * cfg["power"], cfg["v"], cfg["rw"] / 2) * 1e6
    ok &= check_relative(TEST, "melt pool width while moving [um] vs Eagar-Tsai (2 m/s, conduction)",
                         s["melt_pool_width_moving_um"], ref, 0.2,
                         xfail=None)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
