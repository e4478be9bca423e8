#!/usr/bin/env python3
"""Runs killed at several points and resumed with `meltdem run CASE --resume` equal the
uninterrupted run. Each kind of case runs once uninterrupted (the reference), then
three copies are killed with SIGKILL to their process group, as a batch system would:

  between   between two checkpoints (past the second write time, before the third),
  write     while a write time is being written (its folder has just appeared),
  twice     before the second checkpoint, and again while the resumed run runs,

and resumed until they end. Kinds (usage: kill_resume_kinds.py coupled|coupled-implicit|coupled-balance|continuum|dem):

  coupled    lmd-track's CI case cut to 0.09 s (powder inserted during the run, melting,
             solid-metal contact, the laser), write times 0.03 s apart, binary fields: the
             ledger and particles.csv identical row for row (bit for bit), the LAMMPS outputs
             (feed.dat of fix ave/time, dump.grains) and the particles at the end identical,
             every summary number equal (wall time aside), the absorbed laser power read over
             all segments equal at every step (no dip at the resume).
  coupled-implicit  the same with particles { heatExchange implicit; } (the heat the energy
             solve owes each grain is in the checkpoint)
  coupled-balance  the coupled case on 2 ranks (`meltdem run --np 2`) with LAMMPS's `fix balance`
             by particle count every 200 DEM steps, killed between checkpoints only: the resumed run
             re-balances from the restart's layout, so the grains' ranks (and the order of the
             exchange's sums) may differ from the uninterrupted run's: the ledger totals equal it to
             1e-10 of the largest total per step, the same rows and steps, the same grains at the end,
             and the ranks' grain counts balanced (largest / mean <= 1.05 + one grain).
  continuum  the same track without powder (laser, melting, flow; meltdemBalance added): the
             fields at the end identical byte for byte, the balance rows over all segments
             equal, the summary's absorbed laser energy equal.
  dem        tests/cli/kill_resume/in.bed (200 grains poured by fix powder/insert, fix
             powder/dt, fix ave/time and a dump) with a checkpoint every 20000 steps: every row
             of the fix ave/time file and every dump frame there exactly once, the rows up to
             the checkpoint identical, the same steps; after the resume the grains go on from
             the checkpoint to round-off (LAMMPS rebuilds its neighbour lists on a restart) and
             granular contacts amplify it, so the bed at the end is compared statistically:
             grain count and volume equal, mean height within 1 % of the bed height, the
             simulated time (fix powder/dt's step follows the speeds) within 0.1 %.
"""
import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import numpy as np

from meltdem.case import foam as fc
from meltdem.io import casedata
from meltdem.testing.cli import SRC, check_absolute, check_at_most, meltdem_command

HERE = os.path.dirname(os.path.abspath(__file__))


IMPLICIT = sys.argv[1] == "coupled-implicit"
BALANCE = sys.argv[1] == "coupled-balance"
KIND = "coupled" if IMPLICIT or BALANCE else sys.argv[1]
T = f"cli.kill_resume.{sys.argv[1].replace('-', '.')}"
ok = True
work = tempfile.mkdtemp(prefix=f"meltdem-kill-{KIND}-")
END, WRITE = 0.09, 0.03


def control(case, **entries):
    p = os.path.join(case, "system", "controlDict")
    text = open(p).read()
    for k, v in entries.items():
        if re.search(rf"^{k}\s", text, re.M):
            text = re.sub(rf"^{k}\s.*$", f"{k} {v};" if v is not None else "", text, flags=re.M)
        elif v is not None:
            text += f"\n{k} {v};\n"
    open(p, "w").write(text)


