#!/usr/bin/env python3
"""foam.evaporation_vapour_jet: meltdemFoam with evaporation `massLoss on; vapourJet on;` on a flat
liquid steel pool at 3300 K (Fuchs2022 parameters, T_v 3000 K) under argon-like gas (1.6 kg/m3) in a
2D box open at the top: the vapour takes its volume as gas, so the gas above the pool streams up.

Checks:
  - the gas leaving through the top in the first step (the patch's flux phi) against the vapour's
    volume, (1/rho_g - 1/rho_m) mdot_v(T0) A (Fuchs2022 eq. 18; the surface on cell faces, where the
    gas side's sum(2 (1 - alpha) |grad alpha| V) is the area exactly), and the same at the end against
    the evaporated mass booked in that step;
  - the metal stays: no metal leaves through the top, none rises more than two cells above the
    initial surface, the metal mass balance with the evaporated mass booked closes;
  - the enthalpy balance (the vapour's enthalpy as gas booked) and the momentum balance close; no
    cell heats above T0;
  - np 2 equals serial; a run resumed at half time ends as the uninterrupted one, bit for bit; in a
    closed box the solver stops before the first step.
usage: evaporation_vapour_jet.py [--keep]
"""
import os
import re
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.loader import load_module
from meltdem.testing.report import check_at_most, check_relative, report

TEST = "foam.evaporation_vapour_jet"
ML = load_module(os.path.join(paths.source_dir(), "tests", "foam", "evaporation_mass_loss",
                              "evaporation_mass_loss.py"))
RHO_M, RHO_G = ML.RHO_M, 1.6
T0 = ML.T0
LX, LY, N = 1e-3, 2e-3, 20
DEPTH = 0.5e-3
DT, STEPS = 2e-7, 100


def build(case, grid=None, nz=1, extra_properties=""):
    """The pool on grid (default N x 2N cells), nz cells deep (foam.amr_evaporation: 3D, refining)."""
    g = grid or fc.Grid2D(LX, LY, N, 2 * N)
    g.block_mesh(case, patches={"top": ("atmosphere", "patch")}, nz=nz)
    alpha = np.tile(np.where(g.y < DEPTH, 1.0, 0.0), nz)
    zg = "type zeroGradient;"
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha,
             {"walls": zg, "atmosphere": "type inletOutlet; inletValue uniform 0; value uniform 0;"})
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(alpha.size, T0),
             {"walls": zg, "atmosphere": f"type inletOutlet; inletValue uniform {T0!r}; value uniform {T0!r};"})
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((alpha.size, 3)),
             {"walls": "type noSlip;",
              "atmosphere": "type pressureInletOutletVelocity; value uniform (0 0 0);"}, vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(alpha.size),
             {"walls": "type fixedFluxPressure; value uniform 0;",
              "atmosphere": "type totalPressure; p0 uniform 0; value uniform 0;"})
    fc.transport(case, RHO_M, 6e-3 / RHO_M, RHO_G, 2.2e-5 / RHO_G, 0.0)
    fc.gravity(case, (0.0, -9.81, 0.0))
    extra = f"""metal {{ Tsolidus 1700; Tliquidus 1710; L 2.7e5; cp 965; k 35.95; }}
gas {{ cp 520; k 0.026; }}
energyControls {{ nCorrectors 50; tolerance 1e-12; }}
evaporation {{ pAmbient {ML.P_AMB!r}; CT {ML.CT!r}; Tboil {ML.TBOIL!r}; hv {ML.HV!r}; cp 965; Th0 663.731;
              CM {ML.CM!r}; massLoss on; vapourJet on; }}
{extra_properties}"""
    fc.meltdem_properties(case, physics={"flow": "on", "energy": "on", "evaporation": "on",
                                         "surfaceTension": "off"}, extra=extra)
    fc.control_dict(case, "meltdemFoam", STEPS * DT, DT, DT, adjustable=False,
                    extra="functions\n{\n    balance { type meltdemBalance; }\n}\n")
    fc.fv_schemes(case, extra_div="    div(rhoCpPhi,T) Gauss vanLeer;\n")
    fc.fv_solution(case, alpha_tolerance=1e-14,
                   extra_solvers='    "T.*" { solver PBiCGStab; preconditioner DILU; '
                                 'tolerance 1e-13; relTol 0; }\n')
    fc.run(["blockMesh"], case, "log.blockMesh")
    return g


