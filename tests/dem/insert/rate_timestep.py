#!/usr/bin/python3
"""fix powder/insert rate / massrate with a timestep that changes between runs: the number
(mass) of particles drawn follows rate * elapsed time to within one particle at every output,
and everything drawn is placed (roomy region)."""
import math
import sys

import numpy as np

from meltdem.testing.lammps_run import printed_value, run
from meltdem.testing.report import check_absolute, check_at_most
from insert_common import thermo

TEST = "dem.insert.rate_timestep"
HEAD = """units si
atom_style sphere
boundary p p p
region box block 0 0.05 0 0.05 0 0.05
create_box 1 box
region ins block 0.002 0.048 0.002 0.048 0.002 0.048
fix nve all nve/sphere
"""
RUNS = """thermo_style custom step time f_ins[1] f_ins[2] f_ins[3] f_ins[4] f_ins[5] f_ins[6]
thermo_modify norm no format float %.17g
thermo 25
timestep 1e-6
run 500
timestep 2.5e-6
run 400
timestep 0.7e-6
run 300
"""
RATE = 1.0e5                   # particles per second
MASSRATE = 0.2                 # kg per second
DMAX, RHO = 1.2e-3, 2500.0
MMAX = RHO * np.pi / 6 * DMAX**3

ok = True
_, out = run(HEAD + f"fix ins all powder/insert 100000 7 region ins diam uniform 0.8e-3 1.2e-3 dens {RHO} "
             f"rate {RATE}\n" + RUNS)
t = thermo(out)
time, ins, pend, drawn = t[:, 1], t[:, 2], t[:, 3], t[:, 7]
ok &= check_absolute(TEST, f"drawn at t = {time[-1]:.4g} s vs rate*t (rate {RATE:g}/s)", drawn[-1], RATE * time[-1],
                     1.0)
ok &= check_at_most(TEST, "max (rate*t - drawn) over all outputs, particles (0 <= . < 1)",
                    np.max(RATE * time - drawn), 1.0 - 1e-9)
ok &= check_at_most(TEST, "max (drawn - rate*t) over all outputs, particles", np.max(drawn - RATE * time), 1e-6)
ok &= check_at_most(TEST, "max pending over all outputs (roomy region, rate-limited)", np.max(pend), 2)

_, out = run(HEAD + f"fix ins all powder/insert 100000 7 region ins diam uniform 0.8e-3 1.2e-3 dens {RHO} "
             f"massrate {MASSRATE}\n" + RUNS)
t = thermo(out)
time, mins, mpend = t[:, 1], t[:, 5], t[:, 6]
due = MASSRATE * time
ok &= check_absolute(TEST, f"mass drawn at t = {time[-1]:.4g} s vs massrate*t, kg", mins[-1] + mpend[-1], due[-1], MMAX)
ok &= check_at_most(TEST, "max |massrate*t - mass drawn| over all outputs / largest particle mass",
                    np.max(np.abs(due - mins - mpend)) / MMAX, 1.0)

# fix powder/dt defined before fix powder/insert resets dt at the end of each step before the
# insert fix books it: the credit takes the step just taken (212 drawn of 214 due when it took
# the new one). A grain accelerated by a force makes powder/dt change dt every step.
ORDER = """units si
atom_style sphere
atom_modify map array
boundary p p f
newton off
comm_modify vel yes
region box block 0 3e-4 0 3e-4 0 4e-4 units box
create_box 2 box
neighbor 1e-5 bin
neigh_modify delay 0
pair_style granular/powder 4.5e-5
pair_coeff * * hertz/material 200e9 0.5 0.3 damping tsuji tangential mindlin NULL 1.0 0.5
create_atoms 2 single 1.5e-4 1.5e-4 1e-5
set atom 1 diameter 30e-6 density 7900
group fast type 2
fix integrate all nve/sphere
fix push fast addforce 0 0 1e-3
region feed block 0 3e-4 0 3e-4 1e-4 3.5e-4 units box
fix d all powder/dt steps 10 vmin 0.01
fix ins all powder/insert 1000 1234 region feed diam one 30e-6 dens 7900 rate 1e8
variable drawn equal f_ins[6]
variable due equal 1e8*time
timestep 1e-9
run 400
print "DRAWN ${drawn}"
print "DUE ${due}"
"""
_, out = run(ORDER)
drawn, due = printed_value(out, "DRAWN"), printed_value(out, "DUE")
ok &= check_absolute(TEST, f"powder/dt defined first, dt changing each step: drawn vs floor(rate t) "
                           f"(rate t = {due:.6g})", drawn, math.floor(due + 1e-9), 0)
sys.exit(0 if ok else 1)
