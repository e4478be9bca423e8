#!/usr/bin/env python3
"""The recoil term on fixed fields (meltdemTermCheck): its surface pressure is Fuchs2022 eq. 10,
p_v(T) = 0.54 p_a exp[-C_T (1/T - 1/T_v)], in every cell (0.54 p_a at the boiling point), and it
acts through surfacePressure only (the solver adds it to the interface force)."""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing import terms
from meltdem.testing.report import check_at_most, check_relative

TEST = "foam.term.recoil"
# Fuchs2022 table 1 (stainless steel)
EV = dict(pAmbient=1e5, CT=5.0e4, Tboil=3000.0, hv=6.583e6, cp=965.0, Th0=663.731, CM=1.1095e-3)
grid = fc.Grid2D(1e-3, 1e-3, 8, 8)
n = grid.nx * grid.ny
T = np.linspace(1500.0, 4000.0, n)
T[n // 2] = EV["Tboil"]
props = ("physics { energy on; flow on; recoil on; }\nevaporation\n{\n"
         + "".join(f"    {k} {v!r};\n" for k, v in EV.items()) + "}\n")

work = tempfile.mkdtemp(prefix="term_recoil_")
hooks, out = terms.evaluate(os.path.join(work, "case"), "recoil", grid,
                            {"alpha.metal": np.linspace(0.0, 1.0, n), "T": T}, props)
ok = terms.check_hooks(TEST, hooks, ["surfacePressure"])
p = out["termSurfacePressure"]
expected = 0.54 * EV["pAmbient"] * np.exp(-EV["CT"] * (1.0 / T - 1.0 / EV["Tboil"]))
ok &= check_at_most(TEST, "p_v vs 0.54 p_a exp[-C_T (1/T - 1/T_v)], 1500-4000 K, max deviation / max p_v",
                    terms.max_relative_deviation(p, expected), 1e-10)
ok &= check_relative(TEST, "p_v at the boiling point [Pa] vs 0.54 p_a", p[n // 2], 0.54 * EV["pAmbient"], 1e-10)
sys.exit(fc.finish(ok, work))
