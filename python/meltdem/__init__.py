"""MeltDEM's Python package: the `meltdem` command (cli), case writers (case), readers of what a
run leaves (io), analyses of fields, beads and beds (analysis), the scenes' declarations (scene)
and the test helpers (testing). Importable without path edits: the `meltdem` launcher and ctest
set PYTHONPATH to this folder's parent, and the build writes a .pth for direct script runs."""

try:
    import numpy as _np
except ImportError:  # the launcher's own commands run without numpy
    _np = None
if _np is not None and int(_np.__version__.split(".")[0]) >= 2:
    # case writers print numbers with repr (f"{x!r}") for exact round trips: numpy 2 would write
    # a numpy scalar as "np.float64(...)" into LAMMPS inputs and OpenFOAM dictionaries
    _np.set_printoptions(legacy="1.25")
