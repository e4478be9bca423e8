"""`meltdem run CASE --resume` with a stand-in solver (fake_meltdemFoam) on a built ded-stream CI
case given fake checkpoints: meltdemRestart/1e-06 and 2e-06 complete, 3e-06 without `complete`
(killed while writing), 4e-06 complete but its OpenFOAM time folder lost. Measured: the time chosen
(2e-06), startFrom/startTime the solver saw, no meshing on resume, controlDict restored after the
run, the progress starting at the checkpoint, what the stopped run wrote after the checkpoint
removed (3e-06, 4e-06); errors naming what is missing (no meltdemRestart/, no complete
checkpoint, decomposed case on another rank count, a DEM-only case that never wrote a checkpoint);
a run without --resume starts from startTime as written and says the earlier output is
overwritten."""
import json
import os
import re
import shutil
import sys
import tempfile

from meltdem.cli import run as mrun
from meltdem.cli.examples import StepError
from meltdem.io import foamdict as fd
from meltdem.testing.cli import SRC, build_example, check_absolute, meltdem

HERE = os.path.dirname(os.path.abspath(__file__))


T = "cli.resume"
ok = True
work = tempfile.mkdtemp(prefix="cli_resume_")
fakebin = os.path.join(work, "bin")
os.makedirs(fakebin)
shutil.copy(os.path.join(HERE, "fake_meltdemFoam"), os.path.join(fakebin, "meltdemFoam"))
os.environ["MELTDEM_BIN"] = fakebin
case = os.path.join(work, "ded")
build_example("ded-stream", case)


def checkpoint(t, complete=True, foam=True):
    d = os.path.join(case, "meltdemRestart", t)
    os.makedirs(d)
    for f in ("lammps.restart", "ledger.state") + (("complete",) if complete else ()):
        open(os.path.join(d, f), "w").close()
    if foam:
        shutil.copytree(os.path.join(case, "0"), os.path.join(case, t))


def error_of(fn, *a):
    try:
        fn(*a)
    except StepError as e:
        return str(e)
    return ""


# no checkpoint folder at all
rc, out, err = meltdem("run", case, "--resume", "--no-analyse")
print(out, err)
ok &= check_absolute(T, "no meltdemRestart/: exit code", rc, 1, 0)
ok &= check_absolute(T, "no meltdemRestart/: the message names it",
                     int("meltdemRestart" in err and "cannot resume" in err), 1, 0)
checkpoint("3e-06", complete=False)
e = error_of(mrun.latest_checkpoint, case)
print(e)
ok &= check_absolute(T, "only an incomplete checkpoint: message names <time>/complete", int("complete" in e), 1, 0)
checkpoint("1e-06")
checkpoint("2e-06")
checkpoint("4e-06", foam=False)
t, _, decomposed = mrun.latest_checkpoint(case)
ok &= check_absolute(T, "latest complete checkpoint with a time folder [s]", float(t), 2e-6, 0)

rc, out, err = meltdem("run", case, "--resume", "--no-analyse", env={"MELTDEM_BIN": fakebin})
print(out, err)
seen = json.load(open(os.path.join(case, "fake_started.json")))
ok &= check_absolute(T, "resume: exit code", rc, 0, 0)
ok &= check_absolute(T, "solver saw startFrom startTime", int(seen["startFrom"] == "startTime"), 1, 0)
ok &= check_absolute(T, "solver saw startTime [s]", float(seen["startTime"]), 2e-6, 0)
ok &= check_absolute(T, "no meshing on resume (no log.blockMesh)",
                     int(os.path.exists(os.path.join(case, "log.blockMesh"))), 0, 0)
prog = re.findall(r"^t = (\S+) / (\S+) s \((\d+) %\)", out, re.M)
ok &= check_absolute(T, "last progress line: t [s]", float(prog[-1][0]) if prog else 0, 2e-5, 1e-12)
cd = fd.read(os.path.join(case, "system", "controlDict"))
ok &= check_absolute(T, "controlDict startTime restored after the run [s]", fd.number(cd, "startTime"), 0.0, 0)
ok &= check_absolute(T, "checkpoints kept by a resume (those after 2e-06 were the stopped run's)",
                     len(os.listdir(os.path.join(case, "meltdemRestart"))), 2, 0)

# decomposed case: the processor folders decide the rank count and hold the time folders
for p in ("processor0", "processor1"):
    os.makedirs(os.path.join(case, p, "1e-06"))
t, _, decomposed = mrun.latest_checkpoint(case)
ok &= check_absolute(T, "decomposed: checkpoint with processor0/<time> [s]", float(t), 1e-6, 0)
e = error_of(mrun.run_foam, case, 3, True)
print(e)
ok &= check_absolute(T, "decomposed into 2, --np 3: message says --np 2", int("--np 2" in e), 1, 0)
for p in ("processor0", "processor1"):
    shutil.rmtree(os.path.join(case, p))

# a fresh run of the case: from startTime as written, earlier output said and removed
rc, out, err = meltdem("run", case, "--no-analyse", env={"MELTDEM_BIN": fakebin})
print(out, err)
seen = json.load(open(os.path.join(case, "fake_started.json")))
ok &= check_absolute(T, "fresh run: startTime the solver saw [s]", float(seen["startTime"]), 0.0, 0)
ok &= check_absolute(T, "fresh run: says the earlier output is overwritten", int("overwritten" in out), 1, 0)
left = [d for d in fd.time_dirs(case) if float(d) > 0]
ok &= check_absolute(T, "fresh run: earlier time folders left", len(left), 0, 0)

# DEM-only: a case that never ran has no checkpoint to resume from
pour = os.path.join(work, "pour")
os.makedirs(pour)
shutil.copy(os.path.join(SRC, "examples", "powder-pour", "in.pour"), pour)
rc, out, err = meltdem("run", pour, "--resume")
print(out, err)
ok &= check_absolute(T, "DEM-only --resume without a checkpoint: exit code", rc, 1, 0)
ok &= check_absolute(T, "DEM-only --resume without a checkpoint: says so",
                     int("no complete checkpoint" in err and "meltdemRestart" in err), 1, 0)
if ok:
    shutil.rmtree(work, ignore_errors=True)
else:
    print(f"kept {work}")
sys.exit(0 if ok else 1)
