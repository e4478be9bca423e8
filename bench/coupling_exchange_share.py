#!/usr/bin/python3
"""Share of the coupled meltdemFoam + LAMMPS step time spent in the particle <-> cell
exchange (target <= 5 %), a few thousand particles, serial and np 2.

    /usr/bin/python3 bench/coupling_exchange_share.py [--bin build/bin] [--np 1,2]
        [--models centre,neighbours,overlap] [--scenarios granular,ballistic] [--steps 60] [--repeat 2]
        [--per-axis 15] [--cells 20] [--quick] [--out bench] [--keep]

Case (written with meltdem.case.coupled): a closed 1 x 1 x 1 mm box of quiescent
argon-like gas at 1500 K (rho 0.32, mu 5.6e-5, cp 520, k 0.06; no-slip adiabatic walls),
--cells^3 hexahedra (20^3: h = 50 um), energy on, flow on, fluid step fixed at 1 us
(maxDeltaT; the quiescent gas never reaches the Courant limit). The particles: a simple
cubic lattice of spacing 60 um filling [0.05, 0.95] mm^3 (15^3 = 3375 particles, 4.8 % solid
volume; lattice origin 0.4 spacings, so that no centre lies on a cell face, where the cell
search has to break a tie), diameters uniform 20-40 um (atom-style random, fixed seed; 0.4-0.8 cells per
diameter on 20^3 cells), steel rho 7900, cp 500, created at 300 K, fix powder/melt Tmelt 1700 K
above the gas temperature: they HEAT BUT DO NOT MELT (no mass/enthalpy handed over, but the
heat, drag and buoyancy of every particle are sampled and deposited every step, which is the
whole exchange), fix gravity 9.81 m/s^2 (-z), LAMMPS box 0.1 mm larger than the mesh on
each side. Two DEM scenarios:
  * granular : pair_style granular/powder (hertz/material, tsuji/alpha damping, mindlin), as
               examples/powder-bed; DEM step 1e-8 s (Hertz contact time of 30 um steel at
               0.1 m/s resolved by ~14 steps), 100 DEM sub-cycles per fluid step. The
               particles start 20-40 um apart, so no contact forms in the simulated 0.1 ms:
               LAMMPS pays for neighbour lists and the pair loop, not for contacts;
  * ballistic: no pair style (pair_style none), DEM step = fluid step (1 sub-cycle): LAMMPS
               costs almost nothing, so the exchange share is the largest it can be.
For each scenario, distribution model and rank count the solver runs --steps fluid steps;
the shares are taken over steps 2..N (the first step holds LAMMPS's setup):
  exchange share = d(exchange_seconds) / d(loop time), LAMMPS share likewise, fluid = rest,
with exchange_seconds and lammps_seconds from postProcessing/particleLedger/particles.csv
(rank 0's wall clock: sampling, distribution, deposit, lost-particle handling) and the loop
time = the wall-clock time between the log's ExecutionTime lines of steps 1 and N, stamped
as the solver prints them (the log's own ExecutionTime is CPU time to 0.01 s and ClockTime
whole seconds: too coarse). On np 2 both clocks start after a barrier: a rank's wait for
the other's fluid solve is fluid time, its wait for the other's DEM steps LAMMPS time. Each
configuration runs --repeat times (interleaved) and the run with the shortest loop is kept
(the machine is shared).
Writes coupling_exchange_share.md and .png into --out. --quick: 8^3 particles, 10^3 cells,
12 steps, one repeat (about 15 s). Not a timed test; ctest -L bench runs --quick at a tiny size as a
smoke test.
"""
import argparse
import os
import shutil
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import coupled as cc
from meltdem.case import exchange_box as eb

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
os.environ.setdefault("MELTDEM_SOURCE_DIR", ROOT)

ap = argparse.ArgumentParser()
ap.add_argument("--bin", default=paths.bin_dir())
ap.add_argument("--np", default="1,2")
ap.add_argument("--models", default="centre,neighbours,overlap")
ap.add_argument("--scenarios", default="granular,ballistic")
ap.add_argument("--steps", type=int, default=60)
ap.add_argument("--repeat", type=int, default=2, help="runs per configuration, fastest kept")
ap.add_argument("--per-axis", type=int, default=15, help="particles per axis of the lattice")
ap.add_argument("--cells", type=int, default=20, help="cells per axis")
ap.add_argument("--quick", action="store_true", help="8^3 particles, 10^3 cells, 12 steps")
ap.add_argument("--out", default=HERE)
ap.add_argument("--keep", action="store_true", help="keep the cases (printed)")
args = ap.parse_args()
if args.quick:
    args.per_axis, args.cells, args.steps, args.repeat = 8, 10, 12, 1
