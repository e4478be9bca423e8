#!/usr/bin/env python3
"""A closed melting dam break on a refining mesh: metal mass and enthalpy through every refine
and unrefine.

Closed 3D box 4 x 4 x 0.5 mm (16 x 16 x 2 cells of 0.25 mm), gravity: a liquid steel column
(2000 K, 1 mm x 2 mm) collapses onto a solid steel floor (1 mm, 1600 K, bottom wall held at
1600 K) in gas at 1600 K; flow, energy (latent heat 1700..1710 K) and the Darcy sink on, as in
foam.mass_drift. constant/meltdemProperties refinement{} asks for level 2 (62.5 um) at the
interface and level 1 in mushy and liquid metal, so cells are split where the front arrives and
merged where it has left.

Checks:
  - every mesh change conserves metal mass and enthalpy: the largest |after/before - 1| of each
    change in postProcessing/refinement (meltdemFoam's remap ledger) <= 1e-12;
  - no cell's T leaves the range of the cells it came from (cells outside: 0);
  - the run both refines and unrefines (cells split and cells merged);
  - every mesh change carries momentum: max |after - before| / |before| <= 1e-12;
  - the whole run's balances (meltdemBalance, closed box): metal mass drift and enthalpy error
    relative to H0 <= 1e-10, as foam.mass_drift on a fixed mesh; momentum at the end <= 5e-3 of
    the exchanged impulse;
  - it is a dam break: the metal front above the floor passes 2 mm.
The same case decomposed in two (np 2, to 3 ms) is held to the same conservation checks.
usage: amr_dam_break.py [--keep]
"""
import glob
import os
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_at_most, report

sys.path.insert(0, os.path.join(paths.source_dir(), "tests", "foam", "mass_drift"))
import mass_drift  # noqa: E402

TEST = "foam.amr_dam_break"
T_END = 0.008
T_END_PARALLEL = 0.003
NZ = 2

REFINEMENT = """refinement
{
    maxLevel        2;
    refineInterval  2;
    nBufferLayers   1;
    criteria
    {
        interface { level 2; }
        meltPool  { level 1; }
    }
}
"""


def build(case, n=16, t_end=T_END):
    mass_drift.build(case, n=n, nz=NZ, t_end=t_end, extra_properties=REFINEMENT, p_ref_cell=0,
                     extra_functions="    centres { type writeCellCentres; libs (fieldFunctionObjects); "
                                     "writeControl writeTime; }\n")


def remap_checks(test, case, label):
    """The remap ledger's checks of one run (postProcessing/refinement), reported under test;
    returns (ok, mesh changes that split cells, mesh changes that merged cells)."""
    ok = True
    ref = np.genfromtxt(glob.glob(os.path.join(case, "postProcessing", "refinement", "*",
                                               "refinement.csv"))[0], delimiter=",", names=True)
    ref = np.atleast_1d(ref)
    split = int(np.sum(ref["cellsAfter"] > ref["cellsBefore"]))
    merged = int(np.sum(ref["cellsAfter"] < ref["cellsBefore"]))
    print(f"{label}: {len(ref)} mesh changes: cells {int(ref['cellsBefore'][0])} -> "
          f"{int(ref['cellsAfter'][-1])}, most {int(np.max(ref['cellsAfter']))}; {split} changes with more "
          f"cells, {merged} with fewer; finest level {int(np.max(ref['finestLevel']))}")
    mass_remap = float(np.max(np.abs(ref["metalAfter"] / ref["metalBefore"] - 1)))
    h_remap = float(np.max(np.abs(ref["enthalpyAfter"] / ref["enthalpyBefore"] - 1)))
    # momentum: each component's change against the momentum's magnitude before the change
    before = np.sqrt(sum(ref[f"momentum{c}Before"] ** 2 for c in "xyz"))
    change = np.stack([ref[f"momentum{c}After"] - ref[f"momentum{c}Before"] for c in "xyz"])
    p_remap = float(np.max(np.abs(change) / np.maximum(before, 1e-300)))
    lost = float(np.max(np.abs(np.concatenate([ref["metalLost"], ref["enthalpyLost"]]))))
    outside = int(np.sum(ref["TOutsideRange"]))
    ok &= check_at_most(test, f"{label}: metal volume change across each of {len(ref)} refine/unrefine steps, "
                        "max |after/before - 1|", mass_remap, 1e-12)
    ok &= check_at_most(test, f"{label}: enthalpy change across each refine/unrefine step, "
                        "max |after/before - 1|", h_remap, 1e-12)
    ok &= check_at_most(test, f"{label}: momentum change across each refine/unrefine step, "
                        "max |after - before| / |before|", p_remap, 1e-12)
    ok &= check_at_most(test, f"{label}: content no new cell took (metal, enthalpy)", lost, 0.0)
    ok &= check_at_most(test, f"{label}: cells whose T left the range of the cells they came from",
                        outside, 0)
    return ok, split, merged


