#!/usr/bin/python3
"""Powder spreading, DEM only: a blade or a counter-rotating roller spreads a dosed heap over a
build plate (and over a rough previous layer); the scene interface of examples/.

    scene.py build CASE [--ci | --full] [--spreader blade|roller] [--speed V] [--gap G]
                        [--base plate|rough] [--gamma W] [--mu M] [--mur R] [--E E] [--seed S]
                        [--layers N]
    scene.py run CASE [--np N]       meltdem-lmp -in in.powder-spread with the case's variables
    scene.py analyse CASE            layer packing, thickness profile, roughness, segregation,
                                     grains carried past the plate -> CASE/summary.json
    scene.py all CASE [...]

--ci (what tests/dem/powder_spread runs): 0.15 mm wide, 0.4 mm plate, 450 grains (~1 min);
--full (default): 0.4 mm wide, 1.2 mm plate, 3000 grains. README.md gives the definitions, the
defaults and the published values they are compared with.
"""
import json
import math
import os
import shutil

from meltdem.analysis.spread import layer_bed, layer_packing, spread_stats
from meltdem.case.dem import run_actions, run_input, scene_parser, write_case
from meltdem.scene import Scene

HERE = os.path.dirname(os.path.abspath(__file__))
D90 = 42e-6                      # diameters uniform in 15-45 um: d90 = 15 + 0.9 * 30 um

VARIANTS = {
    "ci": {"Lz": "1.5e-4", "Lplate": "4e-4", "Lheap": "4e-4", "N": "450", "every": "5000"},
    "full": {"Lz": "4e-4", "Lplate": "1.2e-3", "Lheap": "1e-3", "N": "3000", "every": "10000"},
}
OPTIONS = {"spreader": "spreader", "speed": "V", "gap": "gap", "base": "base", "gamma": "gamma", "mu": "mu",
           "mur": "mur", "E": "E", "seed": "seed", "layers": "layers"}


def build(case, variant, **opts):
    v = dict(VARIANTS[variant])
    v.update({name: str(opts[k]) for k, name in OPTIONS.items() if opts.get(k) is not None})
    write_case(case, "powder-spread", variant, os.path.join(HERE, "in.powder-spread"), v)
    for part in ("in.powder-spread-stroke", "in.powder-spread-layer"):   # the stroke; once per layer > 1
        shutil.copy(os.path.join(HERE, part), case)


def run(case, np_=1):
    run_input(case, "in.powder-spread", np_)


def analyse(case):
    s = spread_stats(case)                      # the first layer
    layers = layer_packing(case)
    if len(layers) > 1:                         # --layers N: the bed after each layer
        s["layers"] = [{"layer": k, "bed_packing": bed, "packing_below_newest_layer": None if k == 1 else below}
                       for k, (bed, below) in sorted(layers.items())]
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(s, f, indent=1)
    print(f"powder-spread ({s['spreader']}, {s['speed_m_per_s'] * 1e3:.0f} mm/s, gap {s['gap_m'] * 1e6:.0f} um = "
          f"{s['gap_m'] / D90:.1f} d90, base {s['base']}): packing {s['packing_fraction']:.3f}, thickness "
          f"{s['thickness_m'] * 1e6:.1f} um, Sq {s['roughness_Sq_m'] * 1e6:.1f} um, uncovered "
          f"{s['uncovered_fraction']:.2f}, mean d layer/heap {s['mean_diameter_layer_m'] * 1e6:.1f}/"
          f"{s['mean_diameter_heap_m'] * 1e6:.1f} um, last/first third {s['segregation_last_over_first_third']:.3f}, "
          f"carried past the plate {s['grains_carried_past_plate']} grains "
          f"({s['mass_fraction_carried_past_plate']:.2f} of the mass)")
    for row in s.get("layers", [])[1:]:
        print(f"after layer {row['layer']}: bed packing {row['bed_packing']:.3f}, below the newest layer "
              f"{row['packing_below_newest_layer']:.3f}")
    return s


def uniform_mean_volume(dlo, dhi):
    """mean sphere volume of diameters uniform in [dlo, dhi]"""
    return math.pi / 6 * (dhi ** 4 - dlo ** 4) / (4 * (dhi - dlo))


def spread_bed(work, lx, lz, dlo=15e-6, dhi=45e-6, diam=None, mean_volume=None, **opts):
    """A spread layer as the bed of a melt scene (slm-track --bed spread, pbf-point/pbf-line
    --bed-process spread): this scene's CI run in WORK, lz wide, with a plate 4 d_max longer than
    lx and a heap of the CI variant's solid volume per dosed area (grains of mean volume
    mean_volume; diam a fix powder/insert distribution "style args", default uniform dlo-dhi). Returns
    (WORK/layer.dump, its grain count); a WORK that already holds the run is reused."""
    ci = VARIANTS["ci"]
    dosed = (float(ci["Lheap"]) + float(ci["Lplate"])) * float(ci["Lz"])
    solid = float(ci["N"]) * uniform_mean_volume(15e-6, 45e-6) / dosed      # solid height of the heap
    lplate, lheap = lx + 4 * dhi, float(ci["Lheap"])
    n = int(round(solid * (lheap + lplate) * lz / (mean_volume or uniform_mean_volume(dlo, dhi))))
    build(work, "ci", **opts)
    spec = json.load(open(os.path.join(work, "scene.json")))
    spec["vars"].update({"Lz": repr(lz), "Lplate": repr(lplate), "Lheap": repr(lheap), "N": str(n),
                         "dlo": repr(dlo), "dhi": repr(dhi)})
    if diam:
        spec["vars"]["diam"], spec["vars"]["dargs"] = diam.split(None, 1)
    with open(os.path.join(work, "scene.json"), "w") as f:
        json.dump(spec, f, indent=1)
    if not os.path.exists(os.path.join(work, "spread.dump")):
        run(work)
    out = os.path.join(work, "layer.dump")
    return out, layer_bed(work, lx, out)


def main(argv=None):
    ap = scene_parser(__doc__)
    ap.add_argument("--spreader", choices=["blade", "roller"])
    ap.add_argument("--speed", type=float, help="spreading speed [m/s] (default 0.1)")
    ap.add_argument("--gap", type=float, help="spreader above the plate [m] (default 84e-6 = 2 d90)")
    ap.add_argument("--base", choices=["plate", "rough"], help="bare plate (default) or a rough previous layer")
    ap.add_argument("--gamma", type=float, help="surface energy [J/m2] (DMT cohesion; default 0)")
    ap.add_argument("--mu", type=float, help="sliding friction (default 0.5)")
    ap.add_argument("--mur", type=float, help="rolling friction (default 0.1)")
    ap.add_argument("--E", type=float, help="Young's modulus [Pa] (default 1e9)")
    ap.add_argument("--seed", type=int)
    ap.add_argument("--layers", type=int, help="layers spread, the plate lowered by the gap after each (default 1)")
    a = ap.parse_args(argv)
    run_actions(a, lambda case: build(case, a.variant or "full", **{k: getattr(a, k) for k in OPTIONS}), run, analyse)


SCENE = Scene(name="powder-spread", kind="dem",
              title="Powder spread by a blade or a counter-rotating roller",
              ci_time="~75 s serial", full_time="21 min serial",
              build=lambda case, size: main(["build", case, f"--{size}"]),
              analyse=lambda case: main(["analyse", case]),
              summary=analyse)


if __name__ == "__main__":
    main()
