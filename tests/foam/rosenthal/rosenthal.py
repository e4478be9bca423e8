#!/usr/bin/env python3
"""foam.rosenthal: conduction-only meltdemFoam (physics { flow off; energy on; laser on; }) with a
moving Gaussian laser of small radius vs Rosenthal's quasi-steady point-source solution on a thick
plate: melt-pool width (2 max y of the T = Tm isotherm in the top metal cell plane) <= 5 %.

Half model (symmetry plane y = 0, so the laser power in the case is P/2), metal z < 0 with two gas
cells above (the laser is deposited through grad(alpha) there), L = 0 (Rosenthal has no latent
heat), Fuchs2022's steel (k 35.95, rho 7430, cp 965). eta P = 25 W, v = 0.25 m/s, 1/e^2 radius
10 um (the isotherm is ~39 um off-axis), 5 um cells, 200 um of travel (transient width within
0.8 % of the quasi-steady one; the exact transient Gaussian solution is printed for information).
Also: absorbed laser power in every step = eta P/2 (solver log).
Environment: ROSENTHAL_NP (processors, default 1), ROSENTHAL_CELL (cell size, default 5e-6).
"""
import os
import re
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.analysis.rosenthal import rosenthal, width_at_depth, gaussian_transient
from meltdem.case import foam as fc
from meltdem.testing.report import check_relative, report_info

SRC = paths.source_dir()

TEST = "foam.rosenthal" + (".np" + os.environ["ROSENTHAL_NP"] if os.environ.get("ROSENTHAL_NP", "1") != "1" else "")
K, RHO, CP = 35.95, 7430.0, 965.0
A = K / (RHO * CP)
T0, TM = 300.0, 1700.0
ETA, P_FULL, V, RADIUS = 0.5, 50.0, 0.25, 10e-6
H = float(os.environ.get("ROSENTHAL_CELL", "5e-6"))  # cell size (5 um in the test)
LX, LY, DEPTH, GAS = 350e-6, 120e-6, 120e-6, 10e-6
NX, NY, NZ = int(round(LX / H)), int(round(LY / H)), int(round((DEPTH + GAS) / H))
X0, T_END = 50e-6, 0.8e-3
DT = 5e-6


def build(case):
    z0, z1 = -DEPTH, GAS
    fc.dictionary(case, "system/blockMeshDict", f"""convertToMeters 1;
vertices ( (0 0 {z0!r}) ({LX!r} 0 {z0!r}) ({LX!r} {LY!r} {z0!r}) (0 {LY!r} {z0!r})
           (0 0 {z1!r}) ({LX!r} 0 {z1!r}) ({LX!r} {LY!r} {z1!r}) (0 {LY!r} {z1!r}) );
blocks ( hex (0 1 2 3 4 5 6 7) ({NX} {NY} {NZ}) simpleGrading (1 1 1) );
edges ();
boundary
(
    sym    {{ type symmetryPlane; faces ((0 1 5 4)); }}
    top    {{ type patch; faces ((4 5 6 7)); }}
    start  {{ type patch; faces ((0 4 7 3)); }}
    far    {{ type patch; faces ((1 2 6 5) (3 7 6 2) (0 3 2 1)); }}
);
mergePatchPairs ();
""")
    n = NX * NY * NZ
    zc = -DEPTH + (np.arange(NZ) + 0.5) * H
    alpha = np.repeat((zc < 0).astype(float), NX * NY)
    zg = "type zeroGradient;"
    sym = "type symmetryPlane;"
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha,
             {"sym": sym, "top": zg, "start": zg, "far": zg})
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(n, T0),
             {"sym": sym, "top": zg, "start": zg, "far": f"type fixedValue; value uniform {T0!r};"})
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((n, 3)),
             {"sym": sym, "top": "type noSlip;", "start": "type noSlip;", "far": "type noSlip;"}, vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(n), {"sym": sym, "top": zg, "start": zg, "far": zg})
    fc.transport(case, RHO, 6e-3 / RHO, 7.43, 6e-4 / 7.43, 1.8)
    fc.gravity(case)
    extra = f"""metal {{ Tsolidus {TM - 5!r}; Tliquidus {TM + 5!r}; L 0; cp {CP!r}; k {K!r}; }}
gas {{ cp 10; k 0.026; }}
laser
{{
    power        {P_FULL / 2!r};   // half model: symmetry plane through the beam axis
    absorptivity {ETA!r};
    radius       {RADIUS!r};
    direction    (0 0 -1);
    position     ({X0!r} 0 {GAS!r});
    velocity     ({V!r} 0 0);
    tStop        {T_END!r};
}}
"""
    fc.meltdem_properties(case, physics={"flow": "off", "energy": "on", "surfaceTension": "off",
                                         "laser": "on"}, extra=extra)
    fc.control_dict(case, "meltdemFoam", T_END, DT, T_END, adjustable=False)
    fc.fv_schemes(case)
    fc.fv_solution(case, p_ref_cell=0)
    fc.run(["blockMesh"], case, "log.blockMesh")


