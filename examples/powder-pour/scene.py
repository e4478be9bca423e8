#!/usr/bin/python3
"""Powder pour, the default scene (DEM only): 300 steel grains poured onto a plate by in.pour, a
plain LAMMPS input run by meltdem-lmp. See README.md.

    scene.py build CASE      copy in.pour into CASE (meltdem run powder-pour does this)
"""
import json
import os
import shutil
import sys

from meltdem.scene import Scene


HERE = os.path.dirname(os.path.abspath(__file__))


def build(case, size="ci"):
    """The input as it is (one size): in.pour and scene.json naming the scene."""
    os.makedirs(case, exist_ok=True)
    shutil.copy(os.path.join(HERE, "in.pour"), case)
    with open(os.path.join(case, "scene.json"), "w") as f:
        json.dump({"scene": "powder-pour"}, f)


SCENE = Scene(name="powder-pour", kind="dem",
              title="Powder pour: 300 steel grains poured onto a plate (the default scene, DEM only)",
              ci_time="about 1.4 s wall", full_time=None, build=build)

if __name__ == "__main__" and len(sys.argv) == 3 and sys.argv[1] == "build":
    build(os.path.abspath(sys.argv[2]))
elif __name__ == "__main__":
    sys.exit(__doc__)
