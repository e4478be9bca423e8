#!/usr/bin/env python3
"""Kill a coupled run mid-way, resume it, compare with an uninterrupted run.

The case is examples/pbf-point's CI case (100 grains on a substrate under the laser) cut to
9 us with a write time every 3 us and binary fields (OpenFOAM resumes from the fields as
written). One copy runs through with `meltdem run`; the other is started the same way and
killed (SIGKILL to its process group, as a batch system would) as soon as its first checkpoint
(meltdemRestart/3e-06/complete) exists, then continued with `meltdem run CASE --resume`.
Reference: the uninterrupted run. The ledger's final totals and cumulative errors must agree to
round-off (mass, enthalpy: 1e-12 relative; momentum: 1e-6 of the largest momentum, since the
momentum of this case is a small difference of large drag impulses), the ledger must have the
same rows, and the particles at the end the same positions (1e-9 of the box). The LAMMPS input
gets 'variable t0 equal $(time)' (0 when the input is read) and a fix print of it: the resumed run
prints the t0 of the uninterrupted run (a checkpoint records each command as executed; the replay
on the restart evaluated $(time) anew: 3e-06).
"""
import csv
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_least, check_at_most, check_relative

SRC = paths.source_dir()
BIN = paths.bin_dir()

TEST = "cli.kill_resume"
END, WRITE = 9e-06, 3e-06
FIRST = "3e-06"


def set_entry(case, key, value):
    path = os.path.join(case, "system", "controlDict")
    lines = open(path).read().split("\n")
    for i, line in enumerate(lines):
        if line.split(" ")[0] == key:
            lines[i] = f"{key} {value};"
    open(path, "w").write("\n".join(lines))


def meltdem(*args, **kw):
    return subprocess.Popen([os.path.join(BIN, "meltdem"), *args], stdout=kw.pop("stdout", subprocess.DEVNULL),
                            stderr=subprocess.STDOUT, start_new_session=True, **kw)


def ledger(case):
    with open(os.path.join(case, "postProcessing", "particleLedger", "ledger.csv")) as f:
        return list(csv.DictReader(f))


def particles(case, time_name):
    lines = open(os.path.join(case, "particles", time_name + ".dump")).read().split("\n")
    at = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[at].split()[2:]
    data = np.loadtxt(lines[at + 1:], ndmin=2)
    return data[:, [cols.index(c) for c in ("x", "y", "z")]]


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-resume-")
    base = os.path.join(work, "base")
    subprocess.run([sys.executable, os.path.join(SRC, "examples", "pbf-point", "scene.py"), "build", base, "--ci"],
                   check=True, stdout=subprocess.DEVNULL)
    set_entry(base, "endTime", repr(END))
    set_entry(base, "writeInterval", repr(WRITE))
    set_entry(base, "writeFormat", "binary")
    with open(os.path.join(base, "in.particles"), "a") as f:
        f.write('\nvariable t0 equal $(time)\nfix t0print all print 100 "t0 ${t0}" file t0.txt screen no\n')
    whole, killed = os.path.join(work, "whole"), os.path.join(work, "killed")
    shutil.copytree(base, whole)
    shutil.copytree(base, killed)

    with open(os.path.join(work, "whole.log"), "w") as log:
        rc_whole = meltdem("run", whole, stdout=log).wait()
    ok = check_absolute(TEST, "uninterrupted `meltdem run` exit code", rc_whole, 0, 0)

    # the run to kill: SIGKILL its whole process group once the first checkpoint is complete
    with open(os.path.join(work, "killed.log"), "w") as log:
        p = meltdem("run", killed, stdout=log)
        marker = os.path.join(killed, "meltdemRestart", FIRST, "complete")
        t0 = time.time()
        while not os.path.exists(marker) and p.poll() is None and time.time() - t0 < 400:
            time.sleep(0.02)
        os.killpg(p.pid, signal.SIGKILL)
        p.wait()
    rows_at_kill = ledger(killed)
    t_kill = float(rows_at_kill[-1]["time"]) if rows_at_kill else 0.0
    ok &= check_at_most(TEST, "simulated time when killed [s] (before the end: the run was cut)", t_kill, END * 0.999)
    ok &= check_at_least(TEST, "simulated time when killed [s] (past the first checkpoint)", t_kill, WRITE * 0.999)

    with open(os.path.join(work, "resumed.log"), "w") as log:
        rc_resumed = meltdem("run", killed, "--resume", stdout=log).wait()
    ok &= check_absolute(TEST, "`meltdem run CASE --resume` exit code", rc_resumed, 0, 0)

    a, b = ledger(whole), ledger(killed)
    ok &= check_absolute(TEST, "ledger rows, resumed vs uninterrupted", len(b), len(a), 0)
    last_a, last_b = a[-1], b[-1]
    ok &= check_relative(TEST, "final simulated time [s], resumed vs uninterrupted", float(last_b["time"]),
                         float(last_a["time"]), 1e-12)
    for q in ("mass", "enthalpy"):
        ok &= check_relative(TEST, f"final system {q} total, resumed vs uninterrupted", float(last_b[q + "_total"]),
                             float(last_a[q + "_total"]), 1e-12)
        ok &= check_absolute(TEST, f"final cumulative system {q} error, resumed vs uninterrupted",
                             float(last_b[q + "_cumulative_system_error"]),
                             float(last_a[q + "_cumulative_system_error"]), 1e-12)
        ok &= check_relative(TEST, f"{q} in particles at the end, resumed vs uninterrupted",
                             float(last_b[q + "_particles"]), float(last_a[q + "_particles"]), 1e-12)
    p_scale = max(np.sqrt(sum(float(r[f"mom_{c}_total"]) ** 2 for c in "xyz")) for r in a)
    for c in "xyz":
        ok &= check_absolute(TEST, f"final system momentum {c} / largest |momentum|, resumed vs uninterrupted",
                             float(last_b[f"mom_{c}_total"]) / p_scale, float(last_a[f"mom_{c}_total"]) / p_scale,
                             1e-6)
    t0a, t0b = ([float(ln.split()[1]) for ln in open(os.path.join(c, "t0.txt")) if ln.startswith("t0 ")]
                for c in (whole, killed))
    ok &= check_absolute(TEST, "lines of the fix print of t0, resumed vs uninterrupted", len(t0b), len(t0a), 0)
    ok &= check_absolute(TEST, "the $(time) of the input: largest t0 printed by the resumed run vs the uninterrupted "
                         "run's [s]", max(t0b, default=float("nan")), max(t0a, default=float("nan")), 0)
    xa, xb = particles(whole, "9e-06"), particles(killed, "9e-06")
    ok &= check_absolute(TEST, "particles at the end, resumed vs uninterrupted", len(xb), len(xa), 0)
    if len(xa) == len(xb):
        ok &= check_at_most(TEST, "largest particle position difference at the end / box width",
                            float(np.abs(xa - xb).max()) / 160e-6, 1e-9)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
