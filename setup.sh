#!/usr/bin/env bash
# Sets MeltDEM up on a fresh Debian bookworm machine and runs the default scene:
# dependencies (as root), the CMake build into build/, then examples/powder-pour
# with the meltdem command (its output in build/powder-pour/).
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${MELTDEM_BUILD_DIR:-$top/build}
"$top/scripts/install-deps.sh"
"$top/scripts/build.sh" "$build"
echo "meltdem setup: running the default scene examples/powder-pour into $build/powder-pour"
"$build/bin/meltdem" run powder-pour --case "$build/powder-pour"
