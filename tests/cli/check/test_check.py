"""`meltdem check`: exit 0 on built CI cases of examples (ded-stream and lmd-track coupled,
mjt-droplets continuum-only, powder-pour DEM-only); exit 1 on broken copies, each with exactly one
ERROR line that names the file and the entry:

    delete endTime            -> system/controlDict: endTime missing
    units lj                  -> in.particles: units lj
    laser outside             -> constant/meltdemProperties: laser.position ... outside the mesh
    laser path end outside    -> constant/meltdemProperties: laser.end of the path ... outside
    mesh outside the box      -> in.particles: LAMMPS box ... does not contain the mesh box
    metal.k deleted           -> constant/meltdemProperties: metal.k missing
    0/U in m (not m/s)        -> 0/U: dimensions ... not the SI dimensions of U
    latent deleted            -> in.particles: ... fix melt powder/melt: keyword(s) latent missing
    transportProperties gone  -> constant/transportProperties: file missing
    Mars gravity for grains   -> in.particles: fix gravity gives ... but constant/g is ...
    gas.k < 0                 -> constant/meltdemProperties: gas.k = -0.026 must be positive
    DEM: read_data missing    -> in.pour: read_data ...: file missing
    endTime nan               -> system/controlDict: endTime: nan is not a number
    a missing ';'             -> system/controlDict: writeInterval ... a missing ';' after it?
    an unclosed '{'           -> system/fvSolution: cannot be parsed
    alpha.metal 1.5           -> 0/alpha.metal: 1 value(s) outside [0, 1]
    metal rho < 0             -> constant/transportProperties: metal.rho = -7900 must be positive
    insertion above the mesh  -> in.particles: ... region feed ... lies outside the mesh
    case path with a space    -> the case path has white space
    an unreadable file        -> system/fvSchemes: cannot be read (Permission denied), as a user
                                 who may not read it (root runs the check as nobody)
and exit 0 where the input is right but was misread: fix gravity in an included file (it
reported a gravity mismatch).
"""
import os
import re
import shutil
import sys
import tempfile

from meltdem.testing.cli import SRC, build_example, check_absolute, meltdem
from meltdem.testing.cli import meltdem_command

T = "cli.check"
ok = True
work = tempfile.mkdtemp(prefix="cli_check_")


def sub(path, pattern, repl, count=1):
    text = open(path).read()
    new, n = re.subn(pattern, repl, text, count=count, flags=re.M)
    assert n, f"{pattern!r} not found in {path}"
    open(path, "w").write(new)


def run_check(case):
    rc, out, err = meltdem("check", case)
    errors = [ln.strip()[len("ERROR "):] for ln in out.splitlines() if ln.strip().startswith("ERROR ")]
    return rc, out, errors


cases = {}
for name in ("ded-stream", "lmd-track", "mjt-droplets"):
    cases[name] = os.path.join(work, name)
    build_example(name, cases[name])
pour = os.path.join(work, "powder-pour")
os.makedirs(pour)
shutil.copy(os.path.join(SRC, "examples", "powder-pour", "in.pour"), pour)
cases["powder-pour"] = pour
for name, case in cases.items():
    rc, out, errors = run_check(case)
    print(out)
    ok &= check_absolute(T, f"{name} CI case: exit code", rc, 0, 0)
    ok &= check_absolute(T, f"{name} CI case: problems reported", len(errors), 0, 0)


def broken(label, base, edit, expect):
    """A copy of base with edit(case) applied: exit 1, one ERROR line, containing each of expect."""
    global ok
    case = os.path.join(work, re.sub(r"[^A-Za-z0-9.]+", "_", label))
    shutil.copytree(base, case)
    edit(case)
    rc, out, errors = run_check(case)
    print(f"--- {label}\n{out}")
    hit = [e for e in errors if all(x in e for x in expect)]
    ok &= check_absolute(T, f"{label}: exit code", rc, 1, 0)
    ok &= check_absolute(T, f"{label}: ERROR lines", len(errors), 1, 0)
    ok &= check_absolute(T, f"{label}: names '{' ... '.join(expect)}'", len(hit), 1, 0)


