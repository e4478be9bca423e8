"""Scenes declare themselves: each examples/<name>/scene.py defines

    SCENE = Scene(name="lmd-track", kind="coupled", title="...", ci_time="2 min", full_time="...",
                  build=build, run=run, analyse=analyse)

and `meltdem list`, `meltdem run` and `meltdem post` read those declarations (the READMEs are
prose for people). build(case, size) writes a case ('ci' or 'full') and its scene.json naming the
scene; run(case, np) runs it when it is not one solver case (bjt-droplet: a bed, then one case per
speed), else None (meltdem runs the case folder); analyse(case) writes the scene's numbers into
CASE/summary.json after a run; summary(case), where given, is the analysis `meltdem post` runs in
its own process when a case has no summary.json yet."""
import os
from dataclasses import dataclass
from typing import Callable, Optional

from .loader import load_module
from .paths import examples_dir

KINDS = {"dem": "DEM-only", "coupled": "coupled", "continuum": "continuum-only"}


@dataclass
class Scene:
    name: str
    kind: str                       # dem | coupled | continuum
    title: str
    ci_time: Optional[str] = None   # wall time of the CI size on the 2-core machine
    full_time: Optional[str] = None
    build: Optional[Callable] = None       # build(case, size)
    run: Optional[Callable] = None         # run(case, np): scenes that are not one solver case
    analyse: Optional[Callable] = None     # analyse(case): CASE/summary.json
    summary: Optional[Callable] = None     # summary(case): the same, in meltdem post's process

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"scene {self.name}: kind {self.kind!r} is not one of {', '.join(KINDS)}")


def names():
    """The example folders with a scene.py, sorted."""
    d = examples_dir()
    return sorted(n for n in os.listdir(d) if os.path.isfile(os.path.join(d, n, "scene.py")))


def module(name):
    """examples/<name>/scene.py as a module."""
    return load_module(os.path.join(examples_dir(), name, "scene.py"))


def get(name):
    """The Scene declared by examples/<name>/scene.py."""
    s = getattr(module(name), "SCENE", None)
    if not isinstance(s, Scene):
        raise ValueError(f"examples/{name}/scene.py declares no SCENE = Scene(...)")
    return s


def main(argv=None):
    """python3 -m meltdem.scene build|run|analyse NAME CASE [SIZE|NP]: one step of a scene in a
    process of its own (how `meltdem run` calls them)."""
    import sys
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) < 3 or argv[0] not in ("build", "run", "analyse"):
        sys.exit("usage: python3 -m meltdem.scene build|run|analyse NAME CASE [SIZE|NP]")
    action, name, case, rest = argv[0], argv[1], argv[2], argv[3:]
    s = get(name)
    step = getattr(s, action)
    if step is None:
        sys.exit(f"scene {name} has no {action} step")
    if action == "build":
        r = step(case, rest[0] if rest else "ci")
    elif action == "run":
        r = step(case, int(rest[0]) if rest else 1)
    else:
        r = step(case)
    return r if isinstance(r, int) else 0


if __name__ == "__main__":
    # run as `python3 -m meltdem.scene`: the scenes declare meltdem.scene.Scene, not __main__'s
    import sys
    from meltdem.scene import main as scene_main
    sys.exit(scene_main())
