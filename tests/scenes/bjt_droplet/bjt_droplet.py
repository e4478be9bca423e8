#!/usr/bin/env python3
"""CI-sized binder-jetting scene (Fuchs2022 §4.2; examples/bjt-droplet/scene.py --ci):
an 80 um binder droplet (table 4) at 1, 10 and 50 m/s into a DEM-settled log-normal bed of 195
steel particles (16-32 um) on a 200 x 200 um floor, 10 um cells, isothermal coupling (drag and
buoyancy only), to t = 0.1 / 0.05 / 0.02 ms; plus the droplet's fall without particles.

Fuchs2022 gives no numbers, only what it saw; checked here:
  - physical references: binder volume conserved (round-off), the ledger's per-step continuum
    mass balance (Codina2019 eq. 2.20), no heat exchanged (isothermal), the impulse the particles
    took equals what the continuum got (action = reaction), no particle lost, and the droplet's
    velocity before contact against its kinematics (v0 + g t with the gas drag of an isolated
    sphere);
  - Fuchs2022's ordering as measurable statements: footprint(10) > footprint(1) (at Fuchs2022's
    times and the largest over the run), max particle speed(50) > (10) > (1),
    penetration(10) < penetration(1), displaced(50) > displaced(10) > displaced(1), booked XFAIL
    where this unresolved-particle model does not reproduce them (see the scene's README).
"""
import os
import shutil
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem import scene as scenes
from meltdem.case import coupled as cc
from meltdem.testing.report import check_absolute, check_at_least, check_at_most, check_relative

src = paths.source_dir()

scene = scenes.module("bjt-droplet")

TEST = "scenes.bjt-droplet"
UNRESOLVED = ("unresolved particles: the bed only drags on the binder (point drag), it cannot block it; the "
              "binder reaches the substrate at every speed")


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-bjt-")
    ok = True
    # the droplet's fall, VOF only (its bottom is 60 um above the substrate: contact at 6 us)
    fall = os.path.join(work, "fall")
    scene.build(fall, "ci", speeds=[10.0], particles="off", end=[3e-6])
    scene.run(fall)
    rf = scene.analyse(fall)
    ok &= check_relative(TEST, "droplet velocity before contact, 10 m/s, no particles [m/s] vs v0 + g t "
                         "with isolated-sphere gas drag", rf["v10_fall_velocity_m_s"],
                         rf["v10_fall_velocity_reference_m_s"], 0.05)

    case = os.path.join(work, "ci")
    scene.build(case, "ci")
    scene.run(case)
    r = scene.analyse(case)
    p = scene.VARIANTS["ci"]
    dx_um = p["dx"] * 1e6
    for v in p["speeds"]:
        k = scene.speed_dir(v)
        c = os.path.join(case, k)
        ok &= check_at_most(TEST, f"{k}: binder volume, |relative change| at the end",
                            abs(r[f"{k}_binder_volume_rel_error"]), 1e-10)
        ok &= check_absolute(TEST, f"{k}: particles at the end (none lost)", r[f"{k}_particles"], p["N"], 0)
        rows = cc.ledger(c)
        ok &= cc.check_balances(TEST + "." + k, rows, mass=1e-13, energy=1e-13)
        parts = cc.particles_csv(c)
        ok &= check_absolute(TEST, f"{k}: heat absorbed by the particles [J] (isothermal)",
                             float(np.sum(np.abs(parts["heat_absorbed"]))), 0.0, 0.0)
        ok &= check_absolute(TEST, f"{k}: enthalpy exchanged with the continuum [J] (isothermal)",
                             float(np.sum(np.abs(rows["enthalpy_exchange"]))), 0.0, 0.0)
        drag = float(np.sum(parts["drag_impulse_z"]))
        ok &= check_at_most(TEST, f"{k}: |continuum impulse + particle drag impulse| / |drag impulse| (z)",
                            abs(float(np.sum(rows["mom_z_exchange"])) + drag) / max(abs(drag), 1e-300), 1e-12)
        ok &= check_at_least(TEST, f"{k}: impulse the bed took from the binder, -z [kg m/s] (> 0: the droplet "
                             "pushes the bed)", -drag, 1e-30)
    # Fuchs2022's ordering (§4.2), at its times (0.1 ms for 1 m/s, 0.05 ms for 10 m/s)
    ok &= check_at_least(TEST, "footprint radius at the paper's times, 10 m/s minus 1 m/s [um] (paper: spread "
                         "wider; bound dx/2)", r["v10_footprint_radius_um"] - r["v1_footprint_radius_um"], dx_um / 2,
                         xfail="the 10 m/s droplet spreads, then recoils (surface tension): at 0.05 ms its footprint "
                         "is back at or below the 1 m/s one")
    ok &= check_at_least(TEST, "largest footprint radius over the run, 10 m/s minus 1 m/s [um] (bound dx/2)",
                         r["v10_footprint_radius_largest_um"] - r["v1_footprint_radius_largest_um"], dx_um / 2)
    ok &= check_at_least(TEST, "penetration 1 m/s minus 10 m/s [um] (paper: less penetration at 10; bound dx)",
                         r["v1_penetration_um"] - r["v10_penetration_um"], dx_um, xfail=UNRESOLVED)
    ok &= check_at_least(TEST, "displaced particles 10 m/s minus 1 m/s (paper: more powder dynamics)",
                         r["v10_displaced_particles"] - r["v1_displaced_particles"], 1,
                         xfail="drag on a bed held by its contacts and the substrate moves no particle a radius "
                         "at 1 or 10 m/s")
    ok &= check_at_least(TEST, "displaced particles 50 m/s minus 10 m/s (paper: splash, ejects powder)",
                         r["v50_displaced_particles"] - r["v10_displaced_particles"], 1)
    ok &= check_at_least(TEST, "largest particle speed 10 m/s minus 1 m/s [m/s]",
                         r["v10_max_particle_speed_m_s"] - r["v1_max_particle_speed_m_s"], 1e-3)
    ok &= check_at_least(TEST, "largest particle speed 50 m/s minus 10 m/s [m/s]",
                         r["v50_max_particle_speed_m_s"] - r["v10_max_particle_speed_m_s"], 1e-3)
    if ok and not keep:
        shutil.rmtree(work)
    else:
        print("cases kept in", work)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
