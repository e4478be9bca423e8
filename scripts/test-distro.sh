#!/usr/bin/env bash
# Build MeltDEM and run a stated subset of its tests in a chroot of another Debian release
# (run as root), e.g. trixie: LAMMPS 4Feb2025, OpenFOAM v1912 (1912.200626-3), Open MPI 5.
#
#     scripts/test-distro.sh trixie [ctest options...]     (default subset: SUBSET below)
#
# The chroot comes from Debian's archive by debootstrap and is cached with its packages, the
# pinned source packages (.deps inside it) and the build, in $MELTDEM_DISTRO_CACHE/<release>
# (default .deps/distro/<release>); a second run only copies the checkout (tracked and untracked,
# not ignored files) in, rebuilds what changed and runs the tests. The build keeps going past a
# target that fails to compile; the summary says which targets were built and which tests passed.
set -euo pipefail

release=${1:?usage: scripts/test-distro.sh RELEASE [ctest options...]}
shift
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
root=${MELTDEM_DISTRO_CACHE:-$top/.deps/distro}/$release
mirror=${MELTDEM_DEBIAN_MIRROR:-http://deb.debian.org/debian}
# the stated subset: every test, the scenes included, but the CLI's end-to-end runs, the
# benchmarks' smoke runs, the input fuzzer, the wmake build and the style checks (clang-format 19
# there formats otherwise than bookworm's 14, the project's); the full suite is measured in the
# README
SUBSET=(-LE 'long|cli|bench|style|fuzz' -E '^foam\.wmake$')
[ $# -gt 0 ] && SUBSET=("$@")

say() { echo "meltdem test-distro: $*"; }
die() { echo "meltdem test-distro: ERROR: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || die "must run as root (debootstrap, chroot, mounts)"
command -v debootstrap >/dev/null || { say "installing debootstrap"; apt-get install -y -q debootstrap >/dev/null; }

# the chroot's bind mounts (deepest first): a run that was killed may have left them, and no
# rm may ever reach the host's /dev or /proc through them
unmount_all() {
  local m
  for m in $(awk -v r="$root/" 'index($2, r) == 1 {print $2}' /proc/mounts | sort -r); do
    umount -l "$m" 2>/dev/null || true
  done
  ! awk -v r="$root/" 'index($2, r) == 1 {f = 1} END {exit !f}' /proc/mounts
}

start=$(date +%s)
unmount_all || die "mounts under $root remain: umount them first"
if [ ! -f "$root/.meltdem-chroot" ]; then
  say "debootstrap $release into $root"
  rm -rf --one-file-system "$root"
  mkdir -p "$root"
  debootstrap --variant=minbase --include=ca-certificates "$release" "$root" "$mirror" >"$root.debootstrap.log" 2>&1 \
    || die "debootstrap failed (log: $root.debootstrap.log)"
  rm -f "$root/etc/apt/sources.list"
  cat >"$root/etc/apt/sources.list.d/debian.sources" <<EOF
Types: deb deb-src
URIs: $mirror
Suites: $release $release-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
  touch "$root/.meltdem-chroot"
fi

trap unmount_all EXIT
for m in proc sys dev dev/pts; do
  mkdir -p "$root/$m"
  mount --bind "/$m" "$root/$m"
done

say "copying the checkout to $root/src"
rm -rf --one-file-system "$root/src"
mkdir -p "$root/src"
(cd "$top" && git ls-files -co --exclude-standard -z | tar --null -T - -cf -) | tar -xf - -C "$root/src"

say "dependencies, build and tests in the $release chroot"
set +e
chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 \
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
  bash -s -- "${SUBSET[@]}" <<'EOF'
set -u
cd /src
MELTDEM_DEPS_DIR=/deps bash scripts/install-deps.sh || exit 2
cmake -S . -B /build -DMELTDEM_DEPS_DIR=/deps >/build.cmake.log 2>&1 || { tail -30 /build.cmake.log; exit 3; }
cmake --build /build -j2 -- -k >/build.log 2>&1
echo "build exit status $?; targets built:"
ls /build/bin /build/lib 2>/dev/null | tr '\n' ' '; echo
grep -m 20 "error:" /build.log
cd /build && ctest -j2 --timeout 600 "$@"
EOF
rc=$?
set -e
say "$release: ctest exit status $rc, $(($(date +%s) - start)) s in all (build log: $root/build.log)"
exit $rc
