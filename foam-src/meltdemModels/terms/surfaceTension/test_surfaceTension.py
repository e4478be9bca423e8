#!/usr/bin/env python3
"""The surfaceTension term on fixed fields (meltdemTermCheck): a 2D disc of metal (R = 16 cells) at
uniform temperature. Its interface force, reconstructed to the cells, scales with sigma(T) of
Fuchs2022 eq. 8 (not transportProperties' constant sigma: set to 99 N/m here), and the CSF force
(Brackbill1992) on the right half of the disc integrates to the Laplace value -2 sigma per unit
depth (the pull of the two ends of the half-circle): on a smooth interface (tanh, 3 cells) and on
the one-cell interface of a VOF run with the scenes' nSmooth 2, where the curvature of the sharp
colour function falls short of 1/R (an expected miss, shown). The force acts on liquid metal only: it
scales with the liquid fraction f_l and vanishes on a solid disc. It acts through surfaceForce and
limits the step (maxDeltaT) to Brackbill1992's capillary limit sqrt(rho_mean dx^3 / (2 pi sigma))."""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing import terms
from meltdem.testing.report import check_at_most, check_relative

TEST = "foam.term.surfaceTension"
ST = dict(sigma0=1.8, dSigmadT=-4.3e-4, Tsigma0=1700.0, sigmaMin=0.2)
T1, T2 = 1700.0, 2300.0
N, L, R = 64, 1e-3, 0.25e-3
grid = fc.Grid2D(L, L, N, N)
smooth = 0.5 * (1.0 - np.tanh((np.hypot(grid.x - L / 2, grid.y - L / 2) - R) / (3 * grid.dx)))
sharp = fc.smooth_alpha_disc(grid, L / 2, L / 2, R)
SHARP_XFAIL = ("CSF needs a smooth colour function: the curvature of a one-cell VOF interface falls short "
               "of 1/R even after nSmooth 2 (0.78 of it without smoothing)")


def properties(n_smooth):
    return ("physics { flow on; surfaceTension on; }\nsurfaceTension\n{\n"
            + "".join(f"    {k} {v!r};\n" for k, v in ST.items()) + f"    nSmooth {n_smooth};\n}}\n")


def sigma(T):
    return max(ST["sigma0"] + ST["dSigmadT"] * (T - ST["Tsigma0"]), ST["sigmaMin"])


work = tempfile.mkdtemp(prefix="term_surfaceTension_")


RHO_METAL, RHO_GAS = 7000.0, 1.0


def evaluate(name, alpha, T, n_smooth, liquid_fraction=1.0):
    fields = {"alpha.metal": alpha, "T": np.full(N * N, T), "liquidFraction": np.full(N * N, liquid_fraction)}
    return terms.evaluate(os.path.join(work, name), "surfaceTension", grid, fields, properties(n_smooth),
                          transport=(RHO_METAL, 1e-6, RHO_GAS, 1e-5, 99.0))


def force(name, alpha, T, n_smooth, liquid_fraction=1.0):
    hooks, out = evaluate(name, alpha, T, n_smooth, liquid_fraction)
    return hooks, out["termSurfaceForce"]


def right_half(F):
    return float(np.sum(F[grid.x > L / 2, 0]) * grid.dx * grid.dy)


hooks, F1 = force("smooth_T1", smooth, T1, 0)
_, F2 = force("smooth_T2", smooth, T2, 0)
_, F_sharp = force("sharp_nSmooth2", sharp, T1, 2)
ok = terms.check_hooks(TEST, hooks, ["surfaceForce", "maxDeltaT"])
ok &= check_at_most(TEST, f"F({T2:g} K) vs sigma({T2:g})/sigma({T1:g}) F({T1:g} K), max deviation / max |F|",
                    terms.max_relative_deviation(F2, sigma(T2) / sigma(T1) * F1), 1e-9)
ok &= check_relative(TEST, f"force on the right half of the disc [N/m] vs -2 sigma({T1:g} K), smooth interface",
                     right_half(F1), -2.0 * sigma(T1), 0.02)
ok &= check_relative(TEST, f"force on the right half of the disc [N/m] vs -2 sigma({T1:g} K), one-cell interface, "
                     "nSmooth 2", right_half(F_sharp), -2.0 * sigma(T1), 0.02, xfail=SHARP_XFAIL,
                     miss_within=0.2)
_, F_mushy = force("smooth_mushy", smooth, T1, 0, 0.5)
_, F_solid = force("smooth_solid", smooth, T1, 0, 0.0)
ok &= check_at_most(TEST, "mushy disc (f_l 0.5): F vs 0.5 F(liquid), max deviation / max |F|",
                    terms.max_relative_deviation(F_mushy, 0.5 * F1), 1e-9)
ok &= check_at_most(TEST, "solid disc (f_l 0): max |F| / max |F(liquid)|",
                    float(np.max(np.abs(F_solid)) / np.max(np.abs(F1))), 1e-12)
dt_cap = np.sqrt(0.5 * (RHO_METAL + RHO_GAS) * grid.dx ** 3 / (2 * np.pi * sigma(T1)))
_, out = evaluate("smooth_T1_limit", smooth, T1, 0)
ok &= check_relative(TEST, "capillary step limit [s] vs sqrt(rho_mean dx^3 / (2 pi sigma))", out["maxDeltaT"],
                     dt_cap, 1e-6)
sys.exit(fc.finish(ok, work))