def conservation(case, label):
    """The remap ledger's and the balance's checks of one run; returns ok."""
    ok, split, merged = remap_checks(TEST, case, label)
    ok &= report(TEST, f"{label}: mesh changes that split cells (> 0)", split, "> 0", "bound", split > 0)
    ok &= report(TEST, f"{label}: mesh changes that merged cells (> 0)", merged, "> 0", "bound", merged > 0)

    bal = np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"),
                        delimiter=",", names=True)
    m = bal["metalMass"]
    drift = float(np.max(np.abs(m / m[0] - 1.0)))
    drift_h = float(np.max(np.abs(bal["enthalpyErrorRel"])))
    print(f"{label}: {len(bal) - 1} steps to t = {bal['time'][-1]:.4g} s; metal mass {m[0]:.17g} -> "
          f"{m[-1]:.17g} kg")
    ok &= check_at_most(TEST, f"{label}: metal mass drift of the refining run, max |M/M0 - 1| over steps",
                        drift, 1e-10)
    ok &= check_at_most(TEST, f"{label}: enthalpy balance error of the refining run, max over steps, "
                        "relative to H0", drift_h, 1e-10)
    # the Darcy sink booked (meltdemFoam's physicsForce); on the refining mesh the PISO velocity
    # correction leaves about 1e-3 of the exchanged impulse (2e-4 on the uniform meshes)
    ok &= check_at_most(TEST, f"{label}: momentum balance error of the refining run at the end / exchanged impulse",
                        float(bal["momentumErrorRel"][-1]), 5e-3)
    return ok


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="amr_dam_break.")
    case = os.path.join(work, "dam")
    build(case)
    fc.run([fc.solver()], case, "log.solver")
    ok = conservation(case, "serial")

    last = fc.time_dirs(case)[-1]
    a1 = fc.read_internal(os.path.join(case, last, "alpha.metal"))
    C = np.asarray(fc.read_internal(os.path.join(case, last, "C"))).reshape(-1, 3)
    band = (C[:, 1] > 1e-3) & (C[:, 1] < 1.5e-3) & (a1 > 0.5)
    spread = float(np.max(np.where(band, C[:, 0], 0.0)))
    ok &= report(TEST, "the column collapses: metal front above the floor [mm] (> 2 mm)", spread * 1e3,
                 "> 2", "bound", spread > 2e-3)

    par = os.path.join(work, "dam_np2")
    build(par, t_end=T_END_PARALLEL)
    fc.dictionary(par, "system/decomposeParDict", "numberOfSubdomains 2;\nmethod simple;\ncoeffs { n (2 1 1); }\n")
    fc.run(["decomposePar"], par, "log.decomposePar")
    fc.run(["mpirun", "-np", "2", "--oversubscribe", fc.solver(), "-parallel"], par, "log.solver",
           env={"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"})
    ok &= conservation(par, "np 2")
    return fc.finish(ok, work, keep, shown=work)


if __name__ == "__main__":
    sys.exit(main())
