#!/usr/bin/python3
"""Pop-corn (Codina2019 §3.2.1) measured by compute powder/overlap.

Two steel spheres (R = 10 um) collide head-on at 30 m/s; the elastic Hertz overlap peaks
at delta_max = (15 m* U^2 / (16 E* sqrt R*))^(2/5) = 0.032 R. With fix powder/dt steps
S >= 10 the largest overlap stays within 5 % of delta_max and the compute reports no
contact above the default threshold 0.05. With S = 1 a step is the whole contact time:
the gap is chosen so the first step in contact lands 80 % of a step deep (2.3 delta_max),
the compute flags it and warns, and the pair leaves faster than it came (pop-corn)."""
from meltdem.testing.lammps_run import run, thermo_runs
from meltdem.testing.report import check_at_most, check_relative, report
from meltdem.testing.dem import delta_max, mass, t_contact, two_spheres

TEST = "dem.overlap.popcorn"
R, U = 10e-6, 30.0
dmax = delta_max(mass(R), mass(R), R, R, U) / R
# dt at S = 1 is t_c(equal spheres R, U_est = 2 max|v| = U): start 0.2 step apart
dt1 = t_contact(mass(R), mass(R), R, R, U)
gap = 0.2 * U * dt1

ok = True
speeds = {}
for S in (1, 10, 20):
    text = two_spheres(-R - gap / 2, R + gap / 2, 2 * R, 2 * R, U / 2, -U / 2) + f"""
fix dt all powder/dt steps {S}
compute ov all powder/overlap
variable vrel equal vx[2]-vx[1]
thermo_style custom step time dt c_ov[1] c_ov[2] c_ov[3] c_ov[4] v_vrel
thermo_modify format float %.17g
thermo 1
run {4 * S + 4}
"""
    _, out = run(text)
    rows = thermo_runs(out)[0]
    peak = max(r["c_ov[1]"] for r in rows)
    flagged = max(r["c_ov[2]"] for r in rows)
    contacts = max(r["c_ov[4]"] for r in rows)
    vout = rows[-1]["v_vrel"]
    warned = "pop-corn at step" in out
    if S == 1:
        ok &= report(TEST, "S = 1: largest overlap/R vs elastic delta_max/R", peak,
                     f">= 1.5 x {dmax:.4g}", "bound", peak >= 1.5 * dmax)
        ok &= report(TEST, "S = 1: contacts flagged above 0.05", flagged, ">= 1", "bound", flagged >= 1)
        ok &= report(TEST, "S = 1: warning printed", warned, True, "exact", warned)
        ok &= report(TEST, "S = 1: rebound speed / impact speed (pop-corn > 1)", vout / U, "> 1.2", "bound",
                     vout / U > 1.2)
    else:
        ok &= check_relative(TEST, f"S = {S}: largest overlap/R vs elastic delta_max/R", peak, dmax, 0.05)
        ok &= check_at_most(TEST, f"S = {S}: contacts flagged above 0.05", flagged, 0)
        ok &= report(TEST, f"S = {S}: no warning", warned, False, "exact", not warned)
        ok &= check_relative(TEST, f"S = {S}: rebound speed / impact speed (elastic)", vout / U, 1.0, 0.01)
        ok &= report(TEST, f"S = {S}: contact counted", contacts, 1, "exact", contacts == 1)
raise SystemExit(0 if ok else 1)
