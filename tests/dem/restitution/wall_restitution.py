#!/usr/bin/python3
"""Head-on impact of a 30 um steel sphere (E = 200 GPa, nu = 0.3) on fix wall/gran/powder
(plane z = 0; and fix wall/gran/region/powder, the face of a block region) at 2 and 20 m/s, no
gravity, dt = 1e-10 s (t_c/dt ~ 700-1100): the measured e = |v_n after| / |v_n before| must be
the prescribed e within 1 % for 'damping tsuji', and e(alpha) of the dimensionless Hertz-Tsuji
contact (integrated here with scipy) for 'damping tsuji/alpha' (alpha = 1: the Codina2019 wall
value). Stock wall/gran is printed."""
import os
import sys

from meltdem.analysis.hertz import restitution_for_alpha
from meltdem.testing.lammps_run import printed_value, run_file
from meltdem.testing.report import check_relative, report

HERE = os.path.dirname(os.path.abspath(__file__))

T = "dem.restitution.wall"


def run(style, e, v, damp="tsuji", extra="", geom="zplane 0.0 NULL", init2=0):
    wallfix = (f"{style} granular hertz/material 200e9 {e} 0.3 damping {damp} {extra} "
               "tangential linear_nohistory 1.0 0.0")
    _, out = run_file(os.path.join(HERE, 'in.wall_head_on'),
                      dict(v=v, z0='15.01e-6', dt='1e-10', n=3000, every=3000, wallfix=wallfix, wallgeom=geom,
                           init2=init2))
    return printed_value(out, "RESULT")


ok = True
for v in (2, 20):
    for e in (0.3, 0.5, 0.7, 0.9):
        ok &= check_relative(T, f"wall e at {v} m/s (prescribed {e})", run('wall/gran/powder', e, v), e, 0.01)
        report(T, f"stock wall/gran e at {v} m/s (prescribed {e}, not asserted)",
               run('wall/gran', e, v), e, "none", True)
for alpha in (1.0, 0.01):
    ref = restitution_for_alpha(alpha)
    ok &= check_relative(T, f"wall e for tsuji/alpha {alpha} at 20 m/s", run('wall/gran/powder', 0.5, 20,
                         f'tsuji/alpha {alpha}'), ref, 0.01)
# a second init (run 0 before the run) must not change alpha
ok &= check_relative(T, "wall e at 20 m/s after a 'run 0' (prescribed 0.5)", run('wall/gran/powder', 0.5, 20, init2=1),
                     0.5, 0.01)
report(T, "stock wall/gran e at 20 m/s after a 'run 0' (prescribed 0.5, not asserted)",
       run('wall/gran', 0.5, 20, init2=1), 0.5, "none", True)
# region walls (fix wall/gran/region/powder): the bottom face of a block region
for e in (0.3, 0.5, 0.7, 0.9):
    ok &= check_relative(T, f"region wall e at 20 m/s (prescribed {e})",
                         run('wall/gran/region/powder', e, 20, geom='region cup'), e, 0.01)
# a softer wall of another material and a rigid wall change E* but not e
ok &= check_relative(T, "wall e at 20 m/s (prescribed 0.5, wall_material 70e9 0.33)",
                     run('wall/gran/powder', 0.5, 20, extra='wall_material 70e9 0.33'), 0.5, 0.01)
ok &= check_relative(T, "wall e at 20 m/s (prescribed 0.5, wall_material rigid)",
                     run('wall/gran/powder', 0.5, 20, extra='wall_material rigid'), 0.5, 0.01)
sys.exit(0 if ok else 1)
