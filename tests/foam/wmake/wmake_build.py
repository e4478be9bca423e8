#!/usr/bin/env python3
"""foam-src/Allwmake: the OpenFOAM targets (libmeltdemModels, libmeltdemCoupling, meltdemFoam)
built with wmake against a sourced OpenFOAM v1912 (the unpacked source package's etc/bashrc,
Debian's libraries), as an OpenFOAM user builds them, from a copy of foam-src into scratch
$FOAM_USER_LIBBIN / $FOAM_USER_APPBIN; then the ded-stream CI case (coupled: LAMMPS grains,
laser, melting) run with the wmake meltdemFoam and with the CMake one.

Checks (measured | reference | tolerance):
- Allwmake exits 0 and leaves meltdemFoam and both libraries (1 = yes);
- the wmake meltdemFoam loads the wmake libraries, not the CMake build's (1 = yes, ldd);
- the wmake run's ledger (every quantity of every step; not the balance-error columns, which are
  round-off) equals the CMake run's to 1e-12 relative to each column's largest value, its fluid
  steps equal, and its laser closure (continuum + grains = eta P on every lit step) within 1e-9.

    wmake_build.py OPENFOAM_SOURCE_DIR CMAKE_BUILD_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem import scene as scenes
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_most

TEST = "foam.wmake"
SRC = paths.source_dir()


def allwmake(work, foam_dir, build_dir):
    shutil.copytree(os.path.join(SRC, "foam-src"), os.path.join(work, "foam-src"),
                    ignore=shutil.ignore_patterns("lnInclude", "linux*"))
    script = f""". {foam_dir}/etc/bashrc || exit 1
set -e
[ -x "$WM_PROJECT_DIR/platforms/tools/$WM_ARCH$WM_COMPILER/wmkdepend" ] || (cd "$WM_DIR/src" && ./Allmake)
export FOAM_USER_LIBBIN={work}/lib FOAM_USER_APPBIN={work}/bin
export MELTDEM_ROOT={SRC} MELTDEM_BUILD_DIR={build_dir} WM_NCOMPPROCS=2
{work}/foam-src/Allwmake
"""
    with open(os.path.join(work, "log.Allwmake"), "w") as log:
        r = subprocess.run(["bash", "-c", script], stdout=log, stderr=subprocess.STDOUT)
    return r.returncode


def main():
    foam_dir, build_dir = (os.path.abspath(a) for a in sys.argv[1:3])
    work = tempfile.mkdtemp(prefix="meltdem-wmake-")
    rc = allwmake(work, foam_dir, build_dir)
    built = [os.path.join(work, p) for p in ("bin/meltdemFoam", "lib/libmeltdemModels.so", "lib/libmeltdemCoupling.so")]
    ok = check_absolute(TEST, f"Allwmake exit status {rc} and meltdemFoam, libmeltdemModels.so, libmeltdemCoupling.so "
                        "built (1 = yes)", float(rc == 0 and all(map(os.path.exists, built))), 1.0, 0)
    if not ok:
        print(open(os.path.join(work, "log.Allwmake")).read()[-4000:])
        return fc.finish(ok, work)
    env = dict(os.environ, LD_LIBRARY_PATH=os.path.join(work, "lib") + ":" + os.environ.get("LD_LIBRARY_PATH", ""))
    ldd = subprocess.run(["ldd", built[0]], env=env, capture_output=True, text=True).stdout
    mine = all(f"{work}/lib/lib{n}.so" in ldd for n in ("meltdemModels", "meltdemCoupling"))
    ok &= check_absolute(TEST, "the wmake meltdemFoam loads the wmake libmeltdemModels/libmeltdemCoupling (1 = yes)",
                         float(mine), 1.0, 0)

    ded = scenes.module("ded-stream")
    script = os.path.join(SRC, "examples", "ded-stream", "scene.py")
    ledgers = {}
    for name, extra in (("cmake", {}), ("wmake", {"MELTDEM_FOAM_SOLVER": built[0]})):
        case = os.path.join(work, name)
        subprocess.run(["/usr/bin/python3", script, "build", case, "--ci"], check=True, stdout=subprocess.DEVNULL)
        subprocess.run(["/usr/bin/python3", script, "run", case], check=True, stdout=subprocess.DEVNULL,
                       env=dict(env, **extra))
        ledgers[name] = cc.ledger(case)
    a, b = ledgers["cmake"], ledgers["wmake"]
    ok &= check_absolute(TEST, "fluid steps, wmake run vs CMake run", float(len(b)), float(len(a)), 0)
    if len(a) == len(b):
        cols = [c for c in a.dtype.names if not c.endswith("_error")]
        worst = max(float(np.max(np.abs(b[c] - a[c])) / max(float(np.max(np.abs(a[c]))), 1e-300)) for c in cols)
        ok &= check_at_most(TEST, f"worst ledger difference, wmake vs CMake run ({len(cols)} columns, "
                            "relative to each column's largest value)", worst, 1e-12)
    t, dt, cont, part = ded.laser_budget(os.path.join(work, "wmake"))
    lit = t - dt >= -1e-18
    err = np.abs(cont + part - ded.ETA * ded.P_LASER)[lit] / (ded.ETA * ded.P_LASER)
    ok &= check_at_most(TEST, f"wmake run: worst |continuum + grains - eta P| / eta P on {int(lit.sum())} lit steps",
                        float(err.max()), 1e-9)
    return fc.finish(ok, work)


if __name__ == "__main__":
    sys.exit(main())
