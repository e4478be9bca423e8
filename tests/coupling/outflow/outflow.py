#!/usr/bin/env python3
"""A particle that leaves the mesh is booked as outflow, never dropped silently.

The Codina2019 channel shortened to 2.1 x 2.1 x 2.1 mm; a cold d = 100 um grain (no melting)
rides the gas down at 2 m/s from y = 0.5 mm and crosses the outlet after ~0.25 ms. The
coupling removes it from LAMMPS when its centre leaves the mesh and books its mass, enthalpy
and momentum as lost (outflow). Checks: one particle booked lost; the lost mass equals its
mass (1e-12); the whole system's mass and momentum balances (particles + continuum + lost)
close per step (mass <= 1e-13, enthalpy <= 1e-12, momentum <= 1e-7 of the momentum present),
the heat it took from the 1500 K gas in the step it leaves included; none left.
"""
import os
import sys
import tempfile

import numpy as np

from meltdem.testing.report import check_absolute, check_at_most, check_relative
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

TEST = "coupling.outflow"
D, RHO = 100e-6, 7800.0
M_P = RHO * np.pi * D**3 / 6
PARTICLE = dict(d=D, rho=RHO, cp=500.0, Tm=1e4, L=2.7e5, T0=300.0, y=0.5e-3)


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-outflow-")
    case = os.path.join(work, "case")
    cc.channel_case(case, "overlap", PARTICLE, channel=dict(ly=2.1e-3), t_end=4e-4, fluid_dt=1e-5)
    cc.run_solver(case)
    d = cc.ledger(case)
    ok = check_absolute(TEST, "particles booked as lost (outflow)", np.sum(d["lost_particles"]), 1, 0)
    ok &= check_relative(TEST, "mass booked as outflow vs particle mass [kg]", d["mass_cumulative_lost"][-1], M_P,
                         1e-12)
    ok &= check_absolute(TEST, "particles left at the end", d["particles"][-1], 0, 0)
    steps = d[1:]
    ok &= check_at_most(TEST, "worst per-step system mass error", np.max(np.abs(steps["mass_system_error"])), 1e-13)
    # the grain (300 K) takes heat from the 1500 K gas up to the step it leaves: that heat came
    # from its cells, and leaves with it
    ok &= check_at_most(TEST, "worst per-step system enthalpy error (the step it leaves included)",
                        np.max(np.abs(steps["enthalpy_system_error"])), 1e-12)
    worst = max(np.max(np.abs(steps[f"mom_{c}_system_error"])) for c in "xyz")
    ok &= check_at_most(TEST, "worst per-step system momentum error", worst, 1e-7)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
