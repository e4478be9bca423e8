#!/usr/bin/env python3
"""The buoyancy term on fixed fields (meltdemTermCheck): its momentum force density is the
Boussinesq force -alpha rho1 beta (T - Tref) g in every cell, it acts through addMomentum only,
and metal hotter than Tref is pushed against gravity (colder metal along it)."""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing import terms
from meltdem.testing.report import check_absolute, check_at_most

TEST = "foam.term.buoyancy"
BETA, TREF, RHO1, G = 1.2e-4, 1700.0, 7430.0, (0.0, -9.81, 0.0)
grid = fc.Grid2D(1e-3, 1e-3, 8, 8)
n = grid.nx * grid.ny
rng = np.random.default_rng(11)
alpha = rng.uniform(0.0, 1.0, n)
T = rng.uniform(1000.0, 2500.0, n)
props = (f"physics {{ energy on; flow on; buoyancy on; }}\n"
         f"metal {{ beta {BETA!r}; Tref {TREF!r}; }}\n")

work = tempfile.mkdtemp(prefix="term_buoyancy_")
hooks, out = terms.evaluate(os.path.join(work, "case"), "buoyancy", grid,
                            {"alpha.metal": alpha, "T": T}, props, g=G, rho1=RHO1)
ok = terms.check_hooks(TEST, hooks, ["addMomentum"])
F = out["termMomentum"]
expected = -(alpha * RHO1 * BETA * (T - TREF))[:, None] * np.array(G)[None, :]
ok &= check_at_most(TEST, "force density vs -alpha rho1 beta (T - Tref) g, max deviation / max |F|",
                    terms.max_relative_deviation(F, expected), 1e-10)
up = F @ -np.array(G)
ok &= check_absolute(TEST, "cells where metal hotter (colder) than Tref is not pushed up (down)",
                     int(np.sum(np.sign(up) != np.sign(T - TREF))), 0, 0)
sys.exit(fc.finish(ok, work))
