"""`meltdem run --np N` on a case without a decomposeParDict: the ranks are stacked along the mesh's
longest side, but not along a laser's scan (velocity or tracks) or beam axis, where the beam, the pool
and its refined cells would sit on one rank (pbf-line full AMR on 2 ranks split along its track:
19077 against 4608 cells at 58 us). Checks the split written for several lasers and the dictionary
meltdem run writes."""
import os
import sys
import tempfile

from meltdem.cli import run
from meltdem.testing.report import check_absolute

T = "cli.run.decomposition_axis"
BOX = ((0.0, 0.0, 0.0), (9.6e-4, 2.4e-4, 3.2e-4))   # pbf-line: long in x, the beam along -y


def case_with(work, name, laser):
    case = os.path.join(work, name)
    os.makedirs(os.path.join(case, "constant"))
    os.makedirs(os.path.join(case, "system"))
    if laser is not None:
        with open(os.path.join(case, "constant", "meltdemProperties"), "w") as f:
            f.write("physics { laser on; }\nlaser\n{\n" + laser + "}\n")
    return case


def main():
    ok = True
    work = tempfile.mkdtemp(prefix="meltdem-decomp-")
    cases = [
        ("no laser: the longest side (x)", None, BOX, (2, 1, 1)),
        ("scan along x, beam along -y: across the scan (z)",
         "power 312;\ndirection (0 -1 0);\nposition (1.6e-4 2.35e-4 1.6e-4);\nvelocity (2 0 0);\n", BOX, (1, 1, 2)),
        ("beam at rest along -y: the longest side (x)", "power 100;\ndirection (0 -1 0);\n", BOX, (2, 1, 1)),
        ("hatched tracks along x, beam along -y: z",
         "direction (0 -1 0);\ntracks (((1e-4 2e-4 1e-4) (5e-4 2e-4 1e-4)) ((5e-4 2e-4 1.8e-4) (1e-4 2e-4 1.8e-4)));\n",
         BOX, (1, 1, 2)),
        ("scan along z, beam along -y, z longest: x",
         "direction (0 -1 0);\nvelocity (0 0 1);\n", ((0, 0, 0), (2e-4, 1e-4, 5e-4)), (2, 1, 1)),
        ("beam oblique in x-y, scan along x: z", "direction (0.2 -1 0);\nvelocity (1 0 0);\n", BOX, (1, 1, 2)),
        ("every axis scanned or shone along: the longest side",
         "direction (0 -1 0);\nvelocity (1 0 1);\n", BOX, (2, 1, 1)),
    ]
    for k, (what, laser, box, want) in enumerate(cases):
        case = case_with(work, f"c{k}", laser)
        got = run.decomposition_split(case, 2, box)
        print(f"{T}: {what}: split {got}, expected {want}")
        axis_got, axis_want = got.index(2), want.index(2)
        ok &= check_absolute(T, f"{what}: axis of the ranks (0 x, 1 y, 2 z)", axis_got, axis_want, 0)
    # the dictionary itself, as decomposePar reads it (decomposePar is not run here)
    case = case_with(work, "dict", cases[1][1])
    run.tool = lambda args, c, log: None
    run.decompose(case, 4, BOX)
    text = open(os.path.join(case, "system", "decomposeParDict")).read()
    print(text)
    ok &= check_absolute(T, "decomposeParDict n (1 1 4) written", int("n (1 1 4);" in text), 1, 0)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
