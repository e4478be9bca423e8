#!/usr/bin/env python3
"""A coupled run decomposed with cell weights (more ranks where the pool will be): OpenFOAM's
decomposePar `weightField`, the per-rank load in ranks.csv, the ledger equal to serial.

The migration test's case (meltdem.case.exchange_box, 8^3 grains shot along +x across
LAMMPS's processor planes, the gas solved to round-off), its mesh (10^3 cells) split along z by
`simple` with `weightField cellWeight`: cellWeight 8 in the bottom 3 cell layers (where a melt
pool would be), 1 above, written by setFields (boxToCell) as an OpenFOAM user would. Checks
(label coupling mpi):
  - ranks.csv: each rank's cells as simpleGeomDecomp's weighted split puts them (np 2: rank 0
    the bottom layer and 94 cells of the second, 194 cells, rank 1 the other 806; unweighted
    500 each), exactly;
  - the summed cellWeight of each rank's decomposed field within one heavy cell of an equal share;
  - the ledger totals against a serial run, step by step, relative to the largest total <= 1e-10.

usage: weighted_decomposition.py [--np N] [--keep]
"""
import argparse
import csv
import os
import sys
import tempfile

from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_most

import migration

HEAVY_LAYERS, HEAVY, LIGHT = 3, 8.0, 1.0
N = migration.CELLS


def split(np_):
    """Cells and weight of each rank as simpleGeomDecomp splits them: the cells sorted by z
    (bottom up), each rank takes cells until the summed weight reaches its multiple of the
    total over np_, the last takes the rest."""
    w = [HEAVY if k < HEAVY_LAYERS else LIGHT for k in range(N) for _ in range(N * N)]
    jump, total, ind = sum(w) / np_, 0.0, 0
    cells, weights = [], []
    for j in range(np_ - 1):
        start, before = ind, total
        while total < jump * (j + 1):
            total += w[ind]
            ind += 1
        cells.append(ind - start)
        weights.append(total - before)
    cells.append(len(w) - ind)
    weights.append(sum(w) - total)
    return cells, weights, jump


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--keep", action="store_true")
    a = ap.parse_args()
    test = f"coupling.weighted_decomposition.np{a.np}"
    work = tempfile.mkdtemp(prefix="meltdem-weighted-")
    case = os.path.join(work, "case")
    migration.build(case, False)
    cc.uniform_field(case, "cellWeight", "[0 0 0 0 0 0 0]", LIGHT, {"walls": "type zeroGradient;"})
    top = HEAVY_LAYERS * 1e-3 / N
    fc.dictionary(case, "system/setFieldsDict", f"""defaultFieldValues ( volScalarFieldValue cellWeight {LIGHT!r} );
regions
(
    boxToCell
    {{
        box (-1 -1 -1) (1 1 {top!r});
        fieldValues ( volScalarFieldValue cellWeight {HEAVY!r} );
    }}
);
""")
    fc.run(["setFields"], case, "log.setFields")
    fc.dictionary(case, "system/decomposeParDict", f"""numberOfSubdomains {a.np};
method simple;
coeffs {{ n (1 1 {a.np}); }}
weightField cellWeight;
""")
    fc.run(["decomposePar", "-force"], case, "log.decomposePar")
    cc.run_solver(case, a.np)

    expected, _, share = split(a.np)
    with open(os.path.join(case, "postProcessing", "particleLedger", "ranks.csv")) as f:
        rows = [r for r in csv.DictReader(f)]
    first = min(float(r["time"]) for r in rows)
    cells = {int(r["rank"]): int(r["cells"]) for r in rows if float(r["time"]) == first}
    weights = []
    for r in range(a.np):
        w = fc.read_internal(os.path.join(case, f"processor{r}", "0", "cellWeight"))
        weights.append(float(w) * cells.get(r, 0) if w.ndim == 0 else float(w.sum()))
    ok = True
    for r in range(a.np):
        ok &= check_absolute(test, f"rank {r}: cells (the weighted split; {N ** 3 // a.np} unweighted)",
                             cells.get(r, -1), expected[r], 0)
        ok &= check_at_most(test, f"rank {r}: |summed cellWeight - equal share| / heaviest cell",
                            abs(weights[r] - share) / HEAVY, 1.0)
    serial = os.path.join(work, "serial")
    migration.build(serial, False)
    cc.run_solver(serial)
    worst = cc.ledger_totals_difference(cc.ledger(case), cc.ledger(serial))
    ok &= check_at_most(test, f"ledger totals np {a.np} vs serial (relative to the largest total)", worst, 1e-10)
    return fc.finish(ok, work, a.keep)


if __name__ == "__main__":
    sys.exit(main())
