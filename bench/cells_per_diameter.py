#!/usr/bin/python3
"""Cells per particle diameter x particle -> cell model on a COUPLED case: wall time vs the
error of the drag force and of the heat a particle takes from the gas (speed vs accuracy).

    /usr/bin/python3 bench/cells_per_diameter.py [--bin build/bin] [--cpd 0.125,0.25,0.5,1,2,4,8]
        [--models centre,neighbours,overlap] [--t-end 1e-3] [--max-steps 5000] [--max-run 300]
        [--timeout 600] [--quick] [--out bench] [--keep]

The question a user asks: how fine may the mesh be around the grains, and with which
distribution model, before the coupling's answer degrades? In the unresolved coupling the
particle samples the gas of the cells its weights cover -- gas which its own drag has pushed
along and its own heat sink has cooled. The smaller the cells against the grain, the more of
its own disturbance a particle samples: it sees a smaller slip velocity and a smaller
temperature difference than the undisturbed gas (the reference) and takes too little drag and
heat. (bench/distribution_models.* has the standalone weights; this is their coupled effect.)

Case (meltdem.case.coupled.channel_case, its mesh regraded): a steel-like grain
d = 100 um (7800 kg/m3; cp 5000 J/kg K, ten times steel, so that it warms only ~0.5 % in the
run and its heat rate stays steady; Tm 5000 K: no melting) HELD in the middle of a closed
cube of gas (no time integration, `velocity set 0 -0.1 0`: it slips through the gas at
0.1 m/s and stays where it is, so the mesh around it is the same all run). Gas at rest at
1000 K, the particle at 300 K. The gas is artificial (like Codina2019's argon, chosen so that
the near field is steady in a hundred steps): rho 0.12, mu 1.8e-4 (nu 1.5e-3 m2/s), cp 1000,
k 0.18 (Pr 1); Re = 6.7e-3 (Stokes regime: Cd Re / 24 = 1.006), Nu = 2.05.
Cube 40 d = 4 mm; slip walls, top fixed U = 0 / T = 1000 K, bottom p = 0. Mesh: a uniform
core of 2 ceil(c) + 1 cells of h = d / c (c = cells per diameter) around the grain, graded
outwards (cell-to-cell ratio ~1.5) to the walls: 5^3 cells at c = 0.125, 39^3 at c = 8. The
grain's centre sits 0.2 cells off the core cell's centre in x, y and z (a generic position:
at c <= 0.5 the sphere lies inside its cell, finer it crosses faces). Fluid step = DEM step
= 10 us (fixed; Courant <= 0.1), --t-end 1 ms (nu t / d^2 = 150: the disturbance the grain
samples is within ~2 % of steady, see the drift column). Solver tolerances 1e-10 (not the
ledger tests' 1e-14), 2 pressure correctors.
Results, each the mean over the last 10 % of the run (the same window in every run):
  * drag force on the grain (LAMMPS force, y) vs the reference;
  * heat rate into the grain (fix powder/melt f_melt[6] per time) vs the reference;
  * the coldest and hottest gas of the run (below the grain's 300 K or above the 1000 K gas:
    the explicit exchange overshoots, the onset of the instability that crashes `centre`).
Stability: the exchange is a two-body relaxation of the grain and its share of its cells
(doc/foam_particle_coupling.rst), so no fluid step drives the gas beyond the grain's
temperature; should meltdemFoam's bound check (temperatureBounds) still stop a run, it names the
cells' exchange time and the run is repeated at half of it, if it costs at most --max-steps steps
and an estimated --max-run seconds; otherwise its cost is estimated (start-up + cells x steps x
the cost per cell-step of the largest run so far) and it is listed as not run.
Reference: the same LAMMPS input run standalone with the uniform undisturbed gas
(`fix powder/melt ... ambient 1000 0.18 0.12 1.8e-4 1000 0 0 0`), i.e. the drag and
Ranz-Marshall laws at the far-field gas state (the analytic Stokes drag 3 pi mu d v and
Nu = 2 heat are printed for comparison). The drift between the last two 10 % windows is
printed as a steadiness check.
Wall time: the whole solver run (blockMesh excluded), serial, --timeout per run; the
machine is shared, so absolute times are loaded-machine times: compare the ratios. About
15 min on a loaded machine; --quick (c = 0.5 and 1, 0.4 ms, reruns of at most 300 steps)
about 20 s: the smoke test.
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import tempfile
import time

import numpy as np

from meltdem import paths
from meltdem.case import coupled as cc
from meltdem.case import foam as fc

from build_stamp import build_stamp, stamp_line

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
os.environ.setdefault("MELTDEM_SOURCE_DIR", ROOT)

ap = argparse.ArgumentParser()
ap.add_argument("--bin", default=paths.bin_dir())
ap.add_argument("--cpd", default="0.125,0.25,0.5,1,2,4,8", help="cells per particle diameter")
ap.add_argument("--models", default="centre,neighbours,overlap")
ap.add_argument("--t-end", type=float, default=1e-3)
ap.add_argument("--timeout", type=float, default=600, help="seconds per coupled run")
ap.add_argument("--max-steps", type=int, default=5000,
                help="largest number of fluid steps of a rerun at the step the bound check asks for")
ap.add_argument("--max-run", type=float, default=400,
                help="largest estimated wall time (s) of such a rerun")
ap.add_argument("--quick", action="store_true", help="smoke test: c = 0.5, 1, 0.4 ms, reruns of <= 300 steps")
ap.add_argument("--out", default=HERE)
ap.add_argument("--keep", action="store_true", help="keep the cases (printed)")
args = ap.parse_args()
if args.quick:
    args.cpd, args.t_end, args.max_steps = "0.5,1", 4e-4, 300
os.environ["MELTDEM_BIN"] = os.path.abspath(args.bin)
os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
for exe in ("meltdemFoam", "meltdem-lmp"):
    if not os.path.exists(os.path.join(args.bin, exe)):
        raise SystemExit(f"{args.bin}/{exe} not found: build it first")

D, RHO_P, CP_P, T_P = 100e-6, 7800.0, 5000.0, 300.0
V_SLIP = 0.1
GAS = dict(rho=0.12, mu=1.8e-4, cp=1000.0, k=0.18, T=1000.0)
W = 40 * D
DT = 1e-5
OFFSET = 0.2           # of a cell, in x, y and z, from the core cell's centre
GROWTH = 1.5           # cell-to-cell ratio of the graded outer layers
WINDOW = 0.1           # averaging window, fraction of the run

work = tempfile.mkdtemp(prefix="meltdem-cells-per-diameter-")


def grading(c):
    """One direction: (core cells, cell size h, outer cells, outer expansion ratio last/first)."""
    h = D / c
    nc = 2 * math.ceil(c) + 1
    outer = (W - nc * h) / 2
    assert outer > 0
    n = max(1, round(math.log(1 + outer * (GROWTH - 1) / h) / math.log(GROWTH)))
    if n == 1:
        return nc, h, 1, 1.0
    # ratio r with h (r^n - 1) / (r - 1) = outer: the first outer cell as large as a core cell
    lo, hi = 1.0 + 1e-12, 10.0
    if h * n > outer:
        lo, hi = 0.1, 1.0 - 1e-12
    for _ in range(200):
        r = 0.5 * (lo + hi)
        if h * (r**n - 1) / (r - 1) > outer:
            hi = r
        else:
            lo = r
    return nc, h, n, r ** (n - 1)


def graded_mesh(case, c):
    nc, h, n, e = grading(c)
    outer = (W - nc * h) / 2
    # blockMesh multi-section grading: (length fraction, cell fraction, expansion last/first)
    g = f"(({outer / W!r} {n / (nc + 2 * n)!r} {1 / e!r}) ({nc * h / W!r} {nc / (nc + 2 * n)!r} 1) " \
        f"({outer / W!r} {n / (nc + 2 * n)!r} {e!r}))"
    p = os.path.join(case, "system", "blockMeshDict")
    txt = open(p).read()
    txt, k = re.subn(r"hex \(0 1 2 3 4 5 6 7\) \(\d+ \d+ \d+\) simpleGrading \(1 1 1\)",
                     f"hex (0 1 2 3 4 5 6 7) ({nc + 2 * n} {nc + 2 * n} {nc + 2 * n}) simpleGrading ({g} {g} {g})", txt)
    assert k == 1, "the blockMeshDict of meltdem.case.coupled.box_mesh changed"
    open(p, "w").write(txt)
    fc.run(["blockMesh"], case, "log.blockMesh")
    return (nc + 2 * n) ** 3, h, outer + (nc // 2 + 0.5 + OFFSET) * h


LAMMPS_OUT = """compute fpy all property/atom fy
compute fy all reduce sum c_fpy
thermo_style custom step time atoms c_fy f_melt[6]
thermo_modify format float %.15g
thermo 1
"""


def build(case, model, c, dt=DT):
    """The channel_case of meltdem.case.coupled with the held grain, then the graded mesh."""
    centre = W / 2  # placeholder; the grain's position is set once the mesh is known
    particle = dict(d=D, rho=RHO_P, cp=CP_P, Tm=5000.0, L=2.7e5, T0=T_P, x=centre, y=centre, z=centre,
                    v=(0.0, -V_SLIP, 0.0), held=True)
    cc.channel_case(case, model, particle, channel=dict(lx=W, ly=W, lz=W, h=W / 4, u=0.0), gas=GAS,
                    t_end=args.t_end, fluid_dt=dt, dem_dt=dt, extra_lammps=LAMMPS_OUT)
    cells, h, pos = graded_mesh(case, c)
    p = os.path.join(case, "in.particles")
    txt = open(p).read()
    txt, k = re.subn(r"create_atoms 1 single \S+ \S+ \S+", f"create_atoms 1 single {pos!r} {pos!r} {pos!r}", txt)
    assert k == 1
    open(p, "w").write(txt)
    # balances are not the point here: the solver tolerances of an ordinary run (1e-10), not the
    # ledger tests' 1e-14, two pressure correctors, and at most 300 iterations (a run whose
    # fluid diverges fails sooner)
    s = os.path.join(case, "system", "fvSolution")
    txt = open(s).read()
    txt = re.sub(r"tolerance 1e-1[2-5]; relTol 0;", "tolerance 1e-10; relTol 0; maxIter 300;", txt)
    txt, k = re.subn(r"nCorrectors 3;", "nCorrectors 2;", txt)
    assert k == 1
    open(s, "w").write(txt)
    return cells, h


def results(log):
    """(drag, heat rate) averaged over the last WINDOW of the run, and over the WINDOW before it"""
    rows = {}
    for line in open(log):
        w = line.split()
        if len(w) == 5 and re.fullmatch(r"\d+", w[0]):
            try:
                rows[int(w[0])] = [float(x) for x in w[1:]]
            except ValueError:
                pass
    a = np.array([rows[k] for k in sorted(rows)])  # time atoms fy heat
    t, fy, heat = a[:, 0], a[:, 2], a[:, 3]
    span = WINDOW * args.t_end
    out = []
    for t1 in (t[-1], t[-1] - span):
        t0 = t1 - span
        inside = (t > t0 + 1e-12) & (t <= t1 + 1e-12)
        # heat rate: the cumulative heat absorbed across the window, per time
        out += [np.mean(fy[inside]), (np.interp(t1, t, heat) - np.interp(t0, t, heat)) / span]
    gone = np.nonzero(a[:, 1] < 1)[0]
    return out + [t[gone[0]] if len(gone) else None]


def min_max_T(text):
    m = re.findall(r"T min/max now (\S+), (\S+) K", text)
    return f"{float(m[-1][0]):.4g}-{float(m[-1][1]):.4g}" if m else "?"


def coupled(model, c, dt=DT):
    case = os.path.join(work, f"{model}_c{c}_dt{dt:g}")
    cells, h = build(case, model, c, dt)
    t0 = time.perf_counter()
    try:
        with open(os.path.join(case, "log.meltdemFoam"), "w") as log:
            env = dict(os.environ, PWD=os.path.abspath(case))
            rc = subprocess.run([fc.solver()], cwd=case, stdout=log, stderr=subprocess.STDOUT, env=env,
                                timeout=args.timeout).returncode
    except subprocess.TimeoutExpired:
        rc = "timeout"
    wall = time.perf_counter() - t0
    r = dict(model=model, c=c, cells=cells, h=h, wall=wall, rc=rc, gone=None, dt=dt)
    text = open(os.path.join(case, "log.meltdemFoam")).read()
    r["steps_done"] = len(re.findall(r"\nTime = ", text))
    fatal = re.search(r"FOAM FATAL[^\n]*\n(?:[^\n]*\n){0,4}", text)
    # the coupling's bound check (particleCoupling::checkBounded): the heat exchange time it names
    tau = re.search(r"heat capacity over its particles' conductance is (\S+) s", text)
    r["tau"] = float(tau.group(1)) if tau else None
    r["why"] = (f"timed out after {args.timeout:g} s" if rc == "timeout" else
                f"the coupling's bound check (gas {min_max_T(text)} K outside [{T_P:g}, {GAS['T']:g}]; "
                f"its heat exchange time {r['tau']:.2g} s < fluid step)" if tau else
                "floating-point exception (SIGFPE)" if "sigFpe" in text else
                " ".join(fatal.group(0).split()) if fatal else f"exit code {rc}")
    tmin = re.findall(r"T min/max = (\S+), (\S+)", text)
    r["T_min"] = min(float(a) for a, _ in tmin) if tmin else np.nan
    r["T_max"] = max(float(b) for _, b in tmin) if tmin else np.nan
    if rc == 0:
        r["F"], r["Q"], r["F_before"], r["Q_before"], r["gone"] = results(os.path.join(case, "log.lammps"))
        if r["gone"] is not None:
            r["why"] = (f"the grain melted at t = {r['gone'] * 1e3:.3g} ms (gas up to {r['T_max']:.3g} K, "
                        f"down to {r['T_min']:.3g} K: the explicit exchange diverged)")
        elif r["T_min"] < 0:
            r["why"] = (f"ran through, but the gas went to {r['T_min']:.3g} K (negative absolute temperature: "
                        f"the explicit exchange diverged, silently)")
        p = cc.particles_csv(case)
        r["steps"] = len(p)
        r["exchange"] = p["exchange_seconds"][-1]
    r["ok"] = rc == 0 and r["gone"] is None and r["T_min"] >= 0
    if not args.keep:
        shutil.rmtree(case)
    return r


def standalone():
    case = os.path.join(work, "input")
    build(case, "centre", 1.0)
    alone = os.path.join(work, "alone")
    os.makedirs(alone)
    text = open(os.path.join(case, "in.particles")).read()
    g = GAS
    text = re.sub(r"(fix melt all powder/melt .*)",
                  r"\1 ambient %r %r %r %r %r 0 0 0" % (g["T"], g["k"], g["rho"], g["mu"], g["cp"]), text)
    text += f"\nrun {round(args.t_end / DT)}\n"
    open(os.path.join(alone, "in.alone"), "w").write(text)
    subprocess.run([os.path.join(args.bin, "meltdem-lmp"), "-in", "in.alone", "-log", "log.lammps",
                    "-screen", "none"], cwd=alone, check=True)
    return results(os.path.join(alone, "log.lammps"))


STAMP = build_stamp(ROOT, args.bin)
F_ref, Q_ref, F_ref_before, Q_ref_before, _ = standalone()
re_p = GAS["rho"] * V_SLIP * D / GAS["mu"]
F_stokes = 3 * math.pi * GAS["mu"] * D * V_SLIP
Q_nu2 = 2 * GAS["k"] * math.pi * D * (GAS["T"] - T_P)
print(f"reference (standalone ambient): drag {F_ref:.6g} N (Stokes {F_stokes:.6g}), heat rate {Q_ref:.6g} W "
      f"(Nu = 2 at T0: {Q_nu2:.6g}); Re {re_p:.3g}", flush=True)


def nice_step(t):
    """t rounded down to two significant digits"""
    k = math.floor(math.log10(t)) - 1
    return math.floor(t / 10.0**k * (1 + 1e-9)) * 10.0**k


def report(r):
    c, model = r["c"], r["model"]
    if r["ok"]:
        print(f"  c {c:g} {model:10s}: {r['cells']:6d} cells, {r['wall']:7.2f} s, drag {r['F']:.5g} N "
              f"({r['F'] / F_ref - 1:+.2%}), heat {r['Q']:.5g} W ({r['Q'] / Q_ref - 1:+.2%}), "
              f"gas {r['T_min']:.4g}-{r['T_max']:.4g} K", flush=True)
    elif r.get("estimate"):
        print(f"  c {c:g} {model:10s}: not run: {r['why']}", flush=True)
    else:
        what = "stopped" if r.get("tau") else "FAILED"
        print(f"  c {c:g} {model:10s}: {what} after {r['steps_done']} steps, {r['wall']:.1f} s: {r['why']}",
              flush=True)


out = []
for c in [float(x) for x in args.cpd.split(",")]:
    for model in args.models.split(","):
        r = coupled(model, c)
        out.append(r)
        report(r)
        if r["tau"] is None:
            continue
        # rerun at the fluid step the bound check asks for (half its heat exchange time), when
        # that takes at most --max-steps steps; otherwise estimate the cost from the runs so far
        dt = nice_step(r["tau"] / 2)
        steps = math.ceil(args.t_end / dt - 1e-6)
        # cost model: start-up (this run's wall time: it stopped after one step) + the cost per
        # cell-step of the largest run so far (start-up, ~1 s, taken off)
        done = [x for x in out if x["ok"]]
        big = max(done, key=lambda x: x["cells"] * x["steps"]) if done else None
        per = max(big["wall"] - r["wall"], 0.1) / (big["cells"] * big["steps"]) if big else np.nan
        est = r["wall"] + per * r["cells"] * steps
        if steps <= args.max_steps and not est > args.max_run:
            r2 = coupled(model, c, dt)
        else:
            r2 = dict(model=model, c=c, cells=r["cells"], dt=dt, ok=False, estimate=True, steps_done=0,
                      wall=est, rc=None, gone=None, T_min=np.nan, T_max=np.nan,
                      why=f"needs a fluid step <= {dt:.2g} s: {steps} steps, ~{est:.0f} s "
                          f"estimated (start-up + cells x steps x the cost per cell-step of the largest run so far) "
                          f"> --max-steps {args.max_steps} or --max-run {args.max_run:g} s")
        out.append(r2)
        report(r2)

os.makedirs(args.out, exist_ok=True)
md = os.path.join(args.out, "cells_per_diameter.md")
lines = ["# Cells per particle diameter x distribution model, coupled: cost vs accuracy", "",
         "Generated by bench/cells_per_diameter.py"
         + (" --quick (smoke test: not the documented result)" if args.quick else "")
         + ". Serial, shared 2-core machine under load from other jobs (load average 6-9 during the run): "
         "absolute wall times are loaded-machine times (+-30 %), compare ratios within the table. Build: "
         + stamp_line(ROOT, args.bin, STAMP) + ".", "",
         f"A grain d = {D * 1e6:g} um held in gas at rest, slipping at {V_SLIP:g} m/s (Re {re_p:.2g}), {T_P:g} K in "
         f"{GAS['T']:g} K gas (nu = alpha = {GAS['mu'] / GAS['rho']:.2g} m2/s, "
         f"rho cp = {GAS['rho'] * GAS['cp']:g} J/m3 K); "
         f"cube {W / D:g} d, graded mesh with a uniform core of cell size d / c around the grain; "
         f"{args.t_end * 1e3:g} ms, fluid step = DEM step = {DT * 1e6:g} us; results = means over the last "
         f"{WINDOW:.0%} of the run. V_p / V_cell = (pi / 6) c^3.",
         f"Reference: the same LAMMPS input standalone with the undisturbed gas (`ambient`): drag "
         f"{F_ref:.6g} N (analytic Stokes 3 pi mu d v = {F_stokes:.6g} N), heat rate {Q_ref:.6g} W "
         f"(Nu = 2 at the initial temperature difference: {Q_nu2:.6g} W).", "",
         "The fluid step is 10 us; where the coupling's bound check stops a run (the gas left the range of gas "
         "and grain temperatures: the explicit heat exchange overshoots), the run is repeated at a fluid step "
         "of half the heat exchange time the check names (two digits, rounded down) if that takes at most "
         f"{args.max_steps} steps and an estimated {args.max_run:g} s; else its cost is estimated (start-up + cells "
         "x steps x the cost per cell-step of the largest run before it).", "",
         "| cells / d | model | cells | V_p / V_cell | fluid step (s) | fluid steps | wall (s) | exchange (s) | "
         "drag (N) | reference (N) | error | heat rate (W) | reference (W) | error | gas T min / max (K) | "
         "drift of the last two windows (drag / heat) |", "|" + "---|" * 16]
for r in out:
    vr = math.pi / 6 * r["c"] ** 3
    head = f"| {r['c']:g} | {r['model']} | {r['cells']} | {vr:.3g} | {r['dt']:.2g} |"
    if r.get("estimate"):
        lines.append(f"{head} - | ~{r['wall']:.0f} (estimate) | - | not run: {r['why']} | {F_ref:.5g} | - | - | "
                     f"{Q_ref:.5g} | - | - | - |")
    elif not r["ok"]:
        what = "stopped" if r["tau"] else "FAILED"
        lines.append(f"{head} {r['steps_done']} | {r['wall']:.1f} | - | {what}: {r['why']} | {F_ref:.5g} | - | - | "
                     f"{Q_ref:.5g} | - | {r['T_min']:.4g} / {r['T_max']:.4g} | - |")
    else:
        lines.append(
            f"{head} {r['steps']} | {r['wall']:.1f} | {r['exchange']:.2f} | {r['F']:.5g} | {F_ref:.5g} | "
            f"{r['F'] / F_ref - 1:+.1%} | {r['Q']:.5g} | {Q_ref:.5g} | {r['Q'] / Q_ref - 1:+.1%} | "
            f"{r['T_min']:.4g} / {r['T_max']:.4g} | {r['F'] / r['F_before'] - 1:+.1e} / "
            f"{r['Q'] / r['Q_before'] - 1:+.1e} |")
lines += ["", "## Summary", ""]
for model in args.models.split(","):
    rs = [r for r in out if r["model"] == model]
    good = [r for r in rs if r["ok"]]
    txt = f"- `{model}`: "
    if good:
        txt += "runs (c: drag / heat error, wall) " + "; ".join(
            f"{r['c']:g}" + (f" at {r['dt']:.2g} s" if r["dt"] != DT else "")
            + f": {r['F'] / F_ref - 1:+.0%} / {r['Q'] / Q_ref - 1:+.0%}, {r['wall']:.1f} s" for r in good)
    stopped = [r for r in rs if not r["ok"] and not r.get("estimate") and r["tau"]]
    if stopped:
        txt += ("; " if good else "") + "stopped by the bound check at 10 us for c = " + ", ".join(
            f"{r['c']:g}" for r in stopped)
    est = [r for r in rs if r.get("estimate")]
    if est:
        txt += "; too expensive to run: " + ", ".join(
            f"c = {r['c']:g} ({r['dt']:.2g} s step, ~{r['wall']:.0f} s)" for r in est)
    failed = [r for r in rs if not r["ok"] and not r.get("estimate") and not r["tau"]]
    if failed:
        txt += "; FAILED otherwise: c = " + ", ".join(f"{r['c']:g} ({r['why']})" for r in failed)
    lines.append(txt + ".")
lines.append("")
open(md, "w").write("\n".join(lines))
print("\n".join(lines))

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, axes = plt.subplots(1, 3, figsize=(17, 5))
marks = {"centre": "o", "neighbours": "s", "overlap": "^"}
for k, model in enumerate(args.models.split(",")):
    m = marks.get(model, "x")
    rs = [r for r in out if r["model"] == model and r["ok"]]
    bad = [r for r in out if r["model"] == model and not r["ok"] and not any(x["c"] == r["c"] for x in rs)]
    # the three models coincide where the grain lies inside one cell: shift the markers apart
    shift = 2 ** (0.06 * (k - 1))
    for ax, key, ref in ((axes[0], "F", F_ref), (axes[1], "Q", Q_ref)):
        line, = ax.plot([r["c"] * shift for r in rs], [100 * (r[key] / ref - 1) for r in rs], m + "-", label=model)
        if bad:
            ax.plot([r["c"] * shift for r in bad], [-98] * len(bad), "x", ms=10, mew=2, color=line.get_color(),
                    label=f"{model}: stopped / not run")
    if rs:
        axes[2].loglog([r["wall"] for r in rs], [max(abs(r["F"] / F_ref - 1), abs(r["Q"] / Q_ref - 1)) for r in rs],
                       m + "-", label=model)
        for r in rs:
            label = f"{r['c']:g}" + (f" ({r['dt']:.2g} s)" if r["dt"] != DT else "")
            axes[2].annotate(label, (r["wall"], max(abs(r["F"] / F_ref - 1), abs(r["Q"] / Q_ref - 1))),
                             textcoords="offset points", xytext=(4, 3 - 9 * k), fontsize=8)
for ax, t in zip(axes[:2], ("drag force error vs undisturbed gas (%)", "heat rate error vs undisturbed gas (%)")):
    ax.set_xscale("log", base=2)
    ax.set_ylim(-100, 5)
    ax.set_xlabel("cells per particle diameter")
    ax.set_ylabel("error (%)   (x: stopped or not run)")
    ax.set_title(t)
    ax.axhline(0, color="grey", lw=0.5)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
axes[2].set_xlabel("wall time (s, loaded 2-core machine)")
axes[2].set_ylabel("larger |error| of drag and heat")
axes[2].set_title("cost vs error, runs that stayed bounded (labels: cells per d)")
axes[2].grid(True, which="both", alpha=0.3)
axes[2].legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(args.out, "cells_per_diameter.png"), dpi=100)
print(f"wrote {md} and cells_per_diameter.png")
if args.keep:
    print("cases kept in", work)
else:
    shutil.rmtree(work)
