#!/usr/bin/env python3
"""Codina2019 §2.3: one particle melting in a hot gas channel, through the coupled solver.

Channel 2.1 x 18.2 x 2.1 mm, 0.7 mm cells (3 x 26 x 3), gas rho 1.6115, cp 5210.928, k 100,
T 1500 K flowing at U = (0, -2, 0) m/s (inlet at the top, outlet at the bottom, slip walls).
Particle d = 600 um, rho 8020, cp 48.35, Tm = 1000 K, T0 = 0 K, moving with the gas, placed
at y = 17.6 mm on the channel axis (the gas it cools slows the melt: it takes ~8 ms, not
the 2.1 ms of a particle in gas held at 1500 K, so it starts near the inlet). It heats
(Ranz-Marshall with the local gas), melts, and its metal appears in the VOF field, carried off by
the gas. Gravity off (the Codina2019 particle keeps U = -2 m/s: its momentum 1.814e-6 kg m/s is
m 2 m/s).

Checks (measured / reference / tolerance, label coupling):
  - per-step relative balance errors of the continuum (Codina2019 eq. 2.20, 2.26, 2.36) from the
    ledger: mass <= 1e-13, energy <= 1e-6, momentum <= 1e-7 (Codina2019: 2e-13, 1.5e-5, 1.5e-6);
  - integrated heat: sensible = total heat absorbed - L * melted mass - the heat its melt took
    on beyond cp Tm + L (the last step's surplus with the implicit exchange) vs m cp Tm, latent
    (L * melted mass) vs 0.248611 J, each within 1e-4. L is chosen so that m L = 0.248611 J for
    the particle's exact mass m = rho pi d^3 / 6 = 9.0704e-7 kg (Codina2019 rounds to 9.069e-7);
  - everything melted: the metal mass handed over equals m (1e-12), the continuum holds it;
  - the momentum handed over vs m 2 m/s = 1.814e-6 kg m/s (1e-3: the particle keeps U).
Writes the ledger plot (Codina2019 fig. 2.3-2.14 layout) to the report folder.
usage: thesis_particle.py [--np N] [--model centre|neighbours|overlap] [--keep] [--compare-serial]
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.testing.report import check_at_most, check_relative
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

D, RHO_P, CP_P, TM = 600e-6, 8020.0, 48.35, 1000.0
M_P = RHO_P * np.pi * D**3 / 6
E_LATENT = 0.248611
L = E_LATENT / M_P
T_END = 8.5e-3


def build(case, model, particle_y=17.6e-3, **kw):
    cc.channel_case(case, model, dict(d=D, rho=RHO_P, cp=CP_P, Tm=TM, L=L, T0=0.0, y=particle_y),
                    t_end=T_END, **kw)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--model", default="centre")
    ap.add_argument("--keep", action="store_true")
    ap.add_argument("--compare-serial", action="store_true",
                    help="also run serially and compare the ledger totals (np > 1)")
    a = ap.parse_args()
    test = f"coupling.thesis_particle.{a.model}" + (f".np{a.np}" if a.np > 1 else "")
    work = tempfile.mkdtemp(prefix="meltdem-thesis-particle-")
    case = os.path.join(work, "case")
    d, p = cc.build_and_run(case, lambda c: build(c, a.model), a.np)
    ok = cc.check_balances(test, d, momentum=1e-7)
    melted = np.sum(p["mass_melted"])
    heat = np.sum(p["heat_absorbed"])
    latent = L * melted
    # heat beyond what melted the last remnant goes on with its melt (implicit exchange)
    superheat = np.sum(p["enthalpy_handed_over"]) - melted * (CP_P * TM + L)
    print(f"{test}: heat handed on with the melt beyond m (cp Tm + L): {superheat:.4g} J")
    ok &= check_relative(test, "metal mass handed over vs particle mass [kg]", melted, M_P, 1e-12)
    ok &= check_relative(test, "metal mass in the continuum at the end vs particle mass [kg]",
                         d["mass_continuum"][-1] + d["mass_cumulative_boundary_out"][-1], M_P, 1e-10)
    ok &= check_relative(test, "sensible heat absorbed vs m cp Tm [J]", heat - latent - superheat,
                         M_P * CP_P * TM, 1e-4)
    ok &= check_relative(test, "latent heat absorbed vs thesis E_latent [J]", latent, E_LATENT, 1e-4)
    ok &= check_relative(test, "momentum handed over vs m 2 m/s [kg m/s]",
                         -np.sum(p["momentum_handed_over_y"]), M_P * 2.0, 1e-3)
    t_melt = p["time"][np.nonzero(p["particles"] == 0)[0][0]] if np.any(p["particles"] == 0) else np.nan
    print(f"{test}: particle fully molten at t = {t_melt:.4g} s (standalone ambient: 2.107e-3 s)")
    rep = os.environ.get("MELTDEM_REPORT_DIR")
    if rep:
        os.makedirs(rep, exist_ok=True)
        png = os.path.join(rep, f"{test}.ledger.png")
        subprocess.run(["/usr/bin/python3", os.path.join(paths.source_dir(), "scripts", "plot_ledger.py"),
                        os.path.join(case, "postProcessing", "particleLedger", "ledger.csv"), "-o", png,
                        "-c", "mass", "enthalpy", "mom_y"], check=False)
        shutil.copy(os.path.join(case, "postProcessing", "particleLedger", "ledger.csv"),
                    os.path.join(rep, f"{test}.ledger.csv"))
    if a.compare_serial:
        serial = os.path.join(work, "serial")
        build(serial, a.model)
        cc.run_solver(serial)
        s = cc.ledger(serial)
        worst = cc.ledger_totals_difference(d, s)
        ok &= check_at_most(test, f"ledger totals np {a.np} vs serial (relative to the largest total)", worst, 1e-10)

    return fc.finish(ok, work, a.keep)


if __name__ == "__main__":
    sys.exit(main())
