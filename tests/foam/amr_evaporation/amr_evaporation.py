#!/usr/bin/env python3
"""foam.amr_evaporation: evaporation's mass loss and vapour jet on a refining mesh.

1. The closed melting dam break of foam.amr_dam_break (3D, refinement at the interface to level 2
   and in liquid metal to level 1, cells split where the front arrives and merged where it left)
   with evaporation `massLoss on`, T_v lowered to 2100 K so that the 2000 K column evaporates
   (about 10 kg/m2/s): metal leaves through the moving, refining surface.
2. The pool of foam.evaporation_vapour_jet (steel at 3300 K under argon-like gas, open top) in 3D
   on a base mesh twice as coarse, refined to the vapour-jet test's cells at the interface, with
   `massLoss on; vapourJet on;`.

Checks, both cases: every mesh change keeps metal and enthalpy to 1e-12 (the remap ledger) and no
cell's T leaves its parents'/children's range; the whole run's mass and enthalpy balances with the
evaporated metal booked (meltdemBalance) <= 1e-10; metal evaporated. Case 1: cells both split and
merged. Case 2: the gas out of the top in the first step against (1/rho_g - 1/rho_m) mdot_v(T0) A,
as on the uniform mesh (the surface on faces of the finest cells); on 2 ranks the serial run's
evaporated mass to 1e-10 and the jet's heat through the top to 1e-8 (the pressure solver's tolerance).
usage: amr_evaporation.py [--keep]
"""
import os
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.loader import load_module
from meltdem.testing.report import check_at_most, check_relative, report

TEST = "foam.amr_evaporation"
SRC = paths.source_dir()
MD = load_module(os.path.join(SRC, "tests", "foam", "mass_drift", "mass_drift.py"))
AMR = load_module(os.path.join(SRC, "tests", "foam", "amr_dam_break", "amr_dam_break.py"))
ML = load_module(os.path.join(SRC, "tests", "foam", "evaporation_mass_loss", "evaporation_mass_loss.py"))
JET = load_module(os.path.join(SRC, "tests", "foam", "evaporation_vapour_jet", "evaporation_vapour_jet.py"))

DAM_T_END = 0.004
DAM_TBOIL = 2100.0
JET_NZ = 2
JET_REFINEMENT = """refinement
{
    maxLevel        1;
    refineInterval  1;
    nBufferLayers   1;
    criteria { interface { level 1; } }
}
"""


def evaporation_dict(tboil, jet=False):
    return (f"evaporation {{ pAmbient {ML.P_AMB!r}; CT {ML.CT!r}; Tboil {tboil!r}; hv {ML.HV!r}; cp 965; "
            f"Th0 663.731; CM {ML.CM!r}; massLoss on;{' vapourJet on;' if jet else ''} }}\n")


def balances(case, label):
    """meltdemBalance's mass and enthalpy errors with the evaporated metal booked; returns (ok, rows)."""
    bal = np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"),
                        delimiter=",", names=True)
    evaporated = float(bal["evaporatedMass_cum"][-1])
    m = bal["metalMass"]
    print(f"{label}: {len(bal) - 1} steps to t = {bal['time'][-1]:.4g} s; metal {m[0]:.15g} -> {m[-1]:.15g} kg, "
          f"evaporated {evaporated:.6g} kg")
    ok = report(TEST, f"{label}: metal evaporated [kg] (> 0)", evaporated, "> 0", "bound", evaporated > 0)
    ok &= check_at_most(TEST, f"{label}: metal mass balance error with evaporation booked, max |error| / M0",
                        float(np.max(np.abs(bal["massErrorRel"]))), 1e-10)
    ok &= check_at_most(TEST, f"{label}: enthalpy balance error with the evaporated enthalpy booked, "
                        "max |error| / H0", float(np.max(np.abs(bal["enthalpyErrorRel"]))), 1e-10)
    return ok, bal


def dam_break(work):
    case = os.path.join(work, "dam")
    MD.build(case, n=16, nz=AMR.NZ, t_end=DAM_T_END, p_ref_cell=0, extra_physics={"evaporation": "on"},
             extra_properties=AMR.REFINEMENT + evaporation_dict(DAM_TBOIL))
    rc = fc.run([fc.solver()], case, "log.solver", check=False)
    ok = check_at_most(TEST, "dam break: solver exit code", rc, 0)
    if rc != 0:
        return ok
    good, split, merged = AMR.remap_checks(TEST, case, "dam break")
    ok &= good
    ok &= report(TEST, "dam break: mesh changes that split cells (> 0)", split, "> 0", "bound", split > 0)
    ok &= report(TEST, "dam break: mesh changes that merged cells (> 0)", merged, "> 0", "bound", merged > 0)
    ok &= balances(case, "dam break")[0]
    ok &= check_at_most(TEST, "dam break: hottest cell over the run above the column's 2000 K [K] (nothing heats)",
                        fc.temperature_range(case)[1] - MD.T_COLUMN, 1e-3)
    return ok


def build_vapour_jet(case):
    g = fc.Grid2D(JET.LX, JET.LY, JET.N // 2, JET.N)
    JET.build(case, grid=g, nz=JET_NZ, extra_properties=JET_REFINEMENT)
    return g


def vapour_jet_parallel(work, bal):
    """The refining jet pool on 2 ranks, split across the pool, against the serial run's balance rows."""
    par = os.path.join(work, "pool-np2")
    build_vapour_jet(par)
    # (the spread's smoothing sees the neighbours' cells across the processor faces as in serial; the
    # flux through the top carries the pressure solver's tolerance, 1e-9, as on the uniform mesh)
    return JET.np2_against_serial(TEST, par, bal, (1e-10, 1e-8), label="vapour jet: ")


def vapour_jet(work):
    case = os.path.join(work, "pool")
    g = build_vapour_jet(case)
    ok, bal = ML.run(case, TEST)
    if bal is None:
        return ok
    good, split, _ = AMR.remap_checks(TEST, case, "vapour jet")
    ok &= good
    ok &= report(TEST, "vapour jet: mesh changes that split cells (> 0)", split, "> 0", "bound", split > 0)
    ok &= balances(case, "vapour jet")[0]
    # (a mesh change once left phi without the vapour's volume for a step: +460 K)
    ok &= check_at_most(TEST, "vapour jet: hottest cell over the run above T0 [K]",
                        fc.temperature_range(case)[1] - ML.T0, 1e-3)
    area = JET.LX * g.dz * JET_NZ
    ref = (1.0 / JET.RHO_G - 1.0 / JET.RHO_M) * float(ML.mass_flux(ML.T0)) * area
    out = JET.patch_flux(case, fc.time_dirs(case)[1])
    ok &= check_relative(TEST, "vapour jet: gas out through the top, first step, vs (1/rho_g - 1/rho_m) "
                         "mdot_v(T0) A [m3/s]", out, ref, 1e-6)
    ok &= vapour_jet_parallel(work, bal)
    return ok


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="amr_evaporation.")
    ok = vapour_jet(work)
    ok &= dam_break(work)
    return fc.finish(ok, work, keep, shown=work)


if __name__ == "__main__":
    sys.exit(main())