if args.steps < 3:
    raise SystemExit("--steps must be >= 3 (the shares are taken over steps 2..N)")
os.environ["MELTDEM_BIN"] = os.path.abspath(args.bin)
if not os.path.exists(os.path.join(args.bin, "meltdemFoam")):
    raise SystemExit(f"{args.bin}/meltdemFoam not found: build the target meltdemFoam (Release) first")

L = 1e-3                      # box edge [m]
DT = eb.DT
T_GAS, RHO_G, MU_G, CP_G, K_G = eb.T_GAS, eb.RHO_G, eb.MU_G, eb.CP_G, eb.K_G
RHO_P, CP_P, TM, T0 = eb.RHO_P, eb.CP_P, eb.TM, eb.T0
D_LO, D_HI = eb.D_LO, eb.D_HI
FILL = eb.fill(L)             # the lattice fills this cube


def build(case, model, scenario, particles=True):
    eb.build(case, model, scenario, args.per_axis, args.cells, args.steps, edge=L, particles=particles)


timed_solver = eb.timed_solver


def run(label, model, scenario, np_, particles=True):
    case = os.path.join(work, label)
    build(case, model, scenario, particles)
    if np_ > 1:
        cc.decompose(case, np_)
    stamps, wall = timed_solver(case, np_)
    if len(stamps) != args.steps:
        raise SystemExit(f"{label}: {len(stamps)} ExecutionTime lines for {args.steps} steps (see {case})")
    # loop: steps 2..N; first: the launch (MPI, mesh, LAMMPS input) up to the end of step 1
    r = dict(label=label, model=model, scenario=scenario, np=np_, wall=wall, loop=stamps[-1] - stamps[0],
             first=stamps[0])
    if particles:
        p = cc.particles_csv(case)
        if len(p) != args.steps:
            raise SystemExit(f"{label}: particles.csv has {len(p)} rows for {args.steps} steps")
        r.update(particles=int(p["particles"][0]), dem_steps=int(p["dem_steps"][1]),
                 exchange=p["exchange_seconds"][-1] - p["exchange_seconds"][0],
                 lammps=p["lammps_seconds"][-1] - p["lammps_seconds"][0],
                 exchange_total=p["exchange_seconds"][-1], lammps_total=p["lammps_seconds"][-1],
                 heat=float(np.sum(p["heat_absorbed"])), melted=float(np.sum(p["mass_melted"])))
        if r["particles"] != args.per_axis ** 3:
            raise SystemExit(f"{label}: {r['particles']} particles, expected {args.per_axis ** 3}")
    return r


work = tempfile.mkdtemp(prefix="meltdem-exchange-share-")
nps = [int(x) for x in args.np.split(",")]
models = args.models.split(",")
scenarios = args.scenarios.split(",")
load0 = os.getloadavg()
configs = [(sc, m, np_) for np_ in nps for sc in scenarios for m in models]
best = {}
for rep in range(args.repeat):
    for sc, m, np_ in configs:
        r = run(f"{sc}.{m}.np{np_}.{rep}", m, sc, np_)
        print(f"{sc:9s} {m:10s} np {np_} run {rep + 1}: loop {r['loop']:.3f} s, exchange {r['exchange']:.3f} s "
              f"({100 * r['exchange'] / r['loop']:.2f} %), LAMMPS {r['lammps']:.3f} s "
              f"({100 * r['lammps'] / r['loop']:.1f} %), wall {r['wall']:.2f} s", flush=True)
        key = (sc, m, np_)
        r["runs"] = best.get(key, {}).get("runs", []) + [r["loop"]]
        if key not in best or r["loop"] < best[key]["loop"]:
            best[key] = r
        else:
            best[key]["runs"] = r["runs"]
load1 = os.getloadavg()
results = [best[k] for k in configs]

TARGET = 5.0
rows = ["| scenario | model | np | particles | DEM steps / fluid step | loop time (s) | ms / fluid step | "
        "exchange (s) | exchange share | LAMMPS share | fluid + rest share | target ≤ 5 % |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|"]
