#!/usr/bin/env python3
"""Unit checks of meltdem::surfaceForces without the solver (app meltdemSurfaceCheck):
sigma(T) of Fuchs2022 eq. 8 with its lower bound, the direction and the integral of the Marangoni force
on a flat interface (exact: the Gauss gradient telescopes, so sum(F V) = (sigma(T_right) -
sigma(T_left)) dz), its reversal for dSigmadT > 0, its tangency on a curved interface
(circle: integral = |dsigma/dx| pi R dz), the recoil pressure's push into the metal, and the
dictionary checks (FatalIOError naming the entry).
"""
import os
import re
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_relative, check_at_most

src = paths.source_dir()

TEST = "foam.marangoni_force"
APP = paths.binary("meltdemSurfaceCheck")
# Fuchs2022 table 1 (molten stainless steel)
ST = dict(sigma0=1.8, dSigmadT=-1.0e-3, Tsigma0=1700.0, sigmaMin=0.2)


def sigma_ref(T, p):
    return max(p["sigma0"] + p["dSigmadT"] * (T - p["Tsigma0"]), p["sigmaMin"])


def props(case, p, raw=None):
    body = raw if raw is not None else "".join(f"    {k} {v!r};\n" for k, v in p.items())
    fc.dictionary(case, "constant/meltdemProperties", "surfaceTension\n{\n" + body + "}\n")


def make_case(case, grid, alpha, T, TL, TR, p):
    grid.block_mesh(case, {"left": ("left", "wall"), "right": ("right", "wall"),
                           "bottom": ("bottom", "wall"), "top": ("top", "wall")})
    fc.control_dict(case, "meltdemSurfaceCheck", 1.0, 1.0, 1.0)
    fc.fv_schemes(case)
    fc.fv_solution(case)
    props(case, p)
    zg = "type zeroGradient;"
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha,
             {"left": zg, "right": zg, "bottom": zg, "top": zg})
    fc.field(case, "T", "[0 0 0 1 0 0 0]", T,
             {"left": f"type fixedValue; value uniform {TL!r};",
              "right": f"type fixedValue; value uniform {TR!r};", "bottom": zg, "top": zg})
    fc.run(["blockMesh"], case, "log.blockMesh")


def check(case, temps=None, recoil=None):
    cmd = [APP, "-write"] + (["-T", "(" + " ".join(str(t) for t in temps) + ")"] if temps else [])
    cmd += ["-recoil", repr(recoil)] if recoil is not None else []
    fc.run(cmd, case, "log.check")
    out = open(os.path.join(case, "log.check")).read()
    res = {"sigma": {}}
    for line in out.splitlines():
        w = line.split()
        if not w:
            continue
        if w[0] == "sigma":
            res["sigma"][float(w[1])] = float(w[2])
        elif w[0] == "marangoniIntegral":
            res["integral"] = np.array([float(t) for t in w[1:4]])
        elif w[0] == "recoilIntegral":
            res["recoil"] = np.array([float(t) for t in w[1:4]])
        elif w[0] == "marangoniNormalFraction":
            res["normal"] = float(w[1])
        elif w[0] == "marangoniMax":
            res["max"] = float(w[1])
    res["F"] = fc.read_internal(os.path.join(case, "0", "marangoniForce"))
    return res


ok = True
work = tempfile.mkdtemp(prefix="marangoni_force.")
lx, ly, nx, ny = 200e-6, 100e-6, 40, 20
g = fc.Grid2D(lx, ly, nx, ny)
flat = (g.y < ly / 2).astype(float)

# 1. sigma(T) and the flat-interface integral, unclipped: hot left (2000 K), cold right (1000 K)
c = os.path.join(work, "flat")
TL, TR = 2000.0, 1000.0
make_case(c, g, flat, TL + (TR - TL) * g.x / lx, TL, TR, ST)
temps = [300.0, 1700.0, 2500.0, 3300.0, 5000.0]
P_RECOIL = 5.4e4
r = check(c, temps, recoil=P_RECOIL)
err = max(abs(r["sigma"][t] - sigma_ref(t, ST)) for t in temps)
ok &= check_absolute(TEST, "max |sigma(T) - SPH eq. 8| at T=300..5000 K [N/m]", err, 0.0, 1e-12)
ok &= check_absolute(TEST, "sigma(5000 K) bounded by sigmaMin [N/m]", r["sigma"][5000.0], 0.2, 1e-12)
ref = (sigma_ref(TR, ST) - sigma_ref(TL, ST)) * g.dz
ok &= check_relative(TEST, "flat interface: integral F_x [N] = (sigma(T_cold)-sigma(T_hot)) dz",
                     r["integral"][0], ref, 1e-9)
ok &= check_absolute(TEST, "flat interface: F_x > 0 (hot -> cold), sign of integral", np.sign(r["integral"][0]), 1.0, 0)
ok &= check_at_most(TEST, "flat interface: |integral F_y| / |F_x|", abs(r["integral"][1]) / abs(r["integral"][0]), 1e-9)
# recoil pressure adds interpolate(p_v) snGrad(alpha): pushes into the metal (below), p_v per area
ok &= check_relative(TEST, "flat interface: recoil force integral F_y [N] = -p_v Lx dz (into the metal)",
                     r["recoil"][1], -P_RECOIL * lx * g.dz, 1e-9)
