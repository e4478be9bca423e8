#!/usr/bin/python3
"""Per-rank work and traffic of the particle <-> cell exchange against the rank count
(strong scaling at fixed grain counts, weak scaling at a fixed count per rank), from the
counters the run writes (postProcessing/particleLedger/ranks.csv), with a cost
model fitted to the measured exchange time and extrapolated to 64-1024 ranks.

    /usr/bin/python3 bench/scaling.py [--bin build/bin] [--np 1,2,4,8] [--sizes 5000,50000]
        [--weak 5000] [--steps 4] [--model overlap] [--out bench] [--quick] [--keep] [--before-bin DIR]

Case: meltdem.case.exchange_box, ballistic (one DEM step per fluid step): n^3 particles on a
lattice of 60 um spacing (d 20-40 um) in a cube of edge n * 60 um / 0.9, cells of about 50 um.
Strong: n^3 ~ each of --sizes at every --np; weak: n^3 ~ --weak * np. The mesh is decomposed
`simple` into slabs/columns/cubes (np 2: 2x1x1, 4: 2x2x1, 8: 2x2x2); LAMMPS picks its own
processor grid, so a grain's LAMMPS owner need not hold its cells. Counters are per rank and
fluid step over steps 2..N (step 1 holds the start); runs with np > 2 are oversubscribed on
this 2-core machine, so only np 1 and 2 are timed. The cost model:
  t_rank = c * visitors + messages * latency + bytes / bandwidth
c fitted (least squares) to the exchange time of the np 1 and np 2 runs; latency and
bandwidth are ASSUMED cluster values (stated in the table), not measured. Visitors per rank
for P ranks follow the measured halo: ((N/P)^(1/3) + 2 h)^3 lattice sites, h fitted;
messages and bytes per rank the largest measured per neighbour rank and per located grain.
The design before (every rank handled every grain; collectives of the global count) is
modelled alongside with the same c: c * N plus the 316 bytes per grain and step its
allgathers and allreduces carried. --before-bin DIR runs the np 1 and 2 strong cases with
that build's meltdemFoam too and prints the ratio of the exchange times.
Writes scaling.md and scaling.png into --out. --quick: 6^3 and 10^3 grains, np 1,2 (a smoke test).
"""
import argparse
import csv
import os
import shutil
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import coupled as cc
from meltdem.case import exchange_box as eb

HERE = os.path.dirname(os.path.abspath(__file__))
os.environ.setdefault("MELTDEM_SOURCE_DIR", os.path.dirname(HERE))

ap = argparse.ArgumentParser()
ap.add_argument("--bin", default=paths.bin_dir())
ap.add_argument("--np", default="1,2,4,8")
ap.add_argument("--sizes", default="5000,50000", help="grain counts of the strong-scaling series")
ap.add_argument("--weak", type=int, default=5000, help="grains per rank of the weak-scaling series (0: none)")
ap.add_argument("--steps", type=int, default=4)
ap.add_argument("--model", default="overlap")
ap.add_argument("--quick", action="store_true")
ap.add_argument("--out", default=HERE)
ap.add_argument("--keep", action="store_true")
ap.add_argument("--before-bin", default="",
                help="a build of the design before (collectives of the global count): its exchange time "
                     "on the np 1 and 2 strong runs, for the ratio")
args = ap.parse_args()
if args.quick:
    args.np, args.sizes, args.weak, args.steps = "1,2", "216,1000", 0, 3
os.environ["MELTDEM_BIN"] = os.path.abspath(args.bin)

SPACING = 60e-6
CELL = 50e-6
LATENCY, BANDWIDTH = 2e-6, 10e9  # assumed cluster interconnect: s per message, bytes/s
OLD_BYTES_PER_GRAIN = 316.0      # the collectives of the design before, per grain and step
GRID = {1: (1, 1, 1), 2: (2, 1, 1), 4: (2, 2, 1), 8: (2, 2, 2), 16: (4, 2, 2)}
nps = [int(x) for x in args.np.split(",")]
work = tempfile.mkdtemp(prefix="meltdem-scaling-")


