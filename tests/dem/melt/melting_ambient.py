#!/usr/bin/python3
"""The Codina2019 §2.3 particle (d = 600 um, rho = 8020, cp = 48.35, Tm = 1000 K, T0 = 0 K,
v = (0,-2,0) m/s) melts in the table 2.2 gas (1500 K, k = 100, U = (0,-2,0): no slip, Nu = 2)
given by 'ambient'. Everything it absorbs and hands over must be booked:
heat = m cp (Tm - T0) + m L, mass = m, enthalpy = m (cp Tm + L) (eq. 2.9), momentum = m v
(eq. 2.11); the particle is deleted. Argument: number of MPI ranks (the np 2 case melts
8 particles that cross the rank boundary, and goes through write_restart / read_restart
halfway)."""
import math
import sys

from meltdem.testing.lammps_run import printed_value as value, run, thermo_rows as thermo
from meltdem.testing.report import check_absolute, check_at_most, check_relative
from melt_common import HEADER, LEDGER_OUTPUT, THESIS_GAS, THESIS_LATENT, THESIS_MELTING, run_through_restart


def check_rel_error(what, measured, reference, tol):
    """report the relative error itself, so the table shows how close it is"""
    return check_at_most(TEST, what + f" (measured {measured:.17g}, reference {reference:.17g})",
                         abs(measured - reference) / abs(reference), tol)


np = int(sys.argv[1]) if len(sys.argv) > 1 else 1
TEST = "dem.melt.melting_ambient" + ("" if np == 1 else f".np{np}")
d, rho, cp, Tm, T0, Tf, k = THESIS_MELTING
L = THESIS_LATENT
dt = 1e-6
n = 1 if np == 1 else 8

procs = "" if n == 1 else "processors 2 1 1\n"
if n == 1:
    atoms = "create_atoms 1 single 0 0 0\n"
else:
    # 8 particles astride x = 0, the boundary of the two ranks, moving across it
    atoms = "".join(f"create_atoms 1 single {(-1) ** i * 0.002 * (i + 1) / 8:.6f} {0.001 * i:.6f} 0\n"
                    for i in range(n))
melt = (f"fix m all powder/melt cp {cp} Tmelt {Tm} latent {L!r} temp {T0} "
        f"ambient {THESIS_GAS}\n")
text = HEADER.replace("create_box", procs + "create_box") + atoms + f"""
set group all diameter {d} density {rho}
variable vx atom {"4*(x<0)-2" if n > 1 else "0"}
velocity all set v_vx -2 0
variable m0 equal mass[1]
variable m0f format m0 %.17g
print "MASS ${{m0f}}"
timestep {dt}
""" + melt + LEDGER_OUTPUT
if n == 1:
    # halfway: the per-atom outputs [1] temperature and [2] melted fraction
    probe = """variable T equal F_m[1][1]
variable f equal F_m[1][2]
variable mm equal mass[1]
variable Tf format T %.17g
variable ff format f %.17g
variable mmf format mm %.17g
print "TEMP ${Tf}"
print "FRAC ${ff}"
print "MNOW ${mmf}"
"""
    _, out = run(text + "run 1500\n" + probe + "run 800\n")
else:
    # halfway through melting: write_restart, then go on in a new process from the file
    out = run_through_restart(text, procs, melt, dt, np, 1000, 1300)
m = value(out, "MASS")
rows = thermo(out)
last = rows[-1]
ok = True
ok &= check_absolute(TEST, "particles left after melting", last["Atoms"], 0, 0)
ok &= check_rel_error("heat absorbed vs n (m cp (Tm - T0) + m L) relative error", last["f_m[6]"],
                      n * (m * cp * (Tm - T0) + m * L), 1e-10)
ok &= check_rel_error("mass handed over vs n m0 relative error", last["f_m[1]"], n * m, 1e-15)
ok &= check_rel_error("enthalpy handed over vs n m (cp Tm + L) (eq. 2.9) relative error", last["f_m[2]"],
                      n * m * (cp * Tm + L), 1e-12)
ok &= check_rel_error("y momentum handed over vs n m vy (eq. 2.11) relative error", last["f_m[4]"],
                      n * m * -2.0, 1e-12)
if n == 1:
    ok &= check_absolute(TEST, "per-atom temperature while melting [K]", value(out, "TEMP"), Tm, 0.0)
    ok &= check_relative(TEST, "per-atom melted fraction vs 1 - m/m0 (step 1500)", value(out, "FRAC"),
                         1.0 - value(out, "MNOW") / m, 1e-14)
    ok &= check_relative(TEST, "latent heat m L vs thesis E_latent [J]", m * L, 0.248611, 2e-4)
    ok &= check_relative(TEST, "momentum handed over vs thesis 1.814e-6 [kg m/s]", -last["f_m[4]"], 1.814e-6, 1e-3)
    # melt time: heat to Tm (exponential, Nu = 2), then the d^2 law; the atom goes one step later
    tau = rho * cp * d * d / (12.0 * k)
    t_melt = tau * math.log((Tf - T0) / (Tf - Tm)) + d * d * rho * L / (8.0 * k * (Tf - Tm))
    gone = next(r["Step"] for r in rows if r["Atoms"] == 0)
    ok &= check_absolute(TEST, "melt time [s] (particle gone at the next step)", (gone - 1) * dt, t_melt, dt)
else:
    ok &= check_absolute(TEST, "x momentum handed over (+-2 m/s pairs) [kg m/s]", last["f_m[3]"], 0.0, 1e-20)
sys.exit(0 if ok else 1)
