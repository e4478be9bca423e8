#!/usr/bin/env bash
# Builds MeltDEM and runs its test suite (ctest); extra arguments go to ctest,
# e.g. ./run-tests.sh -L dem   or   ./run-tests.sh -L long
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${MELTDEM_BUILD_DIR:-$top/build}
"$top/scripts/install-deps.sh"
"$top/scripts/build.sh" "$build"
rm -rf "$build/validation-report"; mkdir -p "$build/validation-report"
args=("$@")
[ ${#args[@]} -gt 0 ] || args=(-LE long)
rc=0
(cd "$build" && ctest --output-on-failure -j2 "${args[@]}") || rc=$?
"$top/scripts/print-validation-report.sh" "$build/validation-report"
exit $rc
