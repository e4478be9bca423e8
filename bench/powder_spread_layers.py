#!/usr/bin/python3
"""Powder-bed packing over several spread layers (examples/powder-spread --layers N).

A single layer spread over a bare plate packs at 0.10-0.25 (examples/powder-spread/README.md),
where powder-bed densities of laser PBF are 0.38-0.60 (Mahmoodkhani et al. 2019). A bed is made of
many layers: after each stroke the plate goes down by the gap and the next layer is spread over the
last one, filling its empty patches. This runs the scene's CI size with N layers for two seeds (two
at once) and measures, after each layer k, in the plate's inner part (2 d_max in from each end):

- the bed packing: grain volume over plate area x k gaps (from the cavity floor to the spreader's
  lowest point, as a build-box experiment weighs its bed);
- the packing below the newest layer: grain volume below the previous layers' top (y < 0) over
  plate area x (k - 1) gaps, the part of the bed a later layer no longer reaches.

    /usr/bin/python3 bench/powder_spread_layers.py [--layers 8] [--seeds 4242 1] [--work DIR]

Writes powder_spread_layers.md and .png next to this script; a WORK case that already holds its
last layer's dump is analysed again without running.
"""
import argparse
import concurrent.futures as cf
import os
import sys
import time

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "python"))
from meltdem.analysis.spread import layer_packing  # noqa: E402
from meltdem.scene import module  # noqa: E402

BED_RANGE = (0.38, 0.60)     # powder-bed densities of laser PBF, review by Mahmoodkhani et al. 2019


def one(case, layers, seed):
    """the CI case spread over LAYERS layers with SEED (as bench/powder_spread.py runs its cases), unless
    CASE already holds its last layer"""
    if not os.path.exists(os.path.join(case, f"spread_layer{layers}.dump")):
        t = time.time()
        scene = module("powder-spread")
        scene.build(case, "ci", layers=layers, seed=seed)
        scene.run(case)
        print(f"{case}: {time.time() - t:.0f} s", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--layers", type=int, default=8)
    ap.add_argument("--seeds", type=int, nargs="+", default=[4242, 1])
    ap.add_argument("--work", default="/tmp/meltdem-spread-layers")
    ap.add_argument("--out", default=HERE)
    a = ap.parse_args()
    start = time.time()
    cases = [(s, os.path.join(a.work, f"seed{s}")) for s in a.seeds]
    os.makedirs(a.work, exist_ok=True)
    with cf.ThreadPoolExecutor(2) as ex:         # two runs at once
        list(ex.map(lambda sc: one(sc[1], a.layers, sc[0]), cases))
    res = {s: layer_packing(c) for s, c in cases}
    ks = sorted(set.intersection(*[set(r) for r in res.values()]))

    def stat(k, j):
        v = np.array([res[s][k][j] for s in a.seeds])
        return float(v.mean()), float(v.max() - v.min()) / 2

    lines = ["# Powder-bed packing over spread layers (examples/powder-spread --layers)", "",
             f"`bench/powder_spread_layers.py`: the powder-spread CI size (blade, 2 d90 gap, 100 mm/s, "
             f"uniform 15-45 um, E = 1 GPa, friction 0.5, rolling friction 0.1) spread {a.layers} times, the plate "
             "lowered by the gap after each stroke (a build cavity; what the stroke carries into the pit and "
             "what is left on the dosing floor leaves the run, a new heap is dosed each time). Seeds "
             f"{', '.join(map(str, a.seeds))}: mean +- half their range. Plate's inner part (2 d_max in from "
             "each end).", "",
             "| layers k | bed packing (k gaps) | packing below the newest layer (k - 1 gaps) | " +
             " | ".join(f"seed {s}: bed / below" for s in a.seeds) + " |",
             "|---|---|---|" + "---|" * len(a.seeds)]
    for k in ks:
        m0, h0 = stat(k, 0)
        m1, h1 = stat(k, 1)
        below = f"{m1:.3f} +- {h1:.3f}" if k > 1 else "-"
        per = " | ".join(f"{res[s][k][0]:.3f} / " + (f"{res[s][k][1]:.3f}" if k > 1 else "-") for s in a.seeds)
        lines.append(f"| {k} | {m0:.3f} +- {h0:.3f} | {below} | {per} |")
    kl = ks[-1]
    m1, h1 = stat(kl, 1)
    inside = BED_RANGE[0] <= m1 <= BED_RANGE[1]
    lines += ["", f"Below the newest layer after {kl} layers: {m1:.3f} +- {h1:.3f} against the powder-bed densities "
              f"{BED_RANGE[0]}-{BED_RANGE[1]} of laser PBF (Mahmoodkhani et al. 2019): "
              f"{'inside' if inside else 'outside'} that range.", "",
              f"Command: `/usr/bin/python3 bench/powder_spread_layers.py {' '.join(sys.argv[1:])}`; run time "
              f"{(time.time() - start) / 60:.1f} min (cases reused where done)."]
    with open(os.path.join(a.out, "powder_spread_layers.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.axhspan(*BED_RANGE, color="0.9", label="powder-bed densities, laser PBF")
    for j, (label, mk) in enumerate([("bed (k gaps)", "o-"), ("below the newest layer", "s--")]):
        kk = [k for k in ks if j == 0 or k > 1]
        mh = [stat(k, j) for k in kk]
        ax.errorbar(kk, [m for m, _ in mh], yerr=[h for _, h in mh], fmt=mk, capsize=3, label=label)
    ax.set_xlabel("layers spread k")
    ax.set_ylabel("packing fraction")
    ax.set_ylim(0, 0.7)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("powder-spread CI, blade at 2 d90: packing over layers", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "powder_spread_layers.png"), dpi=110)


if __name__ == "__main__":
    main()
