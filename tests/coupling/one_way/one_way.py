#!/usr/bin/env python3
"""One-way coupling (physics { flow off; particles on; }): a grain in a given hot gas stream.

A 50 um steel grain starts at rest and 300 K in a channel of air flowing at U = (0, -2, 0) m/s
at 1200 K, given by the fields and never solved (no flow solve; the energy equation conducts a
uniform field, which stays uniform). The grain accelerates with the stream and heats. The gas
is given, so the grain must move and heat exactly as in a uniform ambient gas: its velocity and
temperature history equals the standalone run of the same LAMMPS input with fix powder/melt
'ambient' (same gas) to 1e-6 (the coupled run's DEM steps are the fluid step's equal parts,
slightly shorter than the input's), and against the closed forms of a Stokes-like response it
is checked by the dem.melt tests already. The continuum must not feel the grain: its enthalpy and
momentum totals stay what they were to round-off, while the ledger books what the grain took
(heat, drag impulse) as the given gas's (the continuum's external source), so the per-step
continuum and system balances close.

--implicit: heatExchange implicit with flow off is refused with a FatalIOError naming it.
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_most, check_relative

IMPLICIT = "--implicit" in sys.argv
TEST = "coupling.one_way" + (".implicit_refused" if IMPLICIT else "")
GAS = dict(rho=0.29, mu=4.7e-5, cp=1180.0, k=0.075, T=1200.0)  # air at 1200 K
GRAIN = dict(d=50e-6, rho=7800.0, cp=500.0, Tm=1700.0, L=2.7e5, T0=300.0, y=3.5e-3, v=(0.0, 0.0, 0.0))
T_END, DEM_DT = 4e-3, 1e-6


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-one-way-")
    case = os.path.join(work, "case")
    thermo = ("compute pv all property/atom vy\ncompute s all reduce sum c_pv f_melt[1]\n"
              "thermo_style custom step time atoms c_s[1] c_s[2]\nthermo_modify format float %.15g\nthermo 100")
    cc.channel_case(case, "centre", GRAIN, channel=dict(lx=2e-3, ly=4e-3, lz=2e-3, h=0.5e-3, u=-2.0), gas=GAS,
                    t_end=T_END, fluid_dt=1e-4, dem_dt=DEM_DT, extra_lammps=thermo,
                    melt_keywords="coefficient_tolerance 0", physics=dict(flow="off"))
    if IMPLICIT:
        props = os.path.join(case, "constant", "meltdemProperties")
        text = open(props).read().replace("demStepsPerFluidStep auto;", "demStepsPerFluidStep auto;\n"
                                          "    heatExchange implicit;")
        open(props, "w").write(text)
        rc = cc.run_solver(case, check=False)
        out = open(os.path.join(case, "log.meltdemFoam")).read()
        refused = rc != 0 and "FOAM FATAL IO ERROR" in out and "heatExchange implicit" in out \
            and "Traceback" not in out
        print(f"{TEST}: exit {rc}, FatalIOError naming heatExchange implicit: {refused}")
        ok = check_absolute(TEST, "heatExchange implicit with flow off refused by a FatalIOError (1 = yes)",
                            1.0 if refused else 0.0, 1.0, 0.0)
        return fc.finish(ok, work, keep)
    cc.run_solver(case)
    coupled = cc.track(os.path.join(case, "log.lammps"))  # (time, vy, T)

    # the same LAMMPS input standalone, in the uniform given gas ('ambient')
    alone = os.path.join(work, "alone")
    os.makedirs(alone)
    text = open(os.path.join(case, "in.particles")).read()
    text = re.sub(r"(fix melt all powder/melt .*?)( coefficient_tolerance 0)",
                  r"\1 ambient %r %r %r %r %r 0 -2.0 0\2" % (GAS["T"], GAS["k"], GAS["rho"], GAS["mu"], GAS["cp"]),
                  text)
    text += f"\nrun {round(T_END / DEM_DT)}\n"
    open(os.path.join(alone, "in.alone"), "w").write(text)
    subprocess.run([paths.binary("meltdem-lmp"), "-in", "in.alone", "-log", "log.lammps", "-screen", "none"],
                   cwd=alone, check=True)
    standalone = cc.track(os.path.join(alone, "log.lammps"))
    common = np.intersect1d(np.round(coupled[:, 0], 12), np.round(standalone[:, 0], 12))
    pick = lambda h: h[np.isin(np.round(h[:, 0], 12), common)]  # noqa: E731
    c, s = pick(coupled), pick(standalone)
    dv = np.max(np.abs(c[:, 1] - s[:, 1])) / np.max(np.abs(s[:, 1]))
    dT = np.max(np.abs(c[:, 2] - s[:, 2])) / np.max(np.abs(s[:, 2] - GRAIN["T0"]))
    print(f"{TEST}: {len(common)} common rows to t = {common[-1]:.4g} s; grain at the end vy {c[-1, 1]:.6g} m/s "
          f"(standalone {s[-1, 1]:.6g}), T {c[-1, 2]:.6g} K (standalone {s[-1, 2]:.6g})")
    ok = check_at_most(TEST, "velocity history, one-way vs standalone ambient (max difference / max |vy|)", dv, 1e-6)
    ok &= check_at_most(TEST, "temperature history, one-way vs standalone ambient (max difference / max rise)",
                        dT, 1e-6)

    led = cc.ledger(case)
    pc = cc.particles_csv(case)
    heat = float(np.sum(pc["heat_absorbed"]))
    impulse = float(np.sum(pc["drag_impulse_y"]))
    H, P = led["enthalpy_continuum"], led["mom_y_continuum"]
    print(f"{TEST}: heat the grain took {heat:.6g} J, drag impulse y {impulse:.6g} N s; continuum enthalpy "
          f"{H[0]:.12g} -> {H[-1]:.12g} J, y momentum {P[0]:.6g} -> {P[-1]:.6g} kg m/s")
    ok &= check_at_most(TEST, "continuum enthalpy change over the run / total (the gas does not feel the grain)",
                        abs(H[-1] - H[0]) / abs(H[0]), 1e-13)
    ok &= check_at_most(TEST, "continuum y momentum change over the run / total", abs(P[-1] - P[0]) / abs(P[0]),
                        1e-13)
    ok &= check_relative(TEST, "given gas's enthalpy source booked vs heat the grain took [J]",
                         float(np.sum(led["enthalpy_continuum_source"])), heat, 1e-12)
    ok &= check_relative(TEST, "given gas's y momentum source booked vs drag impulse the grain took [N s]",
                         float(np.sum(led["mom_y_continuum_source"])), impulse, 1e-12)
    # no other force: the impulse is the grain's momentum (to the velocity-Verlet half step)
    m = GRAIN["rho"] * np.pi / 6.0 * GRAIN["d"] ** 3
    ok &= check_relative(TEST, "drag impulse booked vs the grain's momentum m vy at the end [N s]", impulse,
                         m * c[-1, 1], 1e-3)
    steps = led[1:]
    for comp, kinds in (("mass", ("continuum", "system")), ("enthalpy", ("continuum", "system")),
                        ("mom_y", ("continuum",))):
        for kind in kinds:
            ok &= check_at_most(TEST, f"worst per-step {comp} {kind} error",
                                np.max(np.abs(steps[f"{comp}_{kind}_error"])), 1e-12)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
