#!/usr/bin/env bash
# Smoke test of the project's OpenFOAM CMake module: stock interFoam compiled by it from the
# pinned source must reproduce /usr/bin/interFoam byte for byte on a short dam break,
# serial and (argument 2) decomposed on 2 ranks.
set -euo pipefail
. "$MELTDEM_SOURCE_DIR/tests/support/report.sh"
np=${1:-1}
name=foam.stock_interfoam_smoke.np$np
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}

prepare() {
  cp -r "$MELTDEM_SOURCE_DIR/tests/foam/damBreak" "$1"
  (cd "$1" && cp 0/alpha.water.orig 0/alpha.water && blockMesh > log.blockMesh 2>&1 \
     && setFields > log.setFields 2>&1)
  if [ "$np" != 1 ]; then (cd "$1" && decomposePar > log.decomposePar 2>&1); fi
}
solve() { # case solver
  if [ "$np" = 1 ]; then (cd "$1" && "$2" > log.solver 2>&1)
  else (cd "$1" && mpirun -np "$np" "$2" -parallel > log.solver 2>&1); fi
}
prepare "$work/stock"; prepare "$work/built"
solve "$work/stock" /usr/bin/interFoam
solve "$work/built" "$MELTDEM_BIN/stock-interFoam"

last=0.2
if [ "$np" = 1 ]; then dirs=("$last"); else dirs=(processor0/$last processor1/$last); fi
n=0; same=0
for d in "${dirs[@]}"; do
  for f in "$work/stock/$d"/*; do
    [ -f "$f" ] || continue
    n=$((n+1))
    cmp -s "$f" "$work/built/$d/$(basename "$f")" && same=$((same+1))
  done
done
steps=$(grep -c '^Time = ' "$work/built/log.solver" || true)
echo "compared $n field files after $steps time steps"
if [ "$n" -ge 4 ] && [ "$same" = "$n" ] && [ "$steps" -gt 10 ]; then verdict=PASS; else verdict=FAIL; fi
report "$name" "field files identical to /usr/bin/interFoam at t=$last ($steps steps)" "$same" "$n" 0 "$verdict"
[ "$verdict" = PASS ] || { tail -20 "$work/built/log.solver"; exit 1; }
