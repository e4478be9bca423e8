"""`meltdem check`, `meltdem run`, `--resume`, `meltdem post` and meltdemFoam on the case layouts
OpenFOAM users write, on single-track's CI case cut to 20 us (continuum-only, refined, ~1 s a run)
and ded-stream's CI case cut to 2 us (coupled):
  * start fields in a time folder other than 0/ (from 0.orig), startFrom latestTime: checked there,
    the run starts there and keeps it (the folder was deleted, then the run failed);
  * a finished run continued by startFrom latestTime and a later endTime: it continues from its
    checkpoint, as meltdemFoam alone does (all output was removed and it restarted at 0, rc 0);
  * a bad start field in that folder is reported; gzipped 0/ fields are read;
  * --resume from a checkpoint whose time has more than 6 digits (writeControl timeStep);
  * a time folder without fields (a write cut short) is not the simulated time;
  * meltdem post's bead on a refined run (cells changing between times) equals the uniform run's;
  * meltdemFoam -case DIR from another folder: the LAMMPS input's include and dump are the case's.
"""
import gzip
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

from meltdem import paths
from meltdem.io import foamdict as fd
from meltdem.testing.cli import SRC, check_absolute, meltdem
from meltdem.testing.report import check_at_least

T = "cli.case_layouts"
ok = True
work = tempfile.mkdtemp(prefix="cli_layouts_")
env = paths.tool_env()


def control(case, **entries):
    fd.set_entries(os.path.join(case, "system", "controlDict"), entries)


def tool(cmd, cwd):
    return subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def first_time(case):
    """The first `Time = ` of the latest meltdemFoam log."""
    m = re.search(r"^Time = (\S+)", open(os.path.join(case, "log.meltdemFoam")).read(), re.M)
    return float(m.group(1)) if m else float("nan")


base = os.path.join(work, "base")
subprocess.run(["/usr/bin/python3", os.path.join(SRC, "examples", "single-track", "scene.py"), "build", base,
                "--ci", "--dx", "20", "--track", "0.2"], check=True, env=env, stdout=subprocess.DEVNULL)
control(base, endTime="2e-05", writeInterval="5e-06")
tool(["blockMesh"], base)

# start fields in 1e-05/ (copied from 0.orig), startFrom latestTime
c = os.path.join(work, "latest")
shutil.copytree(base, c)
os.rename(os.path.join(c, "0"), os.path.join(c, "0.orig"))
shutil.copytree(os.path.join(c, "0.orig"), os.path.join(c, "1e-05"))
control(c, startFrom="latestTime", endTime="3e-05")
rc, out, err = meltdem("check", c)
print(out, err)
ok &= check_absolute(T, "meltdem check, start fields in 1e-05/ (startFrom latestTime): exit code", rc, 0, 0)
rc, out, err = meltdem("run", c)
print(out[-3000:], err[-3000:])
ok &= check_absolute(T, "meltdem run of it: exit code", rc, 0, 0)
ok &= check_absolute(T, "its start folder 1e-05/ kept (1 = yes)", int(os.path.isfile(os.path.join(c, "1e-05", "T"))),
                     1, 0)
ok &= check_absolute(T, "its first step [s] (1e-05 + one step of at most 3e-06)", first_time(c), 1.15e-05, 1.5e-06)

# a finished run continued by startFrom latestTime and a later endTime
c = os.path.join(work, "continued")
shutil.copytree(base, c)
rc, out, err = meltdem("run", c)
ok &= check_absolute(T, "a run to 2e-05: exit code", rc, 0, 0)
control(c, startFrom="latestTime", endTime="3e-05")
rc, out, err = meltdem("run", c)
print(out[-3000:], err[-3000:])
ok &= check_absolute(T, "continued by startFrom latestTime to 3e-05: exit code", rc, 0, 0)
ok &= check_absolute(T, "  its first step [s] (2e-05 + one step of at most 3e-06)", first_time(c), 2.15e-05, 1.5e-06)
have = {round(float(t) / 5e-6, 6) for t in fd.time_dirs(c)}
ok &= check_absolute(T, "  time folders 5e-06, 1e-05, ... 3e-05 there (6)", len(have & {1, 2, 3, 4, 5, 6}), 6, 0)
ok &= check_absolute(T, "  controlDict's startFrom as written (1 = latestTime)",
                     int(fd.word(fd.read(os.path.join(c, "system", "controlDict")), "startFrom") == "latestTime"), 1, 0)

# a time folder without fields is not the simulated time
os.makedirs(os.path.join(c, "4e-05"))
rc, out, err = meltdem("post", c)
line = [ln for ln in open(os.path.join(c, "summary.md")) if "simulated time" in ln]
t_sim = float(line[0].split("|")[2]) if line else float("nan")
ok &= check_absolute(T, "meltdem post with an empty 4e-05/: simulated time [s] (last write 3e-05)", t_sim, 3e-05, 1e-12)

