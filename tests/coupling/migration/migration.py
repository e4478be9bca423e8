#!/usr/bin/env python3
"""Grains that change LAMMPS rank during a fluid step: np N equals serial.

The exchange case of the benchmarks (meltdem.case.exchange_box: a closed 1 mm cube of gas at
1500 K, 10^3 cells, 8^3 steel grains of d 20-40 um (from their position) at 300 K that heat and feel
drag but do not melt), the grains shot along +x at 20 m/s with 100 DEM sub-cycles per 1 us fluid
step for 20 steps (400 um: they cross LAMMPS's processor boundaries within the sub-cycles, and the last
rows leave the mesh and are booked as outflow). LAMMPS is split along x only (`processors * 1
1`), the mesh along y (`simple`, 1 N 1), so a grain's LAMMPS rank and the ranks of its cells
differ. With --balance LAMMPS also moves grains between ranks by `fix balance` (by particle
count, every 5 DEM steps). Checks (label coupling mpi):
  - the ledger totals of np N against a serial run (both with the gas solved to round-off),
    step by step, relative to the largest total <= 1e-10 (the heat and impulse a grain took come
    back to the rank that located it);
  - balances as every coupled run (mass 1e-13, energy 1e-6);
  - crossings of the (unbalanced) LAMMPS sub-domain planes during the run > 0 (the test moves
    grains between ranks), and no rank computed the weights of every grain (ranks.csv).

usage: migration.py [--np N] [--balance] [--keep]
"""
import argparse
import csv
import os
import sys
import tempfile

import numpy as np

from meltdem.case import coupled as cc
from meltdem.case import exchange_box as eb
from meltdem.case import foam as fc
from meltdem.testing.report import check_at_least, check_at_most

PER_AXIS, CELLS, STEPS, SPEED = 8, 10, 20, 20.0


def build(case, balance):
    eb.build(case, "overlap", "ballistic", PER_AXIS, CELLS, STEPS)
    path = os.path.join(case, "in.particles")
    with open(path) as f:
        text = f.read()
    text = text.replace("boundary        f f f\n", "boundary        f f f\nprocessors      * 1 1\n")
    text = text.replace(f"timestep        {eb.DT!r}", "timestep        1e-08")
    # diameters from the lattice position (random() draws them per rank and LAMMPS numbers the
    # atoms per rank: either gives other grains other sizes on other rank counts)
    lo, hi = eb.fill(1e-3)
    spacing = (hi - lo) / PER_AXIS
    index = "+".join(f"{m}*floor({c}/{spacing!r})" for m, c in ((7, "x"), (13, "y"), (29, "z")))
    start = text.index("variable        d atom random(")
    end = text.index("\n", start)
    text = text[:start] + f"variable        d atom {eb.D_LO!r}+{eb.D_HI - eb.D_LO!r}*(({index})%101)/100" + text[end:]
    text += f"velocity        all set {SPEED!r} 0 0 units box\n"
    if balance:
        text += "fix             balance all balance 5 1.05 shift x 5 1.05\n"
    with open(path, "w") as f:
        f.write(text)
    # the gas solved to round-off: the decomposed solve then differs from the serial one by
    # round-off too, and the comparison sees the exchange, not the linear solvers' tolerances
    solution = os.path.join(case, "system", "fvSolution")
    with open(solution) as f:
        text = f.read()
    for loose in ("tolerance 1e-8; relTol 0;", "tolerance 1e-9; relTol 0.01;", "tolerance 1e-9; relTol 0;",
                  "tolerance 1e-10; relTol 0;"):
        text = text.replace(loose, "tolerance 1e-30; relTol 0; maxIter 200;")
    with open(solution, "w") as f:
        f.write(text)


def crossings(np_):
    """Grains whose x crosses a plane of LAMMPS's uniform x split during the run (no drag)."""
    lo, hi = eb.fill(1e-3)
    spacing = (hi - lo) / PER_AXIS
    x0 = lo + spacing * (0.4 + np.arange(PER_AXIS))
    x0 = x0[x0 < hi]
    x1 = x0 + SPEED * STEPS * eb.DT
    planes = -1e-4 + 1.2e-3 * np.arange(1, np_) / np_
    return int(sum(np.sum((x0 < p) & (x1 >= p)) for p in planes)) * PER_AXIS ** 2


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--balance", action="store_true")
    ap.add_argument("--keep", action="store_true")
    a = ap.parse_args()
    test = "coupling.migration" + (".balance" if a.balance else "") + f".np{a.np}"
    work = tempfile.mkdtemp(prefix="meltdem-migration-")
    case = os.path.join(work, "case")
    build(case, a.balance)
    cc.decompose(case, a.np, (1, a.np, 1))
    cc.run_solver(case, a.np)
    d = cc.ledger(case)
    ok = cc.check_balances(test, d)
    ok &= check_at_least(test, "grains crossing LAMMPS sub-domain planes during the run", crossings(a.np), 1)
    with open(os.path.join(case, "postProcessing", "particleLedger", "ranks.csv")) as f:
        rows = list(csv.DictReader(f))
    first = min(float(r["time"]) for r in rows)
    grains = int(cc.particles_csv(case)["particles"][0])
    busiest = max(int(r["visitors"]) for r in rows if float(r["time"]) == first) / 2  # two locations a step
    ok &= check_at_most(test, "most grains a rank weighed in step 1 / all grains", busiest / grains, 0.9)
    serial = os.path.join(work, "serial")
    build(serial, False)
    cc.run_solver(serial)
    worst = cc.ledger_totals_difference(d, cc.ledger(serial))
    ok &= check_at_most(test, f"ledger totals np {a.np} vs serial (relative to the largest total)", worst, 1e-10)
    return fc.finish(ok, work, a.keep)


if __name__ == "__main__":
    sys.exit(main())