def set_control(case, replacements):
    """Replace entries in system/controlDict (each must be there)."""
    path = os.path.join(case, "system", "controlDict")
    txt = open(path).read()
    for old, new in replacements.items():
        if old not in txt:
            raise RuntimeError(f"{old!r} not in {path}")
        txt = txt.replace(old, new)
    open(path, "w").write(txt)


NP2_COLUMNS = (("evaporatedMass_cum", "evaporated mass"),
               ("enthalpyAdvIn_atmosphere", "heat carried out by the jet, last step"))


def np2_against_serial(test, par, bal, tolerances, label=""):
    """The case built at par, split across x and run on 2 ranks: its last balance row's
    NP2_COLUMNS against the serial run's bal, each to its tolerance (foam.amr_evaporation too)."""
    fc.decompose(par, 2, direction=(2, 1, 1))
    rc = fc.run_solver(par, np_=2, log="log.solver", check=False)
    ok = check_at_most(test, f"{label}np 2: solver exit code", rc, 0)
    if rc != 0:
        return False
    bal2 = np.genfromtxt(os.path.join(par, "postProcessing", "balance", "0", "balance.csv"), delimiter=",",
                         names=True)
    for (col, what), tol in zip(NP2_COLUMNS, tolerances):
        ok &= check_relative(test, f"{label}np 2 vs serial: {what}", float(bal2[col][-1]), float(bal[col][-1]), tol)
    return ok