def build():
    base = os.path.join(work, "base")
    if KIND == "dem":
        os.makedirs(base)
        shutil.copy(os.path.join(HERE, "in.bed"), base)
        return base
    extra = ["--no-particles"] if KIND == "continuum" else []
    subprocess.run(["/usr/bin/python3", os.path.join(SRC, "examples", "lmd-track", "scene.py"), "build", base,
                    "--ci"] + extra, check=True, stdout=subprocess.DEVNULL)
    # binary fields, the default precisions (a case written from the docs)
    control(base, endTime=repr(END), writeInterval=repr(WRITE), writeFormat="binary", writePrecision=None,
            timePrecision=None)
    if IMPLICIT:
        props = os.path.join(base, "constant", "meltdemProperties")
        text = open(props).read()
        assert "demStepsPerFluidStep auto;" in text
        open(props, "w").write(text.replace("demStepsPerFluidStep auto;",
                                            "demStepsPerFluidStep auto;\n    heatExchange implicit;"))
    if BALANCE:
        inp = os.path.join(base, "in.particles")
        text = open(inp).read()
        anchor = "fix             integrate grains nve/sphere\n"
        assert anchor in text
        balance = "fix             balance all balance 200 1.05 shift xyz 10 1.05\n"
        open(inp, "w").write(text.replace(anchor, anchor + balance))
    if KIND == "continuum":
        with open(os.path.join(base, "system", "controlDict"), "a") as f:
            f.write("\nfunctions { balance { type meltdemBalance; } }\n")
    return base


ARGS = ["--checkpoint-every", "20000"] if KIND == "dem" else (["--np", "2"] if BALANCE else [])


def start(case, resume=False):
    log = open(os.path.join(work, os.path.basename(case) + (".resume" if resume else "") + ".log"), "a")
    return subprocess.Popen(meltdem_command() + ["run", case] + ARGS + (["--resume"] if resume else []),
                            stdout=log, stderr=subprocess.STDOUT, start_new_session=True)


def progress(case):
    """simulated time (meltdemFoam's last 'Time =' line) or DEM step (the last checkpoint)"""
    if KIND == "dem":
        r = os.path.join(case, "meltdemRestart")
        steps = [int(d) for d in os.listdir(r) if d.isdigit()] if os.path.isdir(r) else []
        return max(steps, default=0)
    try:
        times = re.findall(r"^Time = (\S+)", open(os.path.join(case, "log.meltdemFoam"), errors="replace").read(), re.M)
        return float(times[-1]) if times else 0.0
    except OSError:
        return 0.0


def write_started(case, when):
    """the folder of the write time `when` appeared (its files are being written)"""
    if KIND == "dem":
        return os.path.isdir(os.path.join(case, "meltdemRestart", str(when)))
    return os.path.isdir(os.path.join(case, repr(when)))


def kill_when(p, cond, limit=600):
    t0 = time.time()
    while p.poll() is None and not cond() and time.time() - t0 < limit:
        time.sleep(0.005)
    if p.poll() is not None:
        return False
    os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    return True


# kill points: (condition on the case, what it is)
if KIND == "dem":
    B1, B2, W = 60000, 100000, 120000

    def between(c):
        return progress(c) >= B1 and os.path.isfile(os.path.join(c, "meltdemRestart", str(B1), "complete"))
else:
    B1, B2, W = 2 * WRITE, 2.5 * WRITE, 2 * WRITE

    def between(c):
        return progress(c) >= 2.5 * WRITE
SCENARIOS = {
    "between": [between],
    "write": [lambda c: write_started(c, W)],
    "twice": [lambda c: progress(c) >= (1.5 * WRITE if KIND != "dem" else 30000), lambda c: progress(c) >= B2],
}
if BALANCE:
    SCENARIOS = {"between": [between]}

base = build()
whole = os.path.join(work, "whole")
shutil.copytree(base, whole)
rc = start(whole).wait()
ok &= check_absolute(T, "uninterrupted run: exit code", rc, 0, 0)

