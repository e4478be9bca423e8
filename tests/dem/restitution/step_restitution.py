#!/usr/bin/python3
"""Restitution at the step a run takes (issue 20): head-on contacts of 30 um steel spheres
(E = 200 GPa, nu = 0.3) at 2 m/s with 'damping tsuji' integrated in S = 5, 10 and 20 steps
per contact, for e = 0.1 ... 0.95:
  * pair, monodisperse, dt from fix powder/dt steps S (the setting users run);
  * pair, polydisperse (30 and 20 um), dt = t_c/S fixed, pair_style ... impact_speed 2;
  * pair, monodisperse, dt = t_c(2 m/s)/S, impact_speed 2, contacts at 0.5 and 0.02 m/s
    (slower than the calibration speed: more steps per contact);
  * wall (fix wall/gran/powder, plane z = 0), dt = t_c(sphere-wall)/S fixed, impact_speed 2;
  * wall with fix powder/dt steps S (the wall contact then has 1.32 S steps);
  * region wall (fix wall/gran/region/powder, the face z = 0 of a block), as the plane.
Each case at five phases (where within a step the contact starts, both ends included).
Measured e against the prescribed e: within 0.5 % at every phase and S."""
import sys

from meltdem.testing.dem import ESTAR, RHO, head_on, mass, sphere_box, t_contact
from meltdem.testing.lammps_run import run, thermo_runs
from meltdem.testing.report import check_relative

T = "dem.restitution.at_step"
U = 2.0
PHASES = (0.01, 0.1, 0.4, 0.7, 0.99)
E_LIST = (0.1, 0.3, 0.5, 0.7, 0.95)
S_LIST = (5, 10, 20)
R1 = 15e-6


TAIL = """thermo_style custom step v_er
thermo_modify format float %.15g
thermo 1000000
run {steps}
"""


def restitutions(texts):
    """The final e of each input, all run in one meltdem-lmp separated by 'clear'."""
    runs = thermo_runs(run("clear\n".join(texts))[1])
    if len(runs) != len(texts):
        raise SystemExit(f"{len(runs)} runs in the output of {len(texts)} inputs")
    return [rows[-1]["v_er"] for rows in runs]


def pair_case(e, S, phase, R2=R1, powder_dt=True, speed=U):
    dt = t_contact(mass(R1), mass(R2), R1, R2, U) / S
    pair = "granular/powder" if powder_dt else f"granular/powder impact_speed {U}"
    text = head_on(f"hertz/material 200e9 {e} 0.3 damping tsuji tangential linear_nohistory 1.0 0.0", speed,
                   (3 + phase) * speed * dt, R1, R2, pair)
    text += f"fix dt all powder/dt steps {S}\n" if powder_dt else f"timestep {dt}\n"
    # a slower contact lasts (U / speed)^(1/5) longer
    return text + TAIL.format(steps=int(8 * S * (U / speed) ** 0.2) + 20)


def wall_case(e, S, phase, powder_dt=False, region=False):
    m = mass(R1)
    # sphere on a wall of the same material: m* = m, R* = R, E* as for a pair
    tc = 2.87 * (m * m / (R1 * ESTAR * ESTAR * U)) ** 0.2
    dt = tc / S
    gap = (3 + phase) * U * dt
    speed = '' if powder_dt else f' impact_speed {U}'
    return sphere_box("p p f", "-2e-4 2e-4 -1e-4 1e-4 0 2e-4") + f"""pair_style granular/powder {2 * R1}
pair_coeff * * hertz/material 200e9 {e} 0.3 damping tsuji tangential linear_nohistory 1.0 0.0
create_atoms 1 single 0 0 {R1 + gap}
set atom 1 diameter {2 * R1} density {RHO}
velocity all set 0 0 {-U}
region cup block -9e-5 9e-5 -9e-5 9e-5 0 2e-4 side in
fix wall all wall/gran/{'region/' if region else ''}powder granular hertz/material 200e9 {e} 0.3 damping tsuji{speed} \
tangential linear_nohistory 1.0 0.0 {'region cup' if region else 'zplane 0.0 NULL'}
fix nve all nve/sphere
{f'fix dt all powder/dt steps {S}' if powder_dt else f'timestep {dt}'}
variable er equal vz[1]/{U}
thermo_style custom step v_er
thermo_modify format float %.15g
thermo 1000000
run {int(8 * S) + 20}
"""


CASES = [
    ("pair, fix powder/dt", lambda e, S, p: pair_case(e, S, p)),
    ("pair 30/20 um", lambda e, S, p: pair_case(e, S, p, R2=10e-6, powder_dt=False)),
    ("pair at 0.5 m/s, calibrated at 2", lambda e, S, p: pair_case(e, S, p, powder_dt=False, speed=0.5)),
    ("pair at 0.02 m/s, calibrated at 2", lambda e, S, p: pair_case(e, S, p, powder_dt=False, speed=0.02)),
    ("wall", lambda e, S, p: wall_case(e, S, p)),
    ("wall, fix powder/dt", lambda e, S, p: wall_case(e, S, p, powder_dt=True)),
    ("region wall", lambda e, S, p: wall_case(e, S, p, region=True)),
]

ok = True
for name, case in CASES:
    grid = [(e, S) for e in E_LIST for S in S_LIST]
    measured = iter(restitutions([case(e, S, p) for e, S in grid for p in PHASES]))
    for e, S in grid:
        for p in PHASES:
            ok &= check_relative(T, f"{name}: e at S = {S}, phase {p} (prescribed {e})", next(measured), e, 0.005)
sys.exit(0 if ok else 1)
