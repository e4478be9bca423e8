#!/usr/bin/env python3
"""CI variant of examples/ded-stream (Fuchs2022 §4.4): five 16 um steel particles at
10 m/s along a 45 degree axis into the melt pool of a 312 W laser (d_w = 140 um) on a 20 um
substrate; meltdemFoam + LAMMPS coupled, 10 um cells (1.6 per particle diameter, overlap
model). Two variants: laser on throughout (to 0.020 ms) and laser off at 0.012 ms (to 0.026 ms).

Checks (measured | reference | tolerance):
- laser on: pool diameter at 0.018 ms vs Fuchs2022's ~130 um (15 %);
- arrival of the first particle at the substrate vs straight-line kinematics (5 %) and vs
  Fuchs2022's ~0.006 ms (20 %); it is deflected by the solid substrate (Fuchs2022: "a deflection ... as
  it hits the solid substrate at the bottom of the melt pool"): rebound upwards;
- absorbed laser power: continuum + particles = eta P on every lit step (1e-9);
- switch-off (to Fuchs2022's 0.026 ms): no laser power after 0.012 ms (exact), the pool cools,
  shrinks and is solid at 0.026 ms (Fuchs2022's figure), the particle reaching the pool after the
  switch-off (particle 4) is still solid and bounces off the solid metal, and the last one
  (particle 5) bounces off the solidified metal and flies above the substrate, unmolten, at
  0.026 ms (Fuchs2022);
- ledger: continuum mass/energy per-step errors (meltdem.case.coupled.check_balances) and the system
  (particles + continuum) enthalpy balance.
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem import scene as scenes
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_most, check_relative

SRC = paths.source_dir()

scene = scenes.module("ded-stream")

TEST = "scenes.ded-stream"
SCENE = os.path.join(SRC, "examples", "ded-stream", "scene.py")


def run_variant(work, name, extra, reuse=False):
    """Build and run a CI variant (reuse: only analyse the case a kept earlier run left)."""
    case = os.path.join(work, name)
    if not reuse:
        subprocess.run(["/usr/bin/python3", SCENE, "build", case, "--ci"] + extra, check=True)
        subprocess.run(["/usr/bin/python3", SCENE, "run", case], check=True)
    return case, scene.analyse(case)


def laser_checks(case, s, label, test=TEST):
    """eta P on lit steps (reported under test). A particle that melts away during a step stops
    absorbing the light the shadow gave it, and it still shadows (flagged, deleted at the next DEM
    step) in the step after: those steps are checked separately."""
    t, dt, cont, part = scene.laser_budget(case)
    p = cc.particles_csv(case)[:len(t)]
    lit = (t - dt >= -1e-18) & ((t <= scene.T_OFF + 1e-15) if s["switch_off"] else True)
    melt = p["mass_melted"] > 0
    around = melt | np.concatenate(([False], melt[:-1]))
    err = np.abs(cont + part - scene.ETA * scene.P_LASER) / (scene.ETA * scene.P_LASER)
    ok = check_at_most(test, f"{label}: worst |continuum + particles - eta P| / eta P on lit steps without a "
                       f"particle melting away ({int(np.sum(lit & ~around))} steps)",
                       float(np.max(err[lit & ~around])), 1e-9)
    if np.any(lit & around):
        ok &= check_at_most(test, f"{label}: the same on the {int(np.sum(lit & around))} steps where a particle "
                            "melted away (or the step after)", float(np.max(err[lit & around])), 1e-9)
    # (closed because the coupling hands a melting particle's unabsorbed light to its melt and
    # molten particles cast no shadow)
    return ok, lit, t, dt, cont, part


def main():
    keep = "--keep" in sys.argv
    # --reuse DIR: re-check the cases of a run kept with --keep (no simulation)
    reuse = sys.argv[sys.argv.index("--reuse") + 1] if "--reuse" in sys.argv else None
    work = reuse or tempfile.mkdtemp(prefix="meltdem-ded-stream-")
    keep = keep or bool(reuse)
    ok = True

    # ---- laser on
    case, s = run_variant(work, "laser_on", [], reuse)
    d018 = s["pool_diameter_at_0.018ms_um"]
    ok &= check_relative(TEST, "laser on: melt-pool diameter at 0.018 ms [um] (10 um cells) vs paper ~130 um",
                         d018, scene.PAPER["pool_diameter_um"], 0.15, miss_within=0.35,
                         xfail="10 um cells put the absorbed heat into a 10 um top layer: the surface runs "
                               "cooler and the pool is smaller (the 5 um full variant: see README)")
    p1 = s["particles"][0]
    ok &= check_relative(TEST, "laser on: particle 1 arrival at the substrate [ms] vs straight-line kinematics "
                         "(h - R) sqrt(2) / 10 m/s", p1.get("arrival_ms") or np.inf, p1["kinematic_arrival_ms"], 0.05)
    arr = [(e["arrival_ms"], e["kinematic_arrival_ms"]) for e in s["particles"] if e.get("arrival_ms")]
    worst = max((abs(a / k - 1) for a, k in arr), default=np.inf)
    ok &= check_at_most(TEST, f"laser on: worst relative deviation of the {len(arr)} particle arrivals (reaching, "
                        "deflected at or melting within 5 um of the substrate top) from the kinematics", worst, 0.05)
    ok &= check_relative(TEST, "laser on: particle 1 arrival [ms] vs paper (enters the pool at ~0.006 ms)",
                         p1.get("arrival_ms") or np.inf, scene.PAPER["first_enters_pool_ms"], 0.20, miss_within=0.3,
                         xfail="the paper's stated geometry gives 0.0045 ms by kinematics; its 0.006 ms is "
                               "read off figures")
    ok &= check_at_most(TEST, "laser on: particle 1 molten fraction when it reaches the substrate "
                        "(paper: enters the pool still solid)", molten_at_arrival(case, 1), 0.5)
    tr = scene.read_tracks(case)[1]
    ok &= check_absolute(TEST, "laser on: particle 1 deflected upwards by the solid substrate (1 = yes)",
                         float(tr[:, 6].max() > 0), 1.0, 0)
    lok, *_ = laser_checks(case, s, "laser on")
    ok &= lok
    rows = cc.ledger(case)
    ok &= cc.check_balances(TEST, rows)
    ok &= check_at_most(TEST, "laser on: worst per-step system enthalpy error (particles + continuum)",
                        s["worst_enthalpy_system_error"], 1e-6)

    # ---- laser off at 0.012 ms, to 0.026 ms
    case, s = run_variant(work, "switch_off", ["--switch-off"], reuse)
    lok, lit, t, dt, cont, part = laser_checks(case, s, "switch-off")
    ok &= lok
    dark = t - dt >= scene.T_OFF - 1e-15
    ok &= check_absolute(TEST, "switch-off: largest absorbed laser power after 0.012 ms [W]",
                         float(np.max(cont[dark] + part[dark])), 0.0, 0)
    times = np.array(s["pool_time_ms"])
    diam = np.array(s["pool_diameter_um"])
    peak = np.array(s["peak_T_K"])
    i12, iend = int(np.argmin(np.abs(times - 0.012))), len(times) - 1
    ok &= check_at_most(TEST, "switch-off: peak temperature at 0.026 ms / at 0.012 ms (the pool cools: < 1)",
                        peak[iend] / peak[i12], 0.9)
    ok &= check_at_most(TEST, "switch-off: pool diameter at 0.026 ms / at 0.012 ms (the pool shrinks: <= 1)",
                        diam[iend] / diam[i12], 1.0)
    tr4 = scene.read_tracks(case).get(4, np.zeros((1, 10)))
    ok &= check_absolute(TEST, "switch-off: particle 4 (reaching the pool after the switch-off) bounces off the "
                         "solid metal (1 = yes; paper: the particle arriving after the switch-off bounces off)",
                         float(tr4[:, 6].max() > 0), 1.0, 0)
    ok &= check_at_most(TEST, "switch-off: particle 4 molten fraction when it reaches the substrate "
                        "(paper: partially molten)", molten_at_arrival(case, 4), 0.5)
    ok &= check_relative(TEST, "switch-off: simulated time [ms] vs the paper's 0.026 ms", float(times[-1]), 0.026,
                         0.02)
    ok &= check_at_most(TEST, "switch-off: pool diameter at 0.026 ms [um] (paper: solidified; at most one cell)",
                        float(diam[iend]), 10.0)
    last = {e["id"]: e for e in s["particles"]}.get(5, {})
    ok &= check_absolute(TEST, "switch-off: particle 5 (the last) bounced off and is above the substrate at the end "
                         "(1 = yes; paper: it bounces off and flies above the substrate at 0.026 ms)",
                         float(last.get("fate") == "bounced, above the substrate"), 1.0, 0)
    ok &= check_at_most(TEST, "switch-off: particle 5 molten fraction at the end (paper: not melted)",
                        float(last.get("molten_fraction", 1.0)), 0.5)
    rows = cc.ledger(case)
    ok &= cc.check_balances(TEST, rows)
    ok &= check_at_most(TEST, "switch-off: worst per-step system enthalpy error (particles + continuum)",
                        s["worst_enthalpy_system_error"], 1e-6)
    with open(os.path.join(work, "summary.json"), "w") as f:
        json.dump(s, f, indent=1)
    return fc.finish(ok, work, keep)


def molten_at_arrival(case, pid):
    """Molten fraction of particle pid at its arrival (first dump row at the substrate level or
    deflected)."""
    s = json.load(open(os.path.join(case, "summary.json")))
    e = s["particles"][pid - 1]
    tr = scene.read_tracks(case).get(pid)
    if tr is None or e.get("arrival_ms") is None:
        return 1.0   # never arrived: counts as a miss of the 'solid on arrival' checks
    i = np.searchsorted(tr[:, 0], e["arrival_ms"] * 1e-3 - 1e-12)
    r = tr[min(i, len(tr) - 1)]
    return float(max(r[9], 1 - (r[7] / (scene.D_P / 2)) ** 3))


if __name__ == "__main__":
    sys.exit(main())
