#!/usr/bin/python3
"""fix powder/insert: (a) a seed gives the same diameter sequence (by atom ID, IDs follow
the draw order) under mpirun -np 2 as serially, on the tight pour where pending occurs;
(b) the pending queue, counters and random streams survive write_restart/read_restart:
the restarted run resumes with the same vector and inserts the same diameters."""
import os
import sys
import tempfile

import numpy as np

from meltdem.testing.lammps_run import run
from meltdem.testing.report import check_absolute, report
from insert_common import INSERT, OUTPUT, PHYSICS, TIGHT, read_dump, thermo

TEST = "dem.insert.parallel_restart"
N = 2000


def last_frame(d):
    fr = read_dump(os.path.join(d, "dump.ins"))
    return fr[max(fr)]


ok = True
# (a) serial vs two ranks, 1000 steps of the tight pour (about 750 inserted, 1250 pending)
frames = {}
for np_ in (1, 2):
    with tempfile.TemporaryDirectory() as d:
        run(TIGHT + "run 1000\n", np=np_, cwd=d)
        frames[np_] = last_frame(d)
ser = dict(zip(frames[1][:, 0].astype(int), 2 * frames[1][:, 1]))
par = dict(zip(frames[2][:, 0].astype(int), 2 * frames[2][:, 1]))
common = sorted(set(ser) & set(par))
ok &= report(TEST, "particles inserted by step 1000 in both runs (IDs compared)", len(common), ">= 500",
             "bound", len(common) >= 500)
diff = max(abs(ser[i] - par[i]) for i in common)
ok &= check_absolute(TEST, "max |d(np 2) - d(serial)| over common atom IDs", diff, 0.0, 0.0)

# (b) restart in the middle of the pour, while particles are pending
with tempfile.TemporaryDirectory() as d:
    _, out_a = run(TIGHT + "run 600\nwrite_restart pour.restart\nrun 3800\n", cwd=d)
    fa = last_frame(d)
    restarted = ("read_restart pour.restart\nneighbor 0.3e-3 bin\nneigh_modify delay 0 every 1 check yes\n"
                 "comm_modify vel yes\n" + PHYSICS + INSERT + "\n" + OUTPUT + "run 0\nrun 3800\n")
    _, out_b = run(restarted, cwd=d)
    fb = last_frame(d)
ta, tb = thermo(out_a), thermo(out_b)
row_a = ta[ta[:, 0] == 600][0]
row_b = tb[tb[:, 0] == 600][0]
names = ["inserted", "pending", "failed attempts", "inserted mass", "pending mass", "drawn"]
ok &= report(TEST, "pending at the restart step", int(row_a[3]), "> 0", "bound", row_a[3] > 0)
for k, name in enumerate(names):
    ok &= check_absolute(TEST, f"{name} after read_restart - before write_restart", row_b[2 + k] - row_a[2 + k], 0, 0)
ok &= check_absolute(TEST, "max |inserted + pending - N| after restart", np.max(np.abs(tb[:, 2] + tb[:, 3] - N)), 0, 0)
ok &= check_absolute(TEST, "pending at the end of the restarted run", tb[-1, 3], 0, 0)
da = dict(zip(fa[:, 0].astype(int), 2 * fa[:, 1]))
db = dict(zip(fb[:, 0].astype(int), 2 * fb[:, 1]))
ok &= check_absolute(TEST, "atoms at the end, restarted run", len(db), N, 0)
ok &= check_absolute(TEST, "max |d(restarted) - d(continuous)| by atom ID",
                     max(abs(da[i] - db.get(i, np.inf)) for i in da), 0.0, 0.0)
sys.exit(0 if ok else 1)
