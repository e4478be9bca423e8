"""Running meltdem-lmp from a test: one input text in a scratch folder, the output read back.

    from meltdem.testing.lammps_run import run, thermo_runs, check_errors
    rc, out = run(text, np=2)
"""
import os
import re
import subprocess
import tempfile

from .. import paths
from meltdem.testing.report import report


def lmp():
    """The build's meltdem-lmp (MELTDEM_BIN, looked up when called)."""
    return paths.binary("meltdem-lmp")


def _launch(cmd, cwd, np, check, timeout):
    """The LAMMPS command cmd (a list, on np ranks) in cwd; (returncode, stdout+stderr)."""
    if np > 1:
        cmd = ["mpirun", "-np", str(np)] + cmd
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=timeout)
    if check and p.returncode != 0:
        print(p.stdout[-4000:])
        raise SystemExit(f"{os.path.basename(cmd[0])} failed with exit code {p.returncode}")
    return p.returncode, p.stdout


def _var_args(variables):
    """-var NAME VALUE for each item of variables."""
    return [a for name, value in (variables or {}).items() for a in ("-var", name, str(value))]


def run(text, np=1, check=True, cwd=None, timeout=300, variables=None, exe=None):
    """Run an input text (in a scratch folder, or in cwd) with meltdem-lmp, or with exe (a
    command list: another LAMMPS executable and its leading arguments); -var NAME VALUE for each
    item of variables; returns (returncode, stdout+stderr)."""
    with tempfile.TemporaryDirectory() as scratch:
        d = cwd or scratch
        path = os.path.join(d, "in.test")
        with open(path, "w") as f:
            f.write(text)
        cmd = (exe or [lmp()]) + ["-in", path, "-log", "none", "-echo", "none"] + _var_args(variables)
        return _launch(cmd, d, np, check, timeout)


def run_file(path, variables=None, np=1, check=True, timeout=300):
    """Run an input file with -var NAME VALUE for each item of variables, in a scratch
    folder; returns (returncode, stdout+stderr)."""
    cmd = [lmp(), "-in", os.path.abspath(path), "-log", "none"] + _var_args(variables)
    with tempfile.TemporaryDirectory() as d:
        return _launch(cmd, d, np, check, timeout)


def printed_value(out, key):
    """The number printed by an input line 'print "KEY value"'."""
    for line in out.splitlines():
        w = line.split()
        if len(w) == 2 and w[0] == key:
            return float(w[1])
    print(out[-2000:])
    raise SystemExit(f"no '{key}' line in the output")


def thermo_runs(out, first="Step"):
    """Thermo rows grouped per run: a list (one per run) of lists of dicts (columns by name)."""
    runs, rows, cols = [], None, None
    for line in out.splitlines():
        w = line.split()
        if w and w[0] == first:
            cols, rows = w, []
            runs.append(rows)
            continue
        if cols and len(w) == len(cols):
            try:
                rows.append(dict(zip(cols, [float(x) for x in w])))
            except ValueError:
                cols = None
        elif cols and w and w[0] == "Loop":
            cols = None
    return runs


def thermo_rows(out, first="Step"):
    """All thermo rows of all runs, one list of dicts."""
    return [row for rows in thermo_runs(out, first) for row in rows]


def lammps_version():
    """The LAMMPS library's version as YYYYMMDD, from the banner of meltdem-lmp -h."""
    months = "Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec".split()
    out = subprocess.run([lmp(), "-h"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    m = re.search(r"Simulator - (\d+) ([A-Z][a-z][a-z]) (\d{4})", out)
    if m and m.group(2) in months:
        return int(m.group(3)) * 10000 + (months.index(m.group(2)) + 1) * 100 + int(m.group(1))
    raise SystemExit("no LAMMPS version in the banner of meltdem-lmp -h")


def check_errors(test, cases, cwd=None):
    """cases: (what, input text, expected substring of the ERROR line, or a tuple of them: the
    wordings of the LAMMPS releases MeltDEM builds against). Each must stop with an ERROR line
    containing one; returns True when all do."""
    ok = True
    for what, text, expected in cases:
        rc, out = run(text, check=False, cwd=cwd)
        errors = [line.strip() for line in out.splitlines() if line.startswith("ERROR")]
        got = errors[0] if errors else f"(no ERROR line, exit code {rc})"
        wanted = expected if isinstance(expected, tuple) else (expected,)
        good = rc != 0 and any(w in e for e in errors for w in wanted)
        ok &= report(test, what, got, "ERROR containing " + " or ".join(f"'{w}'" for w in wanted), "substring", good)
        if not good:
            print(out[-2000:])
    return ok