F = r["F"]
band = np.abs(g.y - ly / 2) < g.dy
ok &= check_at_most(TEST, "flat interface: force off the interface rows / max", np.abs(F[~band]).max() / r["max"],
                    1e-12)

# 2. clipped: T 4300 K (left) .. 2300 K (right); sigma = sigmaMin above 3300 K
c = os.path.join(work, "clipped")
TL, TR = 4300.0, 2300.0
T = TL + (TR - TL) * g.x / lx
make_case(c, g, flat, T, TL, TR, ST)
r = check(c)
ref = (sigma_ref(TR, ST) - sigma_ref(TL, ST)) * g.dz
ok &= check_relative(TEST, "clipped at sigmaMin: integral F_x [N]", r["integral"][0], ref, 1e-9)
hot = band & (T > 3300.0 + 2 * (TL - TR) / nx)
ok &= check_at_most(TEST, "clipped at sigmaMin: |F| where sigma = sigmaMin / max",
                    np.abs(r["F"][hot]).max() / r["max"], 1e-12)

# 3. dSigmadT > 0 reverses the flow direction (cold -> hot)
c = os.path.join(work, "positive")
p = dict(ST, dSigmadT=1.0e-3)
TL, TR = 2000.0, 1000.0
make_case(c, g, flat, TL + (TR - TL) * g.x / lx, TL, TR, p)
r = check(c)
ref = (sigma_ref(TR, p) - sigma_ref(TL, p)) * g.dz
ok &= check_relative(TEST, "dSigmadT > 0: integral F_x [N] (negative: towards hot)", r["integral"][0], ref, 1e-9)

# 4. curved interface (disc R = 60 um): tangential, total F_x = |dsigma/dx| pi R dz
gc = fc.Grid2D(200e-6, 200e-6, 80, 80)
R = 60e-6
a = fc.smooth_alpha_disc(gc, 100e-6, 100e-6, R)
c = os.path.join(work, "disc")
TL, TR = 2000.0, 1000.0
make_case(c, gc, a, TL + (TR - TL) * gc.x / gc.lx, TL, TR, ST)
r = check(c)
ref = abs(ST["dSigmadT"] * (TR - TL) / gc.lx) * np.pi * R * gc.dz
ok &= check_relative(TEST, "disc R=60um: integral F_x [N] vs |dsigma/dx| pi R dz", r["integral"][0], ref, 0.03)
ok &= check_at_most(TEST, "disc: normal share of |F| (must be tangential)", r["normal"], 1e-6)
top = (np.abs(gc.x - 100e-6) < 10e-6) & (a > 0.01) & (a < 0.99) & (gc.y > 100e-6)
bot = (np.abs(gc.x - 100e-6) < 10e-6) & (a > 0.01) & (a < 0.99) & (gc.y < 100e-6)
ok &= check_absolute(TEST, "disc: F_x > 0 (towards cold) at top and bottom poles, cells failing",
                     int(np.sum(r["F"][top, 0] <= 0) + np.sum(r["F"][bot, 0] <= 0)), 0, 0)

# 5. bad dictionaries stop with a FatalIOError that names the entry
bad = [
    ("missing sigma0", "    dSigmadT -1e-3;\n    Tsigma0 1700;\n    sigmaMin 0.2;\n", "sigma0"),
    ("missing sigmaMin", "    sigma0 1.8;\n    dSigmadT -1e-3;\n    Tsigma0 1700;\n", "sigmaMin"),
    ("sigmaMin < 0", "    sigma0 1.8;\n    dSigmadT -1e-3;\n    Tsigma0 1700;\n    sigmaMin -0.1;\n", "sigmaMin"),
    ("sigma0 <= 0", "    sigma0 0;\n    dSigmadT -1e-3;\n    Tsigma0 1700;\n    sigmaMin 0;\n", "sigma0"),
    ("Tsigma0 <= 0", "    sigma0 1.8;\n    dSigmadT -1e-3;\n    Tsigma0 -5;\n    sigmaMin 0.2;\n", "Tsigma0"),
    ("sigmaMin > sigma0", "    sigma0 1.8;\n    dSigmadT -1e-3;\n    Tsigma0 1700;\n    sigmaMin 2;\n", "sigmaMin"),
    ("nSmooth < 0", "    sigma0 1.8;\n    dSigmadT -1e-3;\n    Tsigma0 1700;\n    sigmaMin 0.2;\n    nSmooth -1;\n",
     "nSmooth"),
    ("dSigmadT not a number", "    sigma0 1.8;\n    dSigmadT abc;\n    Tsigma0 1700;\n    sigmaMin 0.2;\n", "dSigmadT"),
]
c = os.path.join(work, "flat")
caught = 0
for what, body, entry in bad:
    props(c, None, raw=body)
    rc = fc.run([APP], c, "log.bad", check=False)
    out = open(os.path.join(c, "log.bad")).read()
    good = rc != 0 and "FOAM FATAL" in out and re.search(r"\b%s\b" % entry, out) is not None \
        and "Segmentation" not in out
    if not good:
        print(f"bad dictionary '{what}' not caught properly (rc {rc}):\n{out[-1500:]}")
    caught += good
ok &= check_absolute(TEST, f"bad surfaceTension dictionaries stopped naming the entry (of {len(bad)})",
                     caught, len(bad), 0)

if ok:
    import shutil
    shutil.rmtree(work)
else:
    print("cases kept in", work)
sys.exit(0 if ok else 1)
