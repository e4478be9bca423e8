#!/usr/bin/python3
"""A particle that would melt within one fluid step, and a step longer than the cells can feed.
Coupled meltdemFoam + LAMMPS, Codina2019 §2.3 gas (rho 1.6115, cp 5210.9, k 100) at rest at
1500 K in a closed-off 2.1 x 4.2 x 2.1 mm box of 0.7 mm cells, one particle held at the centre
(distribution centre), T0 = 300 K.

Over a fluid step the particle and its share of the cells exchange heat as two bodies
(coupling/particle_melting.h heat_melt_step_two_body): neither passes the other, whatever the
step, so every case runs with the continuum temperature bounded and the balances closed.
  one_step: d = 200 um, rho 8020, cp 48.35, Tm 1000 K, L 2.7409e5 J/kg: in unbounded 1500 K gas it
            would heat (tau = 13 us) and melt (d^2 law, 0.22 ms) within the first 0.5 ms step, but
            its 0.7 mm cell holds C = 2.9e-6 J/K, 1.4e-3 J above Tm, a seventh of the 1e-2 J it
            needs: step 1 takes at most C (1500 K - T0); then the particle melts as conduction
            refills the cell. Checks: heat of step 1 <= C (1500 - T0); heat taken = enthalpy gain +
            enthalpy handed over (1e-10); T in [T0, 1500] K; balances closed.
  melt_pool: the same particle into liquid metal at 2000 K (k 30), whose cells hold the heat:
            melts within the first step (0.39 ms), heat m (cp (Tm - T0) + L) to 1e-10, T in
            [300, 2000] K, balances closed.
  pool_fine: the same in 20 um cells (d/dx = 10, distribution overlap), 0.5 ms steps: runs, T in
            [300, 2000] K, the metal handed over equals the mass lost, balances closed; with
            maxDeltaT 1e-5 s (pool_fine_knob) the same.
  overdraw: d = 600 um, cp 500, Tm 3000 K (no melting): m cp = 4.5e-4 J/K against a cell of
            C = rho cp h^3 = 2.9e-6 J/K; with the gas frozen over a 0.5 ms step it would take
            0.19 J, 40x what the cell holds above 300 K (the explicit exchange drove the cell to
            -151 K). Now: runs; the cell never falls below the particle; the particle never
            passes the gas; balances closed.
  knob:     the same with maxDeltaT = C / G / 2 (G = 2 k pi d): the same, at the short step.
"""
import math
import os
import re
import sys
import tempfile

import numpy as np

from meltdem.testing.report import check_absolute, check_at_least, check_at_most, check_relative
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

T = "extremes.melt_one_step"
GAS = cc.GAS
H = 0.7e-3
CHANNEL = dict(lx=3 * H, ly=6 * H, lz=3 * H, h=H, u=0.0)
T0 = 300.0


def particle(d, cp, Tm, L=2.7409e5):
    return dict(d=d, rho=8020.0, cp=cp, Tm=Tm, L=L, T0=T0, y=3 * H + H / 2, held=True)


def run(work, name, p, dt, t_end, floor=None, channel=CHANNEL, model="centre"):
    case = os.path.join(work, name)
    cc.channel_case(case, model, p, channel=channel, t_end=t_end, fluid_dt=dt, max_co=0.5, floor=floor)
    rc = cc.run_solver(case, check=False)
    log = open(os.path.join(case, "log.meltdemFoam")).read()
    Tr = np.array([[float(a), float(b)] for a, b in re.findall(r"T min/max = (\S+), (\S+)", log)])
    return case, rc, log, Tr


def no_nan(log):
    return int(re.search(r"\bnan\b", log, re.IGNORECASE) is None)