def fv_width(T):
    """2 max y of T >= TM in the top metal cell plane (linear interpolation between centres in y)."""
    T = T.reshape(NZ, NY, NX)
    kz = int(round(DEPTH / H)) - 1  # top metal row
    plane = T[kz]  # (y, x)
    yc = (np.arange(NY) + 0.5) * H
    best = 0.0
    for i in range(NX):
        col = plane[:, i]
        if col[0] < TM:
            continue
        j = np.where(col < TM)[0][0]
        y = yc[j - 1] + (col[j - 1] - TM) / (col[j - 1] - col[j]) * H
        best = max(best, y)
    return 2 * best, plane


def main():
    work = tempfile.mkdtemp(prefix="rosenthal.")
    case = os.path.join(work, "case")
    os.makedirs(case)
    build(case)
    nproc = int(os.environ.get("ROSENTHAL_NP", "1"))
    if nproc > 1:
        fc.dictionary(case, "system/decomposeParDict",
                      f"numberOfSubdomains {nproc};\nmethod simple;\ncoeffs {{ n ({nproc} 1 1); }}\n")
        fc.run(["decomposePar"], case, "log.decomposePar")
        fc.run(["mpirun", "-np", str(nproc), "--oversubscribe", fc.solver(), "-parallel"], case, "log.solver",
               env={"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"})
        fc.run(["reconstructPar", "-latestTime"], case, "log.reconstructPar")
    else:
        fc.run([fc.solver()], case, "log.solver")
    with open(os.path.join(case, "log.solver")) as f:
        log = f.read()
    powers = [float(x) for x in re.findall(r"Laser: absorbed power (\S+) W", log)]
    T = fc.read_internal(os.path.join(case, fc.time_dirs(case)[-1], "T"))
    w_fv, _ = fv_width(T)
    print(f"{len(powers)} steps, T max {T.max():.1f} K, metal cells above Tm {int(np.sum(T >= TM))}")

    q = ETA * P_FULL
    zc = -H / 2
    w_ros = width_at_depth(lambda xi, y, z: rosenthal(xi, y, z, q, K, A, V, T0), TM, zc,
                           (-300e-6, 50e-6), 300e-6, n=1400)
    ok = True
    ok &= check_relative(TEST, "absorbed laser power, every step (min) [W] (eta P/2, half model)",
                         min(powers), q / 2, 1e-6)
    ok &= check_relative(TEST, "absorbed laser power, every step (max) [W]", max(powers), q / 2, 1e-6)
    ok &= check_relative(TEST, f"melt-pool width at z = -dz/2 [m] vs Rosenthal (v {V} m/s, eta P {q} W)",
                         w_fv, w_ros, 0.05)

    # information: exact transient solution of the Gaussian source at T_END (infinite body)
    xsrc = X0 + V * T_END
    best = 0.0
    for xi in np.linspace(-150e-6, 30e-6, 61):
        def g(y):
            return gaussian_transient(xsrc + xi, y, zc, T_END, q, K, A, RHO * CP, T0, RADIUS, X0, V, nt=2000)
        if g(0.0) < TM:
            continue
        lo, hi = 0.0, 200e-6
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if g(mid) >= TM else (lo, mid)
        best = max(best, lo)
    ok &= report_info(TEST, "melt-pool width [m] vs exact transient Gaussian-source solution (info)",
                      w_fv, 2 * best)
    return fc.finish(ok, work, "--keep" in sys.argv, shown=case)


if __name__ == "__main__":
    sys.exit(main())
