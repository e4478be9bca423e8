#!/usr/bin/env bash
# The input command 'clear' rebuilds LAMMPS's style tables from the library; meltdem-lmp
# must register the project styles again, so a style used after 'clear' still exists.
set -euo pipefail
source "$MELTDEM_SOURCE_DIR/tests/support/report.sh"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
cat > in.clear <<'IN'
units si
atom_style sphere 1
clear
units si
atom_style sphere 1
comm_modify vel yes
boundary p p f
region box block 0 1e-3 0 1e-3 0 1e-3
create_box 1 box
pair_style granular/powder 1e-4
pair_coeff * * hertz/material 2e11 0.5 0.3 tangential linear_nohistory 1.0 0.0 damping tsuji
compute ov all powder/overlap
fix ins all powder/insert 10 42 region box diam one 3e-5 dens 7900
timestep 1e-8
run 1
print "INSERTED $(f_ins[1])"
IN
out=$("$MELTDEM_BIN/meltdem-lmp" -in in.clear -log none 2>&1) || { echo "$out"; report lammps.clear_keeps_styles "styles after clear" "run failed" "runs" exact FAIL; exit 1; }
n=$(echo "$out" | sed -n 's/^INSERTED \([0-9.]*\)$/\1/p')
verdict=FAIL; [ "$n" = "10" ] && verdict=PASS
report lammps.clear_keeps_styles "particles inserted by fix powder/insert after clear" "$n" 10 exact $verdict
[ $verdict = PASS ]
