#!/usr/bin/env python3
"""scenes.lmd-track.section: examples/lmd-track's choice of the measured section, on synthetic
end states (no solver run). A track that left solid bead behind its pool is cut in that bead:
the 0.5 mm just behind the pool's tail, when it lies at least 2.8 sigma of the powder spot past
the start; a track whose pool still covers that stretch (the CI's, the 3 mm full one) is cut
1.25-1.75 mm behind the final beam position, as before."""
import sys

import numpy as np

from meltdem import scene as scenes
from meltdem.testing.report import check_absolute

scene = scenes.module("lmd-track")

TEST = "scenes.lmd-track.section"
DX = 0.25e-3
SIG = 0.625e-3            # a quarter of the 2.5 mm spot


def end_state(x_start, x_end, tail, head):
    """Cell centres along x (0.25 mm cells, 1 mm cells before the track and after it) and the
    largest liquid fraction of each column at the end: molten over [tail, head)."""
    xf = np.concatenate([np.arange(x_start - 4e-3, x_start, 1e-3), np.arange(x_start, x_end + 2e-3 + 1e-9, DX)])
    xc = 0.5 * (xf[:-1] + xf[1:])
    liquid = np.where((xc > tail) & (xc < head), 1.0, 0.0)
    return xc, liquid


def main():
    ok = True
    # 8 mm track, a 3.5 mm pool ending 1.5 mm ahead of the beam: solid bead from the start to 12.5 mm
    x0, x1 = 6.5e-3, 14.5e-3
    xc, liq = end_state(x0, x1, 12.5e-3, 16.0e-3)
    cols, kind = scene.measured_section(xc, liq, x0, x1, SIG, DX)
    ok &= check_absolute(TEST, "8 mm track: section in solid bead (1 = yes)", float(kind == "solid"), 1.0, 0)
    ok &= check_absolute(TEST, "8 mm track: section's trailing edge [mm] vs the pool's tail - 0.5 mm",
                         1e3 * (xc[cols[0]] - DX / 2), 12.0, 1e-9)
    ok &= check_absolute(TEST, "8 mm track: section's leading edge [mm] vs the pool's tail",
                         1e3 * (xc[cols[-1]] + DX / 2), 12.5, 1e-9)
    ok &= check_absolute(TEST, "8 mm track: every section column solid at the end (largest liquid fraction)",
                         float(np.max(liq[cols])), 0.0, 0)
    # 3 mm track: the pool's tail 1.1 mm past the start, under 2.8 sigma = 1.75 mm
    x0, x1 = 6.5e-3, 9.5e-3
    xc, liq = end_state(x0, x1, 7.6e-3, 11.0e-3)
    cols, kind = scene.measured_section(xc, liq, x0, x1, SIG, DX)
    ok &= check_absolute(TEST, "3 mm track: section behind the final beam, in the pool (1 = yes)",
                         float(kind == "pool"), 1.0, 0)
    ok &= check_absolute(TEST, "3 mm track: section [mm] vs 1.25-1.75 mm behind the beam, first column centre",
                         1e3 * xc[cols[0]], 7.875, 1e-9)
    ok &= check_absolute(TEST, "3 mm track: section's last column centre [mm]", 1e3 * xc[cols[-1]], 8.125, 1e-9)
    # no pool left at all (a run that stopped the laser): the rule behind the final beam
    xc, liq = end_state(x0, x1, 0.0, 0.0)
    cols, kind = scene.measured_section(xc, liq, x0, x1, SIG, DX)
    ok &= check_absolute(TEST, "no pool at the end: the rule behind the final beam (1 = yes)",
                         float(kind == "pool"), 1.0, 0)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