def run(series, grains, np_):
    n = max(2, round(grains ** (1 / 3)))
    edge = n * SPACING / 0.9
    cells = max(4, round(edge / CELL))
    case = os.path.join(work, f"{series}.n{n}.np{np_}")
    eb.build(case, args.model, "ballistic", n, cells, args.steps, edge=edge)
    if np_ > 1:
        cc.decompose(case, np_, GRID[np_])
    before = None
    if args.before_bin and series == "strong" and np_ <= 2:
        # the same case with the build before (its allocator kept from returning memory, as this
        # build's meltdemFoam does itself, so that the ratio is the exchange's)
        env = dict(os.environ, MELTDEM_FOAM_SOLVER=os.path.join(args.before_bin, "meltdemFoam"),
                   MALLOC_MMAP_THRESHOLD_=str(1 << 30), MALLOC_TRIM_THRESHOLD_=str(1 << 30))
        saved = dict(os.environ)
        os.environ.update(env)
        try:
            eb.timed_solver(case, np_)
        finally:
            os.environ.clear()
            os.environ.update(saved)
        p = cc.particles_csv(case)
        before = (p["exchange_seconds"][-1] - p["exchange_seconds"][0]) / (len(p) - 1)
        shutil.rmtree(os.path.join(case, "postProcessing"))
    stamps, wall = eb.timed_solver(case, np_)
    with open(os.path.join(case, "postProcessing", "particleLedger", "ranks.csv")) as f:
        rows = list(csv.DictReader(f))
    times = sorted({float(r["time"]) for r in rows})[1:]  # steps 2..N
    keys = ["located", "visitors", "weights", "messages_sent", "messages_received", "bytes_sent", "bytes_received"]
    per_rank = np.zeros((np_, len(keys)))
    for r in rows:
        if float(r["time"]) in times:
            per_rank[int(r["rank"])] += [float(r[k]) for k in keys]
    per_rank /= len(times)
    p = cc.particles_csv(case)
    ex = (p["exchange_seconds"][-1] - p["exchange_seconds"][0]) / (len(p) - 1)
    if not args.keep:
        shutil.rmtree(case)
    d = dict(zip(keys, per_rank.T))
    return dict(series=series, grains=n ** 3, np=np_, cells=cells ** 3, edge=edge, wall=wall,
                exchange=ex, before=before, located=d["located"], visitors=d["visitors"], weights=d["weights"],
                messages=d["messages_sent"] + d["messages_received"], bytes=d["bytes_sent"] + d["bytes_received"])


results = []
for size in [int(x) for x in args.sizes.split(",")]:
    for np_ in nps:
        results.append(run("strong", size, np_))
        r = results[-1]
        print(f"strong {r['grains']:6d} grains np {np_}: visitors/rank max {r['visitors'].max():.0f}, "
              f"messages/rank max {r['messages'].max():.0f}, kB/rank max {r['bytes'].max() / 1e3:.1f}, "
              f"exchange {r['exchange'] * 1e3:.2f} ms/step (rank 0), wall {r['wall']:.1f} s", flush=True)
if args.weak:
    for np_ in nps:
        results.append(run("weak", args.weak * np_, np_))
        r = results[-1]
        print(f"weak   {r['grains']:6d} grains np {np_}: visitors/rank max {r['visitors'].max():.0f}, "
              f"messages/rank max {r['messages'].max():.0f}, kB/rank max {r['bytes'].max() / 1e3:.1f}", flush=True)

# the cost model: c per visitor from the timed runs (np 1 and 2; rank 0's clock and counters)
timed = [r for r in results if r["np"] <= 2]
v0 = np.array([r["visitors"][0] for r in timed])
t0 = np.array([r["exchange"] for r in timed])
c = float(v0 @ t0 / (v0 @ v0))
fit_err = float(np.max(np.abs(c * v0 - t0) / t0))
# the halo: visitors = ((N/P)^(1/3) + 2h)^3, the median over the runs at np > 1
halo = [0.5 * (np.mean(r["visitors"]) ** (1 / 3) - (r["grains"] / r["np"]) ** (1 / 3))
        for r in results if r["np"] > 1]
h = float(np.median(halo)) if halo else 0.25
parallel = [r for r in results if r["np"] > 1]
# traffic: messages per neighbour rank and bytes per located particle, the largest measured (the
# LAMMPS and mesh decompositions need not match: most of a rank's particles may go elsewhere)
msgs = max((np.max(r["messages"]) / (r["np"] - 1) if r["np"] <= 8 else 0 for r in parallel), default=22.0)
bytes_per_grain = max((np.max(r["bytes"] / r["located"]) for r in parallel), default=800.0)


def model_new(N, P):
    v = ((N / P) ** (1 / 3) + 2 * h) ** 3
    return c * v + msgs * min(P - 1, 26) * LATENCY + bytes_per_grain * N / P / BANDWIDTH


def model_old(N, P):
    return c * N + 2 * np.log2(max(P, 2)) * 6 * LATENCY + 2 * OLD_BYTES_PER_GRAIN * N / BANDWIDTH