for r in results:
    loop = r["loop"]
    rest = loop - r["exchange"] - r["lammps"]
    r.update(share_ex=100 * r["exchange"] / loop, share_lmp=100 * r["lammps"] / loop, share_rest=100 * rest / loop)
    rows.append(f"| {r['scenario']} | {r['model']} | {r['np']} | {r['particles']} | {r['dem_steps']} | {loop:.3f} | "
                f"{loop / (args.steps - 1) * 1e3:.2f} | {r['exchange']:.3f} | **{r['share_ex']:.2f} %** | "
                f"{r['share_lmp']:.1f} % | {r['share_rest']:.1f} % | "
                f"{'met' if r['share_ex'] <= TARGET else 'MISSED'} |")
table = "\n".join(rows)
print()
print(table)

ms = 1e3 / (args.steps - 1)
cost_rows = ["| scenario | model | np | exchange ms / step | exchange µs / particle / step | LAMMPS ms / step | "
             "fluid + rest ms / step | loop times of the repeats (s) | launch to end of step 1 (s) | run wall (s) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
for r in results:
    cost_rows.append(f"| {r['scenario']} | {r['model']} | {r['np']} | {r['exchange'] * ms:.2f} | "
                     f"{r['exchange'] * ms * 1e3 / r['particles']:.2f} | {r['lammps'] * ms:.2f} | "
                     f"{(r['loop'] - r['exchange'] - r['lammps']) * ms:.2f} | "
                     f"{', '.join(f'{x:.2f}' for x in r['runs'])} | {r['first']:.2f} | {r['wall']:.2f} |")
cost_table = "\n".join(cost_rows)
print()
print(cost_table)

met = [r for r in results if r["share_ex"] <= TARGET]
missed = [r for r in results if r["share_ex"] > TARGET]
lines = []
lines.append(f"Target exchange share ≤ {TARGET:g} %: met in {len(met)} of {len(results)} runs.")
for m in models:
    rm = [r for r in results if r["model"] == m]
    if rm:
        lo, hi = min(r["share_ex"] for r in rm), max(r["share_ex"] for r in rm)
        us = [r["exchange"] * ms * 1e3 / r["particles"] for r in rm]
        lines.append(f"`{m}`: exchange share {lo:.2f}–{hi:.2f} %, {min(us):.2f}–{max(us):.2f} µs per particle "
                     f"and fluid step (rank 0).")
# overlap against centre, per particle, in the same scenario and rank count (targets: overlap at most
# 2x centre's per-particle cost, and at most 10 % of the coupled step)
OVERLAP_COST_TARGET, OVERLAP_SHARE_TARGET = 2.0, 10.0
for r in [r for r in results if r["model"] == "overlap"]:
    c = [q for q in results if q["model"] == "centre" and q["scenario"] == r["scenario"] and q["np"] == r["np"]]
    if c:
        ratio = r["exchange"] / c[0]["exchange"]
        lines.append(f"`overlap` / `centre` exchange cost, {r['scenario']} np {r['np']}: {ratio:.2f} "
                     f"(target ≤ {OVERLAP_COST_TARGET:g}: {'met' if ratio <= OVERLAP_COST_TARGET else 'MISSED'}); "
                     f"`overlap` share {r['share_ex']:.1f} % (target ≤ {OVERLAP_SHARE_TARGET:g} %: "
                     f"{'met' if r['share_ex'] <= OVERLAP_SHARE_TARGET else 'MISSED'}).")
if missed:
    worst = max(missed, key=lambda r: r["share_ex"])
    dom = max((("exchange", worst["share_ex"]), ("LAMMPS", worst["share_lmp"]), ("fluid + rest", worst["share_rest"])),
              key=lambda t: t[1])
    lines.append(f"Largest exchange share: {worst['share_ex']:.1f} % ({worst['scenario']}, {worst['model']}, "
                 f"np {worst['np']}); the largest part of that run is {dom[0]} ({dom[1]:.1f} %).")

os.makedirs(args.out, exist_ok=True)
with open(os.path.join(args.out, "coupling_exchange_share.md"), "w") as f:
    f.write("# Coupled step time: share of the particle <-> cell exchange\n\n")
    f.write(f"Generated by bench/coupling_exchange_share.py (`--np {args.np} --models {args.models} --scenarios "
            f"{args.scenarios} --steps {args.steps} --per-axis {args.per_axis} --cells {args.cells}`; shared 2-core "
            f"machine, Release build, fastest of {args.repeat} interleaved run(s) each; load average "
            f"{load0[0]:.2f} before, {load1[0]:.2f} after: other jobs shared the 2 cores, so timings are ±20 %, np 2 "
            "the most affected).\n\n")
    f.write(f"Case: closed {L * 1e3:g} mm cube of quiescent gas at {T_GAS:g} K (rho {RHO_G:g}, mu {MU_G:g}, cp "
            f"{CP_G:g}, k {K_G:g}), {args.cells}^3 hexahedra (h = {L / args.cells * 1e6:g} µm), energy and flow on, "
            f"fluid step {DT:g} s for {args.steps} steps; {args.per_axis}^3 = {args.per_axis ** 3} steel particles "
            f"(d uniform {D_LO * 1e6:g}–{D_HI * 1e6:g} µm, rho {RHO_P:g}, cp {CP_P:g}) on a simple cubic lattice "
            f"filling [{FILL[0] * 1e3:g}, {FILL[1] * 1e3:g}] mm³ (no centre on a cell face), created at {T0:g} K, "
            "`fix powder/melt` Tmelt "
            f"{TM:g} K above the gas: the particles heat (Ranz–Marshall with the local gas), feel drag and buoyancy "
            "and fall under `fix gravity`, but none melts, so every particle samples the fluid and deposits heat and "
            "momentum every step while no metal is handed over. LAMMPS box 0.1 mm beyond the mesh.\n\n")
    f.write("- **granular**: `pair_style granular/powder` (hertz/material E 200 GPa, tsuji/alpha 1.5, mindlin µ 0.1, "
            "as examples/powder-bed), DEM step 1e-8 s, so 100 DEM sub-cycles per fluid step; the particles start "
            "20–40 µm apart and form no contact within the run (LAMMPS pays for neighbour lists and the pair loop).\n")
    f.write("- **ballistic**: no pair style, DEM step = fluid step (1 sub-cycle): LAMMPS costs almost nothing, the "
            "worst case for the exchange share.\n\n")
    f.write("Shares over fluid steps 2..N (step 1 holds LAMMPS's setup). exchange = Δ`exchange_seconds`, LAMMPS = "
            "Δ`lammps_seconds` of `postProcessing/particleLedger/particles.csv` (rank 0's wall clock); loop time = "
            "wall-clock time between the log lines `ExecutionTime` of steps 1 and N, stamped by the script as the "
            "solver prints them (the log's own ExecutionTime is CPU time to 0.01 s, ClockTime whole seconds). "
            "fluid + rest = loop − exchange − LAMMPS: the fluid "
            "solve (the particles' drag and heat set the gas moving, so it is real work: a particle-free run of the "
            "same gas needs no pressure iterations at all), the `meltdemBalance` function object and the ledger "
            "booking after each step (under 0.5 % of the samples in a profile) and the I/O. On np 2 the exchange "
            "and LAMMPS clocks start after a barrier: rank 0's wait for the other rank's fluid solve counts as "
            "fluid time, its wait for the other's DEM steps as LAMMPS time.\n\n")
    f.write(table + "\n\nCosts per fluid step:\n\n" + cost_table + "\n\n")
    for line in lines:
        f.write(f"- {line}\n")

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, axes = plt.subplots(1, len(scenarios), figsize=(6.5 * len(scenarios), 5.0), squeeze=False)
for ax, sc in zip(axes[0], scenarios):
    rs = [r for r in results if r["scenario"] == sc]
    x = np.arange(len(rs))
    ex = np.array([r["share_ex"] for r in rs])
    lm = np.array([r["share_lmp"] for r in rs])
    fl = np.array([r["share_rest"] for r in rs])
    ax.bar(x, ex, color="tab:red", label="exchange")
    ax.bar(x, lm, bottom=ex, color="tab:blue", label="LAMMPS")
    ax.bar(x, fl, bottom=ex + lm, color="tab:gray", label="fluid + rest")
    for xi, e in zip(x, ex):
        ax.annotate(f"{e:.1f} %", (xi, 101), ha="center", fontsize=8, color="tab:red")
    ax.axhline(TARGET, color="k", ls=":", label=f"target {TARGET:g} %")
    ax.set_xticks(x)
    ax.set_xticklabels([f"{r['model']}\nnp {r['np']}" for r in rs], fontsize=8)
    ax.set_ylim(0, 110)
    ax.set_ylabel("share of the coupled loop time (%)")
    ax.set_title(f"{sc}: {rs[0]['particles'] if rs else 0} particles, {rs[0]['dem_steps'] if rs else 0} DEM "
                 "steps / fluid step", fontsize=9)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=4)
fig.tight_layout()
fig.savefig(os.path.join(args.out, "coupling_exchange_share.png"), dpi=100)
print(f"wrote {os.path.join(args.out, 'coupling_exchange_share.md')} and .png")
if args.keep:
    print("cases kept in", work)
else:
    shutil.rmtree(work)
