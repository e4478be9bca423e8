#!/usr/bin/python3
"""Pull-off force of cohesive contacts against the closed forms (work of adhesion w = 2 gamma,
gamma the surface energy of the jkr/dmt coefficients, as in LAMMPS's pair granular):
    JKR  F = 3/2 pi w R*      DMT  F = 2 pi w R*
Steel spheres (E = 200 GPa, nu = 0.3, gamma = 0.1 J/m^2, 'damping tsuji' e = 0.5): a pair of
30 and 20 um spheres (R* = 6 um) and a 30 um sphere on a plane wall (R* = 15 um). One body is
held (fix freeze / the wall), the other pulled off along the normal by fix move at 1e-5 m/s
from an overlap of 2 nm (quasi-static: the damping force is below 1e-3 of the pull-off); the
measured pull-off is the largest tensile normal force. Tolerance 1 %."""
import math
import sys

from meltdem.testing.dem import sphere_box
from meltdem.testing.lammps_run import run, thermo_runs
from meltdem.testing.report import check_relative

T = "dem.cohesion.pull_off"
E, NU, GAMMA, RHO = 200e9, 0.3, 0.1, 7800.0
V, DT, DELTA0, TRAVEL = 1e-5, 1e-9, 2e-9, 6e-9
STEPS = int(TRAVEL / V / DT)
TAIL = f"""variable f equal {{force}}
thermo_style custom step v_f
thermo_modify format float %.15g
thermo 10
run {STEPS}
"""


def pair(model):
    r1, r2 = 15e-6, 10e-6
    text = sphere_box("f f f", "-1e-4 1e-4 -1e-4 1e-4 -1e-4 1e-4", 1e-6) + f"""pair_style granular/powder
pair_coeff * * {model} {E} 0.5 {NU} {GAMMA} damping tsuji tangential mindlin NULL 1.0 0.5
create_atoms 1 single 0 0 0
create_atoms 1 single {r1 + r2 - DELTA0} 0 0
set atom 1 diameter {2 * r1} density {RHO}
set atom 2 diameter {2 * r2} density {RHO}
group held id 1
group pulled id 2
fix hold held freeze
fix pull pulled move linear {V} 0 0
timestep {DT}
""" + TAIL.format(force="fx[2]")
    rows = thermo_runs(run(text)[1])[0]
    return -min(r["v_f"] for r in rows), r1 * r2 / (r1 + r2)


def wall(model):
    r = 15e-6
    text = sphere_box("p p f", "-1e-4 1e-4 -1e-4 1e-4 0 1e-4", 1e-6) + f"""pair_style granular/powder {2 * r}
pair_coeff * * hertz/material {E} 0.5 {NU} damping tsuji tangential linear_nohistory 1.0 0.0
create_atoms 1 single 0 0 {r - DELTA0}
set atom 1 diameter {2 * r} density {RHO}
fix wall all wall/gran/powder granular {model} {E} 0.5 {NU} {GAMMA} damping tsuji \
tangential mindlin NULL 1.0 0.5 zplane 0.0 NULL
fix pull all move linear 0 0 {V}
timestep {DT}
""" + TAIL.format(force="fz[1]")
    rows = thermo_runs(run(text)[1])[0]
    return -min(r["v_f"] for r in rows), r


ok = True
w = 2 * GAMMA
for model, factor, name in (("jkr", 1.5, "JKR 3/2 pi w R*"), ("dmt", 2.0, "DMT 2 pi w R*")):
    for where, case in (("pair 30/20 um", pair), ("sphere on a plane wall", wall)):
        force, reff = case(model)
        ok &= check_relative(T, f"{where}: {model} pull-off force [N] vs {name}", force,
                             factor * math.pi * w * reff, 0.01)
sys.exit(0 if ok else 1)
