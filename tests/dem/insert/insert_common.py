"""Helpers of the fix powder/insert tests: scenes, running meltdem-lmp, reading dumps/thermo."""
import numpy as np

from meltdem.io import dumps


# 1 mm soft spheres (E = 5 MPa keeps the step at 1e-5 s) in a 10 x 10 x 45 mm box closed by
# fix wall/gran planes on all sides; the insertion region is the 10 mm cube 30..40 mm up,
# so 2000 particles (about 1.1x the region's volume) cannot all fit at once: pending occurs
# and drains as the earlier particles fall out of the region. With 2 ranks the box is cut
# in x, through the insertion region, so the overlap search spans ranks.
GRAN = "hertz/material 5e6 0.5 0.3 damping tsuji tangential linear_nohistory 1.0 0.5"
SETUP = """units si
atom_style sphere
atom_modify map array
boundary f f f
processors * 1 1
region box block 0 0.01 0 0.01 0 0.045
create_box 1 box
comm_modify vel yes
neighbor 0.3e-3 bin
neigh_modify delay 0 every 1 check yes
"""
PHYSICS = f"""pair_style granular 1.2e-3
pair_coeff * * {GRAN}
fix wz all wall/gran granular {GRAN} zplane 0.0 0.045
fix wx all wall/gran granular {GRAN} xplane 0.0 0.01
fix wy all wall/gran granular {GRAN} yplane 0.0 0.01
region ins block 0 0.01 0 0.01 0.030 0.040
fix g all gravity 9.81 vector 0 0 -1
fix nve all nve/sphere
timestep 1e-5
"""
INSERT = ("fix ins all powder/insert 2000 12345 region ins diam uniform 0.8e-3 1.2e-3 dens 2500 "
          "vel 0 0 -1 attempts 50 every 20")
OUTPUT = """thermo_style custom step atoms f_ins[1] f_ins[2] f_ins[3] f_ins[4] f_ins[5] f_ins[6]
thermo_modify norm no format float %.17g
thermo 20
dump d all custom 20 dump.ins id radius x y z
dump_modify d sort id format float %.17g
"""
TIGHT = SETUP + PHYSICS + INSERT + "\n" + OUTPUT


def thermo(out, first="Step"):
    """All thermo rows (lists of floats) of every run in the output."""
    rows, on = [], False
    for line in out.splitlines():
        w = line.split()
        if w and w[0] == first:
            on = True
            continue
        if on:
            try:
                rows.append([float(v) for v in w])
            except ValueError:
                on = False
            if not w:
                on = False
    return np.array(rows)


def read_dump(path):
    """{step: array of rows (id radius x y z)} from a dump custom file."""
    return {fr["step"]: fr["data"] for fr in dumps.read_frames(path)}
