"""Helpers of the fix powder/dt and compute powder/overlap tests: run meltdem-lmp, read
thermo, and eq. 3.1 evaluated independently of the C++ code."""
import math


E, NU, RHO = 200e9, 0.3, 7900.0
ESTAR = 1.0 / (2.0 * (1.0 - NU * NU) / E)  # eq. 3.2, same material

# two steel spheres on the x axis in a closed box, elastic Hertz contact (no damping,
# no friction) so the contact is the one of eq. 3.1
TWO_SPHERES = """units si
atom_style sphere
atom_modify map array
boundary f f f
region box block -2e-4 2e-4 -1e-4 1e-4 -1e-4 1e-4
create_box 1 box
comm_modify vel yes
neighbor 2e-5 bin
neigh_modify delay 0
pair_style granular
pair_coeff * * hertz/material {E} 0.0 {NU} damping velocity tangential linear_nohistory 0 0
create_atoms 1 single {x1} 0 0
create_atoms 1 single {x2} 0 0
set atom 1 diameter {d1} density {RHO}
set atom 2 diameter {d2} density {RHO}
velocity all set 0 0 0
set atom 1 vx {v1}
set atom 2 vx {v2}
fix nve all nve/sphere
"""


def two_spheres(x1, x2, d1, d2, v1, v2):
    return TWO_SPHERES.format(E=E, NU=NU, RHO=RHO, x1=x1, x2=x2, d1=d1, d2=d2, v1=v1, v2=v2)


def mass(R, rho=RHO):
    return 4.0 / 3.0 * math.pi * R ** 3 * rho


def t_contact(m1, m2, R1, R2, U, Es=ESTAR):
    """eq. 3.1 with eq. 3.2"""
    ms = 1.0 / (1.0 / m1 + 1.0 / m2)
    Rs = 1.0 / (1.0 / R1 + 1.0 / R2)
    return 2.87 * (ms * ms / (Rs * Es * Es * U)) ** 0.2


def delta_max(m1, m2, R1, R2, U, Es=ESTAR):
    """largest Hertz overlap of an elastic head-on impact: (15 m* U^2 / (16 E* sqrt R*))^(2/5)"""
    ms = 1.0 / (1.0 / m1 + 1.0 / m2)
    Rs = 1.0 / (1.0 / R1 + 1.0 / R2)
    return (15.0 * ms * U * U / (16.0 * Es * math.sqrt(Rs))) ** 0.4
