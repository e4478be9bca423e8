#!/usr/bin/python3
"""LAMMPS inputs a new user got wrong, which crashed, hung or ran wrongly, on N ranks:

- stop with one LAMMPS ERROR line that names the problem (no C++ backtrace, exit code 1, not
  a signal, no MPI_Abort on N ranks): a Poisson ratio outside (-1, 0.5] in pair
  granular/powder, and in stock pair granular read by fix powder/dt; fix dt/reset together
  with fix powder/dt; fix powder/checkpoint 0 with a folder, N > 0 with NULL;
- run correctly: a fix powder/insert region 'block INF INF INF INF z1 z2' in a p p f box
  (it hung in Domain::remap) inserts all its grains within the time limit; a region wider
  than the periodic box inserts no overlapping grains (it made 136 overlaps, the largest
  1.75 R): compute powder/overlap's count and largest overlap are 0.

usage: bad_input.py NP"""
import signal
import sys

from meltdem.testing.lammps_run import run
from meltdem.testing.report import check_absolute, check_at_most

NP = int(sys.argv[1]) if len(sys.argv) > 1 else 1
TEST = "dem.bad_input" + (f".np{NP}" if NP > 1 else "")
TIMEOUT = 120

BOX = """units si
atom_style sphere
comm_modify vel yes
boundary p p f
region box block 0 3e-4 0 3e-4 0 1e-3
create_box 1 box
neighbor 1e-5 bin
"""
PAIR = ("pair_style granular/powder 5e-5\n"
        "pair_coeff * * hertz/material 2e11 0.5 {nu} damping tsuji tangential mindlin NULL 1.0 0.5\n")
TWO = """create_atoms 1 single 1.5e-4 1.5e-4 5e-4
create_atoms 1 single 1.79e-4 1.5e-4 5e-4
set atom * diameter 3e-5
set atom * density 7900
fix nve all nve/sphere
timestep 1e-9
"""
OVERLAP = "compute ov all powder/overlap threshold 0.001\nthermo_style custom step atoms c_ov[1] c_ov[2] c_ov[3]\n"

ERRORS = [
    ("Poisson ratio 0.7 in pair granular/powder", BOX + PAIR.format(nu=0.7) + TWO + "run 10\n",
     ["ERROR", "Poisson's ratio 0.7", "(-1,0.5]"]),
    ("Poisson ratio 0.7 in stock pair granular, read by fix powder/dt",
     BOX + PAIR.format(nu=0.7).replace("granular/powder 5e-5", "granular") + TWO
     + "fix dt all powder/dt steps 20\nrun 10\n",
     ["ERROR", "Fix powder/dt", "Poisson ratio", "nu 0.7"]),
    ("fix dt/reset together with fix powder/dt", BOX + PAIR.format(nu=0.3) + TWO
     + "fix dt all powder/dt steps 20\nfix reset all dt/reset 1 NULL 1e-9 1e-12\nrun 10\n",
     ["ERROR", "both set the time step"]),
    ("fix powder/checkpoint 0 with a folder (it wrote nothing, silently)", BOX + PAIR.format(nu=0.3) + TWO
     + "fix cp all powder/checkpoint 0 somedir\nrun 10\n", ["ERROR", "DIR must be NULL"]),
    ("fix powder/checkpoint 100 NULL", BOX + PAIR.format(nu=0.3) + TWO
     + "fix cp all powder/checkpoint 100 NULL\nrun 10\n", ["ERROR", "needs a folder DIR"]),
]


def finished(rc):
    """(not a signal, not an abort): a LAMMPS error exits through MPI_Abort/exit with rc 1"""
    return rc >= 0 and rc != 128 + signal.SIGABRT and rc != 134


ok = True
for what, text, words in ERRORS:
    try:
        rc, out = run(text, np=NP, check=False, timeout=TIMEOUT)
    except Exception as e:   # a hang (timeout) fails the row
        rc, out = -1, f"{type(e).__name__}: {e}"
    lines = [ln for ln in out.splitlines() if all(w in ln for w in words)]
    aborted = "MPI_ABORT was invoked" in out
    if len(lines) != 1 or aborted or "Backtrace" in out or "Signal: Aborted" in out:
        print(f"--- {what}:\n{out[-3000:]}")
    ok &= check_absolute(TEST, f"{what}: one intact ERROR line naming it ({', '.join(words)})", len(lines), 1, 0)
    ok &= check_absolute(TEST, f"{what}: no abort or signal (rc {rc})",
                         int(finished(rc) and "Signal: Aborted" not in out and "terminate called" not in out), 1, 0)
    # error->all stops every rank together: the job ends without MPI_Abort, whose notice could
    # cut the message's line in two
    ok &= check_absolute(TEST, f"{what}: ends without MPI_Abort", int(rc == 1 and not aborted), 1, 0)

# INF region in a p p f box: inserts (it hung)
inf = BOX + PAIR.format(nu=0.3) + """region feed block INF INF INF INF 5e-4 9e-4
fix ins all powder/insert 60 123 region feed diam one 3e-5 dens 7900
fix nve all nve/sphere
timestep 1e-10
""" + OVERLAP + "run 2\n"
try:
    rc, out = run(inf, np=NP, check=False, timeout=TIMEOUT)
except Exception as e:
    rc, out = -1, f"{type(e).__name__}: {e}"
rows = [ln.split() for ln in out.splitlines() if ln.split()[:1] == ["2"]]
n_inf = int(rows[-1][1]) if rows else -1
if n_inf != 60:
    print(out[-3000:])
ok &= check_absolute(TEST, f"region block INF INF INF INF in a p p f box: run ends (rc {rc})", int(rc == 0), 1, 0)
ok &= check_absolute(TEST, "region block INF INF INF INF: grains inserted", n_inf, 60, 0)

# a region wider than the periodic box: no overlapping grains
wide = BOX + PAIR.format(nu=0.3) + """region feed block -1e-4 4e-4 -1e-4 4e-4 5e-4 6e-4
fix ins all powder/insert 150 123 region feed diam one 3e-5 dens 7900 attempts 500
fix nve all nve/sphere
timestep 1e-10
""" + OVERLAP + "run 2\n"
rc, out = run(wide, np=NP, check=False, timeout=TIMEOUT)
rows = [ln.split() for ln in out.splitlines() if ln.split()[:1] == ["2"]]
if not rows:
    print(out[-3000:])
atoms, largest, count = (int(rows[-1][1]), float(rows[-1][2]), float(rows[-1][3])) if rows else (-1, 1e9, 1e9)
ok &= check_absolute(TEST, "region wider than the periodic box: grains inserted", atoms, 150, 0)
ok &= check_at_most(TEST, "region wider than the periodic box: overlapping pairs", count, 0)
ok &= check_at_most(TEST, "region wider than the periodic box: largest overlap / R", largest, 0)
sys.exit(0 if ok else 1)
