"""Helpers of the fix powder/dt and compute powder/overlap tests: run meltdem-lmp, read
thermo, and eq. 3.1 evaluated independently of the C++ code."""
import math


E, NU, RHO = 200e9, 0.3, 7900.0
ESTAR = 1.0 / (2.0 * (1.0 - NU * NU) / E)  # eq. 3.2, same material


def sphere_box(boundary="f f f", box="-2e-4 2e-4 -1e-4 1e-4 -1e-4 1e-4", skin=2e-5):
    """Opening of a granular input in SI units: one atom type, spheres, ghost velocities."""
    return f"""units si
atom_style sphere
atom_modify map array
boundary {boundary}
region box block {box}
create_box 1 box
comm_modify vel yes
neighbor {skin} bin
neigh_modify delay 0
"""


# two steel spheres on the x axis in a closed box; the contact is pair_style and pair_coeff's
# model arguments
SPHERES_ON_X = sphere_box() + """pair_style {pair_style}
pair_coeff * * {contact}
create_atoms 1 single {x1} 0 0
create_atoms 1 single {x2} 0 0
set atom 1 diameter {d1} density {RHO}
set atom 2 diameter {d2} density {RHO}
velocity all set 0 0 0
set atom 1 vx {v1}
set atom 2 vx {v2}
fix nve all nve/sphere
"""
# elastic Hertz contact (no damping, no friction): the contact of eq. 3.1
ELASTIC = f"hertz/material {E} 0.0 {NU} damping velocity tangential linear_nohistory 0 0"


def two_spheres(x1, x2, d1, d2, v1, v2):
    return SPHERES_ON_X.format(pair_style="granular", contact=ELASTIC, RHO=RHO, x1=x1, x2=x2, d1=d1, d2=d2, v1=v1,
                               v2=v2)


def head_on(contact, speed, gap, r1=15e-6, r2=15e-6, pair_style="granular/powder"):
    """Spheres of radii r1, r2 a gap apart on the x axis, approaching at relative speed
    'speed' with zero total momentum; the variable er is their restitution (relative speed
    after over before). Append the step control, the run and the output."""
    m1, m2 = mass(r1), mass(r2)
    return SPHERES_ON_X.format(pair_style=pair_style, contact=contact, RHO=RHO, x1=-r1 - gap / 2, x2=r2 + gap / 2,
                               d1=2 * r1, d2=2 * r2, v1=speed * m2 / (m1 + m2),
                               v2=-speed * m1 / (m1 + m2)) + f"variable er equal (vx[2]-vx[1])/{speed}\n"


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
