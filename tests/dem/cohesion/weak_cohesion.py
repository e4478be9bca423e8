#!/usr/bin/python3
"""'damping tsuji' with the cohesive normal models keeps the restitution of their non-cohesive
limit: two 30 um steel spheres at 2 m/s with a negligible surface energy (gamma = 1e-7 J/m^2:
pull-off 1e-11 N against contact forces of 1e-3 N) must return the prescribed e, for dmt (which
damps as Hertz and gets the stepped damping) at 10 steps per contact within 0.5 %, for jkr (the
continuous alpha in the stock force, which damps with the JKR contact radius) at 200 steps per
contact within 1 %."""
import sys

from meltdem.testing.dem import head_on, mass, t_contact
from meltdem.testing.lammps_run import run, thermo_runs
from meltdem.testing.report import check_relative

T = "dem.cohesion.weak_cohesion"
R, U, GAMMA = 15e-6, 2.0, 1e-7


def collide(model, e, S):
    dt = t_contact(mass(R), mass(R), R, R, U) / S
    text = head_on(f"{model} 200e9 {e} 0.3 {GAMMA} damping tsuji tangential mindlin NULL 1.0 0.5", U, 3.3 * U * dt)
    text += f"""fix dt all powder/dt steps {S}
thermo_style custom step v_er
thermo_modify format float %.15g
thermo 1000000
run {int(8 * S) + 20}
"""
    return thermo_runs(run(text)[1])[0][-1]["v_er"]


ok = True
for e in (0.3, 0.7):
    ok &= check_relative(T, f"dmt, 10 steps per contact: e (prescribed {e})", collide("dmt", e, 10), e, 0.005)
    ok &= check_relative(T, f"jkr, 200 steps per contact: e (prescribed {e})", collide("jkr", e, 200), e, 0.01)
sys.exit(0 if ok else 1)