ded = cases["ded-stream"]
lmd = cases["lmd-track"]
broken("delete endTime", ded, lambda c: sub(os.path.join(c, "system/controlDict"), r"^endTime .*\n", ""),
       ["system/controlDict:", "endTime missing"])
broken("units lj", ded, lambda c: sub(os.path.join(c, "in.particles"), r"^units si", "units lj"),
       ["in.particles:", "units lj"])
broken("laser position outside", ded,
       lambda c: sub(os.path.join(c, "constant/meltdemProperties"), r"position\s+\(\S+", "position     (0.01"),
       ["constant/meltdemProperties:", "laser.position", "outside the mesh"])
# lmd-track's laser moves (position + velocity until tOff): twice the speed leaves the plate
broken("laser path end outside", lmd,
       lambda c: sub(os.path.join(c, "constant/meltdemProperties"), r"velocity\s+\((\S+)",
                     lambda m: f"velocity     ({float(m.group(1)) * 40!r}"),
       ["constant/meltdemProperties:", "laser.end of the path", "outside the mesh"])
broken("mesh outside the LAMMPS box", ded,
       lambda c: sub(os.path.join(c, "system/blockMeshDict"), r"^scale 1;", "scale 1.2;"),
       ["in.particles:", "LAMMPS box", "does not contain the mesh box"])
broken("metal.k deleted", ded,
       lambda c: sub(os.path.join(c, "constant/meltdemProperties"), r"^(\s*)k\s+35\.95;\n", ""),
       ["constant/meltdemProperties:", "metal.k missing"])
broken("0/U dimensions not SI", ded,
       lambda c: sub(os.path.join(c, "0/U"), r"dimensions\s+\[[^\]]*\]", "dimensions [0 1 0 0 0 0 0]"),
       ["0/U:", "dimensions [0 1 0 0 0 0 0]", "SI dimensions of U"])
broken("powder/melt keyword missing", ded,
       lambda c: sub(os.path.join(c, "in.particles"), r" latent \S+", ""),
       ["in.particles:", "powder/melt", "latent"])
broken("negative gas conductivity", ded,
       lambda c: sub(os.path.join(c, "constant/meltdemProperties"), r"^gas \{ cp (\S+); k \S+; \}",
                     r"gas { cp \1; k -0.026; }"),
       ["constant/meltdemProperties:", "gas.k = -0.026 must be positive"])
broken("gravity mismatch", ded,
       lambda c: sub(os.path.join(c, "in.particles"), r"^fix gravity all gravity 9.81", "fix gravity all gravity 3.71"),
       ["in.particles:", "fix gravity gives", "constant/g"])
broken("transportProperties deleted", ded, lambda c: os.remove(os.path.join(c, "constant/transportProperties")),
       ["constant/transportProperties:", "file missing"])
broken("DEM read_data file missing", pour,
       lambda c: sub(os.path.join(c, "in.pour"), r"^create_box.*$", "read_data grains.data"),
       ["in.pour:", "read_data grains.data: file missing"])
broken("endTime nan", ded, lambda c: sub(os.path.join(c, "system/controlDict"), r"^endTime .*$", "endTime nan;"),
       ["system/controlDict:", "endTime: nan is not a number"])
broken("a missing ';'", ded, lambda c: sub(os.path.join(c, "system/controlDict"), r"^(writeInterval [^;]*);", r"\1"),
       ["system/controlDict:", "writeInterval", "a missing ';'"])
broken("an unclosed brace", ded,
       lambda c: open(os.path.join(c, "system/fvSolution"), "a").write("\nextra { a 1;\n"),
       ["system/fvSolution:", "cannot be parsed"])
