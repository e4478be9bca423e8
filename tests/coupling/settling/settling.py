#!/usr/bin/env python3
"""A particle settling in quiescent gas through the coupled solver vs the standalone 'ambient'
mode of fix powder/melt: the same terminal velocity within 2 %.

Box 4 x 4 x 4 mm of 0.5 mm cells, air at rest (rho 1.2, mu 1.8e-5, 300 K), gravity -9.81 in y
in both codes. A steel grain d = 10 um (rho 7800, response time tau = rho d^2 / (18 mu) =
2.4 ms) falls from rest for 15 ms (6 tau); the terminal velocity is its mean vy over the last
2 ms. Coupled, the grain feels the local gas (which its drag pushes down a little: the
Stokeslet at one cell's distance is ~1 % of v_t); standalone, a uniform gas at rest. The Stokes
value rho_p g d^2 / (18 mu) (buoyancy 1.5e-4 of it) is printed as a third reference.

--isothermal (coupling.settling.isothermal): the continuum without energy equation (physics
energy off, the binder-jetting mode) and a grain 700 K hotter than the gas: the grain must
settle the same way and exchange no heat at all (its enthalpy unchanged, not one joule handed
over), where the thermal coupling would cool it.
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.testing.report import check_absolute, check_relative
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

ISOTHERMAL = "--isothermal" in sys.argv
TEST = "coupling.settling" + (".isothermal" if ISOTHERMAL else "")
D, RHO_P, RHO_G, MU_G, G = 10e-6, 7800.0, 1.2, 1.8e-5, 9.81
T_END, AVERAGE = 15e-3, 2e-3
PARTICLE = dict(d=D, rho=RHO_P, cp=500.0, Tm=5000.0, L=2.7e5, T0=1000.0 if ISOTHERMAL else 300.0, y=3e-3,
                v=(0.0, 0.0, 0.0))


def terminal(rows):
    last = rows[rows[:, 0] >= rows[-1, 0] - AVERAGE]
    return -np.mean(last[:, 2])


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-settling-")
    case = os.path.join(work, "case")
    cc.channel_case(case, "neighbours", PARTICLE,
                    channel=dict(lx=4e-3, ly=4e-3, lz=4e-3, h=0.5e-3, u=0.0),
                    gas=dict(rho=RHO_G, mu=MU_G, cp=1005.0, k=0.026, T=300.0),
                    t_end=T_END, fluid_dt=2e-4, dem_dt=1e-5, g=(0.0, -G, 0.0), extra_lammps=cc.track_commands(10),
                    physics=dict(energy="off") if ISOTHERMAL else None)
    cc.run_solver(case)
    coupled = terminal(cc.track(os.path.join(case, "log.lammps")))

    # the same LAMMPS input standalone, with the uniform gas at rest ('ambient')
    alone = os.path.join(work, "alone")
    os.makedirs(alone)
    text = open(os.path.join(case, "in.particles")).read()
    text = re.sub(r"(fix melt all powder/melt .*)", r"\1 ambient 300 0.026 %r %r 1005 0 0 0" % (RHO_G, MU_G), text)
    text = text.replace("thermo 10", f"thermo 10\nrun {round(T_END / 1e-5)}")
    open(os.path.join(alone, "in.alone"), "w").write(text)
    subprocess.run([paths.binary("meltdem-lmp"), "-in", "in.alone", "-log", "log.lammps",
                    "-screen", "none"], cwd=alone, check=True)
    standalone = terminal(cc.track(os.path.join(alone, "log.lammps")))
    stokes = (RHO_P - RHO_G) * G * D * D / (18 * MU_G)
    print(f"{TEST}: terminal velocity coupled {coupled:.6g} m/s, standalone ambient {standalone:.6g} m/s, "
          f"Stokes {stokes:.6g} m/s")
    ok = check_relative(TEST, "terminal velocity, coupled vs standalone ambient [m/s]", coupled, standalone, 0.02)
    ok &= check_relative(TEST, "terminal velocity, standalone vs Stokes [m/s]", standalone, stokes, 0.02)
    if ISOTHERMAL:
        pc = cc.particles_csv(case)
        h0 = PARTICLE["cp"] * PARTICLE["T0"] * (PARTICLE["rho"] * np.pi * D**3 / 6)
        print(f"{TEST}: particle enthalpy {pc['particle_enthalpy'][-1]!r} J (initial {h0!r}), heat absorbed "
              f"{np.abs(pc['heat_absorbed']).max()!r} J, enthalpy handed over "
              f"{np.abs(pc['enthalpy_handed_over']).max()!r} J")
        ok &= check_relative(TEST, "isothermal grain: enthalpy at the end vs m cp T0 [J]", pc["particle_enthalpy"][-1],
                             h0, 1e-12)
        ok &= check_absolute(TEST, "isothermal grain: largest heat absorbed in a step [J]",
                             np.abs(pc["heat_absorbed"]).max(), 0.0, 0.0)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
