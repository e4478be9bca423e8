#!/usr/bin/python3
"""Particle/cell size ratio d/dx = 0.1, 1, 10 for a distribution model.

A particle (d = 600 um, rho 8020, cp 48.35, Tm 1000 K, L 2.7e4 J/kg, from T0 = 900 K as in
coupling.big_particle) is held at the centre of a channel of Codina2019 §2.3 gas (1500 K, k 100,
flowing down at 2 m/s) and melts. It moves with the gas (no slip: Nu = 2), held in place. Cells
dx = d / ratio: 1 x 3 x 1 cells of 6 mm, 3 x 5 x 3 of 0.6 mm, 16 x 24 x 16 of 60 um (the particle
covers 524 cell volumes). Fluid step <= 1e-5 s, Courant 0.25.

Reference: the particle in undisturbed gas (constant 1500 K, Nu = 2, the ODEs of
coupling/particle_melting.h integrated with scipy): time to melt half of it. Unresolved coupling
assumes the cells are large against the particle: the particle samples the cells it cools, so at
d/dx >= 1 it sees colder gas and melts later (booked XFAIL there).

Decided behaviour per model and ratio:
  - every model at every ratio runs; no NaN; the continuum temperature stays in [T0, 1500] K;
    per-step continuum mass / energy errors <= 1e-13 / 1e-6; the metal handed over equals the
    mass the particle lost (1e-12); the heat it took = its enthalpy gain plus the enthalpy its
    melt handed over (1e-9); the fluid step does not collapse (>= 1/2 of the first);
  - centre and neighbours at 10 put the particle's whole heat exchange on 1 (7) cells of 1/524
    (7/524) of its volume: the exchange is a two-body relaxation of the particle and its share of
    those cells, so they approach its temperature and never pass it, and the particle melts as
    fast as they are resupplied (slower than the reference: XFAIL above).
usage: size_ratio.py --model centre|neighbours|overlap [--keep]
"""
import argparse
import math
import os
import re
import sys
import tempfile

import numpy as np

from meltdem.testing.report import check_absolute, check_at_most, check_relative, report
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

D, RHO, CP, TM, L, T0 = 600e-6, 8020.0, 48.35, 1000.0, 2.7e4, 900.0
M = RHO * math.pi / 6 * D**3
U = 2.0
SLIP = 0.0  # the particle moves with the gas
CELLS = {0.1: (1, 3, 1), 1.0: (3, 5, 3), 10.0: (16, 24, 16)}
T_END = {0.1: 2.5e-4, 1.0: 5e-4, 10.0: 4e-4}
STOPS = set()  # (model, ratio) that must stop at once: none since the two-body exchange
XFAIL_SLOW = ("unresolved coupling at d/dx >= 1: the particle samples the cells it cools, not the undisturbed "
              "gas of the reference")


def reference_half_time():
    """Heating + melting to half the mass in undisturbed gas (Ranz-Marshall at the slip, shrinking d)."""
    from scipy.integrate import solve_ivp
    g = cc.GAS
    Pr = g["cp"] * g["mu"] / g["k"]

    def G(d):
        return g["k"] * (2 + 0.6 * math.sqrt(g["rho"] * SLIP * d / g["mu"]) * Pr ** (1 / 3)) * math.pi * d

    t_heat = solve_ivp(lambda t, y: [G(D) * (g["T"] - y[0]) / (M * CP)], (0, 1), [T0],
                       events=lambda t, y: y[0] - TM, rtol=1e-12, atol=1e-9).t_events[0][0]

    def dm(t, y):
        d = (6 * y[0] / (math.pi * RHO)) ** (1 / 3)
        return [-G(d) * (g["T"] - TM) / L]
    half = lambda t, y: y[0] - 0.5 * M  # noqa: E731
    half.terminal = True
    t_melt = solve_ivp(dm, (0, 1), [M], events=half, rtol=1e-12, atol=1e-20).t_events[0][0]
    return t_heat + t_melt


