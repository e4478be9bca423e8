#!/usr/bin/env python3
"""foam.amr_laser: the laser refinement criterion marks the beam's footprint on the metal now and
along its path ahead, as far as lookAhead (fluid steps) or lookAheadTime (seconds) reach.

A steel slab (z < 0) under gas, 400 x 100 x 60 um of 20 um cells, a beam of radius R = 15 um
(radii 1, so the footprint is R) at x0 = 60 um on the middle row of cells, moving +x at 1 m/s;
refinement { maxLevel 1; refineInterval 1; nBufferLayers 0; laser {...} }, two fluid steps at a
fixed step dt (the mesh is first updated before the second, at t = dt). The refined cells'
parents must be exactly the top-metal cells of that row whose centre lies within R of the beam's
path from now to now + reach (reach = lookAhead dt or lookAheadTime):
  - every cell within 0.9 R of the path is refined (the path is sampled every R/2), none farther
    than R from it (or from the path's row), and none outside the top metal layer and the gas
    cells over it (refinement keeps equal levels across the metal/gas interface);
  - the furthest refined centre vs the path's end + R - h/2 (the furthest centre within R lies in
    [end + R - h, end + R]), tolerance h/2.
Cases: lookAhead 100 at dt 1 us (100 um ahead); the same count at dt 0.5 us reaches half as far
(steps are not time); lookAhead 1 with lookAheadTime 1e-4 s at dt 0.5 us reaches as far as the
first (what a Courant-limited run needs); lookAhead 0 marks the spot only. A negative
lookAheadTime stops before the first step with the entry named.
usage: amr_laser.py [--keep]
"""
import os
import sys
import tempfile

import numpy as np

from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute

TEST = "foam.amr_laser"
H = 20e-6
NX, NY, NZ = 20, 5, 3
Z0 = -40e-6
R, X0, YB, V = 15e-6, 60e-6, 50e-6, 1.0
TOP_METAL_Z = -10e-6


def build(case, dt, entries):
    fc.dictionary(case, "system/blockMeshDict", f"""convertToMeters 1;
vertices ( (0 0 {Z0!r}) ({NX * H!r} 0 {Z0!r}) ({NX * H!r} {NY * H!r} {Z0!r}) (0 {NY * H!r} {Z0!r})
           (0 0 {Z0 + NZ * H!r}) ({NX * H!r} 0 {Z0 + NZ * H!r}) ({NX * H!r} {NY * H!r} {Z0 + NZ * H!r})
           (0 {NY * H!r} {Z0 + NZ * H!r}) );
blocks ( hex (0 1 2 3 4 5 6 7) ({NX} {NY} {NZ}) simpleGrading (1 1 1) );
edges ();
boundary ( walls {{ type wall; faces ((0 1 5 4) (4 5 6 7) (0 4 7 3) (1 2 6 5) (3 7 6 2) (0 3 2 1)); }} );
mergePatchPairs ();
""")
    n = NX * NY * NZ
    zc = Z0 + (np.arange(NZ) + 0.5) * H
    alpha = np.repeat((zc < 0).astype(float), NX * NY)
    zg = "type zeroGradient;"
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha, {"walls": zg})
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(n, 300.0), {"walls": zg})
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((n, 3)), {"walls": "type noSlip;"}, vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(n), {"walls": zg})
    fc.transport(case, 7430.0, 6e-3 / 7430.0, 7.43, 6e-4 / 7.43, 1.8)
    fc.gravity(case)
    extra = f"""metal {{ Tsolidus 1695; Tliquidus 1705; L 2.7e5; cp 965; k 35.95; }}
gas {{ cp 10; k 0.026; }}
laser
{{
    power        1;
    absorptivity 0.5;
    radius       {R!r};
    direction    (0 0 -1);
    position     ({X0!r} {YB!r} {Z0 + NZ * H!r});
    velocity     ({V!r} 0 0);
    tStop        2e-4;
}}
{fc.refinement_dict(1, 1, [("laser", f"radii 1; {entries}")], buffer_layers=0)}"""
    fc.meltdem_properties(case, physics={"flow": "off", "energy": "on", "surfaceTension": "off", "laser": "on"},
                          extra=extra)
    fc.control_dict(case, "meltdemFoam", 2 * dt, dt, 2 * dt, adjustable=False, extra=fc.CELL_GEOMETRY_FUNCTIONS)
    fc.fv_schemes(case)
    fc.fv_solution(case, p_ref_cell=0)
    fc.run(["blockMesh"], case, "log.blockMesh")


