#!/usr/bin/env python3
"""The meltdemBalance function object on stock interFoam (no meltdemFoam needed).

The stock damBreak (water column, open atmosphere) runs with build/bin/stock-interFoam and
functions { balance { type meltdemBalance; } } loaded from libmeltdemModels.so; the alpha
solver tolerance is 1e-14 and fields are written with 17 digits. Checks:
  - the function object's metal (water) mass equals sum(alpha rho V) from the written fields and
    cell volumes at every write time (1e-12 relative): its volume integral is right;
  - water mass drift (stored change minus the time-integrated boundary flows) <= 1e-10 relative
    over the run (interFoam's MULES is conservative; the flows through the open atmosphere are
    counted);
  - the momentum balance (change of sum(rho U V) minus the integrated advective, pressure and
    viscous boundary flows and gravity's impulse) closes to 1 % of the exchanged impulse
    (what remains: surface tension's discrete net force and the wall-stress approximation).
usage: mass_drift_interfoam.py [np] [--keep]   (np 2: decomposed run, the sums over ranks)
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


def edit(path, fn):
    with open(path) as f:
        txt = f.read()
    with open(path, "w") as f:
        f.write(fn(txt))


def main():
    args = [a for a in sys.argv[1:] if a != "--keep"]
    nproc = int(args[0]) if args else 1
    test = f"foam.mass_drift_interfoam.np{nproc}"
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="mass_drift_interfoam.")
    case = os.path.join(work, "damBreak")
    shutil.copytree(os.path.join(src, "tests", "foam", "damBreak"), case)
    shutil.copy(os.path.join(case, "0", "alpha.water.orig"), os.path.join(case, "0", "alpha.water"))
    lib = os.path.join(os.path.dirname(paths.bin_dir()), "lib", "libmeltdemModels.so")
    edit(os.path.join(case, "system", "controlDict"),
         lambda t: t.replace("writePrecision  6;", "writePrecision  17;")
         .replace("runTimeModifiable yes;", "runTimeModifiable no;")
         + f'\nlibs ("{lib}");\nfunctions\n{{\n    balance {{ type meltdemBalance; }}\n}}\n')
    edit(os.path.join(case, "system", "fvSolution"),
         lambda t: t.replace("tolerance       1e-8;", "tolerance       1e-14;", 1))
    fc.run(["blockMesh"], case, "log.blockMesh")
    fc.run(["setFields"], case, "log.setFields")
    # OpenFOAM builds whose OSHA1stream fails (Debian trixie's v1912) stop a stock tool with a
    # function object at its first step: they run with the project's digest preloaded
    volumes = ["postProcess", "-func", "writeCellVolumes", "-time", "0"]
    preload = None
    if fc.run(volumes, case, "log.V", check=False) != 0:
        if 'error in IOstream "sha1"' not in open(os.path.join(case, "log.V")).read():
            fc.run(volumes, case, "log.V")  # raises with the log's tail
        preload = os.path.join(os.path.dirname(lib), "libmeltdemDictionaryDigest.so")
        fc.run(volumes, case, "log.V", env={"LD_PRELOAD": preload})
    report(test, "stock OpenFOAM tools ran the function objects (needed the digest preload: this OpenFOAM's "
           "OSHA1stream bug; not asserted)", "preload" if preload else "as is", "as is", "none", True)
    solver = paths.binary("stock-interFoam")
    ok = True
    if nproc > 1:
        fc.run(["decomposePar"], case, "log.decomposePar")
        fc.run(["mpirun", "-np", str(nproc)] + (["-x", f"LD_PRELOAD={preload}"] if preload else [])
               + [solver, "-parallel"], case, "log.solver")
    else:
        fc.run([solver], case, "log.solver", env={"LD_PRELOAD": preload} if preload else None)
    if nproc > 1:
        fc.run(["reconstructPar"], case, "log.reconstructPar")

    bal = np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"),
                        delimiter=",", names=True)
    V = fc.read_internal(os.path.join(case, "0", "V"))
    rho = 1000.0
    worst = 0.0
    for d in fc.time_dirs(case):
        a = fc.read_internal(os.path.join(case, d, "alpha.water"))
        m_files = float(np.sum(a * rho * V))
        i = int(np.argmin(np.abs(bal["time"] - float(d))))
        m_fo = float(bal["metalMass"][i])
        print(f"t = {d}: mass from fields {m_files:.15g}, function object {m_fo:.15g} kg (t {bal['time'][i]:.8g})")
        worst = max(worst, abs(m_fo / m_files - 1.0))
    ok &= check_at_most(test, "function object mass vs sum(alpha rho V) of the written fields, max relative "
                        "difference", worst, 1e-12)
    drift = float(np.max(np.abs(bal["massErrorRel"])))
    print(f"{len(bal) - 1} steps; water through the atmosphere {bal['massIn_cum'][-1]:.3e} kg")
    ok &= check_at_most(test, f"water mass balance error (stored change - integrated flows) / M0, max over "
                        f"{len(bal) - 1} steps", drift, 1e-10)
    mom = float(bal["momentumErrorRel"][-1])
    print("momentum change", bal["momentum_x"][-1], bal["momentum_y"][-1], "error",
          bal["momentumError_x"][-1], bal["momentumError_y"][-1])
    ok &= check_at_most(test, "momentum balance error at t_end / exchanged impulse", mom, 0.01)
    return fc.finish(ok, work, keep, shown=case)


if __name__ == "__main__":
    sys.exit(main())
