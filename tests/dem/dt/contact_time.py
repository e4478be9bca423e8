#!/usr/bin/python3
"""fix powder/dt reproduces eq. 3.1-3.4: dt = t_c(R_min, rho_min, E*, 2 max|v|) / S, the
sub-cycle count ceil(interval/dt), and follows changes of speed, radius and density."""
import math
import sys

from meltdem.testing.lammps_run import run, thermo_runs
from meltdem.testing.report import check_absolute, check_at_most, check_relative
from meltdem.testing.dem import ESTAR, RHO, mass, two_spheres

NP = int(sys.argv[1]) if len(sys.argv) > 1 else 1
TEST = "dem.dt.contact_time" + (f".np{NP}" if NP > 1 else "")
S, INTERVAL, DTMAX = 20, 1e-6, 1e-9
COLS = "step time dt f_dt[1] f_dt[2] f_dt[3] f_dt[4] f_dt[5] f_dt[6] f_dt[7] v_v1 v_v2"


def tc_equal(R, rho, U):
    return 2.87 * ((0.5 * mass(R, rho)) ** 2 / (0.5 * R * ESTAR ** 2 * U)) ** 0.2


text = two_spheres(-6e-5, 6e-5, 20e-6, 30e-6, 1.0, -1.0) + f"""
fix dt all powder/dt steps {S} interval {INTERVAL}
variable v1 equal sqrt(vx[1]^2+vy[1]^2+vz[1]^2)
variable v2 equal sqrt(vx[2]^2+vy[2]^2+vz[2]^2)
thermo_style custom {COLS}
thermo_modify format float %.17g
thermo 100
run 0
# faster: U = 2 * 3 m/s
set atom 1 vx 3.0
run 0
# smaller particle: R_min = 7 um
set atom 1 diameter 14e-6 density {RHO}
run 0
# lighter particle: rho_min = 4000
set atom 2 density 4000
run 0
# accelerated during a run: dt follows |v| at every step
fix push all addforce 1e-6 0 0
run 300
unfix dt
# every 50: dt is held between updates
fix dt all powder/dt steps {S} every 50
thermo 10
run 100
unfix push
unfix dt
fix dt all powder/dt steps {S} max {DTMAX}
run 0
"""
_, out = run(text, np=NP)
runs = thermo_runs(out)
ok = True
cases = [("1 m/s, R 10 um", runs[0][0], 10e-6, RHO),
         ("3 m/s", runs[1][0], 10e-6, RHO),
         ("R 7 um", runs[2][0], 7e-6, RHO),
         ("rho 4000", runs[3][0], 7e-6, 4000.0),
         ("during run (step 300)", runs[4][-1], 7e-6, 4000.0)]
for what, row, R, rho in cases:
    U = 2.0 * max(row["v_v1"], row["v_v2"])
    tc = tc_equal(R, rho, U)
    ok &= check_relative(TEST, f"t_c eq. 3.1 [s], {what}", row["f_dt[2]"], tc, 1e-10)
    ok &= check_relative(TEST, f"dt = t_c/{S} [s] (update->dt), {what}", row["Dt"], tc / S, 1e-10)
    ok &= check_relative(TEST, f"U = 2 max|v| [m/s], {what}", row["f_dt[5]"], U, 1e-12)
    ok &= check_relative(TEST, f"R_min [m], {what}", row["f_dt[4]"], R, 1e-12)
    ok &= check_relative(TEST, f"rho_min [kg/m3], {what}", row["f_dt[7]"], rho, 1e-10)
    n = math.ceil(INTERVAL / (tc / S))
    ok &= check_relative(TEST, f"sub-cycles ceil(interval/dt) eq. 3.4, {what}", row["f_dt[3]"], n, 0.0)
ok &= check_relative(TEST, "E* [Pa]", runs[0][0]["f_dt[6]"], ESTAR, 1e-12)
# the run really used the changing dt: elapsed time = sum of the steps
r = runs[4]
ok &= check_at_most(TEST, "U step 0 / U step 300 under a push (dt followed the speed)",
                    r[0]["f_dt[5]"] / r[-1]["f_dt[5]"], 0.995)
r = runs[5]
held = [row["Dt"] for row in r[:5]]  # steps +0 .. +40 after the setup update
ok &= check_absolute(TEST, "every 50: dt held between updates (spread over 40 steps) [s]",
                     max(held) - min(held), 0.0, 0.0)
row = r[5]  # step 50 of this run: updated from the pushed speed
U = 2.0 * max(row["v_v1"], row["v_v2"])
ok &= check_relative(TEST, f"every 50: dt at the update step {int(row['Step'])} [s]", row["Dt"],
                     tc_equal(7e-6, 4000.0, U) / S, 1e-10)
ok &= check_relative(TEST, "dt capped by max [s]", runs[6][0]["Dt"], DTMAX, 1e-15)
raise SystemExit(0 if ok else 1)
