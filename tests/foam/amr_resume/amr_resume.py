#!/usr/bin/env python3
"""`meltdem run CASE --resume` on a refining mesh: the refined mesh and its refinement history come
back from the write time, and the resumed run continues the one it resumes.

The closed melting dam break of foam.amr_dam_break (3D, refinement{} at the interface and in the
melt) runs to 2 ms in one go (A), and to 1 ms, then resumed with `meltdem run --resume` to 2 ms
(B); fields written every 1 ms at 17 digits.

Checks:
  - B's mesh at 1 ms (as read back) and at 2 ms equals A's: cell count and every cell centre;
  - B's metal mass over its whole run (both parts, meltdemBalance) drifts <= 1e-10 and each of its
    mesh changes conserves metal and enthalpy to 1e-12;
  - B's fields at 2 ms equal A's (alpha, T), bit for bit.
usage: amr_resume.py [--keep]
"""
import glob
import os
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_at_most

sys.path.insert(0, os.path.join(paths.source_dir(), "tests", "foam", "amr_dam_break"))
import amr_dam_break as dam  # noqa: E402

TEST = "foam.amr_resume"


def set_control(case, **entries):
    path = os.path.join(case, "system", "controlDict")
    lines = open(path).read().splitlines()
    for key, val in entries.items():
        lines = [f"{key} {val};" if ln.split() and ln.split()[0] == key else ln for ln in lines]
    open(path, "w").write("\n".join(lines) + "\n")


def read(case, t, name):
    return np.asarray(fc.read_internal(os.path.join(case, t, name)))


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="amr_resume.")
    a, b = os.path.join(work, "A"), os.path.join(work, "B")
    for case, end in ((a, 0.002), (b, 0.001)):
        dam.build(case, t_end=end)
        set_control(case, writeInterval=0.001, writePrecision=17)
        fc.run([fc.solver()], case, "log.solver")
    set_control(b, endTime=0.002)
    env = dict(os.environ, MELTDEM_BIN=os.path.dirname(fc.solver()))
    r = subprocess.run([paths.binary("meltdem"), "run", b, "--resume", "--no-analyse"], env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    print(r.stdout.decode(errors="replace")[-800:])
    ok = r.returncode == 0

    for t in ("0.001", "0.002"):
        ca, cb = read(a, t, "C").reshape(-1, 3), read(b, t, "C").reshape(-1, 3)
        same = ca.shape == cb.shape
        diff = float(np.max(np.abs(ca - cb))) if same else np.inf
        print(f"t = {t} s: cells A {len(ca)}, B {len(cb)}")
        ok &= check_at_most(TEST, f"resumed mesh vs uninterrupted at {t} s: max cell-centre difference [m] "
                            f"(cells {len(ca)} vs {len(cb)})", diff, 0.0)

    bal = sorted(glob.glob(os.path.join(b, "postProcessing", "balance", "*", "balance.csv")))
    m = np.concatenate([np.genfromtxt(f, delimiter=",", names=True)["metalMass"] for f in bal])
    ok &= check_at_most(TEST, "resumed run: metal mass drift over both parts, max |M/M0 - 1|",
                        float(np.max(np.abs(m / m[0] - 1))), 1e-10)
    worst = fc.refinement_ledger(b)[1]
    ok &= check_at_most(TEST, "resumed run: metal and enthalpy across each mesh change, max |after/before - 1|",
                        worst, 1e-12)

    if ok:
        for name in ("alpha.metal", "T"):
            d = float(np.max(np.abs(read(a, "0.002", name) - read(b, "0.002", name))))
            ok &= check_at_most(TEST, f"resumed vs uninterrupted {name} at 2 ms, max difference", d, 0.0)
    return fc.finish(ok, work, keep, shown=work)


if __name__ == "__main__":
    sys.exit(main())
