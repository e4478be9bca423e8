#!/usr/bin/python3
"""fix powder/insert never gives an atom ID twice: particles are inserted one per step, the one
with the largest ID is deleted (as a particle that melted away or left the mesh is), and the
insertion goes on: the next ID must follow the deleted one, not take its place. The coupling
keys each particle's fluid state by its ID, so a reused ID made a new grain take a deleted
grain's (hot, liquid) surroundings (found in the lmd-track scene: a cold grain falling
through 300 K gas heated at 5e6 K/s). The restart keeps the last ID given.
"""
import tempfile

from meltdem.testing.lammps_run import run
from meltdem.testing.report import check_absolute
from insert_common import PHYSICS, SETUP

TEST = "dem.insert.ids_not_reused"
INS = "fix ins all powder/insert 40 7 region ins diam uniform 0.8e-3 1.2e-3 dens 2500 rate 1e5 attempts 50"
IDS = """compute id all property/atom id
compute idmax all reduce max c_id
thermo_style custom step atoms c_idmax
thermo_modify norm no
"""


def last_thermo(out):
    rows = [line.split() for line in out.splitlines()]
    rows = [r for r in rows if len(r) == 3 and r[0].isdigit()]
    return int(rows[-1][1]), int(float(rows[-1][2]))


with tempfile.TemporaryDirectory() as d:
    _, out = run(SETUP + PHYSICS + INS + "\n" + IDS + "run 6\n", cwd=d)
    n1, top = last_thermo(out)
    _, out = run(SETUP + PHYSICS + INS + "\n" + IDS + f"""run 6
group top id {top}
delete_atoms group top
run 6
write_restart ids.restart
""", cwd=d)
    n2, top2 = last_thermo(out)
    added = n2 - (n1 - 1)
    print(f"{TEST}: {n1} particles (largest ID {top}), deleted ID {top}, {added} more: largest ID {top2}")
    ok = check_absolute(TEST, "particles inserted after the deletion (at least one)", min(added, 1), 1, 0)
    ok &= check_absolute(TEST, "largest ID after the deletion (the new IDs follow the deleted one)",
                         top2, top + added, 0)
    _, out = run(f"read_restart ids.restart\n{PHYSICS}\n{INS}\n{IDS}run 6\n", cwd=d)
    n3, top3 = last_thermo(out)
    added3 = n3 - n2
    print(f"{TEST}: after the restart {added3} more: largest ID {top3}")
    ok &= check_absolute(TEST, "largest ID after a restart and more insertions", top3, top2 + added3, 0)
raise SystemExit(0 if ok else 1)
