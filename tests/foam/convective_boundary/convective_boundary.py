"""meltdemFoam, conduction only: a metal slab held at T1 on the left and cooled by the
convectiveTemperature boundary (h, Tinf) on the right reaches the steady profile
T(x) = T1 - q x / k with q = (T1 - Tinf) / (Lx/k + 1/h)."""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing.report import check_relative

TEST = "foam.convective_boundary"
LX, NX = 1e-3, 50
K, RHO, CP = 20.0, 8000.0, 500.0
T1, TINF, H = 1000.0, 300.0, 1.0e4        # Biot number h Lx / k = 0.5


def main():
    case = tempfile.mkdtemp(prefix="meltdem_conv_")
    g = fc.Grid2D(LX, LX / NX, NX, 1)
    g.block_mesh(case, patches={"left": ("hot", "patch"), "right": ("cooled", "patch"),
                                "bottom": ("walls", "wall"), "top": ("walls", "wall")})
    n = g.x.size
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", np.ones(n),
             {"hot": "type zeroGradient;", "cooled": "type zeroGradient;", "walls": "type zeroGradient;"})
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((n, 3)),
             {"hot": "type noSlip;", "cooled": "type noSlip;", "walls": "type noSlip;"}, vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(n),
             {"hot": "type zeroGradient;", "cooled": "type zeroGradient;", "walls": "type zeroGradient;"})
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(n, TINF),
             {"hot": f"type fixedValue; value uniform {T1};",
              "cooled": f"type convectiveTemperature; h uniform {H}; Tinf uniform {TINF}; value uniform {TINF};",
              "walls": "type zeroGradient;"})
    tau = LX * LX * RHO * CP / K
    fc.control_dict(case, "meltdemFoam", 10 * tau, tau / 50, 10 * tau, adjustable=False)
    fc.fv_schemes(case)
    fc.fv_solution(case, p_ref_cell=0)
    fc.transport(case, RHO, 1e-6, 1.0, 1e-5, 0.0)
    fc.gravity(case)
    fc.dictionary(case, "constant/meltdemProperties", f"""physics {{ flow off; energy on; }}
metal {{ cp {CP}; k {K}; L 0; Tsolidus 5000; Tliquidus 5100; }}
gas {{ cp 1000; k 0.03; }}
""")
    fc.run(["blockMesh"], case, "log.blockMesh")
    fc.run([fc.solver()], case, "log.meltdemFoam")
    T = fc.read_internal(os.path.join(case, fc.time_dirs(case)[-1], "T"))
    q = (T1 - TINF) / (LX / K + 1 / H)
    ref = T1 - q * g.x / K
    ok = check_relative(TEST, "steady T drop T1 - T at the last cell centre [K]", T1 - T[-1], T1 - ref[-1], 1e-4)
    ok &= check_relative(TEST, "steady T drop T1 - T at mid-slab [K]", T1 - T[NX // 2], T1 - ref[NX // 2], 1e-4)
    # the cooled face value: T_b = Tinf + q/h
    ok &= check_relative(TEST, "heat flux through the cooled face from the profile [W/m2]",
                         K * (T[0] - T[-1]) / (g.x[-1] - g.x[0]), q, 1e-4)
    return ok


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
