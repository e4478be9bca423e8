"""Helpers of the fix powder/melt tests: run meltdem-lmp on an input text, read thermo."""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.environ["MELTDEM_SOURCE_DIR"], "tests", "support"))
from meltdem_report import check_absolute, check_at_most, check_relative, report  # noqa: E402,F401

LMP = os.path.join(os.environ["MELTDEM_BIN"], "meltdem-lmp")

# a single particle in a large periodic box, SI units, radius changes allowed
HEADER = """units si
atom_style sphere 1
atom_modify map array
boundary p p p
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
create_box 1 box
comm_modify vel yes
neighbor 1e-4 bin
"""


def run(text, np=1, check=True, cwd=None):
    """Run an input (in a scratch folder, or in cwd); returns (returncode, stdout+stderr)."""
    with tempfile.TemporaryDirectory() as scratch:
        d = cwd or scratch
        path = os.path.join(d, "in.test")
        with open(path, "w") as f:
            f.write(text)
        cmd = [LMP, "-in", path, "-log", "none", "-echo", "none"]
        if np > 1:
            cmd = ["mpirun", "-np", str(np)] + cmd
        p = subprocess.run(cmd, cwd=d, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True, timeout=120)
    if check and p.returncode != 0:
        print(p.stdout)
        raise SystemExit(f"meltdem-lmp failed with exit code {p.returncode}")
    return p.returncode, p.stdout


def thermo(out, first="Step"):
    """All thermo rows of all runs as a list of dicts (columns by name)."""
    rows, cols = [], None
    for line in out.splitlines():
        w = line.split()
        if w and w[0] == first:
            cols = w
            continue
        if cols and len(w) == len(cols):
            try:
                vals = [float(x) for x in w]
            except ValueError:
                cols = None
                continue
            rows.append(dict(zip(cols, vals)))
        elif cols and w and w[0] == "Loop":
            cols = None
    return rows


def value(out, key):
    """The number printed by an input line 'print "KEY value"'."""
    for line in out.splitlines():
        w = line.split()
        if len(w) == 2 and w[0] == key:
            return float(w[1])
    raise SystemExit(f"no '{key}' line in the output")
