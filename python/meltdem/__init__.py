"""MeltDEM's Python package: the `meltdem` command (cli), case writers (case), readers of what a
run leaves (io), analyses of fields, beads and beds (analysis), the scenes' declarations (scene)
and the test helpers (testing). Importable without path edits: the `meltdem` launcher and ctest
set PYTHONPATH to this folder's parent, and the build writes a .pth for direct script runs."""
