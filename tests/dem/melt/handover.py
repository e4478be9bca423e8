#!/usr/bin/python3
"""fix powder/melt handover: the Codina2019 §2.3 particle (d0 = 600 um) melts in the table 2.2
gas as in melting_ambient.py, with 'handover D' at D = d0 / 2. It heats to Tm, shrinks by the
d^2 law and, in the step its diameter passes D, hands what is left to the continuum whole: the
mass handed over is all of m0, the enthalpy handed over is m0 cp T0 plus the heat absorbed
(the remnant goes with its sensible enthalpy, not melted), the remnant's unmelted mass is that
of a D sphere within one step's melting, and the particle is gone at the time the d^2 law
reaches D."""
import math
import sys

from meltdem.testing.lammps_run import printed_value as value, run, thermo_rows as thermo
from meltdem.testing.report import check_absolute, check_at_most, check_relative
from melt_common import HEADER

TEST = "dem.melt.handover"
d0, rho, cp, Tm, T0, Tf, k = 600e-6, 8020.0, 48.35, 1000.0, 0.0, 1500.0, 100.0
L = 0.248611 / 9.069e-7  # Codina2019: E_latent = 0.248611 J for m = 9.069e-7 kg
D = 0.5 * d0
dt = 1e-6

text = HEADER + f"""create_atoms 1 single 0 0 0
set group all diameter {d0} density {rho}
velocity all set 0 -2 0
variable m0 equal mass[1]
variable m0f format m0 %.17g
print "MASS ${{m0f}}"
timestep {dt}
fix m all powder/melt cp {cp} Tmelt {Tm} latent {L!r} temp {T0} &
    ambient {Tf} {k} 1.6115 2.1e-5 5210.928 0 -2 0 handover {D!r}
fix nve all nve/sphere
thermo_style custom step atoms f_m[1] f_m[2] f_m[3] f_m[4] f_m[5] f_m[6]
thermo_modify format float %.17g
thermo 1
run 2000
"""
_, out = run(text)
m = value(out, "MASS")
rows = thermo(out)
last = rows[-1]


def check_rel_error(what, measured, reference, tol):
    return check_at_most(TEST, what + f" (measured {measured:.17g}, reference {reference:.17g})",
                         abs(measured - reference) / abs(reference), tol)


ok = check_absolute(TEST, "particles left after the handover", last["Atoms"], 0, 0)
ok &= check_rel_error("mass handed over vs m0 relative error", last["f_m[1]"], m, 1e-15)
ok &= check_rel_error("enthalpy handed over vs m0 cp T0 + heat absorbed relative error", last["f_m[2]"],
                      m * cp * T0 + last["f_m[6]"], 1e-12)
ok &= check_rel_error("y momentum handed over vs m0 vy relative error", last["f_m[4]"], m * -2.0, 1e-12)
# the unmelted remnant: what the handed enthalpy lacks of a fully melted grain's m0 (cp Tm + L)
remnant = (m * (cp * Tm + L) - last["f_m[2]"]) / L
m_D = rho * math.pi / 6.0 * D ** 3
shrink = 8.0 * k * (Tf - Tm) / (rho * L)  # d^2 law: d(d^2)/dt = -shrink
one_step = 1.5 * shrink * dt / (D * D) * 1.05  # relative mass melted in one step at D (m ~ d^3)
ok &= check_relative(TEST, "remnant mass handed over unmelted vs rho pi D^3 / 6 (within one step's melting)",
                     remnant, m_D, one_step)
tau = rho * cp * d0 * d0 / (12.0 * k)
t_D = tau * math.log((Tf - T0) / (Tf - Tm)) + (d0 * d0 - D * D) / shrink
gone = next(r["Step"] for r in rows if r["Atoms"] == 0)
ok &= check_absolute(TEST, "handover time [s] (d^2 law reaches D; particle gone at the next step)",
                     (gone - 1) * dt, t_D, dt)
t_full = tau * math.log((Tf - T0) / (Tf - Tm)) + d0 * d0 / shrink
ok &= check_at_most(TEST, "handed over before it would have melted away: t_D / t_melt", t_D / t_full, 0.9)
sys.exit(0 if ok else 1)
