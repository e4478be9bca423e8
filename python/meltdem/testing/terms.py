"""The physics terms' own tests (foam-src/meltdemModels/terms/<name>/test_<name>.py): a small 2D
case of fixed fields, meltdemTermCheck run on it with one term selected by name, and the fields
its hooks wrote read back. Fields are given per cell in blockMesh order (x fastest)."""
import os
import re

import numpy as np

from .. import paths
from ..case import foam as fc

HOOKS = ("heatSource", "linearisedHeatLoss", "surfacePressure", "surfaceForce", "maxDeltaT", "addMomentum")
OUTPUTS = {"termHeatSource": False, "termQ0": False, "termDqdT": False, "termSurfacePressure": False,
           "termSurfaceForce": True, "termMomentum": True, "magGradAlpha": False}
DIMS = {"alpha.metal": "[0 0 0 0 0 0 0]", "liquidFraction": "[0 0 0 0 0 0 0]", "T": "[0 0 0 1 0 0 0]",
        "U": "[0 1 -1 0 0 0 0]"}


def evaluate(case, term, grid, fields, properties, g=None, rho1=1.0, transport=None, rho2=0.0):
    """Write the case, run meltdemTermCheck -term TERM, return (hooks, outputs): hooks maps each
    hook to whether the term acts through it, outputs the fields it wrote (cell arrays, vectors
    as (n, 3)). fields: name -> cell values (alpha.metal and T required; U as (n, 3));
    properties: the text of constant/meltdemProperties; transport: (rho_metal, nu_metal,
    rho_gas, nu_gas, sigma) for the two-phase mixture a surface force needs."""
    os.makedirs(case, exist_ok=True)
    grid.block_mesh(case)
    fc.control_dict(case, "meltdemTermCheck", 1.0, 1.0, 1.0)
    fc.fv_schemes(case)
    fc.fv_solution(case)
    fc.dictionary(case, "constant/meltdemProperties", properties)
    if g is not None:
        fc.gravity(case, g)
    if transport is not None:
        fc.transport(case, *transport)
    for name, values in fields.items():
        vector = name == "U"
        fc.field(case, name, DIMS[name], values, {"walls": "type zeroGradient;"} if not vector
                 else {"walls": "type noSlip;"}, vector=vector)
    fc.run(["blockMesh"], case, "log.blockMesh")
    fc.run([paths.binary("meltdemTermCheck"), "-term", term, "-rho1", repr(rho1), "-rho2", repr(rho2)], case,
           "log.termCheck")
    log = open(os.path.join(case, "log.termCheck")).read()
    hooks = {h: v == "yes" for h, v in re.findall(r"^hook (\w+) (yes|no)$", log, re.M)}
    outputs = {}
    n = grid.nx * grid.ny
    for name, vector in OUTPUTS.items():
        p = os.path.join(case, "0", name)
        if os.path.exists(p):
            v = np.asarray(fc.read_internal(p), dtype=float)
            outputs[name] = np.broadcast_to(v, (n, 3) if vector else (n,)).copy()
    limit = re.search(r"^maxDeltaT (\S+)$", log, re.M)
    if limit:
        outputs["maxDeltaT"] = float(limit.group(1))
    return hooks, outputs


def acts_only_through(hooks, expected):
    """The hooks the term acts through other than EXPECTED, and those of EXPECTED it does not."""
    extra = sorted(h for h in HOOKS if hooks.get(h) and h not in expected)
    missing = sorted(h for h in expected if not hooks.get(h))
    return extra, missing


def max_relative_deviation(measured, expected):
    """max |measured - expected| over the cells, relative to max |expected|."""
    measured, expected = np.asarray(measured, dtype=float), np.asarray(expected, dtype=float)
    return float(np.max(np.abs(measured - expected)) / np.max(np.abs(expected)))


def check_hooks(test, hooks, expected):
    """Report rows: the term acts through EXPECTED and no other hook."""
    from .report import check_absolute
    extra, missing = acts_only_through(hooks, expected)
    ok = check_absolute(test, f"hooks other than {'/'.join(expected)} the term acts through "
                        f"({', '.join(extra) or 'none'})", len(extra), 0, 0)
    ok &= check_absolute(test, f"of {'/'.join(expected)}, hooks it does not act through "
                         f"({', '.join(missing) or 'none'})", len(missing), 0, 0)
    return ok
