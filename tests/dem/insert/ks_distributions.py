#!/usr/bin/python3
"""fix powder/insert: the drawn diameters follow the requested distribution. For each DIST
(and byvolume), N particles are inserted at once into a roomy region and their diameters
are compared with the analytic truncated number CDF by a one-sample Kolmogorov-Smirnov test
(critical value at alpha = 0.01: 1.628/sqrt(N))."""
import os
import sys
import tempfile

import numpy as np
from scipy import integrate
from scipy.stats import norm

from meltdem.testing.lammps_run import run
from meltdem.testing.report import check_at_most
from insert_common import read_dump

TEST = "dem.insert.ks_distributions"
N = 3000
HEAD = """units si
atom_style sphere
boundary p p p
region box block 0 0.1 0 0.1 0 0.1
create_box 1 box
region ins block 0.005 0.095 0.005 0.095 0.005 0.095
timestep 1e-6
"""
TABLE = [(0.8e-3, 1.0), (1.0e-3, 2.0), (1.2e-3, 1.0)]


def truncated(G, lo, hi):
    return lambda d: np.clip((G(np.clip(d, lo, hi)) - G(lo)) / (G(hi) - G(lo)), 0, 1)


def by_volume(pdf, lo, hi):
    """number CDF of a volume distribution with density pdf on [lo, hi]: weights pdf/d^3"""
    total = integrate.quad(lambda x: pdf(x) / x**3, lo, hi, epsabs=0, epsrel=1e-12, limit=200)[0]
    return lambda d: np.array([integrate.quad(lambda x: pdf(x) / x**3, lo, min(max(v, lo), hi),
                                              epsabs=0, epsrel=1e-12, limit=200)[0] / total for v in np.atleast_1d(d)])


def table_cdf(rows, volume=False):
    d = np.array([r[0] for r in rows])
    w = np.array([r[1] for r in rows])
    if volume:
        w = w / d**3
    c = np.cumsum(w) / w.sum()
    return lambda x: np.array([c[d <= v].max() if (d <= v).any() else 0.0 for v in np.atleast_1d(x)])


def ks(sample, cdf):
    """KS statistic, exact for continuous and step (discrete) CDFs"""
    x = np.sort(sample)
    u, cnt = np.unique(x, return_counts=True)
    right = np.cumsum(cnt) / len(x)
    left = right - cnt / len(x)
    F = cdf(u)
    Fl = cdf(u * (1 - 1e-12))
    return max(np.max(np.abs(right - F)), np.max(np.abs(left - Fl)))


lo, hi = 0.7e-3, 1.3e-3


def rr(d):
    return 1 - np.exp(-(d / 1.1e-3) ** 4)


def rr_pdf(d):
    return 4 / d * (d / 1.1e-3) ** 4 * np.exp(-(d / 1.1e-3) ** 4)


ln_mu, ln_s = np.log(1e-3), 0.25
cases = [
    ("one", "one 1e-3", lambda d: (np.asarray(d) >= 1e-3).astype(float)),
    ("uniform", "uniform 0.8e-3 1.2e-3", truncated(lambda d: d, 0.8e-3, 1.2e-3)),
    ("normal", f"normal 1e-3 0.15e-3 {lo} {hi}", truncated(lambda d: norm.cdf((d - 1e-3) / 0.15e-3), lo, hi)),
    ("lognormal", "lognormal 1e-3 0.25 0.6e-3 1.5e-3",
     truncated(lambda d: norm.cdf((np.log(d) - ln_mu) / ln_s), 0.6e-3, 1.5e-3)),
    ("rosin-rammler", "rosin-rammler 1.1e-3 4 0.5e-3 1.6e-3", truncated(rr, 0.5e-3, 1.6e-3)),
    ("table", "table TABLEFILE", table_cdf(TABLE)),
    # byvolume: number weight ~ volume weight / d^3
    ("uniform byvolume", "uniform 0.8e-3 1.2e-3 byvolume",
     lambda d: np.clip((0.8e-3**-2 - np.clip(d, 0.8e-3, 1.2e-3)**-2) / (0.8e-3**-2 - 1.2e-3**-2), 0, 1)),
    # a lognormal volume distribution is a lognormal number distribution, ln-mean shifted by -3 sigma^2
    ("lognormal byvolume", "lognormal 1e-3 0.25 0.6e-3 1.5e-3 byvolume",
     truncated(lambda d: norm.cdf((np.log(d) - (ln_mu - 3 * ln_s**2)) / ln_s), 0.6e-3, 1.5e-3)),
    ("rosin-rammler byvolume", "rosin-rammler 1.1e-3 4 0.5e-3 1.6e-3 byvolume", by_volume(rr_pdf, 0.5e-3, 1.6e-3)),
    ("table byvolume", "table TABLEFILE byvolume", table_cdf(TABLE, volume=True)),
]

ok = True
crit = 1.628 / np.sqrt(N)
for icase, (name, diam, cdf) in enumerate(cases):
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "psd.txt"), "w") as f:
            f.write("# diameter weight\n" + "".join(f"{a} {b}\n" for a, b in TABLE))
        text = HEAD + (f"fix ins all powder/insert {N} {4711 + 10 * icase} region ins "
                       f"diam {diam.replace('TABLEFILE', 'psd.txt')}"
                       " dens 8000\n"
                       "dump d all custom 1 dump.ins id radius x y z\ndump_modify d sort id format float %.17g\n"
                       "run 1\n")
        run(text, cwd=d)
        frames = read_dump(os.path.join(d, "dump.ins"))
    diam_drawn = 2 * frames[1][:, 1]
    if len(diam_drawn) != N:
        print(f"{name}: only {len(diam_drawn)} of {N} inserted")
        ok = False
        continue
    D = ks(diam_drawn, cdf)
    ok &= check_at_most(TEST, f"KS statistic, diam {name} (N={N}, crit alpha=0.01 {crit:.4f})", D, crit)
sys.exit(0 if ok else 1)
