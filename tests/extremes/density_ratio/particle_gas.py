#!/usr/bin/python3
"""Particle/fluid density ratio 1e4: a steel grain (d = 10 um, rho 7430)
shot at 1 m/s through gas of rho 0.743 (mu 2.1e-5, at rest, 1500 K like the grain: no heat
exchange) in 10 um cells (d/dx = 1, distribution centre), coupled. The grain's drag reaction
goes into the gas of its cell: per step it changes that cell's velocity by
S = dt beta / (rho_g V_cell) times the slip, beta >= 3 pi mu d (Stokes): S = 2.7e6 dt.

  fine:   maxDeltaT 1e-6 s (S ~ 2.4; incompressibility shares the force with the neighbours):
          no NaN; the gas stays slower than the grain that drives it (a drag reaction cannot push
          the gas past the grain); continuum mass / energy errors <= 1e-13 / 1e-6, momentum 1e-5;
          the speed the grain loses in 46 us vs the same LAMMPS input standalone in uniform gas at
          rest ('ambient'), 10 %: XFAIL, it loses less -- at d/dx = 1 it drags its own cell's gas
          along and sees only part of the slip (unresolved coupling).
  coarse: maxDeltaT 1e-5 s (S = 27 in the first step): an explicit drag reaction would
          overshoot and drive the gas past the grain; the two-body drag of fix powder/melt (the
          grain and the gas parcel of its cells relax at most to their common velocity) keeps the
          gas below the grain.
usage: particle_gas.py [--keep]
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.testing.report import check_absolute, check_at_most, check_relative
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

TEST = "extremes.density_ratio.particle"
H, D, RHO_P, RHO_G, MU_G, V0 = 10e-6, 10e-6, 7430.0, 0.743, 2.1e-5, 1.0
GAS = dict(rho=RHO_G, mu=MU_G, cp=5210.928, k=0.1, T=1500.0)
XFAIL_DRAGGED = ("d/dx = 1: the grain drags the gas of its own cell along (0.64 m/s) and sees a third of the "
                 "slip of undisturbed gas (unresolved coupling samples the gas it disturbs)")


def run(work, name, dt, t_end):
    case = os.path.join(work, name)
    p = dict(d=D, rho=RHO_P, cp=500.0, Tm=3000.0, L=2.7e5, T0=1500.0, x=5.5 * H, y=15.5 * H, z=5.5 * H,
             v=(0.0, -V0, 0.0))
    cc.channel_case(case, "centre", p, channel=dict(lx=11 * H, ly=20 * H, lz=11 * H, h=H, u=0.0), t_end=t_end,
                    fluid_dt=dt, max_co=0.5, dem_dt=1e-7, gas=GAS, extra_lammps=cc.track_commands(10))
    rc = cc.run_solver(case, check=False)
    log = open(os.path.join(case, "log.meltdemFoam")).read()
    ugas = max(float(np.abs(np.asarray(fc.read_internal(os.path.join(case, t, "U")))).max())
               for t in fc.time_dirs(case) if float(t) > 0)
    return case, rc, log, ugas


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-particle-gas-")
    ok = True
    t_end = 4.6e-5
    case, rc, log, ugas = run(work, "fine", 1e-6, t_end)
    ok &= check_absolute(TEST, "fine: exit code", rc, 0, 0)
    ok &= check_absolute(TEST, "fine: no NaN", int(re.search(r"\bnan\b", log, re.I) is None), 1, 0)
    ok &= check_at_most(TEST, "fine: largest gas speed / grain speed (drag cannot push the gas past it)", ugas / V0,
                        1.0)
    led = cc.ledger(case)
    ok &= cc.check_balances(TEST + ".fine", led, momentum=1e-5)
    tr = cc.track(os.path.join(case, "log.lammps"))
    # the same input standalone, uniform gas at rest
    alone = os.path.join(work, "alone")
    os.makedirs(alone)
    text = open(os.path.join(case, "in.particles")).read()
    text = re.sub(r"(fix melt all powder/melt .*)",
                  r"\1 ambient %r %r %r %r %r 0 0 0" % (GAS["T"], GAS["k"], RHO_G, MU_G, GAS["cp"]), text)
    text = text.replace("thermo 10", f"thermo 10\nrun {round(tr[-1, 0] / 1e-7)}")
    open(os.path.join(alone, "in.alone"), "w").write(text)
    subprocess.run([paths.binary("meltdem-lmp"), "-in", "in.alone", "-log", "log.lammps",
                    "-screen", "none"], cwd=alone, check=True)
    ref = cc.track(os.path.join(alone, "log.lammps"))
    print(f"{TEST}: fine: grain speed at {tr[-1, 0]:.3g} s: coupled {-tr[-1, 2]:.6g} m/s, standalone "
          f"{-ref[-1, 2]:.6g} m/s (time {ref[-1, 0]:.3g} s); largest gas speed {ugas:.3g} m/s")
    ok &= check_relative(TEST, "fine: speed lost by the grain, coupled vs standalone in gas at rest [m/s]",
                         V0 + tr[-1, 2], V0 + ref[-1, 2], 0.1, xfail=XFAIL_DRAGGED,
                         miss_within=0.95)

    case, rc, log, ugas = run(work, "coarse", 1e-5, t_end)
    print(f"{TEST}: coarse: largest gas speed {ugas:.3g} m/s")
    ok &= check_absolute(TEST, "coarse: no NaN", int(re.search(r"\bnan\b", log, re.I) is None), 1, 0)
    ok &= check_at_most(TEST, "coarse: largest gas speed / grain speed", ugas / V0, 1.0)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
