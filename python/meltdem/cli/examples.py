"""The scenes of examples/ as `meltdem list`, `run` and `post` use them: their declarations
(meltdem.scene: name, kind, title, run times) and building, running and analysing a case through
them, each step in a process of its own whose output goes to a log in the case."""
import os
import shutil
import subprocess

from .. import paths, scene
from ..scene import KINDS  # noqa: F401  (the kinds' names for `meltdem list`)

PYTHON = "/usr/bin/python3"


def examples_dir():
    return paths.examples_dir()


def names():
    return scene.names()


def describe():
    """One row per scene: name, title, kind, ci_time, full_time, readme."""
    rows = []
    for n in names():
        s = scene.get(n)
        rows.append(dict(name=n, title=s.title, kind=s.kind, ci_time=s.ci_time, full_time=s.full_time,
                         readme=os.path.join("examples", n, "README.md")))
    return rows


def has_step(name, step):
    """Whether scene NAME declares STEP ('build', 'run', 'analyse', 'summary')."""
    return name in names() and getattr(scene.get(name), step) is not None


def _command(step, name, case, *args):
    return [PYTHON, "-m", "meltdem.scene", step, name, case] + [str(a) for a in args]


def build(name, case, size="ci"):
    """Build CASE from scene NAME; its output goes to CASE/log.build. Returns the command line run."""
    cmd = _command("build", name, case, size)
    # the scene creates CASE itself (some refuse a folder they did not write): log beside it first
    parent = os.path.dirname(os.path.abspath(case))
    os.makedirs(parent, exist_ok=True)
    tmp = os.path.join(parent, f".meltdem-build-{os.path.basename(case)}.log")
    with open(tmp, "w") as f:
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, env=paths.tool_env())
    logpath = os.path.join(case, "log.build") if os.path.isdir(case) else os.path.join(parent, f"log.build.{name}")
    shutil.move(tmp, logpath)
    if r.returncode != 0:
        raise StepError(f"building {name} failed (rc {r.returncode}): read {logpath}")
    return " ".join(cmd)


def analyse(name, case):
    """The scene's analysis of CASE (writes CASE/summary.json; log.analyse); None when it has none."""
    if not has_step(name, "analyse"):
        return None
    logpath = os.path.join(case, "log.analyse")
    with open(logpath, "w") as f:
        r = subprocess.run(_command("analyse", name, case), stdout=f, stderr=subprocess.STDOUT, env=paths.tool_env())
    if r.returncode != 0:
        raise StepError(f"{name} analysis failed (rc {r.returncode}): read {logpath}")
    return logpath


def scene_run(name, case, np_, log):
    """The scene's own run step (scenes whose built case is not one solver case)."""
    f = open(log, "w")
    return subprocess.Popen(_command("run", name, case, np_), stdout=f, stderr=subprocess.STDOUT,
                            env=paths.tool_env()), f


class StepError(RuntimeError):
    """A step failed; the message is the one-line reason (it names the log to read)."""
