"""Shared by the tests/cli tests: runs the `meltdem` command (the build's launcher
MELTDEM_BIN/meltdem when it exists, else tools/meltdem) and reports through testing.report."""
import os
import subprocess

from meltdem import paths
from meltdem.testing.report import check_absolute, check_at_least, check_at_most, report

__all__ = ["SRC", "meltdem_command", "meltdem", "build_example",
           "check_absolute", "check_at_least", "check_at_most", "report"]

SRC = paths.source_dir()


def meltdem_command():
    launcher = paths.binary("meltdem")
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
    """The scene's build step: CASE at SIZE (ci or full)."""
    subprocess.run(["/usr/bin/python3", "-m", "meltdem.scene", "build", name, case, size],
                   check=True, stdout=subprocess.DEVNULL, env=paths.tool_env())
