#!/usr/bin/env python3
"""Powder inserted during a coupled run (the ledger's feed and pending store).

The Codina2019 §2.3 channel (hot argon flowing down at 2 m/s, 0.7 mm cells) with fix powder/insert
feeding steel grains (d 80-120 um, 300 K, at the gas speed) into a slab under the inlet at
5000 grains/s, no gravity, for 4 ms: grains are drawn, wait in the pending queue until the
next DEM step places them, heat in the gas (its conductivity is Codina2019's artificial 100 W/m/K)
and melt. The ledger must book every drawn grain as feed and the queue as the pending store, so that the whole system
(particles + continuum + pending) closes per step to round-off in mass and energy, and its
feed totals equal what LAMMPS says it drew (fix powder/insert vector: inserted + pending).
"""
import os
import re
import sys
import tempfile

import numpy as np

from meltdem.testing.report import check_at_least, check_at_most, check_relative
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

TEST = "coupling.insertion"
RHO, CP, TM, L = 7900.0, 500.0, 1000.0, 2.7e5
T_END, RATE = 4e-3, 5000.0
# one grain already in the channel (channel_case makes one), far below the feed
M0 = RHO * np.pi * 100e-6**3 / 6
PARTICLE = dict(d=100e-6, rho=RHO, cp=CP, Tm=TM, L=L, T0=300.0, y=10e-3, v=(0.0, -2.0, 0.0))
FEED = f"""region feed block 0.3e-3 1.8e-3 16.0e-3 17.5e-3 0.3e-3 1.8e-3
fix ins all powder/insert 1000 8731 region feed diam uniform 80e-6 120e-6 dens {RHO!r} rate {RATE!r} &
    vel 0 -2 0 temp 300
thermo_style custom step time atoms f_ins[1] f_ins[2] f_ins[4] f_ins[5]
thermo_modify format float %.15g
thermo 50
"""


def drawn_mass(log):
    """(inserted + pending) mass fix powder/insert reports on the last thermo line."""
    last = None
    for line in open(log):
        w = line.split()
        if len(w) == 7 and re.fullmatch(r"\d+", w[0]):
            try:
                last = [float(x) for x in w]
            except ValueError:
                pass
    return last[5] + last[6], int(last[3]), int(last[4])


def pending_mass_now(led):
    return float(led["mass_pending"][-1])


def particle_mass_now(led):
    return float(led["mass_particles"][-1])


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-insertion-")
    case = os.path.join(work, "case")
    cc.channel_case(case, "centre", PARTICLE, t_end=T_END, fluid_dt=5e-5, dem_dt=1e-6, extra_lammps=FEED)
    # the alpha solve to machine precision: the 80 steps' mass errors then sum to round-off
    # (at 1e-14 each step keeps about 3e-14 and their random walk reaches the cumulative bound)
    sol = os.path.join(case, "system", "fvSolution")
    txt = open(sol).read()
    open(sol, "w").write(txt.replace("symGaussSeidel; tolerance 1e-14; relTol 0;\n    }",
                                     "symGaussSeidel; tolerance 1e-17; relTol 0;\n    }", 1))
    cc.run_solver(case)
    led = cc.ledger(case)
    steps = led[1:]
    fed = float(np.sum(led["mass_feed"]))
    drawn, inserted, pending = drawn_mass(os.path.join(case, "log.lammps"))
    print(f"{TEST}: {inserted} grains inserted, {pending} pending at the end; feed booked {fed!r} kg, "
          f"LAMMPS drew {drawn!r} kg; largest pending store {led['mass_pending'].max()!r} kg; "
          f"{int(led['lost_particles'].sum())} grains left through the outlet")
    ok = check_at_least(TEST, "grains inserted during the run", inserted, 0.8 * RATE * T_END)
    ok &= check_relative(TEST, "feed booked vs mass fix powder/insert drew [kg]", fed, drawn, 1e-12)
    ok &= check_at_least(TEST, "steps ending with a non-empty pending store",
                         np.count_nonzero(led["mass_pending"] > 0), 1)
    ok &= check_relative(TEST, "metal handed to the continuum vs drawn + first grain - still in grains or pending [kg]",
                         float(np.sum(led["mass_exchange"])),
                         drawn + M0 - pending_mass_now(led) - particle_mass_now(led), 1e-12)
    ok &= check_at_most(TEST, "worst per-step system mass error", np.max(np.abs(steps["mass_system_error"])), 1e-13)
    ok &= check_at_most(TEST, "worst per-step system energy error",
                        np.max(np.abs(steps["enthalpy_system_error"])), 1e-9)
    ok &= check_at_most(TEST, "cumulative system mass error", abs(led["mass_cumulative_system_error"][-1]), 1e-13)
    ok &= cc.check_balances(TEST, led)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
