#!/usr/bin/env python3
"""Mass and enthalpy balances of meltdemFoam through an open boundary (meltdemBalance).

The stock damBreak (water/air densities; tests/foam/damBreak) with physics { energy on; darcy
on; }: the column starts at 1720 K just above the liquidus (1700..1710 K, L 2.7e5 J/kg), the
floor is held at 1500 K (the metal freezes there), the open atmosphere lets gas in at 1500 K and
out at the cell temperature, so heat leaves by conduction through the floor and by advection
through the atmosphere. Fixed deltaT 1e-3 s, 300 steps; alpha tolerance 1e-14, T 1e-12.
Checks (meltdemBalance's balance.csv):
  - metal mass balance error <= 1e-10 of the initial mass (max over steps);
  - enthalpy balance: (stored change - integrated boundary flows) at t_end <= 1e-6 of the heat
    exchanged, which needs the advective boundary flux of the energy equation (rhoPhi and the
    MULES flux, not the end-of-step phi);
  - the atmosphere really carries heat (|advective heat through it| > 1 % of the exchanged heat).
usage: mass_drift_open.py [--keep]
"""
import os
import shutil
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_at_most, report

src = paths.source_dir()

TEST = "foam.mass_drift_open"


def edit(path, fn):
    with open(path) as f:
        txt = f.read()
    new = fn(txt)
    if new == txt:
        raise RuntimeError(f"edit of {path} changed nothing")
    with open(path, "w") as f:
        f.write(new)


def build(case):
    shutil.copytree(os.path.join(src, "tests", "foam", "damBreak"), case)
    shutil.copy(os.path.join(case, "0", "alpha.water.orig"), os.path.join(case, "0", "alpha.water"))
    edit(os.path.join(case, "system", "controlDict"),
         lambda t: t.replace("endTime         0.2;", "endTime         0.3;")
         .replace("adjustTimeStep  yes;", "adjustTimeStep  no;")
         .replace("runTimeModifiable yes;", "runTimeModifiable no;")
         + "\nfunctions\n{\n    balance { type meltdemBalance; }\n}\n")
    edit(os.path.join(case, "system", "fvSchemes"),
         lambda t: t.replace("div(phirb,alpha) Gauss linear;",
                             "div(phirb,alpha) Gauss linear;\n    div(rhoCpPhi,T) Gauss vanLeer;"))
    edit(os.path.join(case, "system", "fvSolution"),
         lambda t: t.replace("tolerance       1e-8;", "tolerance       1e-14;", 1)
         .replace("    U\n    {", '    "T.*"\n    {\n        solver PBiCGStab; preconditioner DILU; '
                  'tolerance 1e-12; relTol 0;\n    }\n\n    U\n    {', 1))
    fc.dictionary(case, "constant/meltdemProperties", """physics { flow on; energy on; darcy on; }
metal { Tsolidus 1700; Tliquidus 1710; L 2.7e5; cp 965; k 35.95; }
gas { cp 1000; k 0.026; }
darcy { C 1e6; b 1e-3; }
energyControls { nCorrectors 50; tolerance 1e-12; }
""")
    fc.write(case, "0/T", "volScalarField", "T", """dimensions [0 0 0 1 0 0 0];
internalField uniform 1720;
boundaryField
{
    lowerWall { type fixedValue; value uniform 1500; }
    leftWall { type zeroGradient; }
    rightWall { type zeroGradient; }
    atmosphere { type inletOutlet; inletValue uniform 1500; value uniform 1720; }
    defaultFaces { type empty; }
}
""")
    fc.run(["blockMesh"], case, "log.blockMesh")
    fc.run(["setFields"], case, "log.setFields")


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="mass_drift_open.")
    case = os.path.join(work, "damBreak")
    build(case)
    fc.run([fc.solver()], case, "log.solver")
    ok = True
    b = np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"),
                      delimiter=",", names=True)
    n = len(b) - 1
    mass = float(np.max(np.abs(b["massErrorRel"])))
    ok &= check_at_most(TEST, f"metal mass balance error / M0, max over {n} steps", mass, 1e-10)

    dt = b["deltaT"][1:]
    adv = float(np.sum(b["enthalpyAdvIn_atmosphere"][1:] * dt))
    cond = float(np.sum(b["enthalpyCondIn_lowerWall"][1:] * dt))
    relx = float(abs(b["enthalpyErrorRelExchanged"][-1]))
    print(f"{n} steps: heat through the floor {cond:.5g} J, advected through the atmosphere {adv:.5g} J, "
          f"stored change {b['enthalpy'][-1] - b['enthalpy'][0]:.5g} J, balance error "
          f"{b['enthalpyError'][-1]:.3g} J (of H0 {b['enthalpyErrorRel'][-1]:.3g})")
    ok &= check_at_most(TEST, "enthalpy balance error at t_end / heat exchanged (open boundary)", relx, 1e-6)
    share = abs(adv) / (abs(adv) + abs(cond))
    ok &= report(TEST, "share of the heat advected through the atmosphere (> 0.01)", share, "> 0.01",
                 "bound", share > 0.01)
    return fc.finish(ok, work, keep, shown=case)


if __name__ == "__main__":
    sys.exit(main())
