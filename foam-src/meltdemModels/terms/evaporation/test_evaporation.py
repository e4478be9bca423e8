#!/usr/bin/env python3
"""The evaporation term on fixed fields (meltdemTermCheck): a plane metal surface (alpha ramping
from 1 to 0 over 4 cells) with T rising along it, columns in pairs 0.01 K apart. Its heat loss,
linearised about T, is Fuchs2022 eq. 18 applied through 2 alpha |grad alpha|:
    q0 = s_v(T) 2 alpha |grad alpha|,  s_v = 0.82 c_s p_v(T) sqrt(C_M/T) (h_v + c_p (T - T_h0)),
dq/dT its T-derivative (checked against the closed form and against the finite difference of q0
between paired columns), q0 >= 0, and it acts through linearisedHeatLoss only."""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing import terms
from meltdem.testing.report import check_absolute, check_at_most

TEST = "foam.term.evaporation"
# Fuchs2022 table 1 (stainless steel)
EV = dict(pAmbient=1e5, CT=5.0e4, Tboil=3000.0, hv=6.583e6, cp=965.0, Th0=663.731, CM=1.1095e-3)
DT = 0.01
NX, NY = 16, 12
grid = fc.Grid2D(1.6e-3, 1.2e-3, NX, NY)
col_T = np.repeat(np.linspace(1800.0, 3600.0, NX // 2), 2) + np.tile([0.0, DT], NX // 2)
row_alpha = np.clip((7.5 - np.arange(NY)) / 4.0, 0.0, 1.0)      # 1 below row 3.5, 0 above row 7.5
T = np.tile(col_T, NY)
alpha = np.repeat(row_alpha, NX)
props = ("physics { energy on; evaporation on; }\nevaporation\n{\n"
         + "".join(f"    {k} {v!r};\n" for k, v in EV.items()) + "}\n")


def s_v(T):
    pv = 0.54 * EV["pAmbient"] * np.exp(-EV["CT"] * (1.0 / T - 1.0 / EV["Tboil"]))
    return 0.82 * pv * np.sqrt(EV["CM"] / T) * (EV["hv"] + EV["cp"] * (T - EV["Th0"]))


def ds_v(T):
    pv = 0.54 * EV["pAmbient"] * np.exp(-EV["CT"] * (1.0 / T - 1.0 / EV["Tboil"]))
    mdot = 0.82 * pv * np.sqrt(EV["CM"] / T)
    return mdot * (EV["CT"] / T ** 2 - 0.5 / T) * (EV["hv"] + EV["cp"] * (T - EV["Th0"])) + mdot * EV["cp"]


work = tempfile.mkdtemp(prefix="term_evaporation_")
hooks, out = terms.evaluate(os.path.join(work, "case"), "evaporation", grid, {"alpha.metal": alpha, "T": T},
                            props)
ok = terms.check_hooks(TEST, hooks, ["linearisedHeatLoss"])
q0, dqdT, g = out["termQ0"], out["termDqdT"], out["magGradAlpha"]
weight = 2.0 * alpha * g
surface = weight > 1e-9 * weight.max()       # the bulk's |grad alpha| is round-off (~1e-12 / m)
ok &= check_absolute(TEST, "cells of the surface (2 alpha |grad alpha| > 1e-9 of its max): 5 rows",
                     int(surface.sum()), 5 * NX, 0)
ok &= check_at_most(TEST, "q0 vs s_v(T) 2 alpha |grad alpha| (eq. 18), max deviation / max q0",
                    terms.max_relative_deviation(q0, s_v(T) * weight), 1e-10)
ok &= check_at_most(TEST, "dq/dT vs d s_v/dT 2 alpha |grad alpha|, max deviation / max dq/dT",
                    terms.max_relative_deviation(dqdT, ds_v(T) * weight), 1e-10)
pairs = q0.reshape(NY, NX)
fd = (pairs[:, 1::2] - pairs[:, 0::2]) / DT
mid = 0.5 * (dqdT.reshape(NY, NX)[:, 1::2] + dqdT.reshape(NY, NX)[:, 0::2])
rows = surface.reshape(NY, NX)[:, 0]
ok &= check_at_most(TEST, "dq/dT vs (q0(T + 0.01 K) - q0(T)) / 0.01 K of paired columns, max deviation / max",
                    terms.max_relative_deviation(fd[rows > 0], mid[rows > 0]), 1e-5)
ok &= check_absolute(TEST, "cells with a negative heat loss q0", int(np.sum(q0 < 0)), 0, 0)
sys.exit(fc.finish(ok, work))
