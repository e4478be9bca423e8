#!/usr/bin/python3
"""Rolling resistance (rolling sds) against the closed form: a sphere rolling without slip on a
flat support under gravity g with a saturated rolling torque mu_r F_n R* (LAMMPS's sds model
caps the rolling pseudo-force at mu_r F_n and applies R* n x F_roll) decelerates uniformly,
    a = -mu_r F_n R* / (R (m + I/R^2)) = -(5/7) mu_r g (R*/R)
and stops after t = v0 / |a|. A 30 um steel sphere ('damping tsuji' e = 0.5, Mindlin friction
0.5, mu_r = 0.1, k_roll 1000 N/m, no rolling damping) starts rolling at 5 mm/s on a plane wall
(fix wall/gran/powder, R* = R) and on top of a held 0.2 m sphere (pair_style granular/powder;
R* = R Rb/(R + Rb); the support's slope along the 18 um of travel changes g by < 1e-4), dt from
fix powder/dt steps 10. Deceleration from a straight-line fit of vx over the middle half of the
roll, within 1 % of the closed form."""
import sys

import numpy as np

from meltdem.testing.dem import sphere_box
from meltdem.testing.lammps_run import run, thermo_runs
from meltdem.testing.report import check_relative

T = "dem.cohesion.rolling"
E, NU, RHO, G, MU_R, V0, R = 200e9, 0.3, 7800.0, 9.81, 0.1, 5e-3, 15e-6
MODEL = f"hertz/material {E} 0.5 {NU} damping tsuji tangential mindlin NULL 1.0 0.5 rolling sds 1000 0 {MU_R}"
T_STOP = V0 / (5.0 / 7.0 * MU_R * G)
TAIL = f"""fix nve ball nve/sphere
fix g ball gravity {G} vector 0 0 -1
fix dt all powder/dt steps 10
variable vx equal vx[1]
variable t equal time
thermo_style custom step v_t v_vx
thermo_modify format float %.15g
thermo 200
run {{steps}}
"""


def decel(text):
    rows = thermo_runs(run(text, timeout=600)[1])[0]
    t = np.array([r["v_t"] for r in rows])
    v = np.array([r["v_vx"] for r in rows])
    sel = (t > 0.25 * T_STOP) & (t < 0.75 * T_STOP)
    return -np.polyfit(t[sel], v[sel], 1)[0]


def wall():
    text = sphere_box("p p f", "-1e-4 1e-4 -1e-4 1e-4 0 1e-4", 2e-6) + f"""pair_style granular/powder {2 * R}
pair_coeff * * {MODEL}
create_atoms 1 single 0 0 {R}
set atom 1 diameter {2 * R} density {RHO}
group ball id 1
velocity all set {V0} 0 0
set atom 1 omega 0 {V0 / R} 0
fix wall all wall/gran/powder granular {MODEL} zplane 0.0 NULL
""" + TAIL
    return decel(text.format(steps=320000)), R


def on_sphere():
    rb = 0.1
    # (no sorting and no binning: LAMMPS 2025 refuses the bins a 0.22 m box of 2 um cutoffs needs)
    text = sphere_box("f f f", "-0.11 0.11 -0.11 0.11 -0.11 0.11", 2e-6) + f"""atom_modify sort 0 0.0
neighbor 2e-6 nsq
pair_style granular/powder
pair_coeff * * {MODEL}
create_atoms 1 single 0 0 {rb + R}
create_atoms 1 single 0 0 0
set atom 1 diameter {2 * R} density {RHO}
set atom 2 diameter {2 * rb} density {RHO}
group ball id 1
group support id 2
fix hold support freeze
velocity ball set {V0} 0 0
set atom 1 omega 0 {V0 / R} 0
""" + TAIL
    return decel(text.format(steps=320000)), R * rb / (R + rb)


ok = True
for where, case in (("plane wall", wall), ("held 0.2 m sphere (pair)", on_sphere)):
    a, reff = case()
    ok &= check_relative(T, f"{where}: rolling deceleration [m/s^2] vs 5/7 mu_r g R*/R", a,
                         5.0 / 7.0 * MU_R * G * reff / R, 0.01)
sys.exit(0 if ok else 1)
