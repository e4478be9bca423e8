#!/usr/bin/python3
"""Collision resolution steps S of fix powder/dt (Codina2019 collisionResolutionSteps): cost
against accuracy, so that a user can pick S.

    /usr/bin/python3 bench/collision_resolution_sweep.py [--bin build/bin] [--S 2,3,5,7,10,15,20,30,40]

For each S (dt = t_c / S from fix powder/dt, eq. 3.1-3.3):
  * head-on elastic collision of two steel spheres (d 30 um, 2 m/s, pair_style
    granular/powder, no damping): contact time vs eq. 3.1 (2.87, and vs exact Hertz,
    2.8683) and largest overlap/R vs the elastic Hertz peak (15 m* U^2/(16 E* sqrt R*))^(2/5);
  * the same collision with damping tsuji e = 0.5 (granular/powder's exact e -> alpha
    map): restitution error against the prescribed 0.5;
  * a small pour: the CI powder bed of examples/powder-bed (0.30 x 0.30 mm floor,
    153 particles, Codina2019 table 4.3 settings), its first 1 ms (injection at -2 m/s and
    the impacts on the floor): wall time (serial), steps, largest overlap/R of any contact
    and largest particle speed (compute powder/overlap every 20 steps, also at S = 10).
Writes bench/collision_resolution_sweep.md and bench/collision_resolution_sweep.png.
"""
import argparse
import os
import re
import subprocess
import tempfile
import time

from meltdem.testing.dem import delta_max, mass, t_contact, two_spheres
from meltdem.testing.lammps_run import run, thermo_runs

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

ap = argparse.ArgumentParser()
ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
ap.add_argument("--S", default="2,3,5,7,10,15,20,30,40")
args = ap.parse_args()
os.environ.setdefault("MELTDEM_BIN", os.path.abspath(args.bin))
os.environ.setdefault("MELTDEM_SOURCE_DIR", ROOT)

LMP = os.path.join(os.path.abspath(args.bin), "meltdem-lmp")
R, U, E_PRESCRIBED = 15e-6, 2.0, 0.5
SS = [float(s) for s in args.S.split(",")]
EXACT = 2.0 * 1.471637592162107 * (15.0 / 16.0) ** 0.4  # exact Hertz: 2.8683 instead of eq. 3.1's 2.87
POUR_EVERY = 20


def collision(S, damped):
    text = two_spheres(-R - 5e-8, R + 5e-8, 2 * R, 2 * R, U / 2, -U / 2).replace("pair_style granular\n",
                                                                                 "pair_style granular/powder\n")
    if damped:
        text = text.replace("hertz/material 200000000000.0 0.0 0.3 damping velocity",
                            f"hertz/material 200000000000.0 {E_PRESCRIBED} 0.3 damping tsuji")
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
    cross = []  # contact starts and ends where the gap changes sign (linear interpolation)
    for k in range(1, len(d)):
        if (d[k - 1] <= 0) != (d[k] <= 0):
            cross.append(t[k - 1] + (t[k] - t[k - 1]) * (0 - d[k - 1]) / (d[k] - d[k - 1]))
    tc = cross[1] - cross[0] if len(cross) >= 2 else float("nan")
    return tc, max(r["c_ov[1]"] for r in rows), rows[-1]["v_vrel"] / U


