#!/usr/bin/env python3
"""The laser term on fixed fields (meltdemTermCheck): a plane metal surface (alpha ramping from 1 to
0 over 3 cells) under a Gaussian beam pointing down (-y). Its heat source is Fuchs2022 eq. 17,
q = C exp(-2 rho^2/r^2) alpha <grad alpha . e>, with C such that the volume integral is eta P:
measured are the integral, the column profile against the Gaussian exp(-2 (x - x0)^2/r^2), no heat
in the gas (alpha = 0), and that it acts through heatSource only. With absorptivityModel linear, eta
follows the beam-weighted mean surface temperature: T rising along x gives eta(sum g T / sum g) P, g the
Gaussian of the columns, and a hot surface the absorptivityMax bound."""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing import terms
from meltdem.testing.report import check_absolute, check_at_most, check_relative

TEST = "foam.term.laser"
P, ETA, R, X0 = 150.0, 0.35, 100e-6, 0.47e-3
NX, NY = 100, 10
grid = fc.Grid2D(1e-3, 0.5e-3, NX, NY)
row_alpha = np.clip((5.0 - np.arange(NY)) / 3.0, 0.0, 1.0)
alpha = np.repeat(row_alpha, NX)
props = ("physics { energy on; laser on; }\n"
         f"laser\n{{\n    power {P!r};\n    absorptivity {ETA!r};\n    radius {R!r};\n"
         f"    direction (0 -1 0);\n    position ({X0!r} 0.5e-3 {grid.dz / 2!r});\n"
         "    timeAveraged no;\n}\n")

work = tempfile.mkdtemp(prefix="term_laser_")
hooks, out = terms.evaluate(os.path.join(work, "case"), "laser", grid, {"alpha.metal": alpha,
                            "T": np.full(NX * NY, 300.0)}, props)
ok = terms.check_hooks(TEST, hooks, ["heatSource"])
q = out["termHeatSource"]
V = grid.dx * grid.dy * grid.dz
ok &= check_relative(TEST, "absorbed power sum(q V) [W] vs eta P", float(np.sum(q) * V), ETA * P, 1e-9)
columns = q.reshape(NY, NX).sum(axis=0)
xc = grid.x[:NX]
gauss = np.exp(-2.0 * (xc - X0) ** 2 / R ** 2)
ok &= check_at_most(TEST, "column profile / its sum vs exp(-2 (x - x0)^2 / r^2) / its sum, max deviation / max",
                    terms.max_relative_deviation(columns / columns.sum(), gauss / gauss.sum()), 1e-9)
ok &= check_absolute(TEST, "heat deposited in the gas (alpha = 0) [W]", float(np.sum(q[alpha == 0]) * V), 0.0, 0.0)

# absorptivityModel linear: eta(T) = ETA + K (T - T_REF), bounded to [0.1, 0.6]
K, T_REF, ETA_MAX = 2e-4, 1700.0, 0.6
linear = props.replace("    timeAveraged no;", "    timeAveraged no;\n    absorptivityModel linear;\n"
                       f"    dAbsorptivitydT {K!r};\n    Tabsorptivity {T_REF!r};\n    absorptivityMin 0.1;\n"
                       f"    absorptivityMax {ETA_MAX!r};")
T_x = 1500.0 + 5.0e9 * (grid.x - X0) ** 2     # 1500 K on the beam axis, hotter away from it
_, out = terms.evaluate(os.path.join(work, "linear"), "laser", grid, {"alpha.metal": alpha, "T": T_x}, linear)
T_mean = float(np.sum(gauss * T_x[:NX]) / np.sum(gauss))
eta = ETA + K * (T_mean - T_REF)
ok &= check_relative(TEST, f"linear absorptivity: sum(q V) [W] vs eta(T_mean = {T_mean:.1f} K) P, eta = {eta:.4f}",
                     float(np.sum(out["termHeatSource"]) * V), eta * P, 1e-9)
_, out = terms.evaluate(os.path.join(work, "hot"), "laser", grid, {"alpha.metal": alpha,
                        "T": np.full(NX * NY, 3000.0)}, linear)
ok &= check_relative(TEST, f"linear absorptivity at 3000 K (unbounded {ETA + K * 1300:.2f}): sum(q V) [W] vs "
                     "absorptivityMax P", float(np.sum(out["termHeatSource"]) * V), ETA_MAX * P, 1e-9)
sys.exit(fc.finish(ok, work))
