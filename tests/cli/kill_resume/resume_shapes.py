#!/usr/bin/env python3
"""DEM-only resumes (meltdem-lmp -checkpoint DIR N -resume) in shapes a user writes, each from
the latest checkpoint of a run that ended (the replay of the input is the same as after a kill):

  ended      a run whose last checkpoint is its last step, resumed: nothing runs, and every
             row of the fix ave/time file and every dump frame is still there, the last row
             identical (the outputs cut back to the checkpoint are written again);
  time       'variable t0 equal $(time)' between two runs, with fix powder/dt changing the step:
             the resumed run's t0 is the value the line had when it first ran (the checkpoint
             records each command as executed), not one evaluated on the restart;
  longer     the run in progress given more steps before the resume: stops, naming the command
             and both ends (a resume continues the run as it started);
  if-run     an if that executed a run before the checkpoint: stops, naming it (a checkpoint
             counts the input's own runs; the replay would run it again); a checkpoint written
             during the run of an if: stops, naming it; an if whose run was not executed (its
             condition false, as powder-spread's rough-base block on a bare plate) resumes;
  np2        'ended' on 2 ranks, three times: the merged fix ave/time rows complete every time
             (a rank removing the scratch copy before rank 0 merged it lost the last row);
  frames     the frame times meltdem post gives after a resume (the logs as meltdem run keeps
             them: the continued run's log.lammps.1, the resumed run's log.lammps) are times
             read from both logs, not step numbers;
  stragglers a meltdem-lmp still working in the case (as the ranks of a killed run do for a
             moment): meltdem run's wait_for_solvers finds it and waits for its end, and stops
             naming it when it outlives the wait.
usage: resume_shapes.py [--keep]"""
import os
import subprocess
import sys
import tempfile
import time

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.cli import caselock
from meltdem.io import vtk_particles
from meltdem.testing.report import check_absolute

TEST = "cli.resume.dem_shapes"
HERE = os.path.dirname(os.path.abspath(__file__))


def bed_input(runs):
    """tests/cli/kill_resume/in.bed with its run replaced by runs and a log every 2500 steps
    that also writes v_t0 (0 until defined)"""
    text = open(os.path.join(HERE, "in.bed")).read()
    text = text.replace("variable        t equal time\n", "variable        t equal time\nvariable t0 equal 0\n")
    text = text.replace("fix             log all ave/time 5000 1 5000 v_t c_ke f_feed[1]",
                        "fix             log all ave/time 2500 1 2500 v_t c_ke f_feed[1] v_t0")
    text = text.replace("dump            bed all custom 20000", "dump            bed all custom 5000")
    return text.replace("run             200000\n", runs)


