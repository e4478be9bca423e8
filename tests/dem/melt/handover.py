#!/usr/bin/python3
"""fix powder/melt handover: the Codina2019 §2.3 particle (d0 = 600 um) melts in the table 2.2
gas as in melting_ambient.py, with 'handover D' at D = d0 / 2. It heats to Tm, shrinks by the
d^2 law and, in the step its diameter passes D, hands what is left to the continuum whole: the
mass handed over is all of m0, the enthalpy handed over is m0 cp T0 plus the heat absorbed
(the remnant goes with its sensible enthalpy, not melted), the remnant's unmelted mass is that
of a D sphere within one step's melting, and the particle is gone at the time the d^2 law
reaches D. Argument: number of MPI ranks (the np 2 case hands over 8 particles that fall
with the gas, six of them across the boundary of the two ranks before the handover, and goes
through write_restart / read_restart before it)."""
import math
import sys

from meltdem.testing.lammps_run import printed_value as value, run, thermo_rows as thermo
from meltdem.testing.report import check_absolute, check_at_most, check_relative
from melt_common import HEADER, LEDGER_OUTPUT, THESIS_GAS, THESIS_LATENT, THESIS_MELTING, run_through_restart

np = int(sys.argv[1]) if len(sys.argv) > 1 else 1
TEST = "dem.melt.handover" + ("" if np == 1 else f".np{np}")
d0, rho, cp, Tm, T0, Tf, k = THESIS_MELTING
L = THESIS_LATENT
D = 0.5 * d0
dt = 1e-6

n = 1 if np == 1 else 8
procs = "" if n == 1 else "processors 1 2 1\n"
if n == 1:
    atoms = "create_atoms 1 single 0 0 0\n"
else:
    # 8 particles above y = 0, the boundary of the two ranks, falling with the gas (2 m/s, no
    # slip: each melts as the single one does); particle i crosses it at (i + 1) 0.25 ms, six of
    # them before the handover at 1.61 ms, three before the restart
    atoms = "".join(f"create_atoms 1 single {0.001 * (i - 4):.6f} {0.0005 * (i + 1):.6f} 0\n" for i in range(n))
melt = (f"fix m all powder/melt cp {cp} Tmelt {Tm} latent {L!r} temp {T0} "
        f"ambient {THESIS_GAS} handover {D!r}\n")
text = HEADER.replace("create_box", procs + "create_box") + atoms + f"""set group all diameter {d0} density {rho}
velocity all set 0 -2 0
variable m0 equal mass[1]
variable m0f format m0 %.17g
print "MASS ${{m0f}}"
timestep {dt}
""" + melt + LEDGER_OUTPUT
if n == 1:
    _, out = run(text + "run 2000\n")
else:
    # before the handover: write_restart, then go on in a new process from the file
    out = run_through_restart(text, procs, melt, dt, np, 1000, 1000)
m = value(out, "MASS")
rows = thermo(out)
last = rows[-1]


def check_rel_error(what, measured, reference, tol):
    return check_at_most(TEST, what + f" (measured {measured:.17g}, reference {reference:.17g})",
                         abs(measured - reference) / abs(reference), tol)


ok = check_absolute(TEST, "particles left after the handover", last["Atoms"], 0, 0)
ok &= check_rel_error("mass handed over vs n m0 relative error", last["f_m[1]"], n * m, 1e-15)
ok &= check_rel_error("enthalpy handed over vs n m0 cp T0 + heat absorbed relative error", last["f_m[2]"],
                      n * m * cp * T0 + last["f_m[6]"], 1e-12)
ok &= check_rel_error("y momentum handed over vs n m0 vy relative error", last["f_m[4]"], n * m * -2.0, 1e-12)
# the unmelted remnant: what the handed enthalpy lacks of a fully melted grain's m0 (cp Tm + L)
remnant = (m * (cp * Tm + L) - last["f_m[2]"] / n) / L
m_D = rho * math.pi / 6.0 * D ** 3
shrink = 8.0 * k * (Tf - Tm) / (rho * L)  # d^2 law: d(d^2)/dt = -shrink
one_step = 1.5 * shrink * dt / (D * D) * 1.05  # relative mass melted in one step at D (m ~ d^3)
ok &= check_relative(TEST, "remnant mass handed over unmelted vs rho pi D^3 / 6 (within one step's melting)",
                     remnant, m_D, one_step)
tau = rho * cp * d0 * d0 / (12.0 * k)
t_D = tau * math.log((Tf - T0) / (Tf - Tm)) + (d0 * d0 - D * D) / shrink
gone = next(r["Step"] for r in rows if r["Atoms"] == 0)
if n > 1:
    before = max(r["Atoms"] for r in rows if r["Step"] == gone - 1)
    ok &= check_absolute(TEST, "particles there the step before (all hand over in one step, as one rank's)",
                         before, n, 0)
ok &= check_absolute(TEST, "handover time [s] (d^2 law reaches D; particle gone at the next step)",
                     (gone - 1) * dt, t_D, dt)
t_full = tau * math.log((Tf - T0) / (Tf - Tm)) + d0 * d0 / shrink
ok &= check_at_most(TEST, "handed over before it would have melted away: t_D / t_melt", t_D / t_full, 0.9)

if n == 1:
    # a grain created smaller than D stays (the doc): it melts by the d^2 law, not handed over at
    # its first melting step (it was, at 0.7 of the time to melt away)
    d_small = 0.8 * D
    small = text.replace(f"diameter {d0}", f"diameter {d_small!r}")
    t_small = tau * (d_small / d0) ** 2 * math.log((Tf - T0) / (Tf - Tm)) + d_small ** 2 / shrink
    _, out2 = run(small + f"run {int(0.9 * t_small / dt)}\n")
    ok &= check_absolute(TEST, f"a grain created at 0.8 D: there at 0.9 of its d^2-law melting time "
                               f"({0.9 * t_small:.3g} s)", thermo(out2)[-1]["Atoms"], 1, 0)
sys.exit(0 if ok else 1)