for name, kills in SCENARIOS.items():
    case = os.path.join(work, name)
    shutil.copytree(base, case)
    killed = 0
    for k, cond in enumerate(kills):
        killed += kill_when(start(case, resume=k > 0), lambda: cond(case))
    rc = start(case, resume=True).wait()
    ok &= check_absolute(T, f"{name}: killed {len(kills)} time(s) before the end", killed, len(kills), 0)
    ok &= check_absolute(T, f"{name}: last meltdem run --resume exit code", rc, 0, 0)
    if rc != 0:
        continue

    if BALANCE:
        from meltdem.case import coupled as cc
        la, lb = cc.ledger(whole), cc.ledger(case)
        ok &= check_absolute(T, f"{name}: ledger rows (fluid steps)", len(lb), len(la), 0)
        same_t = len(la) == len(lb) and np.array_equal(la["time"], lb["time"])
        ok &= check_absolute(T, f"{name}: ledger times identical", int(same_t), 1, 0)
        ok &= check_at_most(T, f"{name}: ledger totals vs the uninterrupted run (relative to the largest total)",
                            cc.ledger_totals_difference(lb, la) if same_t else 1.0, 1e-10)
        pa, pb = cc.particles_csv(whole), cc.particles_csv(case)
        ok &= check_absolute(T, f"{name}: grains in the last particles.csv row", int(pb["particles"][-1]),
                             int(pa["particles"][-1]), 0)
        rows = list(csv.DictReader(open(os.path.join(case, "postProcessing", "particleLedger", "ranks.csv"))))
        last = max(float(r["time"]) for r in rows)
        owned = [int(r["particles"]) for r in rows if float(r["time"]) == last]
        worst = max(owned) / max(np.mean(owned), 1e-30)
        ok &= check_at_most(T, f"{name}: grains per rank at the end, largest / mean ({owned})", worst,
                            1.05 + 1 / max(np.mean(owned), 1))
        ok &= cc.check_balances(T, lb)
    elif KIND == "coupled":
        for f in ("ledger.csv", "particles.csv"):
            a = list(csv.reader(open(os.path.join(whole, "postProcessing", "particleLedger", f))))
            b = list(csv.reader(open(os.path.join(case, "postProcessing", "particleLedger", f))))
            timing = [i for i, h in enumerate(a[0]) if h.endswith("seconds")]
            strip = lambda rows: [[x for i, x in enumerate(r) if i not in timing] for r in rows]  # noqa: E731
            same = sum(x == y for x, y in zip(strip(a), strip(b)))
            ok &= check_absolute(T, f"{name}: {f} rows identical to the uninterrupted run's (of {len(a)})",
                                 same if len(a) == len(b) else -1, len(a), 0)
        # the per-rank load (the exchange's counters of the first step after a resume differ: it
        # locates the particles anew)
        a, b = (list(csv.reader(open(os.path.join(c, "postProcessing", "particleLedger", "ranks.csv"))))
                for c in (whole, case))
        same = sum(x[:5] == y[:5] for x, y in zip(a, b))
        ok &= check_absolute(T, f"{name}: ranks.csv time, rank, cells, metal cells, particles identical to the "
                             f"uninterrupted run's (of {len(a)} rows)", same if len(a) == len(b) else -1, len(a), 0)
        last = sorted(os.listdir(os.path.join(whole, "particles")), key=lambda x: float(x[:-5]))[-1]
        for f in ("feed.dat", "dump.grains", os.path.join("particles", last)):
            same = open(os.path.join(whole, f), "rb").read() == open(os.path.join(case, f), "rb").read()
            ok &= check_absolute(T, f"{name}: {f} identical", int(same), 1, 0)
    elif KIND == "continuum":
        tend = sorted((d for d in os.listdir(whole) if re.fullmatch(r"[0-9.e+-]+", d)), key=float)[-1]
        for f in ("T", "U", "alpha.metal", "p_rgh"):
            same = open(os.path.join(whole, tend, f), "rb").read() == open(os.path.join(case, tend, f), "rb").read()
            ok &= check_absolute(T, f"{name}: {tend}/{f} identical byte for byte", int(same), 1, 0)
    if KIND in ("coupled", "continuum") and not BALANCE:
        _, ra = casedata.balance_rows(whole)
        _, rb = casedata.balance_rows(case)
        cols = [c for c in ra.dtype.names if c != "time"] if ra is not None else []
        diff = max((float(np.max(np.abs(ra[c] - rb[c]) / np.maximum(np.abs(ra[c]), 1e-300))) for c in cols),
                   default=1.0) if ra is not None and rb is not None and len(ra) == len(rb) else 1.0
        ok &= check_absolute(T, f"{name}: balance rows over all segments: count", len(rb) if rb is not None else 0,
                             len(ra) if ra is not None else -1, 0)
        # balance.csv is written with 15 digits
        ok &= check_at_most(T, f"{name}: balance rows over all segments: largest relative difference", diff, 1e-14)
        sa, sb = (json.load(open(os.path.join(c, "summary.json"))) for c in (whole, case))
        keys = [k for k, v in sa.items() if isinstance(v, (int, float)) and not isinstance(v, bool)
                and k not in ("wall_time_s", "postprocess_seconds")]
        differ = [k for k in keys if sb.get(k) != sa[k]]
        if differ:
            print(name, "summary differs:", {k: (sa[k], sb.get(k)) for k in differ})
        ok &= check_absolute(T, f"{name}: summary numbers equal to the uninterrupted run's (of {len(keys)})",
                             len(keys) - len(differ), len(keys), 0)
    if KIND == "dem":
        la = np.loadtxt(os.path.join(whole, "bed_log.dat"), ndmin=2)
        lb = np.loadtxt(os.path.join(case, "bed_log.dat"), ndmin=2)
        ok &= check_absolute(T, f"{name}: fix ave/time rows (each step once)", len(lb), len(la), 0)
        steps_ok = len(la) == len(lb) and np.array_equal(la[:, 0], lb[:, 0])
        ok &= check_absolute(T, f"{name}: fix ave/time steps as in the uninterrupted run", int(steps_ok), 1, 0)
        ck = max(int(d) for d in os.listdir(os.path.join(case, "meltdemRestart")) if d.isdigit())
        upto = la[:, 0] <= B1
        ok &= check_absolute(T, f"{name}: fix ave/time rows up to step {B1} identical",
                             int(steps_ok and np.array_equal(la[upto], lb[upto])), 1, 0)
        frames = re.findall(r"ITEM: TIMESTEP\n(\d+)", open(os.path.join(case, "bed.dump")).read())
        ok &= check_absolute(T, f"{name}: dump frames, each once (steps 0, 20000, ..., 200000)",
                             int(frames == [str(s) for s in range(0, 200001, 20000)]), 1, 0)
        # fix powder/dt sets the step from the grains' speeds, which the resume changes at round-off
        ok &= check_absolute(T, f"{name}: simulated time at the end [s] (variable step)", lb[-1, 1], la[-1, 1],
                             1e-3 * la[-1, 1])

        def bed(c):
            text = open(os.path.join(c, "bed.dump")).read()
            block = text.rsplit("ITEM: ATOMS", 1)[1].splitlines()
            cols = block[0].split()
            d = np.loadtxt(block[1:], ndmin=2)
            return d[:, cols.index("z")], d[:, cols.index("radius")]
        (za, ra_), (zb, rb_) = bed(whole), bed(case)
        ok &= check_absolute(T, f"{name}: grains at the end", len(zb), len(za), 0)
        ok &= check_absolute(T, f"{name}: grain volume at the end [m3]", float(np.sum(rb_ ** 3)),
                             float(np.sum(ra_ ** 3)), 1e-12 * float(np.sum(ra_ ** 3)))
        top = float(np.max(za + ra_))
        ok &= check_at_most(T, f"{name}: mean grain height at the end, |resumed - uninterrupted| / bed height",
                            abs(float(np.mean(zb)) - float(np.mean(za))) / top, 0.01)


sys.exit(fc.finish(ok, work))
