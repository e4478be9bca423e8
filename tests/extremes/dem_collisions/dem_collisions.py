#!/usr/bin/python3
"""Extremes of the DEM contact: Young's modulus 1e6 ... 2e11 Pa and impact speeds
0.1 ... 100 m/s. Two 30 um steel spheres (rho 7800) meet head-on; fix powder/dt sets the step
(S = 20 steps per contact) and guards Hertz's small-overlap assumption (max_overlap 0.3).

For every (E, v): where the predicted undamped head-on overlap (10 pi sqrt(2)/16 rho U^2/E*)^0.4
stays below 0.3 R the collision must happen (soft particles still collide: Codina2019 ch. 5
"non-rigid collisions"): restitution within 0.5 % of the prescribed 0.5, the largest measured
overlap within 1 % of the damped Hertz value (the dimensionless contact ODE
x'' = -x^1.5 - alpha x^0.25 x' integrated here with scipy: with Tsuji's delta^(1/4) damping the
contact is self-similar, so the damped maximum is the undamped one times x_max(alpha) / (5/4)^0.4),
nothing NaN, no particle lost. Where it does not, the run must stop at once with the message naming the
knobs (Young's modulus, impact speed, max_overlap) -- never compute nonsense silently.
"""
import math
import sys

from meltdem.testing.report import check_absolute, check_relative
from meltdem.testing.lammps_run import run

T = "extremes.dem_collisions"
# damping tsuji acts over the step just taken (exact e at any phase, doc/pair_granular_powder.rst),
# i.e. half a step late: the peak overlap is first order in 1/S (stock: -0.4 to -2.2 % by phase)
OVERLAP_MISS = "stepped damping: peak overlap +1.2 to +1.6 % at 20 steps per contact"
R, RHO, NU, E_REST = 15e-6, 7800.0, 0.3, 0.5


def text(E, v):
    return f"""units si
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
region box block -1e-4 1e-4 -1e-4 1e-4 -1e-4 1e-4
create_box 1 box
create_atoms 1 single {-R!r} 0 0
create_atoms 1 single {R!r} 0 0
set group all diameter {2 * R!r}
set group all density {RHO!r}
set atom 1 vx {v / 2!r}
set atom 2 vx {-v / 2!r}
pair_style granular/powder
pair_coeff * * hertz/material {E!r} {E_REST} {NU} damping tsuji tangential linear_nohistory 1.0 0.0
neighbor 2e-6 bin
fix 1 all nve/sphere
fix dt all powder/dt steps 20 max_overlap 0.3
compute ov all powder/overlap warn no
variable er equal (vx[1]-vx[2])/(-{v!r})
thermo_style custom step atoms c_ov[1] v_er
thermo_modify format float %.10g
thermo 1
run 120
print "RESULT ${{er}}"
"""


def damped_factor(alpha):
    """x_max(alpha) / x_max(0) of x'' = -x^1.5 - alpha x^0.25 x', x(0) = 0, x'(0) = 1."""
    from scipy.integrate import solve_ivp

    def f(t, y):
        x = max(y[0], 0.0)
        return [y[1], -x ** 1.5 - alpha * x ** 0.25 * y[1]]
    turn = lambda t, y: y[1]  # noqa: E731
    turn.terminal, turn.direction = True, -1
    sol = solve_ivp(f, (0, 10), [0.0, 1.0], events=turn, rtol=1e-12, atol=1e-14)
    return sol.y_events[0][0][0] / 1.25 ** 0.4


def main():
    ok = True
    from meltdem.analysis.hertz import restitution_for_alpha
    from scipy.optimize import brentq
    alpha = brentq(lambda a: restitution_for_alpha(a) - E_REST, 0.0, 2.0, xtol=1e-12)
    factor = damped_factor(alpha)
    print(f"{T}: damped / undamped largest overlap for e = {E_REST}: {factor:.6f}")
    for E in (1e6, 1e8, 2e11):
        estar = E / (2 * (1 - NU * NU))
        for v in (0.1, 1.0, 10.0, 100.0):
            predicted = (10 * math.pi * math.sqrt(2) / 16 * RHO * v * v / estar) ** 0.4
            rc, out = run(text(E, v), check=False)
            tag = f"E = {E:.0e} Pa, {v:g} m/s"
            if predicted > 0.3:
                stopped = rc != 0 and "raise Young's modulus" in out and "max_overlap" in out
                ok &= check_absolute(T, f"{tag}: predicted overlap {predicted:.3g} R > 0.3: stops naming the "
                                     "knobs (1 = yes)", float(stopped), 1.0, 0)
                continue
            rows = [ln.split() for ln in out.splitlines()]
            rows = [r for r in rows if len(r) == 4 and r[0].isdigit()]
            overlaps = [float(r[2]) for r in rows]
            atoms = {r[1] for r in rows}
            e = float(out.split("RESULT")[-1].split()[0]) if "RESULT" in out else float("nan")
            ok &= check_absolute(T, f"{tag}: run completed, 2 atoms throughout (1 = yes)",
                                 float(rc == 0 and atoms == {"2"}), 1.0, 0)
            ok &= check_relative(T, f"{tag}: restitution", e, E_REST, 0.005)
            ok &= check_relative(T, f"{tag}: largest overlap vs damped Hertz [R]", max(overlaps),
                                 predicted * factor, 0.01, xfail=OVERLAP_MISS, miss_within=0.03)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
