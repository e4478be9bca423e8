#!/bin/sh
# The house style: C++ outside foam-src/ as .clang-format lays it out, Python as setup.cfg's
# flake8 settings want it. $1: cpp | python. Prints the offending files; exit 1 when any.
set -u
cd "${MELTDEM_SOURCE_DIR:?}" || exit 2
# the tracked and new files of a git checkout, else every file (a source tarball)
list() {
  if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files -co --exclude-standard "$@" | while read -r f; do [ -e "$f" ] && echo "$f"; done
  else
    for p in "$@"; do find . -path './.deps' -prune -o -path './build' -prune -o -path "./$p" -print; done | sed 's|^\./||'
  fi
}
case "$1" in
  cpp)
    files=$(list 'coupling/*.h' 'coupling/*.cpp' 'lammps-src/*.h' 'lammps-src/*.cpp')
    [ -n "$files" ] || { echo "no C++ files found"; exit 1; }
    # shellcheck disable=SC2086
    clang-format --dry-run --Werror $files || { echo "reformat with: clang-format -i <file>"; exit 1; }
    echo "clang-format: $(echo "$files" | wc -l) files formatted" ;;
  python)
    files=$(list '*.py' | grep -v '^\.deps/\|^build/'; echo tools/meltdem)
    # shellcheck disable=SC2086
    /usr/bin/python3 -m flake8 $files || exit 1
    echo "flake8: $(echo "$files" | wc -l) files clean" ;;
  *) echo "usage: $0 cpp|python"; exit 2 ;;
esac
