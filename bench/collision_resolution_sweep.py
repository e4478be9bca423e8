#!/usr/bin/python3
"""Collision resolution steps S of fix powder/dt: cost against accuracy.

    /usr/bin/python3 bench/s_sweep.py [--bin build/bin] [--S 2,3,5,7,10,15,20,30,40]

For each S:
  * head-on elastic collision of two steel spheres (d 30 um, 2 m/s): contact time error
    vs eq. 3.1, largest overlap vs the Hertz value (15 m* U^2/(16 E* sqrt R*))^(2/5),
    restitution error |e - 1|;
  * the same collision with damping (pair_style granular, damping tsuji, e 0.5):
    restitution error against the converged value (S = 400), i.e. the time-step error;
  * wall time of the CI powder bed (examples/powder-bed, 0.3 x 0.3 mm, first 1 ms:
    injection and impact) with pair_style granular/powder if built, else with the stock
    granular styles at the nearest stock damping (noted in the table).
Writes bench/s_sweep.md and bench/s_sweep.png.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "tests", "dem", "dt"))

ap = argparse.ArgumentParser()
ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
ap.add_argument("--S", default="2,3,5,7,10,15,20,30,40")
args = ap.parse_args()
os.environ.setdefault("MELTDEM_BIN", args.bin)
os.environ.setdefault("MELTDEM_SOURCE_DIR", ROOT)
from dt_common import delta_max, mass, run, t_contact, thermo_runs, two_spheres  # noqa: E402

LMP = os.path.join(args.bin, "meltdem-lmp")
R, U = 15e-6, 2.0
SS = [float(s) for s in args.S.split(",")]


def collision(S, damping):
    text = two_spheres(-R - 5e-8, R + 5e-8, 2 * R, 2 * R, U / 2, -U / 2)
    if damping:
        text = text.replace("hertz/material 200000000000.0 0.0 0.3 damping velocity",
                            "hertz/material 200000000000.0 0.5 0.3 damping tsuji")
    text += f"""fix dt all powder/dt steps {S}
compute ov all powder/overlap warn no
variable delta equal {2 * R}-(x[2]-x[1])
variable vrel equal vx[2]-vx[1]
thermo_style custom step time v_delta c_ov[1] v_vrel
thermo_modify format float %.17g
thermo 1
run {int(12 * S) + 40}
"""
    _, out = run(text)
    rows = thermo_runs(out)[0]
    t = [r["Time"] for r in rows]
    d = [r["v_delta"] for r in rows]
    cross = []
    for k in range(1, len(d)):
        if (d[k - 1] <= 0) != (d[k] <= 0):
            cross.append(t[k - 1] + (t[k] - t[k - 1]) * (0 - d[k - 1]) / (d[k] - d[k - 1]))
    tc = cross[1] - cross[0] if len(cross) >= 2 else float("nan")
    return tc, max(r["c_ov[1]"] for r in rows) * R, rows[-1]["v_vrel"] / U


def have_powder_styles():
    p = subprocess.run([LMP, "-log", "none", "-echo", "none"], input="units si\natom_style sphere\n"
                       "region b block 0 1 0 1 0 1\ncreate_box 1 b\npair_style granular/powder\n",
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return "Unrecognized" not in p.stdout


def bed_walltime(S, stock):
    src = open(os.path.join(ROOT, "examples", "powder-bed", "in.powder-bed")).read()
    if stock:  # stand-in: stock styles, Tsuji e at the bottom of its range (alpha ~1.2)
        src = (src.replace("granular/powder", "granular").replace("wall/gran/powder", "wall/gran")
               .replace("tsuji/alpha", "tsuji").replace("apart   equal 1.5", "apart   equal 0.01")
               .replace("awall   equal 1.0", "awall   equal 0.05"))
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "in.bed")
        open(path, "w").write(src)
        t0 = time.time()
        p = subprocess.run([LMP, "-in", path, "-log", "none", "-echo", "none", "-var", "Lx", "3e-4", "-var",
                            "Lz", "3e-4", "-var", "sides", "periodic", "-var", "tend", "1e-3", "-var", "S",
                            str(S)], cwd=d, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        wall = time.time() - t0
    steps = re.findall(r"Loop time of \S+ on \d+ procs for (\d+) steps", p.stdout)
    return wall, int(steps[-1]) if steps else 0


ref_tc = t_contact(mass(R), mass(R), R, R, U)
ref_dmax = delta_max(mass(R), mass(R), R, R, U)
e_conv = collision(400, True)[2]
stock = not have_powder_styles()
rows = []
for S in SS:
    tc, dm, e_el = collision(S, False)
    _, _, e_d = collision(S, True)
    wall, steps = bed_walltime(S, stock)
    rows.append((S, tc / ref_tc - 1, dm / ref_dmax - 1, abs(e_el - 1), abs(e_d / e_conv - 1), wall, steps))
    print(rows[-1], flush=True)

bedtxt = ("stock granular stand-in (granular/powder not built)" if stock else "granular/powder, table 4.3")
with open(os.path.join(HERE, "s_sweep.md"), "w") as f:
    f.write("# fix powder/dt: collision resolution steps S, cost vs accuracy\n\n")
    f.write(f"Head-on collision of two steel spheres, d 30 um, 2 m/s (eq. 3.1: t_c = {ref_tc:.4g} s, "
            f"delta_max = {ref_dmax:.4g} m); damped: tsuji e 0.5 vs its S = 400 value ({e_conv:.5f}). "
            f"Bed: CI powder bed, first 1 ms, serial, {bedtxt}. Generated by bench/s_sweep.py.\n\n")
    f.write("| S | contact time error | largest overlap error | elastic restitution error | "
            "damped restitution error | bed wall time (s) | bed steps |\n|---|---|---|---|---|---|---|\n")
    for r in rows:
        f.write(f"| {r[0]:g} | {r[1]:+.2%} | {r[2]:+.2%} | {r[3]:.2%} | {r[4]:.2%} | {r[5]:.2f} | {r[6]} |\n")

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
fig, ax = plt.subplots(1, 2, figsize=(10, 4))
S = [r[0] for r in rows]
for k, lab in ((1, "contact time"), (2, "largest overlap"), (3, "elastic restitution"), (4, "damped restitution")):
    ax[0].loglog(S, [max(abs(r[k]), 1e-6) for r in rows], "o-", label=lab)
ax[0].axhline(0.02, color="gray", ls=":", label="2 %")
ax[0].set_xlabel("collision resolution steps S")
ax[0].set_ylabel("|relative error|")
ax[0].legend()
ax[1].plot([r[5] for r in rows], [max(abs(r[2]), 1e-6) for r in rows], "o-")
for r in rows:
    ax[1].annotate(f"S={r[0]:g}", (r[5], max(abs(r[2]), 1e-6)))
ax[1].set_yscale("log")
ax[1].set_xlabel("wall time of the CI bed, 1 ms (s)")
ax[1].set_ylabel("largest overlap error")
fig.tight_layout()
fig.savefig(os.path.join(HERE, "s_sweep.png"), dpi=100)
