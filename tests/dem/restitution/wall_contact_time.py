#!/usr/bin/python3
"""Contact duration of a 30 um steel sphere (E = 200 GPa, nu = 0.3, rho = 7800) hitting
fix wall/gran/powder head-on, elastic (damping tsuji/alpha 0), vs Codina2019 eq. 3.1 with the
particle-wall values m* = m, R* = R and 1/E* = (1-nu^2)/E + (1-nu_w^2)/E_w: same-material
wall, a 70 GPa wall (wall_material) and a rigid wall, at 2 and 20 m/s, plane and region (fix
wall/gran/region/powder) walls; dt = 1e-10 s (t_c/dt ~ 600-1100) and at S = t_c/dt = 10 (<= 2 %).
The contact starts and ends where the gap z - r crosses 0 (linear interpolation between steps: the
sphere moves force-free on both sides). Stock wall/gran (E* too stiff by 1+nu) is printed."""
import math
import os
import sys

from meltdem.analysis.hertz import hertz_contact_time
from meltdem.testing.lammps_run import run_file
from meltdem.testing.report import check_relative, report

HERE = os.path.dirname(os.path.abspath(__file__))

T = "dem.restitution.wall_contact_time"
E, NU, RHO, D = 200e9, 0.3, 7800.0, 30e-6
R = D / 2
M = RHO * math.pi / 6 * D ** 3


def measured_contact_time(style, v, dt, extra="", geom="zplane 0.0 NULL"):
    wallfix = (f"{style} granular hertz/material {E} 0.5 {NU} damping tsuji/alpha 0 {extra} "
               "tangential linear_nohistory 1.0 0.0")
    if style == 'wall/gran':    # stock: no tsuji/alpha; viscoelastic with 0 damping is elastic
        wallfix = (f"wall/gran granular hertz/material {E} 0 {NU} damping viscoelastic "
                   "tangential linear_nohistory 1.0 0.0")
    z0 = R + 3 * v * dt
    n = int(2.5e-7 / dt) + 10 if v < 10 else int(1.5e-7 / dt) + 10
    _, out = run_file(os.path.join(HERE, 'in.wall_head_on'),
                      dict(v=v, z0=repr(z0), dt=repr(dt), n=n, every=1, wallfix=wallfix, wallgeom=geom))
    rows = []
    for line in out.splitlines():
        f = line.split()
        if len(f) == 5:
            try:
                rows.append([float(x) for x in f])
            except ValueError:
                pass
    if not rows:
        sys.exit(f"no thermo output from meltdem-lmp:\n{out[-2000:]}")
    t = [r[1] for r in rows]
    gap = [r[2] - R for r in rows]
    cross = [t[k] + gap[k] / (gap[k] - gap[k + 1]) * (t[k + 1] - t[k])
             for k in range(len(gap) - 1) if (gap[k] > 0) != (gap[k + 1] > 0)]
    if len(cross) != 2:
        sys.exit(f"expected one contact (2 gap crossings), got {len(cross)}")
    return cross[1] - cross[0]


def estar(Ew=None, nuw=None, rigid=False):
    inv = (1 - NU ** 2) / E + (0.0 if rigid else (1 - (nuw or NU) ** 2) / (Ew or E))
    return 1.0 / inv


ok = True
for v in (2, 20):
    for label, extra, es in (("same material", "", estar()),
                             ("wall_material 70e9 0.33", "wall_material 70e9 0.33", estar(70e9, 0.33)),
                             ("wall_material rigid", "wall_material rigid", estar(rigid=True))):
        ref = hertz_contact_time(M, R, es, v)
        ok &= check_relative(T, f"t_c at {v} m/s, {label}, dt 1e-10 (S = {ref / 1e-10:.0f})",
                             measured_contact_time('wall/gran/powder', v, 1e-10, extra), ref, 0.005)
    ref = hertz_contact_time(M, R, estar(), v)
    ok &= check_relative(T, f"t_c at {v} m/s, region wall (block face), same material, dt 1e-10",
                         measured_contact_time('wall/gran/region/powder', v, 1e-10, geom='region cup'), ref, 0.005)
    ok &= check_relative(T, f"t_c at {v} m/s, same material, S = 10",
                         measured_contact_time('wall/gran/powder', v, ref / 10), ref, 0.02)
    report(T, f"stock wall/gran t_c at {v} m/s, same material (not asserted)",
           measured_contact_time('wall/gran', v, 1e-10), ref, "none", True)
sys.exit(0 if ok else 1)
