#!/usr/bin/python3
"""CI-sized powder spreading (examples/powder-spread --ci): a blade at 100 mm/s and 2 d90 above a
bare plate spreads a 450-grain heap (15-45 um steel, E = 1 GPa, mu 0.5, rolling friction 0.1).

Checks (definitions in python/meltdem/analysis/spread.py and the scene's README):
  * every grain booked: dosing area + plate + carried past the plate = grains in the box =
    requested (the run stops on a lost grain);
  * the heap's mean diameter against the uniform 15-45 um distribution's 30 um, within three
    standard errors (8.66 um / sqrt(N));
  * effective layer packing V / (A gap) against the LPBF bed range 0.38-0.60 (Mahmoodkhani et
    al. 2019), XFAIL: a blade at 2 d90 leaves empty patches (Nan et al. 2018), see the README
    (a bed of several layers: dem.powder_spread.layers);
  * the layer exported for the melt scenes' --bed: every grain wholly inside the bed's box.
"""
import math
import os
import tempfile

from meltdem.analysis.spread import layer_bed
from meltdem.io import dumps
from meltdem.scene import module
from meltdem.testing.report import check_absolute, report

TEST = "dem.powder_spread.ci"
scene = module("powder-spread")
with tempfile.TemporaryDirectory() as d:
    case = os.path.join(d, "spread")
    scene.build(case, "ci")
    scene.run(case)
    s = scene.analyse(case)
    n = int(scene.VARIANTS["ci"]["N"])
    lx = 3e-4
    nb = layer_bed(case, lx, os.path.join(d, "layer.dump"))
    b = dumps.columns(dumps.read_frames(os.path.join(d, "layer.dump"))[-1])
    lz = float(scene.VARIANTS["ci"]["Lz"])

ok = True
booked = s["grains_behind_plate"] + s["grains_on_plate"] + s["grains_carried_past_plate"]
ok &= check_absolute(TEST, "grains booked: dosing area + plate + carried past (requested N)", booked, n, 0)
ok &= check_absolute(TEST, "grains in the box at the end (requested N)", s["grains"], n, 0)
ok &= check_absolute(TEST, "heap mean diameter [m] (uniform 15-45 um: 30 um, 3 standard errors)",
                     s["mean_diameter_heap_m"], 30e-6, 3 * (30e-6 / math.sqrt(12)) / math.sqrt(n))
ok &= check_absolute(TEST, "effective layer packing V/(A gap) (LPBF beds 0.38-0.60, Mahmoodkhani 2019)",
                     s["packing_fraction"], 0.49, 0.11, miss_within=0.4,
                     xfail="a blade at 2 d90 over a bare plate leaves empty patches (Nan et al. 2018): 0.10-0.25 "
                           "over the cases and seeds of bench/powder_spread.md; the bed under later layers packs "
                           "in range (dem.powder_spread.layers, bench/powder_spread_layers.md)")
out = max(float(max(-(b["x"] - b["radius"]).min(), (b["x"] + b["radius"]).max() - lx)),
          float(max(-(b["z"] - b["radius"]).min(), (b["z"] + b["radius"]).max() - lz)), 0.0)
ok &= report(TEST, f"layer bed ({lx * 1e3:g} x {lz * 1e3:g} mm): grains, largest reach outside the box [m]",
             f"{nb}, {out:g}", "> 0, 0", "exact", nb > 0 and out <= 1e-12)
print(f"INFO packing {s['packing_fraction']:.3f}, thickness {s['thickness_m'] * 1e6:.1f} um, Sq "
      f"{s['roughness_Sq_m'] * 1e6:.1f} um, uncovered {s['uncovered_fraction']:.2f}, mean d layer "
      f"{s['mean_diameter_layer_m'] * 1e6:.1f} um, last/first third {s['segregation_last_over_first_third']:.3f}, "
      f"carried past the plate {s['mass_fraction_carried_past_plate']:.2f} of the mass")
raise SystemExit(0 if ok else 1)