def pour(S):
    with tempfile.TemporaryDirectory() as d:
        t0 = time.time()
        p = subprocess.run([LMP, "-in", os.path.join(ROOT, "examples", "powder-bed", "in.powder-bed"), "-log",
                            "none", "-echo", "none", "-var", "Lx", "3e-4", "-var", "Lz", "3e-4", "-var", "sides",
                            "periodic", "-var", "tend", "1e-3", "-var", "S", str(S), "-var", "every",
                            str(POUR_EVERY), "-var", "dump", "bed.dump"],
                           cwd=d, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        wall = time.time() - t0
    if p.returncode != 0:
        print(p.stdout[-3000:])
        raise SystemExit(f"pour at S = {S} failed")
    rows = thermo_runs(p.stdout)[0]
    steps = int(re.findall(r"Loop time of \S+ on \d+ procs for (\d+) steps", p.stdout)[-1])
    return dict(wall=wall, steps=steps, pour_ov=max(r["c_ov[1]"] for r in rows),
                vmax=max(r["c_ov[3]"] for r in rows),
                popcorn=int(max(r["c_ov[2]"] for r in rows)), atoms=int(rows[-1]["Atoms"]))


m = mass(R)
ref_tc = t_contact(m, m, R, R, U)
ref_exact = ref_tc * EXACT / 2.87
ref_ov = delta_max(m, m, R, R, U) / R
rows = []
for S in SS:
    tc, ov, e_el = collision(S, False)
    _, _, e_d = collision(S, True)
    pr = pour(S)
    rows.append(dict(S=S, tc31=tc / ref_tc - 1, tcx=tc / ref_exact - 1, ov=ov, overr=ov / ref_ov - 1,
                     e_el=abs(e_el) - 1, e_d=abs(e_d) - E_PRESCRIBED, **pr))
    print({k: (round(v, 6) if isinstance(v, float) else v) for k, v in rows[-1].items()}, flush=True)

with open(os.path.join(HERE, "collision_resolution_sweep.md"), "w") as f:
    f.write("# fix powder/dt: collision resolution steps S, cost vs accuracy\n\n")
    f.write(f"Generated by bench/collision_resolution_sweep.py (serial, shared 2-core machine: wall times "
            f"+-10 %).\n\n"
            f"- Collision: two steel spheres head-on, d 30 um, 2 m/s, pair_style granular/powder; eq. 3.1 "
            f"t_c = {ref_tc:.4g} s (exact Hertz {ref_exact:.4g} s), elastic peak overlap/R = {ref_ov:.4g}. "
            f"Restitution error: damping tsuji e = {E_PRESCRIBED} prescribed, measured e - {E_PRESCRIBED} "
            f"(elastic: e - 1).\n"
            f"- Pour: CI powder bed (examples/powder-bed, 0.30 x 0.30 mm, 153 particles, alpha 1.5/1, "
            f"g x 10, -2 m/s), first 1 ms; compute powder/overlap every {POUR_EVERY} steps (its cost is "
            f"included). Pop-corn = contacts above overlap/R 0.01 (1.6 x the elastic peak of the hardest "
            f"impact possible in this pour).\n\n")
    f.write("| S | contact time vs eq. 3.1 | vs exact Hertz | peak overlap/R (collision) | vs elastic Hertz | "
            "elastic e - 1 | damped e - 0.5 | pour wall time (s) | pour steps | pour largest overlap/R | "
            "pour pop-corn contacts | pour largest speed (m/s) |\n|" + "---|" * 12 + "\n")
    for r in rows:
        f.write(f"| {r['S']:g} | {r['tc31']:+.2%} | {r['tcx']:+.2%} | {r['ov']:.4g} | {r['overr']:+.2%} | "
                f"{r['e_el']:+.4f} | {r['e_d']:+.4f} | {r['wall']:.2f} | {r['steps']} | {r['pour_ov']:.3g} | "
                f"{r['popcorn']} | {r['vmax']:.3g} |\n")
    best = [r for r in rows if abs(r["tc31"]) <= 0.02 and abs(r["e_d"]) <= 0.01 and r["popcorn"] == 0]
    if best:
        f.write(f"\nSmallest S with contact time within 2 %, restitution within 0.01 and no pop-corn: "
                f"S = {best[0]['S']:g} (pour {best[0]['wall']:.2f} s).\n")

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
S = [r["S"] for r in rows]
for k, lab in (("tc31", "contact time vs eq. 3.1"), ("overr", "peak overlap vs Hertz"),
               ("e_el", "elastic restitution (e - 1)"), ("e_d", "damped restitution (e - 0.5)")):
    ax[0].loglog(S, [max(abs(r[k]), 1e-5) for r in rows], "o-", label=lab)
ax[0].axhline(0.02, color="gray", ls=":", label="2 %")
ax[0].set_xlabel("collision resolution steps S")
ax[0].set_ylabel("|error| (relative; restitution absolute)")
ax[0].legend(fontsize=8)
ax[1].plot([r["wall"] for r in rows], [r["pour_ov"] for r in rows], "o-", label="pour: largest overlap/R")
ax[1].plot([r["wall"] for r in rows], [r["ov"] for r in rows], "s--", label="collision: peak overlap/R")
ax[1].axhline(0.01, color="gray", ls=":", label="pop-corn threshold 0.01")
ax[1].set_xlabel("wall time of the 1 ms pour (s)")
ax[1].set_ylabel("largest overlap / R")
ax[1].set_yscale("log")
for r in rows:
    ax[1].annotate(f"S={r['S']:g}", (r["wall"], r["pour_ov"]), fontsize=8)
ax[1].legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(HERE, "collision_resolution_sweep.png"), dpi=100)
