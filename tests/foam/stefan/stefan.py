#!/usr/bin/env python3
"""1D one-phase Stefan melting with meltdemFoam (physics { flow off; energy on; }).

Metal everywhere (alpha.metal = 1), initially solid at the melting temperature Tm; at t = 0 the
wall x = 0 is held at Tw > Tm. Neumann's solution: the front is at s = 2 lambda sqrt(a t) with
lambda exp(lambda^2) erf(lambda) = St / sqrt(pi), St = cp (Tw - Tm) / L, a = k / (rho cp).
The solver needs a solidus-liquidus interval; a narrow one (Tsolidus = Tm, Tliquidus = Tm + 1 K,
i.e. 1/300 of Tw - Tm) keeps the reference the sharp-front one. The measured front position is
the molten length sum(f_l dx), which the sharp solution gives as s.

Checks: front at t_end and at 3 earlier times within 3 % on the chosen mesh (40 um cells), a
finer mesh (20 um) closer to the reference than the coarse one (worst error over the 4 times:
the error oscillates as the front crosses cells), and the enthalpy balance of the run
(meltdemBalance function object: stored-enthalpy change minus the time-integrated wall heat flux,
relative to the heat that entered) -- an energy-conservation check of the conduction solver.
usage: stefan.py [--keep]
"""
import os
import sys
import tempfile

import numpy as np
from scipy.optimize import brentq
from scipy.special import erf

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_relative, check_at_most

src = paths.source_dir()

TEST = "foam.stefan"
RHO, CP, K, L = 7430.0, 965.0, 35.95, 2.7e5      # steel-like (Fuchs2022 table 1; L typical of steel)
TM, TW, DT_MELT = 1700.0, 2000.0, 1.0
LENGTH, T_END = 1.0e-3, 0.04
A = K / (RHO * CP)
ST = CP * (TW - TM) / L
LAM = brentq(lambda lam: lam * np.exp(lam * lam) * erf(lam) - ST / np.sqrt(np.pi), 1e-6, 5.0)


def front(t):
    return 2.0 * LAM * np.sqrt(A * t)


def build(case, nx, nsteps):
    g = fc.Grid2D(LENGTH, LENGTH / nx, nx, 1, dz=LENGTH / nx)
    g.block_mesh(case, patches={"left": ("hot", "patch"), "right": ("cold", "patch"),
                                "bottom": ("sides", "empty"), "top": ("sides", "empty")})
    ends = {"hot": None, "cold": None, "sides": "type empty;"}

    def bnd(hot, cold):
        b = dict(ends)
        b["hot"], b["cold"] = hot, cold
        return b

    zg = "type zeroGradient;"
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", np.ones(nx), bnd(zg, zg))
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(nx, TM),
             bnd(f"type fixedValue; value uniform {TW!r};", zg))
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((nx, 3)),
             bnd("type noSlip;", "type noSlip;"), vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(nx), bnd(zg, zg))
    fc.transport(case, RHO, 6e-3 / RHO, 7.43, 6e-4 / 7.43, 1.8)
    fc.gravity(case)
    extra = f"""metal {{ Tsolidus {TM!r}; Tliquidus {TM + DT_MELT!r}; L {L!r}; cp {CP!r}; k {K!r}; }}
gas {{ cp 10; k 0.026; }}
energyControls {{ nCorrectors 100; tolerance 1e-12; }}
"""
    fc.meltdem_properties(case, physics={"flow": "off", "energy": "on", "surfaceTension": "off"},
                          extra=extra)
    dt = T_END / nsteps
    fc.control_dict(case, "meltdemFoam", T_END, dt, T_END / 4, adjustable=False, extra="""functions
{
    balance { type meltdemBalance; }
}
""")
    fc.fv_schemes(case, extra_div="    div(rhoCpPhi,T) Gauss upwind;\n")
    fc.fv_solution(case, p_ref_cell=0,
                   extra_solvers='    "T.*" { solver PBiCGStab; preconditioner DILU; tolerance 1e-13; relTol 0; }\n')
    fc.run(["blockMesh"], case, "log.blockMesh")
    return g


def solve(case, nx, nsteps):
    """Front positions (sum f_l dx) at the written times, and the balance table."""
    g = build(case, nx, nsteps)
    fc.run([fc.solver()], case, "log.solver")
    fronts = []
    for d in fc.time_dirs(case):
        if float(d) > 0:
            f = fc.read_internal(os.path.join(case, d, "liquidFraction"))
            fronts.append((float(d), float(np.sum(f) * g.dx)))
    bal = np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"),
                        delimiter=",", names=True)
    return fronts, bal


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="stefan.")
    ok = True
    print(f"St = {ST:.4f}, lambda = {LAM:.6f}, a = {A:.4e} m2/s, front at t = {T_END:g} s: "
          f"{front(T_END) * 1e6:.2f} um")
    res = {}
    for nx, nsteps in ((25, 400), (50, 800)):
        case = os.path.join(work, f"nx{nx}")
        fronts, bal = solve(case, nx, nsteps)
        print(f"dx = {LENGTH / nx * 1e6:.0f} um, {nsteps} steps:")
        for t, s in fronts:
            print(f"   t = {t:.4g} s: front {s * 1e6:.3f} um vs Neumann {front(t) * 1e6:.3f} um "
                  f"({100 * (s - front(t)) / front(t):+.3f} %)")
        t, s = fronts[-1]
        worst = max(abs(s_ - front(t_)) / front(t_) for t_, s_ in fronts)
        res[nx] = (t, s, front(t), (s - front(t)) / front(t), bal, worst)

    t, s, ref, err, bal, worst = res[25]
    ok &= check_relative(TEST, f"front position at t = {t:g} s [um], 40 um cells (Neumann, 1 K interval)",
                         s * 1e6, ref * 1e6, 0.03)
    ok &= check_at_most(TEST, "max |front error| at t = 0.01, 0.02, 0.03, 0.04 s, 40 um cells", worst, 0.03)
    t2, s2, ref2, err2, bal2, worst2 = res[50]
    ok &= check_relative(TEST, f"front position at t = {t2:g} s [um], 20 um cells (Neumann)",
                         s2 * 1e6, ref2 * 1e6, 0.03)
    # the front error oscillates as the front crosses cells: compare the worst over the times
    ok &= check_at_most(TEST, "max |front error| 20 um cells / 40 um cells (convergence: < 1)",
                        worst2 / worst, 0.99)

    # enthalpy balance of the conduction run (meltdemBalance)
    for nx, r in res.items():
        b = r[4]
        rel = float(np.max(np.abs(b["enthalpyErrorRelExchanged"][1:])))
        q = float(b["enthalpyIn_cum"][-1])
        dH = float(b["enthalpy"][-1] - b["enthalpy"][0])
        print(f"nx {nx}: heat in through the hot wall {q:.6g} J, stored-enthalpy change {dH:.6g} J, "
              f"max |relative balance error| {rel:.3e}")
        # the analytic heat input per wall area: k (Tw - Tm) / erf(lambda) * 2 sqrt(t / (pi a))
        area = (LENGTH / nx) ** 2
        q_ref = K * (TW - TM) / erf(LAM) * 2.0 * np.sqrt(r[0] / (np.pi * A)) * area
        print(f"   analytic heat input {q_ref:.6g} J ({100 * (q - q_ref) / q_ref:+.2f} %)")
        if nx == 25:
            ok &= check_at_most(TEST, "enthalpy balance error of the conduction run "
                                "(max over steps, relative to the heat exchanged), 40 um cells", rel, 1e-8)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
