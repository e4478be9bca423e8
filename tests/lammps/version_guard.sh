#!/usr/bin/env bash
# A driver built against headers of another LAMMPS version must refuse to start, with a message.
set -uo pipefail
. "$MELTDEM_SOURCE_DIR/tests/support/report.sh"
out=$(echo "print should-not-run" | "$MELTDEM_BIN/../tests/bin/meltdem-lmp-version-mismatch" -log none 2>&1)
rc=$?
echo "$out"
if [ $rc -ne 0 ] && grep -q "compiled against LAMMPS headers of version 20000101" <<<"$out" \
   && ! grep -q should-not-run <<<"$out"; then verdict=PASS; else verdict=FAIL; fi
report lammps.version_guard "refuses mismatched library (exit code)" "$rc" "non-zero" - "$verdict"
[ "$verdict" = PASS ]