def lmp(case, resume=False, np=1):
    cmd = [paths.binary("meltdem-lmp"), "-in", "in.x", "-log", "log.lammps" + (".resumed" if resume else ""),
           "-screen", "none", "-checkpoint", "ck", "5000"] + (["-resume"] if resume else [])
    if np > 1:
        cmd = ["mpirun", "-np", str(np)] + cmd
    p = subprocess.run(cmd, cwd=case, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    log = os.path.join(case, "log.lammps" + (".resumed" if resume else ""))
    return p.returncode, p.stdout + (open(log).read() if os.path.exists(log) else "")


def rows(case):
    return [ln for ln in open(os.path.join(case, "bed_log.dat")) if not ln.startswith("#")]


def frames(case):
    text = open(os.path.join(case, "bed.dump")).read().split("ITEM: TIMESTEP\n")[1:]
    return [int(f.split()[0]) for f in text]


def case_with(work, name, runs):
    case = os.path.join(work, name)
    os.makedirs(case)
    with open(os.path.join(case, "in.x"), "w") as f:
        f.write(bed_input(runs))
    return case


def error_lines(out):
    return [ln for ln in out.splitlines() if ln.startswith("ERROR")]


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="resume_shapes.")
    ok = True

    # ended, time: two runs, t0 fixed between them; the last checkpoint is the last step
    case = case_with(work, "ended", "run 10000\nvariable t0 equal $(time)\nrun 10000\n")
    rc, out = lmp(case)
    ok &= check_absolute(TEST, "ended: the run's exit code", rc, 0, 0)
    before_rows, before_frames = rows(case), frames(case)
    t0 = float(before_rows[-1].split()[4])
    t_first = float([r for r in before_rows if int(r.split()[0]) == 10000][0].split()[1])
    rc, out = lmp(case, resume=True)
    if rc != 0:
        print(out[-3000:])
    ok &= check_absolute(TEST, "ended: the resume's exit code", rc, 0, 0)
    after_rows, after_frames = rows(case), frames(case)
    print(f"{TEST}: ended: rows {len(before_rows)} -> {len(after_rows)}, frames {before_frames} -> {after_frames}")
    ok &= check_absolute(TEST, "ended: fix ave/time rows after the resume vs before", len(after_rows),
                         len(before_rows), 0)
    ok &= check_absolute(TEST, "ended: dump frames after the resume vs before", len(after_frames),
                         len(before_frames), 0)
    ok &= check_absolute(TEST, "ended: the last row after the resume is the last row before (1 = yes)",
                         int(after_rows[-1:] == before_rows[-1:]), 1, 0)
    ok &= check_absolute(TEST, "time: t0 of the run (time at step 10000 of fix powder/dt's steps) [s]", t0, t_first,
                         0)
    last = [r for r in after_rows if int(r.split()[0]) == 20000]
    ok &= check_absolute(TEST, "time: t0 in the step 20000 row the resume wrote (replayed as first executed) vs the "
                         "run's [s]", float(last[0].split()[4]) if last else float("nan"), t0, 0)

    # frames: the logs as meltdem run's keep_log leaves them
    os.replace(os.path.join(case, "log.lammps"), os.path.join(case, "log.lammps.1"))
    os.replace(os.path.join(case, "log.lammps.resumed"), os.path.join(case, "log.lammps"))
    times, source = vtk_particles.frame_times(case, [{"step": s, "time": None} for s in after_frames])
    print(f"{TEST}: frames: times {times} from {source}")
    ok &= check_absolute(TEST, "frames: time of the last frame after a resume vs the log's time at step 20000 [s]",
                         times[-1], float(last[0].split()[1]) if last else float("nan"), 1e-15)
    os.replace(os.path.join(case, "log.lammps"), os.path.join(case, "log.lammps.resumed"))
    os.replace(os.path.join(case, "log.lammps.1"), os.path.join(case, "log.lammps"))

    # longer: the second run given 5000 more steps, then resumed
    text = open(os.path.join(case, "in.x")).read()
    with open(os.path.join(case, "in.x"), "w") as f:
        f.write(text[:text.rindex("run 10000")] + "run 15000\n")
    rc, out = lmp(case, resume=True)
    err = error_lines(out)
    print(f"{TEST}: longer: rc {rc}: {err[:1]}")
    ok &= check_absolute(TEST, "longer: stops (exit code 1)", rc, 1, 0)
    ok &= check_absolute(TEST, "longer: one ERROR naming the run and both ends (1 = yes)",
                         int(len(err) == 1 and all(w in err[0] for w in ("run 15000", "25000", "20000"))), 1, 0)
    ok &= check_absolute(TEST, "longer: the outputs untouched (rows)", len(rows(case)), len(before_rows), 0)

    # if-run: an if that ran a run before the checkpoint; a checkpoint written during the if's run;
    # an if whose run did not execute
    for name, runs, words in (
            ("before", "run 5000\nif \"1 > 0\" then \"run 5000\"\nrun 5000\n", ["its if executed a run"]),
            ("during", "run 5000\nif \"1 > 0\" then \"run 10000\"\n", ["written during the run its if executed"]),
            ("not executed", "run 5000\nif \"1 > 2\" then \"run 5000\"\nrun 5000\n", None)):
        case = case_with(work, "if_run_" + name.replace(" ", "_"), runs)
        rc, out = lmp(case)
        ok &= check_absolute(TEST, f"if-run, {name}: the run's exit code", rc, 0, 0)
        n0 = len(rows(case))
        rc, out = lmp(case, resume=True)
        err = error_lines(out)
        print(f"{TEST}: if-run, {name}: rc {rc}: {err[:1]}")
        if words:
            ok &= check_absolute(TEST, f"if-run, {name}: the resume stops (exit code 1)", rc, 1, 0)
            ok &= check_absolute(TEST, f"if-run, {name}: one ERROR naming the if (1 = yes)",
                                 int(len(err) == 1 and all(w in err[0] for w in words) and "in.x:" in err[0]), 1, 0)
        else:
            ok &= check_absolute(TEST, f"if-run, {name}: the resume's exit code", rc, 0, 0)
            ok &= check_absolute(TEST, f"if-run, {name}: fix ave/time rows after the resume vs before", len(rows(case)),
                                 n0, 0)

    # np2: the ended run resumed on 2 ranks, three times
    case = case_with(work, "np2", "run 10000\n")
    rc, out = lmp(case, np=2)
    ok &= check_absolute(TEST, "np2: the run's exit code", rc, 0, 0)
    n0 = len(rows(case))
    complete = 0
    for _ in range(3):
        rc, out = lmp(case, resume=True, np=2)
        complete += int(rc == 0 and len(rows(case)) == n0)
    ok &= check_absolute(TEST, "np2: resumes with every fix ave/time row, of 3", complete, 3, 0)

    # stragglers: a meltdem-lmp busy for 3 s in the case
    case = os.path.join(work, "stragglers")
    os.makedirs(case)
    with open(os.path.join(case, "in.sleep"), "w") as f:
        f.write("shell sleep 3\n")
    for timeout in (0.5, 20.0):
        p = subprocess.Popen([paths.binary("meltdem-lmp"), "-in", "in.sleep", "-log", "none", "-screen", "none"],
                             cwd=case)
        time.sleep(0.5)
        try:
            waited, stopped = caselock.wait_for_solvers(case, timeout=timeout), ""
        except caselock.CaseLocked as e:
            waited, stopped = [], str(e)
        ended = p.poll() is not None
        p.wait()
        print(f"{TEST}: stragglers, wait {timeout:g} s: waited for {waited}, ended {ended}, stop {stopped!r}")
        if timeout < 1:
            ok &= check_absolute(TEST, "stragglers: a wait shorter than the process stops naming it (1 = yes)",
                                 int(f"pid {p.pid} meltdem-lmp" in stopped and not ended), 1, 0)
        else:
            ok &= check_absolute(TEST, "stragglers: the wait returns after the process ended, naming it (1 = yes)",
                                 int(waited == [(p.pid, "meltdem-lmp")] and ended), 1, 0)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