def patch_flux(case, time, patch="atmosphere"):
    """Sum of phi over a patch [m3/s] (positive out of the domain)."""
    txt = open(os.path.join(case, time, "phi")).read()
    block = re.search(patch + r"\s*\{(.*?)\}", txt, re.S).group(1)
    m = re.search(r"value\s+nonuniform\s+List<scalar>\s*\d+\s*\((.*?)\)\s*;", block, re.S)
    if m:
        return float(np.sum(np.array(m.group(1).split(), dtype=float)))
    mesh = os.path.join(case, time, "polyMesh", "boundary")   # written where a refining mesh changed
    if not os.path.exists(mesh):
        mesh = os.path.join(case, "constant", "polyMesh", "boundary")
    faces = int(re.search(patch + r"\s*\{[^}]*nFaces\s+(\d+);", open(mesh).read(), re.S).group(1))
    return float(re.search(r"value\s+uniform\s+(\S+);", block).group(1)) * faces


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="evap_jet.")
    case = os.path.join(work, "pool")
    g = build(case)
    ok, bal = ML.run(case, TEST)
    if bal is None:
        return fc.finish(False, work, keep, shown=case)
    area = LX * g.dz
    expansion = 1.0 / RHO_G - 1.0 / RHO_M
    times = fc.time_dirs(case)
    first, last = times[1], times[-1]
    out1 = patch_flux(case, first)
    ref1 = expansion * float(ML.mass_flux(T0)) * area
    print(f"vapour speed (1/rho_g - 1/rho_m) mdot_v(T0) = {ref1 / area:.4g} m/s")
    ok &= check_relative(TEST, "gas out through the top, first step, vs (1/rho_g - 1/rho_m) mdot_v(T0) A [m3/s]",
                         out1, ref1, 1e-6)
    out_end = patch_flux(case, last)
    evap_last = float(bal["evaporatedMass_cum"][-1] - bal["evaporatedMass_cum"][-2]) / DT
    ok &= check_relative(TEST, "gas out through the top, last step, vs (1/rho_g - 1/rho_m) x the metal "
                         "evaporated in it [m3/s]", out_end, expansion * evap_last, 0.02)
    U = fc.read_internal(os.path.join(case, last, "U")).reshape(2 * N, N, 3)
    print(f"mean vertical gas speed in the top row at the end {np.mean(U[-1, :, 1]):.4g} m/s")

    a1 = fc.read_internal(os.path.join(case, last, "alpha.metal")).reshape(2 * N, N)
    k_surf = int(round(DEPTH / g.dy))
    ok &= check_at_most(TEST, "metal more than two cells above the initial surface, max alpha",
                        float(np.max(a1[k_surf + 2:])), 1e-6)
    # (what leaves is the interface's numerical smear, alpha ~ 1e-8 in the gas, carried off by the jet)
    ok &= check_at_most(TEST, "metal through the open top / M0",
                        abs(float(bal["massIn_cum"][-1])) / float(bal["metalMass"][0]), 1e-9)
    ok &= check_at_most(TEST, "metal mass balance error with evaporation booked, max |error| / M0",
                        float(np.max(np.abs(bal["massErrorRel"]))), 1e-10)
    ok &= check_at_most(TEST, "enthalpy balance error at t_end / heat exchanged (open boundary)",
                        abs(float(bal["enthalpyErrorRelExchanged"][-1])), 1e-6)
    ok &= check_at_most(TEST, "momentum balance error at t_end / exchanged impulse",
                        float(bal["momentumErrorRel"][-1]), 0.01)
    tmax = fc.temperature_range(case)[1]
    # (the gas streams through the cells: the convection scheme's and the solver's round-off remain)
    ok &= check_at_most(TEST, "hottest cell over the run above T0 [K]", tmax - T0, 1e-3)

    # the same on 2 ranks (split across the pool): the vapour's spread crosses the processor faces
    par = os.path.join(work, "pool-np2")
    build(par)
    ok &= np2_against_serial(TEST, par, bal, (1e-8, 1e-8))

    # resumed at half time (the fields written at full precision): the uninterrupted run's end state
    # (vapourDilatation, the volume the written phi carries, is read back)
    halves = [os.path.join(work, name) for name in ("whole", "resumed")]
    for c in halves:
        build(c)
        set_control(c, {"writeInterval 2e-07;": f"writeInterval {STEPS * DT / 2!r};",
                        "writePrecision 12;": "writePrecision 17;"})
    fc.run([fc.solver()], halves[0], "log.solver")
    set_control(halves[1], {f"endTime {STEPS * DT!r};": f"endTime {STEPS * DT / 2!r};"})
    fc.run([fc.solver()], halves[1], "log.solver")
    set_control(halves[1], {f"endTime {STEPS * DT / 2!r};": f"endTime {STEPS * DT!r};",
                            "startFrom startTime;": "startFrom latestTime;"})
    fc.run([fc.solver()], halves[1], "log.resumed")
    end = fc.time_dirs(halves[0])[-1]
    worst = max(float(np.max(np.abs(fc.read_internal(os.path.join(halves[0], end, f))
                                    - fc.read_internal(os.path.join(halves[1], end, f)))))
                for f in ("alpha.metal", "T", "U"))
    ok &= check_at_most(TEST, f"resumed at {STEPS * DT / 2 * 1e6:g} us vs uninterrupted, max |difference| of "
                        "alpha, T [K], U [m/s] at the end", worst, 0.0)

    # a closed box cannot take the vapour's volume: the solver stops before the first step
    closed = os.path.join(work, "closed")
    os.makedirs(closed)
    ML.build(closed)
    props = os.path.join(closed, "constant", "meltdemProperties")
    with open(props) as f:
        txt = f.read()
    with open(props, "w") as f:
        f.write(txt.replace("massLoss on;", "massLoss on; vapourJet on;"))
    rc = fc.run([fc.solver()], closed, "log.solver", check=False)
    log = open(os.path.join(closed, "log.solver")).read()
    stopped = rc is not None and rc > 0 and "FOAM FATAL ERROR" in log and "vapourJet" in log \
        and "Time = " not in log
    ok &= report(TEST, "vapourJet in a closed box: stops before the first step, naming vapourJet",
                 "stopped" if stopped else f"rc {rc}", "FatalError naming the entry", "exact", stopped)
    return fc.finish(ok, work, keep, shown=case)


if __name__ == "__main__":
    sys.exit(main())
