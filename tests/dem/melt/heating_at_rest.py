#!/usr/bin/python3
"""Heating at rest (Nu = 2, zero slip): T(t) = Tf + (T0 - Tf) exp(-t/tau),
tau = rho cp d^2 / (6 Nu k_f); the heat booked must equal m cp (T - T0).
Two time steps (tau/200 and tau/5): the exact step integration makes both exact."""
import math
import sys

from meltdem.testing.lammps_run import printed_value as value, run, thermo_rows as thermo
from meltdem.testing.report import check_at_most, check_relative
from melt_common import HEADER

TEST = "dem.melt.heating_at_rest"
d, rho, cp, k, Tf, T0 = 600e-6, 8020.0, 48.35, 100.0, 1500.0, 300.0
tau = rho * cp * d * d / (6.0 * 2.0 * k)

ok = True
for per_tau in (200, 5):
    dt = tau / per_tau
    text = HEADER + f"""
create_atoms 1 single 0 0 0
set atom 1 diameter {d} density {rho}
# Tmelt far above the gas: no melting
fix m all powder/melt cp {cp} Tmelt 1e9 latent 2.7e5 temp {T0} ambient {Tf} {k} 1.2 1.8e-5 520 0 0 0
timestep {dt!r}
variable T equal F_m[1][1]
variable m0 equal mass[1]
variable m0f format m0 %.17g
print "MASS ${{m0f}}"
thermo_style custom step time v_T f_m[6]
thermo_modify format float %.17g
thermo {per_tau // 2}
run {3 * per_tau}
"""
    _, out = run(text)
    m = value(out, "MASS")
    rows = thermo(out)
    for r in rows[1:]:
        t = r["Time"]
        T_ref = Tf + (T0 - Tf) * math.exp(-t / tau)
        ok &= check_relative(TEST, f"T(t = {t / tau:.1f} tau), dt = tau/{per_tau} [K]", r["v_T"], T_ref, 5e-3)
    last = rows[-1]
    ok &= check_relative(TEST, f"heat absorbed = m cp (T - T0), dt = tau/{per_tau} [J]", last["f_m[6]"],
                         m * cp * (last["v_T"] - T0), 1e-10)
    # the 0.5 % contract is loose for an exact integrator: show how exact it is
    worst = max(abs(r["v_T"] - (Tf + (T0 - Tf) * math.exp(-r["Time"] / tau))) /
                (Tf + (T0 - Tf) * math.exp(-r["Time"] / tau)) for r in rows[1:])
    ok &= check_at_most(TEST, f"worst relative T error over 3 tau, dt = tau/{per_tau}", worst, 1e-9)
sys.exit(0 if ok else 1)
