#!/usr/bin/env bash
# Prints the validation rows written by the tests as one table.
dir=${1:?report dir}
shopt -s nullglob
files=("$dir"/*.tsv)
[ ${#files[@]} -gt 0 ] || { echo "(no validation rows written)"; exit 0; }
echo
echo "Validation report: measured vs reference (tolerance)"
cat "${files[@]}" | sort | awk -F'\t' '
  { printf "%-4s %-48s %-58s measured %-16s reference %-16s tol %s\n", $6, $1, $2, $3, $4, $5
    n++; if ($6 ~ /^XFAIL/) x++; else if ($6 == "INFO") i++; else if ($6 != "PASS") f++ }
  END { printf "%d validation rows, %d not passing, %d expected failures (reason in the row), %d for information\n", n, f+0, x+0, i+0 }'
