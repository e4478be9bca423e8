#!/usr/bin/env bash
# meltdem-lmp without project styles must behave exactly as /usr/bin/lmp: run the default
# granular pour through both (serial and mpirun -np 2) and compare every thermo line.
set -euo pipefail
. "$MELTDEM_SOURCE_DIR/tests/support/report.sh"
name=lammps.stock_equivalence
np=${1:-1}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cp "$MELTDEM_SOURCE_DIR/examples/powder-pour/in.pour" "$work/"
cd "$work"

launch() { if [ "$np" = 1 ]; then "$@"; else mpirun -np "$np" "$@"; fi; }
thermo() { awk '/^ *Step /{on=1} on&&/^Loop time/{on=0} on' "$1"; }

launch /usr/bin/lmp -in in.pour -var nsteps 20000 -log none -screen stock.out >/dev/null
launch "$MELTDEM_BIN/meltdem-lmp" -in in.pour -var nsteps 20000 -log none -screen meltdem.out >/dev/null
thermo stock.out > stock.thermo
thermo meltdem.out > meltdem.thermo
n=$(wc -l < stock.thermo)
same=$(paste -d'\n' stock.thermo meltdem.thermo | awk 'NR%2{a=$0;next} a==$0{c++} END{print c+0}')
if [ "$n" -gt 5 ] && cmp -s stock.thermo meltdem.thermo; then verdict=PASS; else verdict=FAIL; fi
report "$name.np$np" "identical thermo lines (granular pour, 20000 steps)" "$same" "$n" 0 "$verdict"
[ "$verdict" = PASS ] || { diff stock.thermo meltdem.thermo | head -20; exit 1; }
