#!/usr/bin/env python3
"""foam-src/<target>/Make/files of the wmake build (foam-src/Allwmake) lists exactly the .C files
CMake compiles for the target (every *.C of meltdemModels' folders and of meltdemCoupling; the
sources of meltdemFoam's add_executable), so a source added to one build is not missing from the other."""
import glob
import os
import re
import sys

from meltdem import paths
from meltdem.testing.report import check_absolute

FOAM = os.path.join(paths.source_dir(), "foam-src")
CMAKE_SOURCES = {
    "meltdemModels": lambda d: [p for p in glob.glob(os.path.join(d, "**", "*.C"), recursive=True)
                                if "/lnInclude/" not in p and "/Make/" not in p],
    "meltdemCoupling": lambda d: glob.glob(os.path.join(d, "*.C")),
    # the sources of its add_executable()
    "meltdemFoam": lambda d: [os.path.join(d, f) for f in re.search(
        r"add_executable\(meltdemFoam\s+([^)]*)\)", open(os.path.join(d, "CMakeLists.txt")).read()).group(1).split()],
}

ok = True
for target, sources in CMAKE_SOURCES.items():
    d = os.path.join(FOAM, target)
    want = {os.path.relpath(p, d) for p in sources(d)}
    listed = {w for w in open(os.path.join(d, "Make", "files")).read().split() if w.endswith(".C")}
    diff = sorted(want ^ listed)
    ok &= check_absolute("style.wmake_files", f"{target}: sources in only one of CMake and Make/files "
                         f"({' '.join(diff) or 'none'})", float(len(diff)), 0.0, 0)
sys.exit(0 if ok else 1)
