#!/usr/bin/python3
"""A restart keeps 'damping tsuji' at the step: two 30 um steel spheres, e = 0.3, 10 steps per
contact (fixed dt, pair_style granular/powder impact_speed 2). The input writes a restart file
before the collision; a second input reads it without any pair_coeff and runs the same
collision. Its e must equal the uninterrupted run's (to 1e-12) and the prescribed e (0.5 %). The
same with a global cutoff, mindlin and fix powder/dt after the restart (e and dt as without it)."""
import os
import sys
import tempfile

from meltdem.testing.dem import head_on, mass, t_contact
from meltdem.testing.lammps_run import printed_value, run
from meltdem.testing.report import check_absolute, check_relative

T = "dem.restitution.restart"
R, U, E = 15e-6, 2.0, 0.3
DT = t_contact(mass(R), mass(R), R, R, U) / 10
STEPS = 120
FIRST = head_on(f"hertz/material 200e9 {E} 0.3 damping tsuji tangential linear_nohistory 1.0 0.0", U, 3.3 * U * DT,
                pair_style=f"granular/powder impact_speed {U}") + f"""timestep {DT}
write_restart before.restart
"""
COLLIDE = f"""fix nve all nve/sphere
variable er equal (vx[2]-vx[1])/{U}
run {STEPS}
print "RESULT ${{er}}"
"""


def resume(d):
    return (f"atom_modify map array\nread_restart {os.path.join(d, 'before.restart')}\n"
            "comm_modify vel yes\nneighbor 2e-5 bin\nneigh_modify delay 0\n")


with tempfile.TemporaryDirectory() as d:
    straight = printed_value(run(FIRST + COLLIDE, cwd=d)[1], "RESULT")
    resumed = printed_value(run(resume(d) + COLLIDE, cwd=d)[1], "RESULT")
ok = check_relative(T, "e without a restart (prescribed 0.3, 10 steps per contact)", straight, E, 0.005)
ok &= check_absolute(T, "e read from the restart minus e without it", resumed - straight, 0.0, 1e-12)

# the shape that crashed (segfault, bad_array_new_length or 'Neighbor history overflow' in 5 of 5
# runs): a global cutoff, a tangential model with history, and fix powder/dt after the restart,
# which reads the pair's E and nu (they and the cutoff were not in the restart)
FIRST_B = head_on(f"hertz/material 200e9 {E} 0.3 damping tsuji tangential mindlin NULL 1.0 0.5", U,
                  3.3 * U * DT, pair_style=f"granular/powder 4.5e-5 impact_speed {U}") + f"""timestep {DT}
write_restart before.restart
"""
COLLIDE_B = COLLIDE.replace("run ", "fix pdt all powder/dt steps 10\nrun ").replace(
    'print "RESULT ${er}"', 'variable dtf equal f_pdt[1]\nprint "RESULT ${er}"\nprint "DT ${dtf}"')
with tempfile.TemporaryDirectory() as d:
    rc_s, out_s = run(FIRST_B + COLLIDE_B, cwd=d)
    rc_r, out_r = run(resume(d) + COLLIDE_B, cwd=d, check=False)
ok &= check_absolute(T, "global cutoff, mindlin, powder/dt: resumed run's exit code", rc_r, 0, 0)
if rc_r == 0:
    ok &= check_absolute(T, "  e read from the restart minus e without it",
                         printed_value(out_r, "RESULT") - printed_value(out_s, "RESULT"), 0.0, 1e-12)
    ok &= check_absolute(T, "  fix powder/dt's step after the restart minus without it [s]",
                         printed_value(out_r, "DT") - printed_value(out_s, "DT"), 0.0, 1e-24)
else:
    print(out_r[-3000:])
sys.exit(0 if ok else 1)
