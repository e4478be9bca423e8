#!/usr/bin/python3
"""Settling of a 20 um steel sphere (rho_p = 8000) under fix gravity in a liquid
(rho_f = 1000) with drag and buoyancy of fix powder/melt (eq. 2.14), both drag laws:
 - mu = 0.1 Pa s (Re ~ 4e-6): v_t = (rho_p - rho_f) g d^2 / (18 mu) (Stokes), <= 2 %;
 - mu = 1e-3 Pa s (Re ~ 0.03, where Cd Re departs from 24 by 1-2 %): the terminal velocity
   of the law itself, (rho_p - rho_f) V g = 3 pi mu d (Cd Re / 24) v_t, solved here, to 1e-6 with
   coefficient_tolerance 0 (the law evaluated every step), and within the held coefficients'
   tolerance with coefficient_tolerance 0.01 (the drag coefficient within 1 % of the law)."""
import math
import sys

from scipy.optimize import brentq

from meltdem.testing.lammps_run import run, thermo_rows as thermo
from meltdem.testing.report import check_relative
from melt_common import HEADER

TEST = "dem.melt.stokes_settling"
d, rho_p, rho_f, g = 20e-6, 8000.0, 1000.0, 9.81


def cd_re(model, Re):
    if model == "thesis":
        return 24.0 + 4.0 * Re ** (2.0 / 3.0)
    return 24.0 * (1.0 + 0.15 * Re ** 0.687)


def settle(model, mu, keywords=""):
    tau_v = rho_p * d * d / (18.0 * mu)  # velocity response time
    dt = tau_v / 100.0
    nsteps = 1500  # 15 tau_v: exp(-15), at terminal velocity
    text = HEADER + f"""
create_atoms 1 single 0 0 0
set atom 1 diameter {d} density {rho_p}
fix m all powder/melt cp 500 Tmelt 1700 latent 2.7e5 temp 300 ambient 300 0.6 {rho_f} {mu} 4180 0 0 0 &
    drag {model} {keywords}
fix g all gravity {g} vector 0 0 -1
fix nve all nve/sphere
timestep {dt!r}
variable vz equal vz[1]
thermo_style custom step time v_vz f_m[6]
thermo_modify format float %.17g
thermo {nsteps}
run {nsteps}
"""
    _, out = run(text)
    return -thermo(out)[-1]["v_vz"]


ok = True
for model in ("thesis", "schiller-naumann"):
    mu = 0.1
    v = settle(model, mu)
    vt = (rho_p - rho_f) * g * d * d / (18.0 * mu)
    Re = rho_f * v * d / mu
    ok &= check_relative(TEST, f"Stokes terminal velocity, drag {model}, Re = {Re:.1e} [m/s]", v, vt, 0.02)

    mu = 1e-3
    weight = (rho_p - rho_f) * math.pi / 6.0 * d ** 3 * g
    vt = brentq(lambda u: 3.0 * math.pi * mu * d * cd_re(model, rho_f * u * d / mu) / 24.0 * u - weight,
                1e-9, 1.0, xtol=1e-16, rtol=1e-14)
    v = settle(model, mu, "coefficient_tolerance 0")
    Re = rho_f * v * d / mu
    ok &= check_relative(TEST, f"terminal velocity of the {model} law, Re = {Re:.2g}, every step [m/s]", v, vt, 1e-6)
    v = settle(model, mu, "coefficient_tolerance 0.01")
    ok &= check_relative(TEST, f"terminal velocity of the {model} law, Re = {Re:.2g}, held coefficients [m/s]",
                         v, vt, 1e-2)
sys.exit(0 if ok else 1)
