#!/usr/bin/env python3
"""A particle entering liquid metal is captured and melts.

Box 2 x 2 x 2 mm of 0.2 mm cells; a liquid steel pool (alpha = 1, 1800 K, above Tliquidus
1700 K) fills y < 0.6 mm; gas at rest, gravity off. A d = 100 um steel grain at 300 K comes
down at 0.3 m/s from y = 0.8 mm, with the solid_metal wall on (liquid is not a wall). In the
pool it samples the melt (density, viscosity, k, T of the cells it overlaps): the melt's drag
stops it and the melt's heat melts it. Checks: it went below the pool surface (captured,
not bounced: lowest centre below the surface), it slowed to less than 10 % of its entry speed,
all its mass was handed over (1e-12), continuum balances (mass <= 1e-13, energy <= 1e-6).
"""
import os
import sys
import tempfile

import numpy as np

from meltdem.testing.report import check_at_most, check_relative
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

TEST = "coupling.capture"
D, POOL, V0 = 100e-6, 0.6e-3, 0.3
M_P = 7800.0 * np.pi * D**3 / 6
PARTICLE = dict(d=D, rho=7800.0, cp=500.0, Tm=1700.0, L=2.7e5, T0=300.0, y=0.8e-3, v=(0.0, -V0, 0.0))
GAS = dict(rho=1.2, mu=1.8e-5, cp=1005.0, k=0.026, T=300.0)


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-capture-")
    case = os.path.join(work, "case")
    cc.channel_case(case, "overlap", PARTICLE, channel=dict(lx=2e-3, ly=2e-3, lz=2e-3, h=0.2e-3, u=0.0),
                    gas=GAS, t_end=2e-3, fluid_dt=2e-5, dem_dt=1e-8, floor=(POOL, 1800.0),
                    extra_lammps=cc.track_commands(100), melt_keywords="solid_metal 1e9 0.5")
    cc.run_solver(case)
    t = cc.track(os.path.join(case, "log.lammps"))
    p, d = cc.particles_csv(case), cc.ledger(case)
    depth = (POOL - np.min(t[:, 1])) / (D / 2)
    slowest = np.min(np.abs(t[t[:, 1] < POOL, 2])) if np.any(t[:, 1] < POOL) else np.nan
    gone = p["time"][np.nonzero(p["particles"] == 0)[0][0]] if np.any(p["particles"] == 0) else np.nan
    print(f"{TEST}: lowest centre {depth:.3g} R below the pool surface, slowest {slowest:.3g} m/s in the "
          f"pool, fully molten at t = {gone:.4g} s")
    ok = check_at_most(TEST, "captured: lowest centre height above the pool surface / R", -depth, 0.0)
    ok &= check_at_most(TEST, "speed in the pool / entry speed", slowest / V0, 0.1)
    ok &= check_relative(TEST, "metal mass handed over vs particle mass [kg]", np.sum(p["mass_melted"]), M_P, 1e-12)
    ok &= cc.check_balances(TEST, d)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
