#!/usr/bin/python3
"""Density ratio 1e4 in the VOF: a liquid steel drop (Fuchs2022 table 1 metal,
rho 7430) falls through a gas of rho 0.743 in a closed 2D box, energy on (isothermal 2000 K,
liquid), the surfaceTension term off: interFoam's constant sigma of transportProperties acts (the
term's capillary step would only make it slower; the case runs with it on too). The same case at
ratio 1e3 (gas rho 7.43) is the comparison.

Box 4 x 4 mm, 40 x 40 cells; drop radius 0.6 mm (12 cells across) centred 1 mm below the lid;
gravity 9.81 m/s^2 down; 8 ms (the drop falls 0.31 mm, clear of the floor). Checks:
  - no NaN, the run reaches t_end;
  - balances closed (meltdemBalance, every step): metal mass drift <= 1e-10, enthalpy drift
    <= 1e-10 of the stored enthalpy; momentum <= 1e-3 of the exchanged impulse at both ratios
    (the surface force's impulse booked: meltdemFoam's physicsForce);
  - bounded velocities: the drop's centroid falls g t^2/2 (1 - rho_g/rho_m) within 2 % (gas drag
    ~1e-3 of its weight); the largest speed at 1e4 within 2x that at 1e3; the largest gas speed
    vs 2 g t (potential flow past a cylinder; XFAIL: interface gas currents of the VOF).
usage: density_ratio.py [--keep]
"""
import math
import os
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_most, check_relative

src = paths.source_dir()

TEST = "extremes.density_ratio"
M = fc.METAL
RHO_G = M["rho"] / 1e4
MU_G = 6e-5
L, N, R = 4e-3, 40, 0.6e-3
XC, YC = 2e-3, 3e-3
G = 9.81
T_END = 8e-3
XFAIL_GAS = ("gas beside the interface moves at 0.7-1.15 m/s over the run (7x potential flow; 0.8 m/s at ratio "
             "1e3): momentum transport at the density jump is not consistent with the alpha transport")


def build(case, ratio=1e4, sigma=True):
    g = fc.Grid2D(L, L, N, N)
    g.block_mesh(case)
    alpha = fc.smooth_alpha_disc(g, XC, YC, R)
    zg = {"walls": "type zeroGradient;"}
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha, zg)
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(alpha.size, 2000.0), zg)
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((alpha.size, 3)), {"walls": "type noSlip;"}, vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(alpha.size),
             {"walls": "type fixedFluxPressure; value uniform 0;"})
    rho_g = M["rho"] / ratio
    fc.transport(case, M["rho"], M["mu"] / M["rho"], rho_g, MU_G / rho_g, M["sigma0"])
    fc.gravity(case, (0.0, -G, 0.0))
    # isothermal liquid: sigma(T) uniform, no Marangoni; solidus/liquidus far below
    fc.meltdem_properties(case, physics={"flow": "on", "energy": "on", "surfaceTension": "on" if sigma else "off"},
                          surface={"dSigmadT": 0.0},
                          extra="""metal { Tsolidus 1690; Tliquidus 1700; L 2.7e5; cp 965; k 35.95; }
gas { cp 10; k 0.026; }
energyControls { nCorrectors 50; tolerance 1e-12; }
""")
    rho_avg = 0.5 * (M["rho"] + rho_g)
    dt_cap = 0.5 * math.sqrt(rho_avg * g.dx ** 3 / (2 * math.pi * M["sigma0"])) if sigma else 1e-4
    fc.control_dict(case, "meltdemFoam", T_END, 1e-7, T_END / 4, max_co=0.2, max_alpha_co=0.2,
                    max_dt=dt_cap, extra="""functions
{
    balance { type meltdemBalance; }
}
""")
    fc.fv_schemes(case)
    fc.fv_solution(case, p_ref_cell=N * N - 1,
                   extra_solvers='    "T.*" { solver PBiCGStab; preconditioner DILU; tolerance 1e-13; relTol 0; }\n',
                   alpha_tolerance=1e-14)
    path = os.path.join(case, "system", "controlDict")
    txt = open(path).read().replace("writePrecision 12;", "writePrecision 17;")
    open(path, "w").write(txt)
    fc.run(["blockMesh"], case, "log.blockMesh")
    return g, alpha


