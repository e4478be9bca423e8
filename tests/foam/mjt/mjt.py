#!/usr/bin/env python3
"""CI-sized material-jetting scene (Fuchs2022 §4.3, tables 1-3; builder and full-size
variant in examples/mjt-droplets): axisymmetric 50 um steel droplet at 2500 K, 1.6 m/s onto a
20 um substrate at 1500 K (Fuchs2022: remelt depth ~16 um at t ~ 0.075 ms) and at 500 K (Fuchs2022: no
noticeable remelting). 2 um cells, cylinder radius 60 um, height 100 um, to t = 0.08 ms.
"""
import os
import shutil
import sys
import tempfile
import argparse

from meltdem import paths
from meltdem.loader import load_module
from meltdem.paths import examples_dir
from meltdem.testing.report import check_relative, check_at_most

src = paths.source_dir()

mjt_case = load_module(os.path.join(examples_dir(), "mjt-droplets", "mjt_case.py"))

TEST = "foam.mjt"
work = tempfile.mkdtemp(prefix="mjt.")
ok = True
res = {}
peak = {}
for Tsub in (1500.0, 500.0):
    case = os.path.join(work, f"sub{int(Tsub)}")
    args = argparse.Namespace(case=case, Tsub=Tsub, dx=2e-6, radius=60e-6, height=100e-6, end=8.0e-5,
                              write=2.5e-6, nsmooth=2, base="Tsub")
    mjt_case.build(args)
    mjt_case.run(case)
    res[Tsub] = mjt_case.depth(case)
    peak[Tsub] = mjt_case.surface_peak(case)
    d, t, r = res[Tsub]
    print(f"substrate {Tsub:g} K: remelt depth {d * 1e6:.2f} um at t = {t * 1e3:.4f} ms, r = {r * 1e6:.1f} um")

ok &= check_relative(TEST, "remelt depth, substrate 1500 K [um] (2 um cells, axisymmetric)",
                     res[1500.0][0] * 1e6, 16.0, 0.25)
ok &= check_at_most(TEST, "remelt depth, substrate 500 K [um] (no noticeable remelting: <= 1 cell)",
                    res[500.0][0] * 1e6, 2.0)
# the 500 K result means something only if the droplet landed: the top substrate cells must
# reach about the contact temperature of equal semi-infinite bodies, (2500 + 500)/2 K
ok &= check_relative(TEST, "substrate 500 K: peak T of the top substrate cells [K] vs contact estimate (2500+500)/2",
                     peak[500.0], 1500.0, 0.25)
if ok:
    shutil.rmtree(work)
else:
    print("cases kept in", work)
sys.exit(0 if ok else 1)