def main():
    ok = True
    work = tempfile.mkdtemp(prefix="meltdem-melt-one-step-")
    keep = "--keep" in sys.argv

    # one_step: would melt within the first fluid step in unbounded gas; its cell cannot feed that
    p = particle(200e-6, 48.35, 1000.0)
    m = p["rho"] * math.pi / 6 * p["d"] ** 3
    G = 2 * GAS["k"] * math.pi * p["d"]
    t_melt = (m * p["cp"] / G * math.log((GAS["T"] - T0) / (GAS["T"] - p["Tm"]))
              + p["rho"] * p["L"] * p["d"] ** 2 / (4 * 2 * GAS["k"] * (GAS["T"] - p["Tm"])))
    case, rc, log, Tr = run(work, "one_step", p, 1e-3, 2e-3)
    pc, led = cc.particles_csv(case), cc.ledger(case)
    print(f"{T}: one_step: analytic heating + melting time {t_melt:.3g} s at 1500 K, first fluid step "
          f"{pc['dt'][0]:.3g} s")
    ok &= check_absolute(T, "one_step: exit code", rc, 0, 0)
    ok &= check_absolute(T, "one_step: no NaN in the output", no_nan(log), 1, 0)
    C = GAS["rho"] * GAS["cp"] * H ** 3
    ok &= check_at_most(T, "one_step: heat taken in step 1 [J] vs what its cell holds above T0, C (1500 K - T0)",
                        pc["heat_absorbed"][0], C * (GAS["T"] - T0))
    gain = pc["particle_enthalpy"][-1] - m * p["cp"] * T0 + np.sum(pc["enthalpy_handed_over"])
    ok &= check_relative(T, "one_step: heat taken vs particle enthalpy gain + enthalpy handed over [J]",
                         np.sum(pc["heat_absorbed"]), gain, 1e-10)
    ok &= check_at_most(T, "one_step: T0 - lowest continuum T [K] (bounded below)", T0 - Tr[:, 0].min(), 0.0)
    ok &= check_at_most(T, "one_step: highest continuum T - 1500 K [K] (bounded above)", Tr[:, 1].max() - GAS["T"],
                        1e-6)
    ok &= cc.check_balances(T + ".one_step", led)

    # melt_pool: the same cold particle dropped into liquid metal at 2000 K (the lower half of the
    # box; the metal the melt displaces leaves through the open bottom, booked as boundary flow)
    p = particle(200e-6, 48.35, 1000.0)
    G = 2 * 30.0 * math.pi * p["d"]  # metal k = 30 (meltdem.case.coupled), Nu = 2
    t_melt = (m * p["cp"] / G * math.log((2000.0 - T0) / (2000.0 - p["Tm"]))
              + p["rho"] * p["L"] * p["d"] ** 2 / (4 * 2 * 30.0 * (2000.0 - p["Tm"])))
    p["y"] = 1.5 * H
    case, rc, log, Tr = run(work, "melt_pool", p, 1e-3, 2e-3, floor=(3 * H, 2000.0))
    pc, led = cc.particles_csv(case), cc.ledger(case)
    ok &= check_absolute(T, "melt_pool: exit code", rc, 0, 0)
    ok &= check_absolute(T, "melt_pool: no NaN in the output", no_nan(log), 1, 0)
    ok &= check_at_most(T, "melt_pool: analytic melting time in 2000 K melt / first fluid step", t_melt / pc["dt"][0],
                        1.0)
    ok &= check_relative(T, "melt_pool: mass melted in the first step [kg]", pc["mass_melted"][0], m, 1e-12)
    ok &= check_relative(T, "melt_pool: heat taken in step 1 vs m (cp (Tm - T0) + L) [J]", pc["heat_absorbed"][0],
                         m * (p["cp"] * (p["Tm"] - T0) + p["L"]), 1e-10)
    ok &= check_at_most(T, "melt_pool: T0 - lowest continuum T [K]", T0 - Tr[:, 0].min(), 0.0)
    ok &= check_at_most(T, "melt_pool: highest continuum T - 2000 K [K]", Tr[:, 1].max() - 2000.0, 1e-3)
    ok &= cc.check_balances(T + ".melt_pool", led)

    # pool_fine: the same in 20 um cells (d/dx = 10, overlap) at 0.5 ms steps and at maxDeltaT 1e-5 s:
    # bounded and closed
    hf = 20e-6
    fine = dict(lx=15 * hf, ly=30 * hf, lz=15 * hf, h=hf, u=0.0)
    p = dict(particle(200e-6, 48.35, 1000.0), x=7.5 * hf, y=7.5 * hf, z=7.5 * hf)
    case, rc, log, Tr = run(work, "pool_fine", p, 1e-3, 2e-3, floor=(15 * hf, 2000.0), channel=fine, model="overlap")
    pc, led = cc.particles_csv(case), cc.ledger(case)
    print(f"{T}: pool_fine: {len(Tr)} steps, {1 - pc['solid_mass'][-1] / m:.3f} molten by 2 ms")
    ok &= check_absolute(T, "pool_fine: exit code", rc, 0, 0)
    ok &= check_absolute(T, "pool_fine: no NaN in the output", no_nan(log), 1, 0)
    ok &= check_at_most(T, "pool_fine: T0 - lowest continuum T [K]", T0 - Tr[:, 0].min(), 0.0)
    ok &= check_at_most(T, "pool_fine: highest continuum T - 2000 K [K]", Tr[:, 1].max() - 2000.0, 1e-3)
    ok &= check_relative(T, "pool_fine: metal handed over vs mass lost [kg]", np.sum(pc["mass_melted"]),
                         m - pc["solid_mass"][-1], 1e-12)
    ok &= cc.check_balances(T + ".pool_fine", led)
    case, rc, log, Tr = run(work, "pool_fine_knob", p, 1e-5, 5e-4, floor=(15 * hf, 2000.0), channel=fine,
                            model="overlap")
    pc, led = cc.particles_csv(case), cc.ledger(case)
    print(f"{T}: pool_fine_knob: {len(Tr)} steps, {1 - pc['solid_mass'][-1] / m:.3f} molten by 0.5 ms, "
          f"T min/max {Tr[:, 0].min():.5g} / {Tr[:, 1].max():.6g} K")
    ok &= check_absolute(T, "pool_fine_knob: exit code", rc, 0, 0)
    ok &= check_at_most(T, "pool_fine_knob: T0 - lowest continuum T [K]", T0 - Tr[:, 0].min(), 0.0)
    ok &= check_at_most(T, "pool_fine_knob: highest continuum T - 2000 K [K]", Tr[:, 1].max() - 2000.0, 1e-3)
    ok &= check_relative(T, "pool_fine_knob: metal handed over vs mass lost [kg]", np.sum(pc["mass_melted"]),
                         m - pc["solid_mass"][-1], 1e-12)
    ok &= cc.check_balances(T + ".pool_fine_knob", led)

    # overdraw: the cold particle takes more than the cell holds -> stop after step 1
    p = particle(600e-6, 500.0, 3000.0)
    C = GAS["rho"] * GAS["cp"] * H ** 3
    G = 2 * GAS["k"] * math.pi * p["d"]
    case, rc, log, Tr = run(work, "overdraw", p, 1e-3, 2e-3)
    pc, led = cc.particles_csv(case), cc.ledger(case)
    mp = p["rho"] * math.pi / 6 * p["d"] ** 3
    Tp = pc["particle_enthalpy"] / (mp * p["cp"])
    print(f"{T}: overdraw: {len(Tr)} fluid steps of 0.5 ms (the explicit limit C / G = {C / G:.3g} s); particle "
          f"{T0:g} -> {Tp[-1]:.5g} K; continuum T min/max {Tr[:, 0].min():.5g} / {Tr[:, 1].max():.6g} K")
    ok &= check_absolute(T, "overdraw: exit code (the bound guard stops a run whose cells overshoot)", rc, 0, 0)
    ok &= check_absolute(T, "overdraw: no NaN in the output", no_nan(log), 1, 0)
    ok &= check_at_most(T, "overdraw: T0 - lowest continuum T [K] (no cell passes the particle)",
                        T0 - Tr[:, 0].min(), 0.0)
    ok &= check_at_most(T, "overdraw: highest particle T - 1500 K [K] (the particle never passes the gas)",
                        Tp.max() - GAS["T"], 0.0)
    ok &= check_at_least(T, "overdraw: fluid step / explicit exchange limit C / G", pc["dt"].min() / (C / G), 10.0)
    ok &= cc.check_balances(T + ".overdraw", led)

    # knob: maxDeltaT = C / G / 2 as the message asks: bounded and closed
    case, rc, log, Tr = run(work, "knob", p, 0.5 * C / G, 2e-4)
    led = cc.ledger(case)
    pc = cc.particles_csv(case)
    print(f"{T}: knob: {len(Tr)} fluid steps of <= {0.5 * C / G:.3g} s; particle heat taken "
          f"{np.sum(pc['heat_absorbed']):.4g} J; T min/max {Tr[:, 0].min():.5g} / {Tr[:, 1].max():.6g} K")
    ok &= check_absolute(T, "knob: exit code", rc, 0, 0)
    ok &= check_absolute(T, "knob: no NaN in the output", no_nan(log), 1, 0)
    ok &= check_at_most(T, "knob: T0 - lowest continuum T [K] (bounded below)", T0 - Tr[:, 0].min(), 0.0)
    ok &= check_at_most(T, "knob: highest continuum T - 1500 K [K]", Tr[:, 1].max() - GAS["T"], 1e-6)
    ok &= cc.check_balances(T + ".knob", led)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
