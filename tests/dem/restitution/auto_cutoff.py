#!/usr/bin/python3
"""pair_style granular/powder without a cutoff sizes it from what fix powder/insert will
insert (stock granular gives 0 for an empty box and fix powder/insert refuses it): 300
soft 15-45 um spheres inserted into an empty box closed by fix wall/gran/powder, falling
onto the floor under gravity. The neighbor cutoff must be dmax + skin, and the run must
be identical (every position, every digit) to the same run with the explicit cutoff
'pair_style granular/powder 4.5e-5'; contacts must have happened (so the comparison
covers pair forces). Serial and mpirun -np 2."""
import os
import re
import sys
from meltdem.testing.report import check_relative, report
from meltdem.testing.lammps_run import run

T = "dem.restitution.auto_cutoff"
GRAN = "hertz/material 5e6 0.5 0.3 damping tsuji tangential linear_nohistory 1.0 0.5"
SKIN = 5e-6
SCENE = f"""units si
atom_style sphere
atom_modify map array
boundary f f f
region box block 0 3e-4 0 3e-4 0 3e-4
create_box 1 box
comm_modify vel yes
neighbor {SKIN} bin
neigh_modify delay 0 every 1 check yes
pair_style granular/powder {{cut}}
pair_coeff * * {GRAN}
fix wz all wall/gran/powder granular {GRAN} zplane 0.0 3e-4
fix wx all wall/gran/powder granular {GRAN} xplane 0.0 3e-4
fix wy all wall/gran/powder granular {GRAN} yplane 0.0 3e-4
region ins block 0 3e-4 0 3e-4 0 2e-4
fix ins all powder/insert 300 4711 region ins diam uniform 15e-6 45e-6 dens 7800 vel 0 0 -0.2
fix g all gravity 9.81 vector 0 0 -1
fix nve all nve/sphere
compute nc all contact/atom
compute ncs all reduce sum c_nc
timestep 5e-7
thermo_style custom step atoms c_ncs
thermo 1000
run 4000
write_dump all custom final.dump id x y z vx vy vz modify sort id format float %.17g
"""


def positions(d):
    with open(os.path.join(d, 'final.dump')) as f:
        return f.read().split('ITEM: ATOMS')[1]


ok = True
for np_ in (1, 2):
    outs = {}
    for cut in ("", "4.5e-5"):
        d = f"/tmp/meltdem_auto_cutoff_{np_}_{cut or 'auto'}"
        os.makedirs(d, exist_ok=True)
        rc, out = run(SCENE.format(cut=cut), np=np_, cwd=d)
        outs[cut] = (out, positions(d))
    out, pos = outs[""]
    m = re.search(r"master list distance cutoff = (\S+)", out)
    ok &= check_relative(T, f"np {np_}: neighbor cutoff without pair cutoff (dmax + skin)",
                         float(m.group(1)) if m else 0.0, 45e-6 + SKIN, 1e-6)
    contacts = [float(line.split()[2]) for line in out.splitlines() if re.match(r"^\s*4000\s+300\s", line)]
    n = contacts[0] if contacts else 0.0
    ok &= report(T, f"np {np_}: contacts at the end (must be > 0)", n, "> 0", "bound", n > 0)
    same = pos == outs["4.5e-5"][1]
    ok &= report(T, f"np {np_}: final positions/velocities identical to explicit cutoff 4.5e-5",
                 "yes" if same else "no", "yes", "exact", same)
sys.exit(0 if ok else 1)
