#!/usr/bin/python3
"""Head-on collision of two 30 um steel spheres (E = 200 GPa, nu = 0.3), relative
speed 2 and 20 m/s, dt = 1e-10 s (t_c / dt ~ 800 at 2 m/s): pair_style granular/powder
with 'damping tsuji' must return the prescribed e within 1 %; tsuji/alpha 1.5 must give
coupling::restitution_for_alpha(1.5) = 0.05833. Stock granular's biased e is printed."""
import os
import sys
from meltdem.testing.report import check_relative, report
from meltdem.testing.lammps_run import printed_value, run_file

T = "dem.restitution.monodisperse"
IN = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'in.head_on')


def run(style, e, v, damp="tsuji"):
    _, out = run_file(IN, dict(v=v, style=style, e=e, damp=damp, dt=1e-10, n=3000))
    return printed_value(out, "RESULT")


ok = True
for v in (1, 10):
    for e in (0.3, 0.5, 0.7, 0.9):
        ok &= check_relative(T, f"e at {2 * v} m/s (prescribed {e})", run('granular/powder', e, v), e, 0.01)
        report(T, f"stock granular e at {2 * v} m/s (prescribed {e}, not asserted)",
               run('granular', e, v), e, "none", True)
ok &= check_relative(T, "e for tsuji/alpha 1.5 at 20 m/s", run('granular/powder', 0.5, 10, 'tsuji/alpha 1.5'),
                     0.0583279, 0.01)
sys.exit(0 if ok else 1)
