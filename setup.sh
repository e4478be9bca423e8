#!/usr/bin/env bash
# Sets MeltDEM up on a fresh Debian bookworm machine and runs the default scene:
# dependencies (as root), the CMake build into build/, then examples/powder-pour.
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${MELTDEM_BUILD_DIR:-$top/build}
"$top/scripts/install-deps.sh"
"$top/scripts/build.sh" "$build"
echo "meltdem setup: running the default scene examples/powder-pour"
cd "$top/examples/powder-pour"
"$build/bin/meltdem-lmp" -in in.pour -log log.lammps