broken("alpha.metal 1.5", ded, lambda c: sub(os.path.join(c, "0/alpha.metal"), r"^internalField .*$",
                                             "internalField uniform 1.5;"),
       ["0/alpha.metal:", "outside [0, 1]"])
broken("negative metal density", ded,
       lambda c: sub(os.path.join(c, "constant/transportProperties"), r"(metal\s*\{[^}]*?rho\s+)(\S+);", r"\1-\2;"),
       ["constant/transportProperties:", "metal.rho", "must be positive"])
broken("powder inserted above the mesh", ded,
       lambda c: open(os.path.join(c, "in.particles"), "a").write(
           "region feed block 1e-4 1.6e-4 1e-4 1.6e-4 2.41e-4 2.59e-4\n"
           "fix ins all powder/insert 10 1 region feed diam one 1.6e-5 dens 7900\n"),
       ["in.particles:", "region feed", "lies outside the mesh", "booked lost"])
broken("misspelt top-level block (refinment)", ded,
       lambda c: open(os.path.join(c, "constant/meltdemProperties"), "a").write(
           "\nrefinment { maxLevel 1; criteria { interface { level 1; } } }\n"),
       ["constant/meltdemProperties:", "refinment: unknown entry", "refinement"])
shutil.copytree(ded, os.path.join(work, "with space"))
rc, out, errors = run_check(os.path.join(work, "with space"))
print(f"--- case path with a space\n{out}")
ok &= check_absolute(T, "case path with a space: exit code", rc, 1, 0)
ok &= check_absolute(T, "case path with a space: ERROR naming it", int(any("white space" in e for e in errors)), 1, 0)


def gravity_included(c):
    p = os.path.join(c, "in.particles")
    text = open(p).read()
    line = re.search(r"^fix gravity .*$", text, re.M).group(0)
    open(p, "w").write(text.replace(line, "include gravity.in"))
    open(os.path.join(c, "gravity.in"), "w").write(line + "\n")


inc = os.path.join(work, "gravity_included")
shutil.copytree(ded, inc)
gravity_included(inc)
rc, out, errors = run_check(inc)
print(f"--- fix gravity in an included file\n{out}")
ok &= check_absolute(T, "fix gravity in an included file: exit code", rc, 0, 0)
ok &= check_absolute(T, "fix gravity in an included file: ERROR lines", len(errors), 0, 0)

# an unreadable file, for a user who may not read it (root reads everything: check as nobody)
unread = os.path.join(work, "unreadable")
shutil.copytree(ded, unread)
os.chmod(os.path.join(unread, "system", "fvSchemes"), 0)
as_user = []
if os.geteuid() == 0 and shutil.which("setpriv"):
    for d in (work, unread) + tuple(os.path.join(r, x) for r, ds, _ in os.walk(unread) for x in ds):
        os.chmod(d, 0o755)
    for r, _, fs in os.walk(unread):
        for f in fs:
            if f != "fvSchemes":
                os.chmod(os.path.join(r, f), 0o644)
    as_user = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"]
import subprocess  # noqa: E402
p = subprocess.run(as_user + meltdem_command() + ["check", unread], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                   text=True, timeout=300)
print(f"--- an unreadable file\n{p.stdout}{p.stderr}")
errors = [ln.strip()[len("ERROR "):] for ln in p.stdout.splitlines() if ln.strip().startswith("ERROR ")]
ok &= check_absolute(T, "unreadable system/fvSchemes: exit code", p.returncode, 1, 0)
ok &= check_absolute(T, "unreadable system/fvSchemes: no traceback", int("Traceback" in p.stderr), 0, 0)
ok &= check_absolute(T, "unreadable system/fvSchemes: ERROR naming it",
                     int(any("system/fvSchemes" in e and "cannot be read" in e for e in errors)), 1, 0)
if ok:
    shutil.rmtree(work, ignore_errors=True)
else:
    print(f"kept {work}")
sys.exit(0 if ok else 1)
