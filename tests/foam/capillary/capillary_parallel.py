#!/usr/bin/env python3
"""foam.capillary_parallel: the capillary step limit (Brackbill1992, sqrt(rho_mean h^3 / (2 pi
sigma)) over the faces of the cells the interface crosses) is the same on 2 ranks as in serial
when the face that sets it is a processor face.

A 2D column of metal (20 x 10 cells of 2 um, metal in the left 9 columns, the 10th crossed with
alpha 0.5, gas beyond) at 2000 K (sigma 1.5 N/m), except the first gas column at 300 K (sigma 3.2
N/m): the face between the crossed column and that cold column sets the limit. Split into 2 ranks
across x, that face is on the processor boundary. The limit the solver states in its first step
on 1 and on 2 ranks against the closed form with sigma(300 K).
"""
import os
import re
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing.report import check_relative

TEST = "foam.capillary_parallel"
M, G = fc.METAL, fc.GAS
NX, NY, H = 20, 10, 2e-6
T_HOT, T_COLD = 2000.0, 300.0
STEP_LINE = r"^Capillary step limit = (\S+) s"


def sigma(T):
    return max(M["sigma0"] + M["dSigmadT"] * (T - M["Tsigma0"]), M["sigmaMin"])


def build(case):
    g = fc.Grid2D(NX * H, NY * H, NX, NY)
    g.block_mesh(case)
    dt = 1e-10
    fc.control_dict(case, "meltdemFoam", dt, dt, dt, adjustable=False)
    fc.fv_schemes(case)
    fc.fv_solution(case, p_ref_cell=0)
    fc.transport(case, M["rho"], M["mu"] / M["rho"], G["rho"], G["mu"] / G["rho"], M["sigma0"])
    fc.gravity(case)
    fc.meltdem_properties(case)
    column = np.round((g.x - 0.5 * H) / H).astype(int)
    alpha = np.where(column < NX // 2 - 1, 1.0, np.where(column == NX // 2 - 1, 0.5, 0.0))
    T = np.where(column == NX // 2, T_COLD, T_HOT)
    zg = {"walls": "type zeroGradient;"}
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha, zg)
    fc.field(case, "T", "[0 0 0 1 0 0 0]", T, zg)
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((g.x.size, 3)), {"walls": "type noSlip;"}, vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(g.x.size),
             {"walls": "type fixedFluxPressure; value uniform 0;"})
    fc.run(["blockMesh"], case, "log.blockMesh")


def first_limit(case):
    found = re.findall(STEP_LINE, open(os.path.join(case, "log.solver")).read(), re.M)
    return float(found[0]) if found else float("nan")


def main():
    work = tempfile.mkdtemp(prefix="capillary_parallel.")
    rho_mean = 0.5 * (M["rho"] + G["rho"])
    ref = np.sqrt(rho_mean * H ** 3 / (2 * np.pi * sigma(T_COLD)))
    ok = True
    for np_ in (1, 2):
        case = os.path.join(work, f"np{np_}")
        build(case)
        if np_ > 1:
            fc.decompose(case, np_, direction=(np_, 1, 1))
        rc = fc.run_solver(case, np_=np_, log="log.solver", check=False)
        ok &= check_relative(TEST, f"np {np_}: capillary step limit of the first step [s] vs "
                             "sqrt(rho_mean h^3 / (2 pi sigma(300 K))), the face across the split",
                             first_limit(case) if rc == 0 else float("nan"), ref, 1e-6)
    return fc.finish(ok, work, "--keep" in sys.argv, shown=work)


if __name__ == "__main__":
    sys.exit(main())
