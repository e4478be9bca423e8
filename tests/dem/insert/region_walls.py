#!/usr/bin/python3
"""fix powder/insert against curved granular walls: a cylindrical container made by
fix wall/gran/region, and by fix wall/gran zcylinder, around an insertion block whose
corners lie outside the container, and a plane wall across the block. No new particle may touch
the wall or another particle, or lie behind a wall."""
import os
import sys
import tempfile

import numpy as np
from scipy.spatial import cKDTree

from meltdem.testing.lammps_run import run
from meltdem.testing.report import check_absolute, check_at_most
from insert_common import GRAN, read_dump

TEST = "dem.insert.region_walls"
R = 5e-3
N = 300
HEAD = f"""units si
atom_style sphere
boundary f f f
region box block -0.006 0.006 -0.006 0.006 0 0.02
create_box 1 box
comm_modify vel yes
pair_style granular 1.2e-3
pair_coeff * * {GRAN}
region ins block -0.005 0.005 -0.005 0.005 0.002 0.018
timestep 1e-6
"""
WALLS = {
    "wall/gran/region cylinder": f"region cyl cylinder z 0 0 {R} 0 0.02 side in\n"
                                 f"fix w all wall/gran/region granular {GRAN} region cyl\n",
    "wall/gran zcylinder": f"fix w all wall/gran granular {GRAN} zcylinder {R}\n",
}
ok = True
for name, wall in WALLS.items():
    with tempfile.TemporaryDirectory() as d:
        run(HEAD + wall + f"fix ins all powder/insert {N} 99 region ins diam uniform 0.8e-3 1.2e-3 dens 2500 "
            "gap 1e-5 attempts 200\n"
            "dump d all custom 1 dump.ins id radius x y z\ndump_modify d sort id format float %.17g\nrun 1\n",
            cwd=d)
        fr = read_dump(os.path.join(d, "dump.ins"))[1]
    r, x = fr[:, 1], fr[:, 2:5]
    ok &= check_absolute(TEST, f"{name}: particles inserted at once", len(r), N, 0)
    clearance = R - np.hypot(x[:, 0], x[:, 1]) - r
    ok &= check_at_most(TEST, f"{name}: -(smallest wall clearance - gap), m", -(clearance.min() - 1e-5), 1e-12)
    pairs = cKDTree(x).query_pairs(2 * 0.6e-3 + 1e-5, output_type="ndarray")
    gapij = np.linalg.norm(x[pairs[:, 0]] - x[pairs[:, 1]], axis=1) - r[pairs[:, 0]] - r[pairs[:, 1]]
    ok &= check_at_most(TEST, f"{name}: -(smallest particle gap - gap), m", -(gapij.min() - 1e-5), 1e-12)
    corner = (np.hypot(x[:, 0], x[:, 1]) > R).sum()
    ok &= check_absolute(TEST, f"{name}: particles in the block corners outside the cylinder", corner, 0, 0)

# a plane wall across the insertion block (zplane 0.01 NULL: particles live above z = 0.01): none
# may be placed behind it (43 of 100 were, when only the distance to the plane was checked)
with tempfile.TemporaryDirectory() as d:
    run(HEAD + f"fix w all wall/gran granular {GRAN} zplane 0.01 NULL\n"
        "fix ins all powder/insert 100 99 region ins diam uniform 0.8e-3 1.2e-3 dens 2500 gap 1e-5 attempts 200\n"
        "dump d all custom 1 dump.ins id radius x y z\ndump_modify d sort id format float %.17g\nrun 1\n", cwd=d)
    fr = read_dump(os.path.join(d, "dump.ins"))[1]
ok &= check_absolute(TEST, "zplane 0.01 NULL across the block: particles inserted at once", len(fr), 100, 0)
ok &= check_at_most(TEST, "zplane 0.01 NULL: -(smallest clearance above the plane - gap), m",
                    -((fr[:, 4] - fr[:, 1] - 0.01).min() - 1e-5), 1e-12)
sys.exit(0 if ok else 1)