def run_ratio(test, work, model, ratio, t_ref, keep):
    n = CELLS[ratio]
    h = D / ratio
    ch = dict(lx=n[0] * h, ly=n[1] * h, lz=n[2] * h, h=h, u=-U)
    p = dict(d=D, rho=RHO, cp=CP, Tm=TM, L=L, T0=T0, x=ch["lx"] / 2, y=ch["ly"] / 2, z=ch["lz"] / 2, held=True)
    case = os.path.join(work, f"ratio{ratio:g}")
    cc.channel_case(case, model, p, channel=ch, t_end=T_END[ratio], fluid_dt=1e-5, max_co=0.25)
    rc = cc.run_solver(case, check=False)
    log = open(os.path.join(case, "log.meltdemFoam")).read()
    tag = f"d/dx = {ratio:g}"
    ok = check_absolute(test, f"{tag}: no NaN in the output", int(re.search(r"\bnan\b", log, re.I) is None), 1, 0)
    Tr = np.array([[float(a), float(b)] for a, b in re.findall(r"T min/max = (\S+), (\S+)", log)])
    if (model, ratio) in STOPS:
        msg = re.search(r"FOAM FATAL ERROR.*\n(.*)", log)
        text = msg.group(1) if msg else ""
        print(f"{test}: {tag}: {text[:400]}")
        ok &= check_absolute(test, f"{tag}: stops (nonzero exit)", int(rc != 0), 1, 0)
        ok &= check_absolute(test, f"{tag}: fluid steps before the stop", len(Tr), 1, 0)
        ok &= check_absolute(test, f"{tag}: the message names distribution overlap, maxDeltaT, demStepsPerFluidStep",
                             int(all(k in text for k in ("distribution overlap", "maxDeltaT", "demStepsPerFluidStep"))),
                             1, 0)
        return ok
    ok &= check_absolute(test, f"{tag}: exit code", rc, 0, 0)
    pc, led = cc.particles_csv(case), cc.ledger(case)
    ok &= check_at_most(test, f"{tag}: T0 - lowest continuum T [K]", T0 - Tr[:, 0].min(), 0.0)
    ok &= check_at_most(test, f"{tag}: highest continuum T - 1500 K [K]", Tr[:, 1].max() - cc.GAS["T"], 1e-3)
    ok &= cc.check_balances(f"{test}.ratio{ratio:g}", led)
    melted = np.cumsum(pc["mass_melted"])
    ok &= check_absolute(test, f"{tag}: metal handed over vs mass the particle lost [kg] (to 1e-12 m)", melted[-1],
                         M - pc["solid_mass"][-1], 1e-12 * M)
    # the particle's energy: what it took = its enthalpy gain + the enthalpy its melt handed over
    gain = pc["particle_enthalpy"][-1] - M * CP * T0 + np.sum(pc["enthalpy_handed_over"])
    ok &= check_relative(test, f"{tag}: heat taken vs particle enthalpy gain + enthalpy handed over [J]",
                         np.sum(pc["heat_absorbed"]), gain, 1e-9)
    ok &= check_at_most(test, f"{tag}: fluid step collapse: first step / smallest", pc["dt"][0] / pc["dt"].min(), 2.0)
    t = pc["time"]
    i = np.searchsorted(melted, 0.5 * M)
    if i < len(t):
        t0 = t[i - 1] if i > 0 else 0.0
        m0 = melted[i - 1] if i > 0 else 0.0
        t_half = t0 + (0.5 * M - m0) / (melted[i] - m0) * (t[i] - t0)
    else:
        t_half = None  # not half molten by the run's end
    amax = max([float(x) for x in re.findall(r"Max\(alpha.metal\) = (\S+)", log)] or [0])
    half = f"half molten at {t_half:.4g} s" if t_half is not None else f"not half molten by {t[-1]:.4g} s"
    print(f"{test}: {tag}: {half} (reference {t_ref:.4g} s), {len(t)} fluid steps, "
          f"T min {Tr[:, 0].min():.5g} K, max alpha.metal {amax:.3g}, "
          f"momentum error {np.max(np.abs(led['mom_y_continuum_error'][1:])):.2g}")
    xfail = XFAIL_SLOW if ratio >= 1 else None
    if t_half is not None:
        ok &= check_relative(test, f"{tag}: time to melt half the particle vs undisturbed gas [s]", t_half, t_ref,
                             0.02, xfail=xfail, miss_within=5.0)
    else:
        # never half molten: the run's end, a lower bound of that time, booked as a miss
        ok &= report(test, f"{tag}: time to melt half the particle (not reached: the run's end) vs undisturbed gas [s]",
                     float(t[-1]), t_ref, "0.02 relative", False, xfail)
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--model", default="overlap")
    ap.add_argument("--keep", action="store_true")
    a = ap.parse_args()
    test = f"extremes.size_ratio.{a.model}"
    work = tempfile.mkdtemp(prefix="meltdem-size-ratio-")
    t_ref = reference_half_time()
    ok = True
    for ratio in (0.1, 1.0, 10.0):
        ok &= run_ratio(test, work, a.model, ratio, t_ref, a.keep)
    return fc.finish(ok, work, a.keep)


if __name__ == "__main__":
    sys.exit(main())
