#!/usr/bin/env python3
"""The marangoni term on fixed fields (meltdemTermCheck): a plane metal surface (alpha ramping from
1 to 0 over 4 cells) with T rising linearly along it. Its momentum force density is the tangential
Marangoni force (I - n n) & grad(sigma(T)) |grad alpha| of Fuchs2022 eq. 8: on every interior column
its integral across the surface is dsigma/dT dT/dx exactly (the Gauss gradient of alpha
telescopes to 1), pointing from hot to cold for dsigma/dT < 0, with no normal component; it acts
through addMomentum only. The force acts on liquid metal only: with the liquid fraction f_l falling
from 1 to 0 along the surface, each column's integral is f_l dsigma/dT dT/dx, and 0 where solid. It is
density-scaled with marangoniDensityScaled yes, 2 rho / (rho_m + rho_g): on this symmetric ramp the column
integral is unchanged, and a pure gas cell of the interface keeps 2 rho_g / (rho_m + rho_g) of the unscaled
force."""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing import terms
from meltdem.testing.report import check_at_most

TEST = "foam.term.marangoni"
RHO_M, RHO_G = 7000.0, 1.0
ST = dict(sigma0=1.8, dSigmadT=-4.3e-4, Tsigma0=1700.0, sigmaMin=0.2)
GRAD_T = 4.0e5          # K/m: 1500-1900 K over the 1 mm, sigma above sigmaMin everywhere
NX, NY = 20, 16
grid = fc.Grid2D(1e-3, 0.8e-3, NX, NY)
row_alpha = np.clip((9.5 - np.arange(NY)) / 4.0, 0.0, 1.0)
alpha = np.repeat(row_alpha, NX)
T = ST["Tsigma0"] + GRAD_T * (grid.x - 0.5e-3)
props = ("physics { energy on; flow on; surfaceTension on; marangoni on; }\nsurfaceTension\n{\n"
         + "".join(f"    {k} {v!r};\n" for k, v in ST.items()) + "}\n")

work = tempfile.mkdtemp(prefix="term_marangoni_")
hooks, out = terms.evaluate(os.path.join(work, "case"), "marangoni", grid, {"alpha.metal": alpha, "T": T}, props,
                            rho1=RHO_M, rho2=RHO_G)
ok = terms.check_hooks(TEST, hooks, ["addMomentum"])
F = out["termMomentum"]
Fx = F[:, 0].reshape(NY, NX)[:, 1:-1]        # interior columns: grad T there is exact
column = Fx.sum(axis=0) * grid.dy
expected = ST["dSigmadT"] * GRAD_T
ok &= check_at_most(TEST, f"column integral of F_x [N/m2] vs dsigma/dT dT/dx = {expected:g}, max deviation / |ref|",
                    float(np.max(np.abs(column - expected)) / abs(expected)), 1e-9)
ok &= check_at_most(TEST, "normal (y) share of the force, max |F_y| / max |F_x|",
                    float(np.max(np.abs(F[:, 1])) / np.max(np.abs(F[:, 0]))), 1e-9)

# liquid fraction 1 in the left quarter, 0 in the right half, linear between (a mushy surface)
col_fl = np.clip((0.75e-3 - grid.x[:NX]) / 0.5e-3, 0.0, 1.0)
_, out = terms.evaluate(os.path.join(work, "mushy"), "marangoni", grid,
                        {"alpha.metal": alpha, "T": T, "liquidFraction": np.tile(col_fl, NY)}, props,
                        rho1=RHO_M, rho2=RHO_G)
column = out["termMomentum"][:, 0].reshape(NY, NX)[:, 1:-1].sum(axis=0) * grid.dy
weighted = col_fl[1:-1] * expected
ok &= check_at_most(TEST, "column integral of F_x vs f_l dsigma/dT dT/dx on a mushy surface (f_l 1 -> 0), "
                    "max deviation / |dsigma/dT dT/dx|", float(np.max(np.abs(column - weighted)) / abs(expected)), 1e-9)
solid = col_fl[1:-1] == 0
ok &= check_at_most(TEST, f"largest |column integral| over the {int(solid.sum())} solid columns / |dsigma/dT dT/dx|",
                    float(np.max(np.abs(column[solid])) / abs(expected)), 1e-12)

# density scaling: against the unscaled force, the pure gas cells of the interface keep
# 2 rho_g / (rho_m + rho_g) of it and the pure metal cells 2 rho_m / (rho_m + rho_g)
F1 = F[:, 0]
_, out = terms.evaluate(os.path.join(work, "scaled"), "marangoni", grid, {"alpha.metal": alpha, "T": T},
                        props.replace("sigmaMin", "marangoniDensityScaled yes;\n    sigmaMin"), rho1=RHO_M, rho2=RHO_G)
F = out["termMomentum"]
column = F[:, 0].reshape(NY, NX)[:, 1:-1].sum(axis=0) * grid.dy
ok &= check_at_most(TEST, "density-scaled: column integral of F_x vs dsigma/dT dT/dx, max deviation / |ref|",
                    float(np.max(np.abs(column - expected)) / abs(expected)), 1e-9)
for name, cells, scale in (("gas", (alpha == 0) & (np.abs(F1) > 0), 2 * RHO_G / (RHO_M + RHO_G)),
                           ("metal", (alpha == 1) & (np.abs(F1) > 0), 2 * RHO_M / (RHO_M + RHO_G))):
    ok &= check_at_most(TEST, f"pure {name} cells of the interface ({int(cells.sum())}): max |F(density-scaled) / "
                        f"F - {scale:.6g}|", float(np.max(np.abs(F[cells, 0] / F1[cells] - scale))), 1e-9)
sys.exit(fc.finish(ok, work))