def refined_parents(case):
    """(x, y, z) centres of the coarse cells that were split, from the last time's cell centres."""
    last = fc.time_dirs(case)[-1]
    C = np.asarray(fc.read_internal(os.path.join(case, last, "C"))).reshape(-1, 3)
    # a coarse centre sits at (k + 1/2) h, a child's a quarter cell off it
    off = np.abs((C / H - 0.5) - np.round(C / H - 0.5)) > 0.1
    child = np.any(off, axis=1)
    parents = (np.floor(C[child] / H) + 0.5) * H
    parents[:, 2] = (np.floor((C[child, 2] - Z0) / H) + 0.5) * H + Z0
    return np.unique(np.round(parents / 1e-9) * 1e-9, axis=0), int(len(C))


def path_distance(x, y, a, b):
    """horizontal distance of (x, y) from the beam path x in [a, b] on y = YB"""
    return np.hypot(np.maximum(np.maximum(a - x, x - b), 0.0), y - YB)


def check_case(label, case, dt, reach):
    ok = True
    parents, ncells = refined_parents(case)
    print(f"{label}: {len(parents)} cells split, {ncells} cells; reach {reach * 1e6:g} um")
    # the mesh is updated before the second step, at t = dt
    start, end = X0 + V * dt, X0 + V * (dt + reach)
    xc = (np.arange(NX) + 0.5) * H
    needed = xc[path_distance(xc, YB, start, end) <= 0.9 * R]
    got = {round(p[0] / 1e-9) for p in parents if abs(p[1] - YB) < 1e-9 and abs(p[2] - TOP_METAL_Z) < 1e-9}
    missing = sum(round(x / 1e-9) not in got for x in needed)
    off_layer = (np.abs(parents[:, 2] - TOP_METAL_Z) > 1e-9) & (np.abs(parents[:, 2] - TOP_METAL_Z - H) > 1e-9)
    far = path_distance(parents[:, 0], parents[:, 1], start, end) > R * (1 + 1e-9)
    stray = int(np.sum(far | off_layer))
    ok &= check_absolute(TEST, f"{label}: top-metal cells of the beam's row within 0.9 R of its path not refined "
                         f"(of {len(needed)})", missing, 0, 0)
    ok &= check_absolute(TEST, f"{label}: refined cells farther than R from the path or off the top metal layer "
                         "(and the gas over it)",
                         stray, 0, 0)
    furthest = float(np.max(parents[:, 0])) if len(parents) else float("nan")
    ok &= check_absolute(TEST, f"{label}: furthest refined centre [m] vs path end + R - h/2", furthest,
                         end + R - H / 2, H / 2)
    return ok


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-amr-laser-")
    ok = True
    cases = [("lookAhead 100, dt 1 us", 1e-6, "lookAhead 100;", 100e-6),
             ("lookAhead 100, dt 0.5 us (steps, not time: half as far)", 0.5e-6, "lookAhead 100;", 50e-6),
             ("lookAhead 1 + lookAheadTime 1e-4 s, dt 0.5 us (as far as 100 steps of 1 us)", 0.5e-6,
              "lookAhead 1; lookAheadTime 1e-4;", 100e-6),
             ("no look-ahead (the spot only)", 1e-6, "", 0.0)]
    for i, (label, dt, entries, reach) in enumerate(cases):
        case = os.path.join(work, f"case{i}")
        build(case, dt, entries)
        fc.run([fc.solver()], case, "log.solver")
        ok &= check_case(label, case, dt, reach)
    # a negative look-ahead time: FatalIOError naming the entry, before the first step
    case = os.path.join(work, "negative")
    build(case, 1e-6, "lookAheadTime -1e-6;")
    rc = fc.run([fc.solver()], case, "log.solver", check=False)
    log = open(os.path.join(case, "log.solver"), errors="replace").read()
    said = rc != 0 and "lookAheadTime" in log and "FOAM FATAL IO ERROR" in log and "\nTime = " not in log
    ok &= check_absolute(TEST, "negative lookAheadTime stops before the first step naming it (1 = yes)",
                         float(said), 1.0, 0)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
