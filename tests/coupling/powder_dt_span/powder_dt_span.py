#!/usr/bin/python3
"""fix powder/dt in a coupled run: each sub-cycle spans the fluid step exactly.

ded-stream's CI case (20 us, writeInterval 1 us, maxDeltaT 0.25 us) with `fix powder/dt steps 10`
and a stream of grains inserted at 2 m/s: powder/dt changes the DEM step during the sub-cycles.
Before, it reset the host's shortened sub-step to its own longer one at the first sub-step, so
LAMMPS ran past the fluid step: fluid steps of 2.64e-7 > maxDeltaT, write folders 1.800159e-05,
1.9002612e-05 and the run's end 2.000133e-05. Checked: the largest fluid step against maxDeltaT,
the end against endTime, every write time on the 1 us grid, the DEM step changed during the run
(so the test exercises powder/dt), and the ledger's per-step system mass and enthalpy errors.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.io import casedata
from meltdem.io import foamdict as fd
from meltdem.testing.report import check_absolute, check_at_least, check_at_most

T = "coupling.powder_dt_span"
SRC = paths.source_dir()
env = paths.tool_env()
work = tempfile.mkdtemp(prefix="powder_dt_span_")
case = os.path.join(work, "ded")
subprocess.run(["/usr/bin/python3", os.path.join(SRC, "examples", "ded-stream", "scene.py"), "build", case, "--ci"],
               check=True, env=env, stdout=subprocess.DEVNULL)
cd = os.path.join(case, "system", "controlDict")
fd.set_entries(cd, {"endTime": "2e-05", "writeInterval": "1e-06"})
ctl = fd.read(cd)
t_end, write, max_dt = fd.number(ctl, "endTime"), fd.number(ctl, "writeInterval"), fd.number(ctl, "maxDeltaT")
inp = os.path.join(case, "in.particles")
text = open(inp).read()
text = re.sub(r"^thermo\s.*$", "thermo 100", text, count=1, flags=re.M)
text += """fix pdt all powder/dt steps 10
region feed block 60e-6 200e-6 60e-6 200e-6 150e-6 220e-6
fix ins all powder/insert 30 8731 region feed diam uniform 12e-6 18e-6 dens 7430 rate 1e6 vel 0 0 -2 temp 500
thermo_style custom step time dt atoms
thermo_modify format float %.15g
"""
open(inp, "w").write(text)
subprocess.run(["blockMesh"], cwd=case, env=env, stdout=subprocess.DEVNULL, check=True)
r = subprocess.run([os.path.join(paths.bin_dir(), "meltdemFoam")], cwd=case, env=env, stdout=subprocess.PIPE,
                   stderr=subprocess.STDOUT, text=True)
open(os.path.join(case, "log.meltdemFoam"), "w").write(r.stdout)
ok = check_absolute(T, "meltdemFoam exit code", r.returncode, 0, 0)
if r.returncode != 0:
    print(r.stdout[-4000:])
    sys.exit(1)

led = np.genfromtxt(casedata.ledger_path(case), delimiter=",", names=True)
dems = set()
for line in open(os.path.join(case, "log.lammps")):
    w = line.split()
    if len(w) == 4 and w[0].isdigit():
        dems.add(float(w[2]))
ok &= check_at_least(T, "distinct DEM steps in the thermo output (powder/dt acted)", len(dems), 3)
ok &= check_at_most(T, "largest fluid step / maxDeltaT", float(led["dt"].max()) / max_dt, 1 + 1e-12)
ok &= check_absolute(T, "the run's end [s] (endTime)", float(led["time"][-1]), t_end, 1e-12 * t_end)
times = [float(t) for t in fd.time_dirs(case) if float(t) > 0]
off = max(abs(t / write - round(t / write)) for t in times)
ok &= check_absolute(T, f"write times: {len(times)} (endTime / writeInterval)", len(times), round(t_end / write), 0)
ok &= check_at_most(T, "write times' largest distance from the writeInterval grid [intervals]", off, 1e-6)
for q in ("mass", "enthalpy"):   # the ledger's errors are relative (doc/foam_particle_coupling.rst)
    ok &= check_at_most(T, f"worst per-step relative system {q} error", float(np.abs(led[f"{q}_system_error"]).max()),
                        1e-12)
shutil.rmtree(work, ignore_errors=True)
sys.exit(0 if ok else 1)
