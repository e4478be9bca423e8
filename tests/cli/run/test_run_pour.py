"""`meltdem run powder-pour --case DIR [--np N]` builds the default scene into a scratch folder and
runs it: exit 0, log.lammps complete (the run's 100000 steps, 300 grains), the progress line
printed (non-tty: the first and the last, `t = ... / 1.00e-03 s (100 %) ... steps/s  ETA`).
A broken copy (an unknown command) stops with exit 1 and one line naming log.lammps and the
LAMMPS error; a bad case (no input at all) with the reason; --case given with a case folder
(which runs where it is) and --checkpoint-every 0 stop before anything runs."""
import os
import re
import shutil
import sys
import tempfile

from meltdem.testing.cli import SRC, check_absolute, check_at_least, meltdem

np_ = int(sys.argv[1]) if len(sys.argv) > 1 else 1
T = "cli.run.powder_pour" + (f".np{np_}" if np_ > 1 else "")
work = tempfile.mkdtemp(prefix="cli_run_")
case = os.path.join(work, "pour")
ok = True
rc, out, err = meltdem("run", "powder-pour", "--case", case, "--np", str(np_), cwd=work)
print(out, err)
ok &= check_absolute(T, "exit code", rc, 0, 0)
log = os.path.join(case, "log.lammps")
text = open(log).read() if os.path.isfile(log) else ""
m = re.search(r"Loop time of \S+ on (\d+) procs for (\d+) steps with (\d+) atoms", text)
ok &= check_absolute(T, "log.lammps: steps run", int(m.group(2)) if m else 0, 100000, 0)
ok &= check_absolute(T, "log.lammps: MPI ranks", int(m.group(1)) if m else 0, np_, 0)
ok &= check_absolute(T, "log.lammps: grains poured", int(m.group(3)) if m else 0, 300, 0)
prog = re.findall(r"^t = (\S+) / (\S+) s \((\d+) %\)\s+(\S+) steps/s\s+ETA (\d+:\d\d:\d\d)$", out, re.M)
ok &= check_at_least(T, "progress lines printed", len(prog), 1)
last = prog[-1] if prog else ("0", "0", "0", "0", "")
ok &= check_absolute(T, "last progress line: end time [s]", float(last[1]), 1e-3, 1e-15)
ok &= check_absolute(T, "last progress line: simulated time [s]", float(last[0]), 1e-3, 1e-15)
ok &= check_absolute(T, "last progress line: percent", int(last[2]), 100, 0)

# a failing run: an unknown LAMMPS command
bad = os.path.join(work, "bad")
os.makedirs(bad)
inp = open(os.path.join(SRC, "examples", "powder-pour", "in.pour")).read()
open(os.path.join(bad, "in.pour"), "w").write(inp.replace("run             ${nsteps}",
                                                          "fix oops all no/such/style\nrun 10"))
rc, out, err = meltdem("run", bad, "--np", str(np_))
print(out, err)
line = [ln for ln in err.splitlines() if ln.startswith("meltdem: ERROR")]
ok &= check_absolute(T, "broken input: exit code", rc, 1, 0)
ok &= check_absolute(T, "broken input: one ERROR line naming log.lammps and the fix style",
                     sum(1 for ln in line if "log.lammps" in ln and "no/such/style" in ln), 1, 0)
rc, out, err = meltdem("run", work)
print(out, err)
ok &= check_absolute(T, "folder that is no case: exit code", rc, 1, 0)
ok &= check_absolute(T, "folder that is no case: reason given",
                     int("not a case" in err and "system/controlDict" in err), 1, 0)
# options that would be dropped stop before anything runs
elsewhere = os.path.join(work, "elsewhere")
rc, out, err = meltdem("run", case, "--case", elsewhere, "--no-analyse")
print(out, err)
ok &= check_absolute(T, "case folder with --case: exit code", rc, 1, 0)
ok &= check_absolute(T, "case folder with --case: reason given, nothing made there",
                     int("--case applies to example names only" in err and not os.path.exists(elsewhere)), 1, 0)
rc, out, err = meltdem("run", case, "--checkpoint-every", "0")
print(out, err)
ok &= check_absolute(T, "--checkpoint-every 0: exit code", rc, 2, 0)
ok &= check_absolute(T, "--checkpoint-every 0: reason given", int("--checkpoint-every must be >= 1" in err), 1, 0)
if ok:
    shutil.rmtree(work, ignore_errors=True)
else:
    print(f"kept {work}")
sys.exit(0 if ok else 1)
