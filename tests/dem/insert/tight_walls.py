#!/usr/bin/python3
"""fix powder/insert: 2000 particles into a tight region bounded by fix wall/gran planes.
Zero overlaps at insertion (particle-particle and particle-wall, from the dump right after
each insertion), inserted + pending = requested at every output, pending drains later."""
import os
import sys
import tempfile

import numpy as np
from scipy.spatial import cKDTree

from meltdem.testing.lammps_run import run
from meltdem.testing.report import check_absolute, check_at_most, report
from insert_common import TIGHT, read_dump, thermo

NP = int(sys.argv[1]) if len(sys.argv) > 1 else 1
TEST = "dem.insert.tight_walls" + (f".np{NP}" if NP > 1 else "")
N = 2000
BOX = (0.0, 0.01, 0.0, 0.01, 0.0, 0.045)

with tempfile.TemporaryDirectory() as d:
    rc, out = run(TIGHT + "run 4400\n", np=NP, cwd=d)
    frames = read_dump(os.path.join(d, "dump.ins"))
t = thermo(out)
steps, atoms, ins, pend, failed, mins, mpend, drawn = t.T

ok = True
# 1) overlaps of the particles new in each frame against everything in that frame
worst_pp, worst_wall, n_pp, n_wall, n_checked = -1.0, -1.0, 0, 0, 0
prev_ids = set()
for step in sorted(frames):
    fr = frames[step]
    ids = fr[:, 0].astype(int)
    new = np.array([i not in prev_ids for i in ids])
    prev_ids = set(ids)
    if not new.any():
        continue
    r, x = fr[:, 1], fr[:, 2:5]
    tree = cKDTree(x)
    for k in np.nonzero(new)[0]:
        n_checked += 1
        for j in tree.query_ball_point(x[k], r[k] + 1.2e-3 / 2):
            if j == k:
                continue
            ov = (r[k] + r[j] - np.linalg.norm(x[k] - x[j])) / r[k]
            worst_pp = max(worst_pp, ov)
            n_pp += ov > 0
        walls = [x[k, 0] - BOX[0], BOX[1] - x[k, 0], x[k, 1] - BOX[2], BOX[3] - x[k, 1],
                 x[k, 2] - BOX[4], BOX[5] - x[k, 2]]
        ov = (r[k] - min(walls)) / r[k]
        worst_wall = max(worst_wall, ov)
        n_wall += ov > 0
ok &= check_absolute(TEST, f"particles checked right after insertion (of {N})", n_checked, N, 0)
ok &= check_absolute(TEST, "particle-particle overlaps at insertion", n_pp, 0, 0)
ok &= check_absolute(TEST, "particle-wall overlaps at insertion", n_wall, 0, 0)
ok &= check_at_most(TEST, "largest (r_i+r_j-dist)/r_i of a new particle (<0: clear)", worst_pp, 0.0)
ok &= check_at_most(TEST, "largest (r-wall distance)/r of a new particle (<0: clear)", worst_wall, 0.0)

# 2) bookkeeping at every output
ok &= check_absolute(TEST, "max |inserted + pending - N| over all outputs", np.max(np.abs(ins + pend - N)), 0, 0)
ok &= check_absolute(TEST, "max |atoms - inserted| over all outputs", np.max(np.abs(atoms - ins)), 0, 0)
mtot = mins + mpend
ok &= check_absolute(TEST, "max relative spread of inserted + pending mass", np.ptp(mtot) / mtot[0], 0, 1e-12)
# 3) the region was tight: pending occurred, placements failed, and it all drained
ok &= report(TEST, "largest pending count (tight region)", int(pend[1:].max()), "> 0", "bound", pend[1:].max() > 0)
ok &= report(TEST, "failed placement attempts", int(failed[-1]), "> 0", "bound", failed[-1] > 0)
ok &= check_absolute(TEST, "pending at the end (drained)", pend[-1], 0, 0)
ok &= check_absolute(TEST, "inserted at the end", ins[-1], N, 0)
ok &= check_absolute(TEST, "atoms at the end (nothing lost)", atoms[-1], N, 0)
sys.exit(0 if ok else 1)