rows = ["| series | grains | np | cells | located / rank (max) | visitors / rank (mean, max) | "
        "weights / rank (max) | messages / rank (max) | kB / rank (max) | exchange ms / step (rank 0) | "
        "before: ms / step | before / now |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|"]
for r in results:
    timed_s = f"{r['exchange'] * 1e3:.2f}" if r["np"] <= 2 else "(oversubscribed)"
    before_s = (f"{r['before'] * 1e3:.2f} | {r['before'] / r['exchange']:.2f}" if r.get("before") else "– | –")
    rows.append(f"| {r['series']} | {r['grains']} | {r['np']} | {r['cells']} | {r['located'].max():.0f} | "
                f"{r['visitors'].mean():.0f}, {r['visitors'].max():.0f} | {r['weights'].max():.0f} | "
                f"{r['messages'].max():.0f} | {r['bytes'].max() / 1e3:.1f} | {timed_s} | {before_s} |")
P = [64, 128, 256, 512, 1024]
sizes_x = [5e4, 1e6, 1e7]
ext = ["| grains | " + " | ".join(f"P = {p}" for p in P) + " |", "|---|" + "---|" * len(P)]
for N in sizes_x:
    cells_ = [f"{model_new(N, p) * 1e3:.3f} ms (before: {model_old(N, p) * 1e3:.1f})" for p in P]
    ext.append(f"| {N:.0e} | " + " | ".join(cells_) + " |")

os.makedirs(args.out, exist_ok=True)
with open(os.path.join(args.out, "scaling.md"), "w") as f:
    f.write("# Exchange scaling: per-rank work and traffic against the rank count\n\n")
    f.write(f"Generated by bench/scaling.py (`--np {args.np} --sizes {args.sizes} --weak {args.weak} --steps "
            f"{args.steps} --model {args.model}`), counters from `ranks.csv` per rank and fluid step "
            "(steps 2..N). Ballistic case of meltdem.case.exchange_box (lattice spacing 60 µm, d 20–40 µm, "
            "cells ≈ 50 µm). np > 2 oversubscribed on 2 cores: counted, not timed.\n\n")
    f.write("\n".join(rows) + "\n\n")
    f.write(f"Cost model fitted to the np 1 and 2 runs: c = {c * 1e9:.0f} ns per visitor and fluid step (worst "
            f"fit error {100 * fit_err:.0f} %); halo h = {h:.2f} lattice spacings; {msgs:.1f} messages per "
            f"neighbour rank and step and {bytes_per_grain:.0f} bytes per located grain and step (sent + "
            "received, the largest measured: the LAMMPS and mesh decompositions need not match). ASSUMED "
            f"interconnect: {LATENCY * 1e6:g} µs per message, {BANDWIDTH / 1e9:g} GB/s. The design before: "
            f"c N per rank plus {OLD_BYTES_PER_GRAIN:g} bytes per grain and step, twice (allreduce), and "
            "12 log2 P latencies.\n\n")
    f.write("Predicted exchange time per rank and fluid step (strong scaling; in brackets the design before, "
            "every rank handling every grain with collectives of the global count):\n\n")
    f.write("\n".join(ext) + "\n")

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
for series, marker in (("strong", "o"), ("weak", "s")):
    for N in sorted({r["grains"] for r in results if r["series"] == series}) if series == "strong" else [None]:
        rs = [r for r in results if r["series"] == series and (N is None or r["grains"] == N)]
        if not rs:
            continue
        label = f"{series} {N} grains" if N else f"weak {args.weak}/rank"
        x = [r["np"] for r in rs]
        axes[0].plot(x, [r["visitors"].max() for r in rs], marker + "-", label=label)
        axes[1].plot(x, [r["bytes"].max() / 1e3 for r in rs], marker + "-", label=label)
axes[0].set(xscale="log", yscale="log", xlabel="ranks", ylabel="visitors per rank (max)", title="work per rank")
axes[1].set(xscale="log", xlabel="ranks", ylabel="kB per rank and step (max)", title="traffic per rank")
for N in sizes_x:
    axes[2].loglog(P, [model_new(N, p) * 1e3 for p in P], "o-", label=f"{N:.0e} grains")
    axes[2].loglog(P, [model_old(N, p) * 1e3 for p in P], "x--", label=f"{N:.0e} grains, design before")
axes[2].set(xlabel="ranks", ylabel="ms per rank and step", title="cost model (extrapolated)")
for ax in axes:
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(args.out, "scaling.png"), dpi=110)
print(f"wrote {args.out}/scaling.md and .png")
if not args.keep:
    shutil.rmtree(work, ignore_errors=True)
else:
    print(f"cases kept in {work}")
