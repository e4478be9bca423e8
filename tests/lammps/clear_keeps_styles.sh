#!/usr/bin/env bash
# The input command 'clear' rebuilds LAMMPS's style tables from the library; meltdem-lmp
# must register the project styles again, so a style used after 'clear' still exists.
set -euo pipefail
source "$MELTDEM_SOURCE_DIR/tests/support/report.sh"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
{ printf 'units si\natom_style sphere 1\nclear\n'; cat "$MELTDEM_SOURCE_DIR/tests/lammps/in.project_styles"; } > in.clear
out=$("$MELTDEM_BIN/meltdem-lmp" -in in.clear -log none 2>&1) || { echo "$out"; report lammps.clear_keeps_styles "styles after clear" "run failed" "runs" exact FAIL; exit 1; }
n=$(echo "$out" | sed -n 's/^INSERTED \([0-9.]*\)$/\1/p')
verdict=FAIL; [ "$n" = "10" ] && verdict=PASS
report lammps.clear_keeps_styles "particles inserted by fix powder/insert after clear" "$n" 10 exact $verdict
[ $verdict = PASS ]
