#!/usr/bin/env python3
"""A particle meeting the continuum's solid metal bounces off it as off a granular wall
(fix powder/melt solid_metal E* e).

Box 2 x 2 x 2 mm of 0.2 mm cells; a solid steel floor (alpha = 1, 300 K, below Tsolidus) fills
y < 0.6 mm; gas at rest. A d = 100 um steel grain (no melting: Tm 1700 K, all at 300 K) comes
down at 1 m/s from y = 1 mm (gravity off). The coupling hands the grain the floor's surface
(the top faces of the solid cells) and fix powder/melt applies the Hertz/Tsuji contact with
E* = 1 GPa and e = 0.5.
Checks: rebound speed / impact speed vs e = 0.5 (3 %), and the grain does not sink: its
lowest centre height above the floor >= 0.95 R. Without the keyword the grain sinks into the
'solid' (it only feels the metal's drag): printed for comparison.
"""
import os
import sys
import tempfile

import numpy as np

from meltdem.testing.report import check_at_most, check_relative
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

TEST = "coupling.solid_metal"
D, FLOOR, E_REST, V0 = 100e-6, 0.6e-3, 0.5, 1.0
PARTICLE = dict(d=D, rho=7800.0, cp=500.0, Tm=1700.0, L=2.7e5, T0=300.0, y=1.0e-3, v=(0.0, -V0, 0.0))
GAS = dict(rho=1.2, mu=1.8e-5, cp=1005.0, k=0.026, T=300.0)


def run(work, name, keywords):
    case = os.path.join(work, name)
    cc.channel_case(case, "overlap", PARTICLE, channel=dict(lx=2e-3, ly=2e-3, lz=2e-3, h=0.2e-3, u=0.0),
                    gas=GAS, t_end=6e-4, fluid_dt=2e-5, dem_dt=1e-8, floor=(FLOOR, 300.0),
                    extra_lammps=cc.track_commands(50), melt_keywords=keywords)
    cc.run_solver(case)
    return cc.track(os.path.join(case, "log.lammps"))


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-solid-metal-")
    t = run(work, "wall", f"solid_metal 1e9 {E_REST}")
    gap = (np.min(t[:, 1]) - FLOOR) / (D / 2)
    # the speed once the contact is over (centre more than R above the floor again): inside
    # the contact the undamped-tension Tsuji force first overshoots, then pulls back
    low = np.argmin(t[:, 1])
    after = np.nonzero((np.arange(len(t)) > low) & (t[:, 1] - FLOOR > D / 2))[0]
    rebound = t[after[0], 2] if len(after) else np.nan
    print(f"{TEST}: lowest centre {gap:.4f} R above the floor, rebound {rebound:.5g} m/s")
    ok = check_relative(TEST, "rebound / impact speed off the solid metal vs e", rebound / V0, E_REST, 0.03)
    ok &= check_at_most(TEST, "penetration into the solid metal (1 - lowest centre height / R)", 1 - gap, 0.05)
    if "--compare" in sys.argv:
        t0 = run(work, "no_wall", "")
        print(f"{TEST}: without solid_metal the lowest centre is {(np.min(t0[:, 1]) - FLOOR) / (D / 2):.3f} R "
              f"above the floor top")
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
