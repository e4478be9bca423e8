#!/usr/bin/env python3
"""Bad refinement input to meltdemFoam stops before the first step, naming the entry.

A tiny closed 3D box of 4 x 2 x 2 hexahedra (metal below, gas above, flow and energy on) with
constant/meltdemProperties refinement{} runs three steps cleanly, refining at its interface;
then it is broken one thing at a time: a 2D mesh (empty front and back), a mesh of prisms, an
unknown criterion type, a field criterion on a field the run lacks, levels out of range or beyond
the label range, an unknown entry of refinement{} or of a criterion, a meltPool minAlpha of 1 or
more, a user-written dynamicMeshDict next to refinement{}, OpenFOAM's own dynamicRefineFvMesh
without refinement{}, criteria whose switch is off, a corrected
snGrad(alpha.metal) or snGrad(rho) (surface and gravity forces on split faces). Each variant must
exit non-zero without a signal, print a FOAM FATAL (IO) ERROR naming the entry, and take no step.
usage: amr_bad_input.py [--keep]
"""
import os
import re
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import report

sys.path.insert(0, os.path.join(paths.source_dir(), "tests", "foam", "bad_input"))
import bad_input  # noqa: E402

TEST = "foam.amr_bad_input"
METAL = "metal { Tsolidus 1700; Tliquidus 1710; L 2.7e5; cp 965; k 35.95; }\ngas { cp 10; k 0.026; }\n"
GOOD = "interface { level 1; }"


def refinement(criteria=GOOD, max_level=1, extra=""):
    return (f"refinement\n{{\n    maxLevel {max_level};\n    refineInterval 1;\n{extra}"
            f"    criteria {{ {criteria} }}\n}}\n")


# name -> (what is wrong, refinement text, mesh kind, physics overrides, words the message must hold)
VARIANTS = {
    "mesh_2d": ("a 2D mesh (front and back empty)", refinement(), "2d", {}, ["empty", "3D"]),
    "mesh_prisms": ("a mesh of prisms", refinement(), "prisms", {}, ["hexahedra"]),
    "unknown_criterion": ("criterion type 'surface'", refinement("surface { level 1; }"), "box", {},
                          ["surface", "interface"]),
    "unknown_field": ("field criterion on field 'Tmelt'",
                      refinement("hot { type field; field Tmelt; min 1500; }"), "box", {}, ["Tmelt", "field"]),
    "field_without_range": ("field criterion without min or max", refinement("hot { type field; field T; }"),
                            "box", {}, ["min", "max"]),
    "max_level_zero": ("maxLevel 0", refinement(max_level=0), "box", {}, ["maxLevel"]),
    "max_level_label_range": ("maxLevel 9 on 16 cells (8^9 x 16 > 2^31 - 1)", refinement(max_level=9), "box", {},
                              ["maxLevel", "label range"]),
    "criterion_above_max_level": ("criterion level 3 above maxLevel 1", refinement("interface { level 3; }"),
                                  "box", {}, ["level 3", "maxLevel"]),
    "unknown_entry": ("refinement { maxLevl 1; }", refinement(extra="    maxLevl 2;\n"), "box", {}, ["maxLevl"]),
    "unknown_criterion_entry": ("interface { levl 1; }", refinement("interface { levl 1; }"), "box", {},
                                ["levl", "interface", "margin"]),
    "melt_pool_min_alpha": ("meltPool { minAlpha 1.5; }", refinement("meltPool { level 1; minAlpha 1.5; }"), "box",
                            {}, ["minAlpha", "below 1"]),
    "no_criteria": ("refinement without criteria", "refinement { maxLevel 1; }\n", "box", {}, ["criteria"]),
    "user_mesh_dict": ("a user dynamicMeshDict next to refinement{}", refinement(), "box+dict", {},
                       ["dynamicMeshDict", "refinement"]),
    "stock_refine_mesh": ("OpenFOAM's dynamicRefineFvMesh without refinement{}", "", "box+dict", {},
                          ["dynamicRefineFvMesh", "refinement"]),
    "melt_pool_without_energy": ("meltPool criterion with energy off", refinement("meltPool { level 1; }"), "box",
                                 {"energy": "off"}, ["meltPool", "energy"]),
    "laser_without_laser": ("laser criterion with the laser off", refinement("laser { level 1; }"), "box", {},
                            ["laser"]),
    "corrected_alpha_sn_grad": ("snGrad(alpha.metal) corrected", refinement(), "box+corrected alpha.metal", {},
                                ["snGradSchemes", "snGrad(alpha.metal)", "uncorrected"]),
    "corrected_rho_sn_grad": ("snGrad(rho) corrected", refinement(), "box+corrected rho", {},
                              ["snGradSchemes", "snGrad(rho)", "uncorrected"]),
}