def centroid_y(g, alpha):
    return float(np.sum(alpha * g.y) / np.sum(alpha))


def run_case(work, ratio):
    case = os.path.join(work, f"ratio{ratio:g}")
    g, alpha0 = build(case, ratio, sigma=False)
    rc = fc.run([fc.solver()], case, "log.solver", check=False)
    log = open(os.path.join(case, "log.solver")).read()
    bal = np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"), delimiter=",",
                        names=True)
    last = fc.time_dirs(case)[-1]
    alpha = fc.read_internal(os.path.join(case, last, "alpha.metal"))
    U = np.asarray(fc.read_internal(os.path.join(case, last, "U"))).reshape(-1, 3)
    speed = np.hypot(U[:, 0], U[:, 1])
    return dict(rc=rc, log=log, bal=bal, t=float(last), fall=centroid_y(g, alpha) - centroid_y(g, alpha0),
                umax=float(speed.max()), umetal=float(speed[alpha > 0.99].max()),
                ugas=float(speed[alpha < 0.01].max()))


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="density_ratio.")
    ok = True
    r4 = run_case(work, 1e4)
    r3 = run_case(work, 1e3)
    ok &= check_absolute(TEST, "solver exit code", r4["rc"], 0, 0)
    ok &= check_absolute(TEST, "no NaN in the solver output", int("nan" in r4["log"].lower()), 0, 0)
    bal = r4["bal"]
    print(f"{TEST}: {len(bal) - 1} steps to t = {bal['time'][-1]:.4g} s (ratio 1e3: {len(r3['bal']) - 1})")
    ok &= check_relative(TEST, "end time reached [s]", r4["t"], T_END, 1e-9)
    m = bal["metalMass"]
    ok &= check_at_most(TEST, "metal mass drift max |M/M0 - 1|", float(np.max(np.abs(m / m[0] - 1))), 1e-10)
    ok &= check_at_most(TEST, "enthalpy balance error max over steps, relative to H0",
                        float(np.max(np.abs(bal["enthalpyErrorRel"]))), 1e-10)
    rho_g = M["rho"] / 1e4
    free = -0.5 * G * (1 - rho_g / M["rho"]) * T_END ** 2
    ok &= check_relative(TEST, "drop centroid fall at t_end vs free fall g t^2/2 [m]", r4["fall"], free, 0.02)
    print(f"{TEST}: largest speed at t_end: metal {r4['umetal']:.3g} m/s, gas {r4['ugas']:.3g} m/s "
          f"(ratio 1e3: {r3['umetal']:.3g}, {r3['ugas']:.3g}); free fall g t = {G * T_END:.3g} m/s")
    ok &= check_at_most(TEST, "largest speed at ratio 1e4 / the same case at 1e3 (the ratio adds no instability)",
                        r4["umax"] / r3["umax"], 2.0)
    ok &= check_at_most(TEST, "largest gas speed / 2 g t (potential flow past the drop)", r4["ugas"] / (2 * G * T_END),
                        1.0, xfail=XFAIL_GAS, miss_within=19.0)
    worst = float(np.max(np.abs(bal["momentumErrorRel"][len(bal) // 10:])))
    worst3 = float(np.max(np.abs(r3["bal"]["momentumErrorRel"][len(r3["bal"]) // 10:])))
    print(f"{TEST}: momentum balance error relative to the exchanged impulse: ratio 1e4 {worst:.3g}, 1e3 {worst3:.3g}")
    ok &= check_at_most(TEST, "momentum balance error relative to the exchanged impulse (after the first 10 %)", worst,
                        1e-3)
    ok &= check_at_most(TEST, "momentum balance error relative to the exchanged impulse at ratio 1e3 (after the first "
                        "10 %)", worst3, 1e-3)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
