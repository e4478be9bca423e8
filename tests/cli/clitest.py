"""Shared by the tests/cli tests: runs the `meltdem` command (the build's launcher
MELTDEM_BIN/meltdem when it exists, else tools/meltdem) and reports through meltdem_report."""
import os
import subprocess
import sys

SRC = os.environ.get("MELTDEM_SOURCE_DIR") or os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(SRC, "tests", "support"))
sys.path.insert(0, os.path.join(SRC, "tools"))
from meltdem_report import check_absolute, check_at_least, check_at_most, report  # noqa: E402,F401


def meltdem_command():
    launcher = os.path.join(os.environ.get("MELTDEM_BIN", ""), "meltdem")
    if os.access(launcher, os.X_OK):
        return [launcher]
    return ["/usr/bin/python3", os.path.join(SRC, "tools", "meltdem")]


def meltdem(*args, cwd=None, env=None, timeout=300):
    """(returncode, stdout, stderr) of `meltdem args...`."""
    e = dict(os.environ)
    e.update(env or {})
    p = subprocess.run(meltdem_command() + list(args), cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       text=True, env=e, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def build_example(name, case, size="ci"):
    """examples/<name>/scene.py build CASE --ci (the scene interface)."""
    subprocess.run(["/usr/bin/python3", os.path.join(SRC, "examples", name, "scene.py"), "build", case, f"--{size}"],
                   check=True, stdout=subprocess.DEVNULL)