# a bad start field where the run starts; gzipped fields in 0/
c = os.path.join(work, "badstart")
shutil.copytree(base, c)
shutil.copytree(os.path.join(c, "0"), os.path.join(c, "1e-05"))
control(c, startTime="1e-05", endTime="3e-05")
p = os.path.join(c, "1e-05", "alpha.metal")
open(p, "w").write(re.sub(r"internalField\s+[^;]*;", "internalField uniform 2;", open(p).read(), count=1))
rc, out, err = meltdem("check", c)
print(out, err)
ok &= check_absolute(T, "meltdem check, alpha.metal = 2 in the start folder 1e-05/: exit code", rc, 1, 0)
ok &= check_absolute(T, "  the problem names 1e-05/alpha.metal (1 = yes)", int("1e-05/alpha.metal" in out), 1, 0)
c = os.path.join(work, "gz")
shutil.copytree(base, c)
for f in os.listdir(os.path.join(c, "0")):
    p = os.path.join(c, "0", f)
    with open(p, "rb") as src, gzip.open(p + ".gz", "wb") as dst:
        dst.write(src.read())
    os.remove(p)
rc, out, err = meltdem("check", c)
print(out, err)
ok &= check_absolute(T, "meltdem check, gzipped 0/ fields: exit code", rc, 0, 0)

# --resume from a checkpoint whose time has more than 6 digits
c = os.path.join(work, "longtime")
shutil.copytree(base, c)
control(c, writeControl="timeStep", writeInterval="7")
rc, out, err = meltdem("run", c)
times = fd.time_dirs(os.path.join(c, "meltdemRestart"))
long_name = [t for t in times if len(t.split("e")[0].replace(".", "")) > 6]
ok &= check_absolute(T, "writeControl timeStep: the last checkpoint named with more than 6 digits (1 = yes)",
                     int(bool(times) and times[-1] in long_name), 1, 0)
control(c, endTime="3e-05")
rc, out, err = meltdem("run", c, "--resume")
print(out[-3000:], err[-3000:])
ok &= check_absolute(T, f"--resume from {times[-1] if times else '?'}: exit code", rc, 0, 0)
ok &= check_absolute(T, "  its first step [s] (the checkpoint's + one step of at most 3e-06)", first_time(c),
                     float(times[-1]) + 1.5e-06, 1.5e-06)
ctl = fd.read(os.path.join(c, "system", "controlDict"))
ok &= check_absolute(T, "  controlDict's startTime restored (0)", fd.number(ctl, "startTime"), 0, 0)

# meltdem post's bead on a refined run (its cells change between written times: the section is
# sampled on one lattice) against the uniform run of the finest cells, the track's 0.25 ms
bead = {}
for refine in (0, 1):
    c = os.path.join(work, f"bead{refine}")
    subprocess.run(["/usr/bin/python3", os.path.join(SRC, "examples", "single-track", "scene.py"), "build", c,
                    "--ci", "--dx", "20", "--refine", str(refine), "--track", "0.2"], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    control(c, endTime="2.5e-04", writeInterval="2.5e-05")
    rc, out, err = meltdem("run", c, "--no-analyse")
    s = json.load(open(os.path.join(c, "summary.json")))
    print(refine, rc, {k: s.get(k) for k in ("bead_width_m", "penetration_m")}, s["meltdem_post"].get("notes"))
    bead[refine] = s
for k in ("bead_width_m", "penetration_m"):
    ok &= check_absolute(T, f"meltdem post on the refined run (40 -> 20 um): {k} [m] (uniform 20 um run's, one "
                            f"cell)", bead[1].get(k, float("nan")), bead[0].get(k, float("nan")), 20e-6)
ok &= check_at_least(T, "  the uniform run's fused width [m] (the track melted the section)",
                     bead[0].get("bead_width_m", 0.0), 20e-6)
ran = sum(any("analysis" in n for n in bead[r]["meltdem_post"].get("notes", [])) for r in (0, 1))
ok &= check_absolute(T, "  runs with --no-analyse whose post-processing ran the scene's analysis", ran, 0, 0)

# meltdemFoam -case DIR from another folder: relative names in the LAMMPS input are the case's
c = os.path.join(work, "ded")
subprocess.run(["/usr/bin/python3", os.path.join(SRC, "examples", "ded-stream", "scene.py"), "build", c, "--ci"],
               check=True, env=env, stdout=subprocess.DEVNULL)
control(c, endTime="2e-06")
tool(["blockMesh"], c)
inp = os.path.join(c, "in.particles")
open(os.path.join(c, "extra.lmp"), "w").write("variable fromInclude equal 1\n")
text = open(inp).read()
open(inp, "w").write(re.sub(r"^(units\s.*)$", r"\1\ninclude extra.lmp", text, count=1, flags=re.M))
elsewhere = os.path.join(work, "elsewhere")
os.makedirs(elsewhere)
r = tool([os.path.join(paths.bin_dir(), "meltdemFoam"), "-case", "../ded"], elsewhere)
print(r.stdout[-3000:])
ok &= check_absolute(T, "meltdemFoam -case ../ded from another folder, input with `include extra.lmp`: exit code",
                     r.returncode, 0, 0)
dumps = [f for f in os.listdir(c) if f.endswith(".dump")]
ok &= check_absolute(T, "  files the input writes that land in the folder it started in", len(os.listdir(elsewhere)),
                     0, 0)
ok &= check_absolute(T, "  dump files in the case (>= 1)", min(len(dumps), 1), 1, 0)

shutil.rmtree(work, ignore_errors=True)
sys.exit(0 if ok else 1)
