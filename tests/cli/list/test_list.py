"""`meltdem list` names every example folder (scene.py or a LAMMPS in.* input), with its kind
(DEM-only / coupled / continuum-only) and its README title."""
import os
import subprocess
import sys

from meltdem import paths
from meltdem.testing.cli import SRC, check_absolute, meltdem, meltdem_command

T = "cli.list"
ex = os.path.join(SRC, "examples")
expected = sorted(n for n in os.listdir(ex) if os.path.isdir(os.path.join(ex, n)) and
                  (os.path.isfile(os.path.join(ex, n, "scene.py")) or
                   any(f.startswith("in.") for f in os.listdir(os.path.join(ex, n)))))
rc, out, err = meltdem("list")
print(out, err)
rows = {ln.split()[0]: ln for ln in out.splitlines()[1:] if ln.strip() and not ln.startswith(" ")}
listed = [n for n in expected if n in rows]
with_kind = [n for n in listed if any(k in rows[n] for k in ("DEM-only", "coupled", "continuum-only"))]
ok = check_absolute(T, "exit code", rc, 0, 0)
ok &= check_absolute(T, f"examples listed (of {len(expected)} folders)", len(listed), len(expected), 0)
ok &= check_absolute(T, "examples listed with a kind", len(with_kind), len(expected), 0)
# the default scene is DEM-only, a coupled scene coupled, mjt continuum-only (top-level README table)
kinds = {"powder-pour": "DEM-only", "slm-track": "coupled", "mjt-droplets": "continuum-only"}
right = sum(1 for n, k in kinds.items() if n in rows and k in rows[n])
ok &= check_absolute(T, "kinds of powder-pour / slm-track / mjt-droplets", right, len(kinds), 0)
no_title = [n for n in listed if "(no README)" in rows[n]]
ok &= check_absolute(T, "examples without a README title", len(no_title), 0, 0)
# the package runs as the command too: `python3 -m meltdem` and `python3 -m meltdem.cli.main`
for module in ("meltdem", "meltdem.cli.main"):
    p = subprocess.run(["/usr/bin/python3", "-m", module, "list"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       text=True, env=paths.tool_env())
    ok &= check_absolute(T, f"`python3 -m {module} list` prints what `meltdem list` prints (1 = yes)",
                         int(p.stdout == out), 1, 0)
# `meltdem list | head -c 10`: a reader that closes the pipe early is no error (was "ERROR: Broken pipe", rc 1)
broken = 0
for _ in range(5):
    p = subprocess.Popen(meltdem_command() + ["list"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.close()
    err = p.stderr.read().decode()
    broken += int(p.wait() != 0 or "ERROR" in err)
ok &= check_absolute(T, "runs of 5 with the pipe closed early that fail or print an error", broken, 0, 0)
sys.exit(0 if ok else 1)
