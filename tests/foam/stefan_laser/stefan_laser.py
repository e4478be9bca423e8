#!/usr/bin/env python3
"""Laser melting of a metal slab (conduction only): the enthalpy balance with a heat source.

2D closed box 1 mm x 0.5 mm (50 x 25 cells): metal below y = 0.25 mm (solid at 300 K), gas
above; physics { flow off; energy on; laser on; }: a Gaussian beam (P = 10 W on a 20 um deep slice,
absorptivity 0.5, radius 100 um) shines down from the middle of the top, on for 0.5 ms of the
1 ms run. All walls adiabatic, so every joule the metal stores came from the laser.
Checks (meltdemBalance's balance.csv):
  - absorbed power = absorptivity * P on every lit step (1e-6 relative), 0 after tOff, and the
    laser energy = absorptivity P tOn within one step of beam time (the source is evaluated once
    per step);
  - stored-enthalpy change = time integral of the absorbed power (1e-8 of it);
  - the metal melts under the beam (liquid metal at the end of the heating);
  - metal mass unchanged (flow off).
usage: stefan_laser.py [--keep]
"""
import os
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_at_most, check_relative, report

src = paths.source_dir()

TEST = "foam.stefan_laser"
P, ETA, R = 10.0, 0.5, 100e-6
T_ON, T_END = 0.5e-3, 1.0e-3


def build(case):
    g = fc.Grid2D(1e-3, 0.5e-3, 50, 25, dz=20e-6)
    g.block_mesh(case)
    alpha = fc.alpha_rect(g, -1.0, 2.0, -1.0, 0.25e-3)
    zg = "type zeroGradient;"
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha, {"walls": zg})
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(alpha.size, 300.0), {"walls": zg})
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((alpha.size, 3)), {"walls": "type noSlip;"}, vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(alpha.size), {"walls": zg})
    fc.transport(case, 7430.0, 6e-3 / 7430.0, 7.43, 6e-4 / 7.43, 1.8)
    fc.gravity(case)
    extra = f"""metal {{ Tsolidus 1700; Tliquidus 1710; L 2.7e5; cp 965; k 35.95; }}
gas {{ cp 10; k 0.026; }}
energyControls {{ nCorrectors 50; tolerance 1e-12; }}
laser
{{
    power {P!r}; absorptivity {ETA!r}; radius {R!r}; direction (0 -1 0);
    position (0.5e-3 0.5e-3 10e-6); velocity (0 0 0);
    tOn 0; tOff {T_ON!r};
}}
"""
    fc.meltdem_properties(case, physics={"flow": "off", "energy": "on", "laser": "on", "surfaceTension": "off"},
                          extra=extra)
    fc.control_dict(case, "meltdemFoam", T_END, 5e-6, T_ON, adjustable=False,
                    extra="functions\n{\n    balance { type meltdemBalance; }\n}\n")
    fc.fv_schemes(case, extra_div="    div(rhoCpPhi,T) Gauss upwind;\n")
    fc.fv_solution(case, p_ref_cell=0, extra_solvers='    "T.*" { solver PBiCGStab; preconditioner DILU; '
                                                     'tolerance 1e-13; relTol 0; }\n')
    fc.run(["blockMesh"], case, "log.blockMesh")
    return g


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="stefan_laser.")
    case = os.path.join(work, "slab")
    g = build(case)
    fc.run([fc.solver()], case, "log.solver")
    ok = True
    b = np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"),
                      delimiter=",", names=True)
    t, p, dt = b["time"][1:], b["laserPower"][1:], float(b["deltaT"][1])
    lit = p > 0
    err_on = float(np.max(np.abs(p[lit] / (ETA * P) - 1.0)))
    ok &= check_at_most(TEST, f"absorbed power / (absorptivity P) - 1 on the {lit.sum()} lit steps, max",
                        err_on, 1e-6)
    late = float(np.max(np.abs(p[t > T_ON * (1 + 1e-9)])))
    ok &= check_at_most(TEST, "absorbed power after tOff [W]", late, 0.0)
    # the source is evaluated once per step (at its end time), so the beam time is resolved to a step
    ok &= check_at_most(TEST, f"|lit steps - tOn/dt| ({lit.sum()} vs {T_ON / dt:g})",
                        abs(lit.sum() - T_ON / dt), 1.0)
    e_laser = float(b["laserEnergy_cum"][-1])
    dH = float(b["enthalpy"][-1] - b["enthalpy"][0])
    print(f"laser energy {e_laser:.6g} J (eta P tOn = {ETA * P * T_ON:.6g} J), stored change {dH:.6g} J")
    ok &= check_relative(TEST, "laser energy absorbed [J] vs absorptivity P tOn (within one step of beam time)",
                         e_laser, ETA * P * T_ON, dt / T_ON)
    ok &= check_at_most(TEST, "enthalpy balance error at t_end / energy exchanged",
                        abs(float(b["enthalpyErrorRelExchanged"][-1])), 1e-8)
    f = fc.read_internal(os.path.join(case, fc.time_dirs(case)[1], "liquidFraction"))
    a = fc.read_internal(os.path.join(case, fc.time_dirs(case)[1], "alpha.metal"))
    molten = float(np.sum(a * f) * g.dx * g.dy)
    ok &= report(TEST, "molten metal area at tOff [um2] (> 0)", molten * 1e12, "> 0", "bound", molten > 0)
    ok &= report(TEST, "metal mass change (flow off)", float(np.max(np.abs(b["massErrorRel"]))), 0.0,
                 "1e-15", float(np.max(np.abs(b["massErrorRel"]))) <= 1e-15)
    return fc.finish(ok, work, keep, shown=case)


if __name__ == "__main__":
    sys.exit(main())
