"""`meltdem run ded-stream --case DIR` (the CI size; coupled meltdemFoam + LAMMPS, five grains into
a laser melt pool): exit 0, blockMesh and the solver run to endTime (log.meltdemFoam 'End'), the
progress line ends at endTime, a checkpoint at the last write time (meltdemRestart/<T>/complete),
the post-processor's ParaView series and the scene's summary.json (with the post-processor's
numbers merged into it)."""
import json
import os
import re
import shutil
import sys
import tempfile

from meltdem.testing.cli import check_absolute, meltdem

from meltdem.io import foamdict as fd

T = "cli.run.ded_stream"
work = tempfile.mkdtemp(prefix="cli_coupled_")
case = os.path.join(work, "ded")
ok = True
rc, out, err = meltdem("run", "ded-stream", "--case", case, cwd=work, timeout=280)
print(out, err)
ok &= check_absolute(T, "exit code", rc, 0, 0)
log = (open(os.path.join(case, "log.meltdemFoam")).read() if os.path.isfile(os.path.join(case, "log.meltdemFoam"))
       else "")
ok &= check_absolute(T, "log.meltdemFoam ends with End", int(bool(re.search(r"^End\s*$", log, re.M))), 1, 0)
ok &= check_absolute(T, "blockMesh ran (log.blockMesh)", int(os.path.isfile(os.path.join(case, "log.blockMesh"))), 1, 0)
t_end = fd.number(fd.read(os.path.join(case, "system", "controlDict")), "endTime")
prog = re.findall(r"^t = (\S+) / (\S+) s \((\d+) %\)", out, re.M)
ok &= check_absolute(T, "last progress line: t [s]", float(prog[-1][0]) if prog else 0.0, t_end, 1e-12)
last = (fd.time_dirs(case) or ["0"])[-1]
ok &= check_absolute(T, "last time folder [s]", float(last), t_end, 1e-12)
ok &= check_absolute(T, f"checkpoint meltdemRestart/{last}/complete",
                     int(os.path.isfile(os.path.join(case, "meltdemRestart", last, "complete"))), 1, 0)
pvd = [f for f in ("fields.pvd", "particles.pvd") if os.path.isfile(os.path.join(case, "VTK", f))]
ok &= check_absolute(T, "ParaView series VTK/fields.pvd, VTK/particles.pvd", len(pvd), 2, 0)
try:
    s = json.load(open(os.path.join(case, "summary.json")))
except (OSError, ValueError):
    s = {}
ok &= check_absolute(T, "summary.json: scene analysis (fluid_steps) and post-processing (meltdem_post) in one",
                     int("fluid_steps" in s and isinstance(s.get("meltdem_post"), dict)), 1, 0)
if ok:
    shutil.rmtree(work, ignore_errors=True)
else:
    print(f"kept {work}")
sys.exit(0 if ok else 1)
