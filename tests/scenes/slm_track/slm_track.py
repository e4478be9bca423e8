#!/usr/bin/env python3
"""scenes.slm-track: CI variant of examples/slm-track (Codina2019 §4.2.2, tables 4.5/4.6).

Pours the 0.3 x 0.3 mm powder bed (examples/powder-bed, closed box, Codina2019 table 4.3), then
scans it coupled (meltdemFoam + LAMMPS): 100 W, 0.1 mm Gaussian spot, 0.5 m/s, absorptivity
0.5, SS304 grains 15-45 um with alpha 0.5 (particles and walls), on a solid SS304 substrate,
30 um cells, 0.2 mm of track, surface tension and Marangoni on (the scene's default). Checks:
- absorbed laser power (continuum + particles) = eta P in every fluid step of the scan (1e-9)
  and the absorbed energy = eta P t_scan (1e-9);
- particle ledger balances: worst per-step continuum mass, energy and momentum errors
  (meltdem.case.coupled; momentum with the walls' forces, gravity, the physics terms and the surface
  force booked: the PISO velocity correction is not exactly conservative, 5e-3 of the largest
  momentum);
- track width vs the conduction estimate for the same eta P and v on bare SS304 (Gaussian
  surface source of the 0.1 mm spot, quasi-steady; 30 %: the powder and the latent heat take
  part of the heat, and the cells are 30 um);
- speed of the ejected particles vs Codina2019's ~1 m/s (50 %);
- no DEM update reached the integrator's 10 m/s speed cap (pop-corn watch);
and reports the melted depth, bead height, particle counts and the denudation width.
"""
import os
import sys
import tempfile

from meltdem import paths
from meltdem import scene as scenes
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.testing.report import check_at_most, check_relative, report_info

SRC = paths.source_dir()

scene = scenes.module("slm-track")

TEST = "scenes.slm-track"
# measured on five poured beds of this CI case (the 30 % bound is 89 um)
XFAIL_BED_WIDTH = ("bed realization: 85.5 um on the CI bed without surface forces (seed 4242, poured since fix "
                   "powder/dt holds its speed for two contact times, 93008a3), 97.1 um on the bed poured before, "
                   "98.3/92.6/93.4 um on seeds 1/2/3: the bound lies within the bed-to-bed spread; with surface "
                   "tension and Marangoni (the default since 2026-12-04) 70.6 um: the molten grains on top contract "
                   "into a narrower bead while the melt on the substrate plane keeps its width (80.7 vs 80.1 um)")


def run_exact(test, case, **options):
    """Build the CI case (scene.build options), run and analyse it, and check what is exact: the
    absorbed laser power and energy and the ledger's per-step balances. Returns (summary, ok)."""
    bed = os.environ.get("SLM_TRACK_BED")  # reuse a poured bed (development)
    scene.build(case, "ci", bed=bed, **options)
    scene.run(case)
    s = scene.analyse(case)
    ok = check_at_most(test, "worst |absorbed laser power (continuum + particles) - eta P| / eta P, per step",
                       s["laser_power_worst_rel_error"], 1e-9)
    ok &= check_relative(test, "absorbed laser energy over the scan [J] (eta P t_scan)",
                         s["laser_energy_absorbed_J"], s["laser_energy_eta_P_t_J"], 1e-9)
    ok &= cc.check_balances(test, cc.ledger(case), mass=1e-12, energy=1e-6, momentum=5e-3)
    return s, ok


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-slm-track-")
    case = os.path.join(work, "case")
    s, ok = run_exact(TEST, case)
    ok &= check_relative(TEST, "melted track width [m] vs conduction estimate (Gaussian source, bare SS304)",
                         s["track_width_m"], s["gaussian_width_m"], 0.3, xfail=XFAIL_BED_WIDTH,
                         miss_within=0.6)
    ok &= check_relative(TEST, "median speed of the ejected particles [m/s] vs thesis ~1 m/s",
                         s["ejection_speed_median_m_per_s"], 1.0, 0.5,
                         xfail="no vapour recoil or gas jet in the default run (--vapour-jet has them: "
                         "scenes.slm-track.vapour-jet); grains move only by contacts and the melt")
    ok &= check_at_most(TEST, "DEM updates capped by the 10 m/s speed limit (fix nve/limit; pop-corn watch)",
                        s["dem_updates_speed_limited"], 0)
    ok &= report_info(TEST, "particles ejected (centre above the bed top, moving up) (info)", s["particles_ejected"])
    ok &= report_info(TEST, "denudation width [m] (info, no thesis number)", s["denudation_width_m"])
    ok &= report_info(TEST, "melted depth below the substrate top [m] (info)", s["track_depth_m"])
    ok &= report_info(TEST, "bead height above the substrate top [m] (info; thesis expectation 30 um)",
                      s["bead_height_m"], 30e-6)
    print(f"{TEST}: wall time of the coupled run {s['wall_s']:.0f} s")
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
