#!/usr/bin/python3
"""Three layers spread at the powder-spread CI size (examples/powder-spread --ci --layers 3): the
plate goes down by the gap after each stroke and the next heap is spread over the last layer.

Checks (definitions in python/meltdem/analysis/spread.py, layer_packing, and the scene's README):
  * every layer spread (spread.dump and spread_layer2/3.dump written);
  * the bed below the newest layer (the two older layers, passed over by the later strokes)
    against the LPBF powder-bed range 0.38-0.60 (Mahmoodkhani et al. 2019), where a single layer
    over a bare plate packs at 0.10-0.25 (dem.powder_spread.ci, XFAIL).
"""
import os
import tempfile

from meltdem.analysis.spread import layer_packing
from meltdem.scene import module
from meltdem.testing.report import check_absolute, report

TEST = "dem.powder_spread.layers"
LAYERS = 3
scene = module("powder-spread")
with tempfile.TemporaryDirectory() as d:
    case = os.path.join(d, "spread")
    scene.build(case, "ci", layers=LAYERS)
    scene.run(case)
    res = layer_packing(case)

ok = report(TEST, "layers spread (dumps written)", len(res), LAYERS, "exact", sorted(res) == list(range(1, LAYERS + 1)))
if LAYERS in res:
    bed, below = res[LAYERS]
    ok &= check_absolute(TEST, f"packing below the newest layer after {LAYERS} layers (LPBF beds 0.38-0.60, "
                         "Mahmoodkhani 2019)", below, 0.49, 0.11)
    print("INFO " + "; ".join(f"layer {k}: bed {b:.3f}, below the newest {w:.3f}" for k, (b, w) in sorted(res.items())))
raise SystemExit(0 if ok else 1)
