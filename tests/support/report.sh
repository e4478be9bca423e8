# Shell side of the validation report (see validation_report.h for the C++ side).
# report TEST WHAT MEASURED REFERENCE TOLERANCE VERDICT
report() {
  local test=$1 what=$2 measured=$3 reference=$4 tol=$5 verdict=$6
  printf 'VALIDATION %s | %s | measured %s | reference %s | tolerance %s | %s\n' \
    "$test" "$what" "$measured" "$reference" "$tol" "$verdict"
  if [ -n "${MELTDEM_REPORT_DIR:-}" ]; then
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$test" "$what" "$measured" "$reference" "$tol" "$verdict" \
      >> "$MELTDEM_REPORT_DIR/$test.tsv"
  fi
}