USER_DICT = """dynamicFvMesh dynamicRefineFvMesh;
dynamicRefineFvMeshCoeffs { refineInterval 1; field alpha.metal; lowerRefineLevel 0.01; upperRefineLevel 0.99;
  nBufferLayers 1; maxRefinement 1; maxCells 1000; correctFluxes ((phi none)); dumpLevel false; }
"""


def block_mesh(case, kind):
    """4 x 2 x 2 cells of 0.25 mm; 'prisms' collapses one edge of the block (wedge-shaped cells)."""
    h = 2.5e-4
    if kind == "2d":
        g = fc.Grid2D(4 * h, 4 * h, 4, 4, dz=h)
        g.block_mesh(case)
        return
    verts = [(0, 0, 0), (4 * h, 0, 0), (4 * h, 2 * h, 0), (0, 2 * h, 0),
             (0, 0, 2 * h), (4 * h, 0, 2 * h), (4 * h, 2 * h, 2 * h), (0, 2 * h, 2 * h)]
    hexv = "0 1 2 3 4 5 6 7"
    if kind == "prisms":
        verts = verts[:4] + [(0, 0, 2 * h), (4 * h, 0, 2 * h)]
        hexv = "0 1 2 3 4 5 5 4"
    vs = " ".join(f"({x!r} {y!r} {z!r})" for x, y, z in verts)
    fc.dictionary(case, "system/blockMeshDict", f"""convertToMeters 1;
vertices ( {vs} );
blocks ( hex ({hexv}) (4 2 2) simpleGrading (1 1 1) );
edges ();
boundary ();
defaultPatch {{ name walls; type wall; }}
mergePatchPairs ();
""")


def build(case, text, kind, physics):
    block_mesh(case, kind)
    n = 16
    zg = "type zeroGradient;"
    b = {"walls": zg, "frontAndBack": "type empty;"}
    # metal in the lower half (cell centres below 0.25 mm)
    alpha = np.array([1.0 if (i // 4) % 2 == 0 else 0.0 for i in range(n)])
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha, b)
    fc.field(case, "T", "[0 0 0 1 0 0 0]", np.full(n, 1600.0), b)
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((n, 3)), dict(b, walls="type noSlip;"), vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(n),
             dict(b, walls="type fixedFluxPressure; value uniform 0;"))
    fc.transport(case, 7430.0, 6e-3 / 7430.0, 7.43, 6e-4 / 7.43, 1.8)
    fc.gravity(case, (0.0, 0.0, -9.81))
    ph = {"flow": "on", "energy": "on", "surfaceTension": "off"}
    ph.update(physics)
    fc.meltdem_properties(case, physics=ph, extra=METAL + text)
    fc.control_dict(case, "meltdemFoam", 3e-6, 1e-6, 3e-6, adjustable=False)
    fc.fv_schemes(case, extra_div="    div(rhoCpPhi,T) Gauss upwind;\n")
    if kind.startswith("box+corrected"):
        path = os.path.join(case, "system", "fvSchemes")
        text = open(path).read().replace(f"snGrad({kind.split()[1]}) uncorrected;", "")
        open(path, "w").write(text)
    fc.fv_solution(case, p_ref_cell=0, extra_solvers='    "T.*" { solver PBiCGStab; preconditioner DILU; '
                                                     'tolerance 1e-12; relTol 0; }\n')
    fc.run(["blockMesh"], case, "log.blockMesh")
    if kind == "box+dict":
        fc.dictionary(case, "constant/dynamicMeshDict", USER_DICT)


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="amr_bad_input.")
    ok = True

    clean = os.path.join(work, "clean")
    build(clean, refinement(), "box", {})
    rc, out = bad_input.run(clean)
    refined = re.findall(r"Refinement: (\d+) -> (\d+) cells", out)
    clean_ok = rc == 0 and "End" in out and any(int(b) > int(a) for a, b in refined)
    ok &= report(TEST, "clean tiny case runs to the end and refines (exit code)", rc, 0, "exact", clean_ok)

    for name, (what, text, kind, physics, words) in VARIANTS.items():
        case = os.path.join(work, name)
        build(case, text, kind, physics)
        rc, out = bad_input.run(case)
        i = out.find("FOAM FATAL")
        good, measured = bad_input.judge(name, rc, out, out[i:] if i >= 0 else "", words)
        stepped = "\nTime = " in out
        ok &= report(TEST, f"{what}: stops before the first step naming {' '.join(words)}",
                     measured + (", took a step" if stepped else ""), "fatal error naming the entry", "exact",
                     good and not stepped)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
