#!/usr/bin/python3
"""The ledger CSV a user plots: the Codina2019-particle ledger test writes it, scripts/plot_ledger.py
draws it, and the columns re-evaluated here independently (numpy, plain doubles) give back the
Codina2019 eq. 2.20 / 2.26 / 2.36 errors and the metal that left through the outlet."""
import os
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.cli import plot_ledger
from meltdem.testing.report import check_absolute, check_at_most, check_relative

src = paths.source_dir()

T = "coupling.ledger_csv"
ok = True
with tempfile.TemporaryDirectory() as tmp:
    csv = os.path.join(tmp, "ledger.csv")
    env = dict(os.environ, MELTDEM_LEDGER_CSV=csv)
    r = subprocess.run([paths.binary("coupling_unit_tests"),
                        "--gtest_filter=ConservationLedger.ThesisParticleMeltBalancesClose"],
                       env=env, capture_output=True, text=True)
    if r.returncode != 0 or not os.path.exists(csv):
        print(r.stdout, r.stderr)
        sys.exit("ledger test failed or wrote no CSV")
    png = os.path.join(os.environ.get("MELTDEM_REPORT_DIR", tmp), "ledger_thesis_particle.png")
    plot_ledger.main([csv, "-o", png])
    ok &= os.path.getsize(png) > 10000
    d = plot_ledger.load(csv)
    ok &= check_absolute(T, "rows (1 initial + 200 melt + 50 outflow steps)", len(d), 251, 0)
    # Codina2019 form re-evaluated from the columns: (sources - (new - old)) / new; in plain doubles
    # the rounding of the columns is ~eps of the amounts moved, so it agrees to ~1e-13
    for c, tol in (("mass", 1e-14), ("enthalpy", 1e-12), ("mom_y", 1e-14)):
        new, old = d[c + "_continuum"][1:], d[c + "_continuum"][:-1]
        den = np.maximum(np.abs(new), np.maximum.accumulate(np.abs(d[c + "_total"]))[1:])
        err = (plot_ledger.continuum_sources(d, c)[1:] - (new - old)) / den
        ok &= check_at_most(T, f"{c}: |numpy re-evaluated eq. error - ledger column|",
                            np.max(np.abs(err - d[c + "_continuum_error"][1:])), tol)
    ok &= check_relative(T, "metal through the outlet (cumulative out - in) vs m (1 - 0.9^50)",
                         d["mass_cumulative_boundary_out"][-1] - d["mass_cumulative_boundary_in"][-1],
                         9.069e-7 * (1 - 0.9 ** 50), 1e-12)
    ok &= check_relative(T, "particle mass in the first row (thesis 9.069e-7 kg)", d["mass_particles"][0],
                         9.069e-7, 1e-15)
    ok &= check_relative(T, "particle momentum in the first row (thesis -1.81408e-6 kg m/s)", d["mom_y_particles"][0],
                         -1.81408e-6, 1e-12)
sys.exit(0 if ok else 1)
