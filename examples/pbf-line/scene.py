#!/usr/bin/python3
"""Powder bed fusion, line melting (Fuchs2022 §4.5): 960 x 320 x 240 um, 1500 grains
(log-normal 16-32 um) on an 80 um steel substrate; a 312 W laser (d_w = 140 um) switched on
160 um from one end, at rest until 0.05 ms, then 2 m/s over 640 um, off at 0.37 ms;
meltdemFoam (melt pool, recoil, evaporation) hosting LAMMPS (the grains). The bed generator,
case writer and analysis are shared with examples/pbf-point (pbf.py). See README.md.

    scene.py build CASE [--ci | --full] [--dx 10e-6] [--dist overlap] [--grains N] [--absorptivity ETA]
                   [--dabsorptivity-dt PER_K [--absorptivity-min ETA] [--absorptivity-max ETA]] [--vapour-jet]
    scene.py run CASE [--np N]
    scene.py analyse CASE          (prints the table, writes CASE/summary.json)
    scene.py all CASE [--ci | --full] [--np N]
"""
import os

from meltdem.loader import load_module
from meltdem.scene import Scene


point_scene = load_module(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "pbf-point", "scene.py"))


SCENE = Scene(name="pbf-line", kind="coupled",
              title="Powder bed fusion, line melting (Fuchs2022 §4.5, tables 1–3)",
              ci_time="114 s wall", full_time="about 2.5 h on 2 cores; 21 min with --refine 1 (README)",
              build=lambda case, size: point_scene.main("line", __doc__, ["build", case, f"--{size}"]),
              analyse=lambda case: point_scene.main("line", __doc__, ["analyse", case]),
              summary=point_scene.pbf.summary)

if __name__ == "__main__":
    point_scene.main("line", __doc__)
