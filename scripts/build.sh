#!/usr/bin/env bash
# Configures and builds MeltDEM: build.sh [BUILD_DIR]
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$top/build}
mkdir -p "$build"
cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=Release > "$build/configure.log" 2>&1 \
  || { cat "$build/configure.log"; echo "meltdem build: cmake configure failed" >&2; exit 1; }
cmake --build "$build" -j"${MELTDEM_JOBS:-2}"
