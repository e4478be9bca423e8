#!/usr/bin/env python3
"""The darcy term on fixed fields (meltdemTermCheck): its momentum force density is the
Carman-Kozeny sink -C alpha (1 - f_l)^2 / (f_l^3 + b) U of Codina2019 eq. 2.10 in every cell, it
acts through addMomentum only, and it never pushes along the velocity (F . U <= 0)."""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing import terms
from meltdem.testing.report import check_absolute, check_at_most

TEST = "foam.term.darcy"
C, B = 1.6e10, 1e-3
grid = fc.Grid2D(1e-3, 1e-3, 8, 8)
n = grid.nx * grid.ny
rng = np.random.default_rng(7)
alpha = rng.uniform(0.0, 1.0, n)
fl = rng.uniform(0.0, 1.0, n)
U = np.column_stack([rng.normal(size=n), rng.normal(size=n), np.zeros(n)])
props = f"physics {{ energy on; flow on; darcy on; }}\ndarcy {{ C {C!r}; b {B!r}; }}\n"

work = tempfile.mkdtemp(prefix="term_darcy_")
hooks, out = terms.evaluate(os.path.join(work, "case"), "darcy", grid,
                            {"alpha.metal": alpha, "liquidFraction": fl, "T": np.full(n, 1000.0), "U": U},
                            props)
ok = terms.check_hooks(TEST, hooks, ["addMomentum"])
F = out["termMomentum"]
expected = -(C * alpha * (1 - fl) ** 2 / (fl ** 3 + B))[:, None] * U
ok &= check_at_most(TEST, "force density vs -C alpha (1-f)^2/(f^3+b) U, max deviation / max |F|",
                    terms.max_relative_deviation(F, expected), 1e-10)
ok &= check_absolute(TEST, "cells where the sink pushes along U (F . U > 0)",
                     int(np.sum(np.einsum("ij,ij->i", F, U) > 0)), 0, 0)
sys.exit(fc.finish(ok, work))
