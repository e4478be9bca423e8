#!/usr/bin/python3
"""compute powder/overlap counts every contact once (pairs across processors with
newton_pair off or on, periodic images) and sees flat granular walls.
Set-up: four 20 um spheres on a periodic x line, each overlapping its neighbours by 10 %
of the radius (4 contacts, one through the periodic boundary), and one sphere 10 %
into a zplane wall/gran. Usage: counting.py NP NEWTON"""
import sys

from meltdem.testing.lammps_run import run, thermo_runs
from meltdem.testing.report import check_relative, report

np_, newton = int(sys.argv[1]), sys.argv[2]
TEST = f"dem.overlap.counting.np{np_}.newton_{newton}"
R = 10e-6
pitch = 2 * R - 0.1 * R
L = 4 * pitch
atoms = "".join(f"create_atoms 1 single {(k + 0.5) * pitch} 0 2e-5\n" for k in range(4))
text = f"""units si
atom_style sphere
boundary p p f
newton {newton}
region box block 0 {L} -4e-5 4e-5 0 8e-5
create_box 1 box
comm_modify vel yes
neighbor 5e-6 bin
pair_style granular
pair_coeff * * hertz/material 200e9 0.5 0.3 damping tsuji tangential linear_nohistory 0 0
{atoms}create_atoms 1 single {L / 2} 2e-5 {0.9 * R}
set type 1 diameter {2 * R} density 7900
fix wall all wall/gran granular hertz/material 200e9 0.5 0.3 damping tsuji tangential linear_nohistory 0 0 zplane 0.0 NULL
compute ov all powder/overlap threshold 0.09
thermo_style custom step c_ov[1] c_ov[2] c_ov[3] c_ov[4]
thermo_modify format float %.17g
run 0
"""  # noqa: E501  (a long line of the LAMMPS input written verbatim)
_, out = run(text, np=np_)
row = thermo_runs(out)[0][0]
v = [row[f"c_ov[{k}]"] for k in range(1, 5)]
ok = check_relative(TEST, "largest overlap/R", v[0], 0.1, 1e-9)
ok &= report(TEST, "contacts above 0.09 (4 pairs + 1 wall)", v[1], 5, "exact", v[1] == 5)
ok &= report(TEST, "contacts (4 pairs + 1 wall)", v[3], 5, "exact", v[3] == 5)
raise SystemExit(0 if ok else 1)
