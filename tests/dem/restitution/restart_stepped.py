#!/usr/bin/python3
"""A restart keeps 'damping tsuji' at the step: two 30 um steel spheres, e = 0.3, 10 steps per
contact (fixed dt, pair_style granular/powder impact_speed 2). The input writes a restart file
before the collision; a second input reads it without any pair_coeff and runs the same
collision. Its e must equal the uninterrupted run's (to 1e-12) and the prescribed e (0.5 %)."""
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
with tempfile.TemporaryDirectory() as d:
    straight = printed_value(run(FIRST + COLLIDE, cwd=d)[1], "RESULT")
    resume = (f"atom_modify map array\nread_restart {os.path.join(d, 'before.restart')}\n"
              "comm_modify vel yes\nneighbor 2e-5 bin\nneigh_modify delay 0\n")
    resumed = printed_value(run(resume + COLLIDE, cwd=d)[1], "RESULT")
ok = check_relative(T, "e without a restart (prescribed 0.3, 10 steps per contact)", straight, E, 0.005)
ok &= check_absolute(T, "e read from the restart minus e without it", resumed - straight, 0.0, 1e-12)
sys.exit(0 if ok else 1)
