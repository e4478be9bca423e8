#!/usr/bin/env python3
"""foam.evaporation_mass_loss: meltdemFoam with evaporation's mass loss on (flow, energy, evaporation
`massLoss on`, no laser) on a flat liquid steel pool at 3300 K, above the boiling point of the
Fuchs2022 parameters (T_v 3000 K), in a closed 2D box of gas at the same temperature.

Checks:
  - the first step's evaporated mass against Fuchs2022 eq. (18), mdot_v(T0) = 0.82 p_v(T0) sqrt(C_M/T0),
    times the pool's surface and the step (the surface lies on cell faces, where
    sum(2 alpha |grad alpha| V) is the area exactly): to round-off;
  - the metal mass, enthalpy and momentum balances of meltdemBalance, with what evaporation took out
    booked, over the run (closed box: nothing else leaves);
  - the evaporated metal takes its own enthalpy: no cell heats above T0 (the pool only cools) and the
    heat loss booked is h_v per evaporated kilogram (to the linearisation of the loss in T);
  - the pool's surface recedes: the metal lost matches the mass evaporated.
usage: evaporation_mass_loss.py [--keep]
"""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing.report import check_at_most, check_relative, report

TEST = "foam.evaporation_mass_loss"
RHO_M, RHO_G = 7430.0, 7.43
T0 = 3300.0
P_AMB, CT, TBOIL, HV, CM = 1e5, 5e4, 3000.0, 6.583e6, 1.1095e-3
LX, LY, N = 1e-3, 1e-3, 20
DEPTH = 0.5e-3           # pool depth: on a cell face (N/2 cells)
DT, STEPS = 1e-6, 100


def mass_flux(T):
    """Fuchs2022 eq. (18) mass flux [kg/m2/s], sticking coefficient 1."""
    pv = 0.54 * P_AMB * np.exp(-CT * (1.0 / T - 1.0 / TBOIL))
    return 0.82 * pv * np.sqrt(CM / T)


def build(case):
    g = fc.Grid2D(LX, LY, N, N)
    g.block_mesh(case)
    alpha = np.where(g.y < DEPTH, 1.0, 0.0)
    zg = "type zeroGradient;"
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha, {"walls": zg})
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(alpha.size, T0), {"walls": zg})
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((alpha.size, 3)), {"walls": "type noSlip;"}, vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(alpha.size),
             {"walls": "type fixedFluxPressure; value uniform 0;"})
    fc.transport(case, RHO_M, 6e-3 / RHO_M, RHO_G, 6e-4 / RHO_G, 0.0)
    fc.gravity(case, (0.0, -9.81, 0.0))
    extra = f"""metal {{ Tsolidus 1700; Tliquidus 1710; L 2.7e5; cp 965; k 35.95; }}
gas {{ cp 10; k 0.026; }}
energyControls {{ nCorrectors 50; tolerance 1e-12; }}
evaporation {{ pAmbient {P_AMB!r}; CT {CT!r}; Tboil {TBOIL!r}; hv {HV!r}; cp 965; Th0 663.731; CM {CM!r};
              massLoss on; }}
"""
    fc.meltdem_properties(case, physics={"flow": "on", "energy": "on", "evaporation": "on",
                                         "surfaceTension": "off"}, extra=extra)
    fc.control_dict(case, "meltdemFoam", STEPS * DT, DT, STEPS * DT, adjustable=False,
                    extra="functions\n{\n    balance { type meltdemBalance; }\n}\n")
    fc.fv_schemes(case, extra_div="    div(rhoCpPhi,T) Gauss vanLeer;\n")
    fc.fv_solution(case, p_ref_cell=N * N - 1, alpha_tolerance=1e-14,
                   extra_solvers='    "T.*" { solver PBiCGStab; preconditioner DILU; '
                                 'tolerance 1e-13; relTol 0; }\n')
    fc.run(["blockMesh"], case, "log.blockMesh")
    return g


def run(case, test):
    """The solver in case: (its exit code checked, meltdemBalance's rows or None)."""
    rc = fc.run([fc.solver()], case, "log.solver", check=False)
    ok = check_at_most(test, "solver exit code", rc, 0)
    if rc != 0:
        return ok, None
    return ok, np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"),
                             delimiter=",", names=True)


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="evap_mass.")
    case = os.path.join(work, "pool")
    g = build(case)
    ok, bal = run(case, TEST)
    if bal is None:
        return fc.finish(False, work, keep, shown=case)
    area = LX * g.dz
    first = float(bal["evaporatedMass_cum"][1])
    ref = float(mass_flux(T0)) * area * DT
    print(f"mdot_v({T0:.0f} K) = {mass_flux(T0):.6g} kg/m2/s; surface {area:.4g} m2; step {DT:g} s")
    ok &= check_relative(TEST, "evaporated mass of the first step vs eq. (18) mdot_v(T0) A dt [kg]", first, ref, 1e-9)

    m = bal["metalMass"]
    lost = float(m[0] - m[-1])
    evaporated = float(bal["evaporatedMass_cum"][-1])
    print(f"{len(bal) - 1} steps: metal mass {m[0]:.15g} -> {m[-1]:.15g} kg, evaporated {evaporated:.6g} kg")
    ok &= report(TEST, "metal evaporated over the run [kg] (> 0)", evaporated, "> 0", "bound", evaporated > 0)
    ok &= check_at_most(TEST, f"metal mass balance error with evaporation booked, max |error| / M0 over "
                        f"{len(bal) - 1} steps", float(np.max(np.abs(bal["massErrorRel"]))), 1e-10)
    ok &= check_relative(TEST, "metal lost from the box vs metal evaporated [kg]", lost, evaporated, 1e-8)
    ok &= check_at_most(TEST, "enthalpy balance error with the evaporated enthalpy booked, max |error| / H0",
                        float(np.max(np.abs(bal["enthalpyErrorRel"]))), 1e-10)
    ok &= check_at_most(TEST, "momentum balance error at t_end / exchanged impulse",
                        float(bal["momentumErrorRel"][-1]), 0.01)

    tmin, tmax = fc.temperature_range(case)
    print(f"T over the run: {tmin:.6g} .. {tmax:.10g} K")
    ok &= check_at_most(TEST, "hottest cell over the run above T0 [K] (the pool only cools)", tmax - T0, 1e-6)
    heat = float(bal["evaporationEnergy_cum"][-1])
    ok &= check_relative(TEST, "evaporation heat loss per evaporated kilogram vs h_v [J/kg]",
                         heat / evaporated, HV, 0.02)

    # the surface recedes by the evaporated volume (cells are uniform)
    last = fc.time_dirs(case)[-1]
    a1 = fc.read_internal(os.path.join(case, last, "alpha.metal"))
    recession = DEPTH - float(np.sum(a1)) * g.dx * g.dy / LX
    ok &= check_relative(TEST, "mean surface recession [m] vs evaporated mass / (rho_m A)", recession,
                         evaporated / (RHO_M * area), 1e-6)
    return fc.finish(ok, work, keep, shown=case)


if __name__ == "__main__":
    sys.exit(main())
