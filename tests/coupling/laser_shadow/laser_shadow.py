#!/usr/bin/env python3
"""Particles in the laser beam absorb their share and shadow the continuum: the total absorbed
power stays eta P (coupling/laser_shadowing.h).

Box 2 x 2 x 2 mm of 0.2 mm cells; a solid steel floor fills y < 0.6 mm; gas at rest. A laser
(P = 100 W, eta = 0.5, 1/e^2 radius w = 200 um) points down (-y) at the box centre. Two
d = 100 um grains are held on the beam axis, at y = 1.2 mm and right below it at y = 0.9 mm
(in its shadow). Per fluid step: laser power absorbed by the continuum (solver log) + by the
particles (particles.csv) vs eta P (1e-9 relative). The particles' share vs the upper grain's
projected disk in the Gaussian, eta P (1 - exp(-2 R^2 / w^2)) (1 %: ray discretisation; the
lower grain gets nothing). Continuum energy balance <= 1e-6 and the system enthalpy balance,
with the particles' laser heat booked as a particle source, <= 1e-6.
"""
import os
import re
import sys
import tempfile

import numpy as np

from meltdem.testing.report import check_at_most, check_relative
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

TEST = "coupling.laser_shadow"
D, P, ETA, W = 100e-6, 100.0, 0.5, 200e-6
PARTICLE = dict(d=D, rho=7800.0, cp=500.0, Tm=1700.0, L=2.7e5, T0=300.0, y=1.2e-3, held=True,
                v=(0.0, 0.0, 0.0))
GAS = dict(rho=1.2, mu=1.8e-5, cp=1005.0, k=0.026, T=300.0)
SECOND = f"""create_atoms 1 single 1e-3 0.9e-3 1e-3
set atom 2 diameter {D!r} density 7800.0
"""
LASER = f"""laser
{{
    power {P!r};
    absorptivity {ETA!r};
    radius {W!r};
    position (1e-3 1.5e-3 1e-3);
    direction (0 -1 0);
    tOn -1;
}}
"""


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-laser-shadow-")
    case = os.path.join(work, "case")
    cc.channel_case(case, "overlap", PARTICLE, channel=dict(lx=2e-3, ly=2e-3, lz=2e-3, h=0.2e-3, u=0.0),
                    gas=GAS, t_end=2e-4, fluid_dt=2e-5, dem_dt=1e-6, floor=(0.6e-3, 300.0),
                    extra_lammps=SECOND, physics=dict(laser="on"), extra_properties=LASER)
    cc.run_solver(case)
    log = open(os.path.join(case, "log.meltdemFoam")).read()
    continuum = np.array([float(x) for x in re.findall(r"Laser: absorbed power (\S+) W", log)])
    p, d = cc.particles_csv(case), cc.ledger(case)
    particles = p["laser_heat"] / p["dt"]
    n = min(len(continuum), len(particles))
    total = continuum[:n] + particles[:n]
    print(f"{TEST}: continuum {continuum[0]:.6g} W + particles {particles[0]:.6g} W = {total[0]:.12g} W "
          f"(eta P = {ETA * P} W) over {n} steps")
    ok = check_at_most(TEST, "worst |continuum + particles - eta P| / eta P over the steps",
                       np.max(np.abs(total - ETA * P)) / (ETA * P), 1e-9)
    R = D / 2
    ok &= check_relative(TEST, "laser power absorbed by the particles vs eta P (1 - exp(-2 R^2/w^2)) of the "
                         "upper grain [W]", particles[0], ETA * P * (1 - np.exp(-2 * R * R / W / W)), 0.01)
    ok &= cc.check_balances(TEST, d)
    steps = d[1:]
    ok &= check_at_most(TEST, "worst per-step system energy error (laser on particles booked)",
                        np.max(np.abs(steps["enthalpy_system_error"])), 1e-6)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
