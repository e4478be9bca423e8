#!/usr/bin/python3
"""Held coefficients while the slip changes: two grains (100 and 50 um, rho 8000, cp 500, Tm
1000 K, T0 300 K, L 2.7e5 J/kg) start at rest
in air (1500 K, k 0.026, mu 1.8e-5) flowing at 5 m/s, so the drag slows their slip (Re 33 -> 0)
and with it the Ranz-Marshall Nu (5 -> 2) while they heat; the small grain melts while the large
one is still heating. The held run (the default coefficient_tolerance 0.01: drag and
heat step from lines in s^(1/2), taken together in the fix's post_force with the step's
mid-point velocity) against the same run with every coefficient evaluated every step (0, the
heat at end_of_step with the full-step velocity):
- the temperatures within 1 % of the heating range T_gas - T0 at every output step (the held
  heat factor is within 1 % of the exact one), the velocities within 1 % of the gas speed;
- each run's ledger: heat absorbed = sum m cp (T - T0) before melting (1e-12), and at the end
  heat = sum m (cp (Tm - T0) + L), mass = sum m (1e-13; both grains melted and deleted);
- the per-atom array by atom ID, F_m[I][1], equals the temperature of atom I."""
import math
import sys

from meltdem.testing.lammps_run import run, thermo_runs
from meltdem.testing.report import check_absolute, check_at_least, check_at_most
from melt_common import HEADER

TEST = "dem.melt.heating_with_slip"
rho, cp, Tm, T0, L = 8000.0, 500.0, 1000.0, 300.0, 2.7e5
Tf, k, rho_f, mu, cp_f, U = 1500.0, 0.026, 1.2, 1.8e-5, 1005.0, 5.0
diameters = (100e-6, 50e-6)
masses = [rho * math.pi / 6.0 * d ** 3 for d in diameters]
tau = rho * cp * diameters[0] ** 2 / (6.0 * 2.0 * k)  # the large grain's heating time at Nu = 2
dt = tau / 400
steps = 800  # past the large grain's melting
every = 10


def heat_run(tolerance):
    """thermo rows (per-grain T and vy from compute reduce over one-grain groups); the first run
    also prints the per-atom array by atom ID, F_m[I][1]"""
    text = HEADER + f"""create_atoms 1 single -0.004 0 0
create_atoms 1 single 0.004 0 0
set atom 1 diameter {diameters[0]} density {rho}
set atom 2 diameter {diameters[1]} density {rho}
fix m all powder/melt cp {cp} Tmelt {Tm} latent {L} temp {T0} ambient {Tf} {k} {rho_f} {mu} {cp_f} 0 {U} 0 \
coefficient_tolerance {tolerance}
fix nve all nve/sphere
timestep {dt!r}
group big id 1
group small id 2
compute T1 big reduce max f_m[1]
compute T2 small reduce max f_m[1]
compute v1 big reduce max vy
compute v2 small reduce max vy
variable T1 equal F_m[1][1]
variable T2 equal F_m[2][1]
thermo_style custom step atoms c_T1 c_T2 c_v1 c_v2 f_m[1] f_m[6] v_T1 v_T2
thermo_modify format float %.17g
thermo 4
run 20
thermo_style custom step atoms c_T1 c_T2 c_v1 c_v2 f_m[1] f_m[6]
thermo_modify format float %.17g
thermo {every}
run {steps - 20}
"""
    _, out = run(text)
    return thermo_runs(out)


ok = True
held_runs, exact_runs = heat_run(0.01), heat_run(0)
# the per-atom array by atom ID (LAMMPS reads it with the stride of its two columns)
for j in (1, 2):
    worst = max(abs(r[f"v_T{j}"] - r[f"c_T{j}"]) for r in held_runs[0])
    ok &= check_at_most(TEST, f"F_m[{j}][1] vs the per-atom temperature of atom {j} (compute reduce), "
                        f"worst difference over {len(held_runs[0])} rows [K]", worst, 0.0)
held, exact = (held_runs[0] + held_runs[1][1:]), (exact_runs[0] + exact_runs[1][1:])
# every output step where a grain is there in both runs (compute reduce over an empty group: -1e20)
there = [(a, b, j) for a, b in zip(held, exact) for j in (1, 2)
         if a["Step"] > 0 and a[f"c_T{j}"] > -1e19 and b[f"c_T{j}"] > -1e19]
both = [(a, b) for a, b in zip(held, exact) if a["Atoms"] == 2 and b["Atoms"] == 2 and a["Step"] > 0]
ok &= check_at_least(TEST, "output steps with both grains there (held and exact runs)", len(both), 10)
worst_T = max(abs(a[f"c_T{j}"] - b[f"c_T{j}"]) for a, b, j in there) / (Tf - T0)
worst_v = max(abs(a[f"c_v{j}"] - b[f"c_v{j}"]) for a, b, j in there) / U
ok &= check_at_most(TEST, f"held vs every-step temperatures, worst difference / (T_gas - T0) ({len(there)} values)",
                    worst_T, 0.01)
ok &= check_at_most(TEST, f"held vs every-step velocities, worst difference / U_gas ({len(there)} values)",
                    worst_v, 0.01)
slip_start, slip_end = U - both[0][1]["c_v1"], U - both[-1][1]["c_v1"]
ok &= check_at_most(TEST, "large grain's slip at the last shared output / at the first (the slip changed)",
                    slip_end / slip_start, 0.9)
for name, rows in (("held", held), ("every step", exact)):
    before = [r for r in rows if r["Atoms"] == 2 and r["f_m[1]"] == 0.0 and r["Step"] > 0][-1]
    booked = sum(m * cp * (before[f"c_T{j + 1}"] - T0) for j, m in enumerate(masses))
    ok &= check_at_most(TEST, f"{name}: heat absorbed vs sum m cp (T - T0) before melting, relative "
                        f"(step {before['Step']}, {before['f_m[6]']:.6g} J)",
                        abs(before["f_m[6]"] - booked) / booked, 1e-12)
    last = rows[-1]
    ok &= check_absolute(TEST, f"{name}: grains left at step {last['Step']}", last["Atoms"], 0, 0)
    total = sum(m * (cp * (Tm - T0) + L) for m in masses)
    ok &= check_at_most(TEST, f"{name}: heat absorbed vs sum m (cp (Tm - T0) + L) at the end, relative",
                        abs(last["f_m[6]"] - total) / total, 1e-13)
    ok &= check_at_most(TEST, f"{name}: mass handed over vs sum m at the end, relative",
                        abs(last["f_m[1]"] - sum(masses)) / sum(masses), 1e-13)
sys.exit(0 if ok else 1)
