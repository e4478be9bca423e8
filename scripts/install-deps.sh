#!/usr/bin/env bash
# Installs everything MeltDEM needs on a Debian bookworm (or trixie) machine (run as root):
#   1. Debian binary packages (LAMMPS and OpenFOAM pinned: the headers must match them),
#   2. the pinned Debian *source* packages of LAMMPS and OpenFOAM, checksum-verified,
#      unpacked with Debian's patches into .deps/ (git-ignored),
#   3. the headers the build needs: LAMMPS src/ as is, OpenFOAM lnInclude dirs.
# Idempotent: a second run checks stamps and does nothing.
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
deps=${MELTDEM_DEPS_DIR:-$top/.deps}

codename=bookworm
if [ -r /etc/os-release ]; then
  . /etc/os-release
  codename=${VERSION_CODENAME:-bookworm}
fi
# the pinned versions of each supported release (README: supported versions)
case "$codename" in
  bookworm)
    LAMMPS_SRC_VERSION=20220106.git7586adbb6a+ds1-2
    LAMMPS_BIN_VERSION=20220106.git7586adbb6a+ds1-2+b2
    OPENFOAM_SRC_VERSION=1912.200626-1
    OPENFOAM_BIN_VERSION=1912.200626-1+b1
    # sha256 of the exact files the pinned source versions consist of
    declare -A SHA256=(
      [lammps_20220106.git7586adbb6a+ds1-2.dsc]=058ff77c1fe885c7e29015523bd67ad6ebdb9743b6c665f85d011dfc7b45c81c
      [lammps_20220106.git7586adbb6a+ds1.orig.tar.xz]=65146c615ad24d8b8bc64f4e05e86226a7f1fdb45c0b5ea9416562b9f3863082
      [lammps_20220106.git7586adbb6a+ds1-2.debian.tar.xz]=f1db31cf6250324613ada9e7a856811293b31abc867762b5530f06b243925fe8
      [openfoam_1912.200626-1.dsc]=14b904563677b6939d78ae3e637794cad81a099c60b5c0d04bdffddfd731bd40
      [openfoam_1912.200626.orig.tar.bz2]=c75ca0f04cc4f49708296c1926cbde9d0138b3fef298fed54270dfe29e2df404
      [openfoam_1912.200626-1.debian.tar.xz]=87a9059001b2f3a58d6bae3fb69284b124974ea39bc6881ae16623e482a367e0
    )
    ;;
  trixie)
    LAMMPS_SRC_VERSION=20250204+dfsg.1-2
    LAMMPS_BIN_VERSION=20250204+dfsg.1-2
    OPENFOAM_SRC_VERSION=1912.200626-3
    OPENFOAM_BIN_VERSION=1912.200626-3+b1
    # the archive these machines reach serves trixie's tarballs but not its .dsc files (nor
    # openfoam's -3 Debian tarball): the sources are unpacked from the tarballs (unpack below),
    # OpenFOAM's headers from the upstream tarball, the same as bookworm's (the -1/-3 Debian
    # patches change its build, not its headers)
    declare -A SHA256=(
      [lammps_20250204+dfsg.1.orig.tar.xz]=3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7
      [lammps_20250204+dfsg.1-2.debian.tar.xz]=508b9627ec8a70c57318b25330e1843d093392e8858c311359d01b7da2ea0a46
      [openfoam_1912.200626.orig.tar.bz2]=c75ca0f04cc4f49708296c1926cbde9d0138b3fef298fed54270dfe29e2df404
    )
    ;;
  *)
    echo "meltdem install-deps: ERROR: Debian $codename is not supported (bookworm, trixie)" >&2
    exit 1
    ;;
esac

PACKAGES=(
  "lammps=$LAMMPS_BIN_VERSION" "liblammps-dev=$LAMMPS_BIN_VERSION"
  "openfoam=$OPENFOAM_BIN_VERSION" "libopenfoam=$OPENFOAM_BIN_VERSION"
  openmpi-bin libopenmpi-dev libeigen3-dev googletest libgtest-dev
  cmake g++ make dpkg-dev xz-utils bzip2 python3 python3-numpy python3-scipy python3-matplotlib
  flake8 clang-format
)

# OpenFOAM library folders whose lnInclude the project compiles against
FOAM_LNINCLUDE_DIRS=(
  OpenFOAM OSspecific/POSIX finiteVolume meshTools sampling surfMesh fileFormats
  dynamicMesh dynamicFvMesh fvOptions functionObjects/field
  transportModels/incompressible transportModels/interfaceProperties
  transportModels/twoPhaseMixture transportModels/immiscibleIncompressibleTwoPhaseMixture
  TurbulenceModels/turbulenceModels TurbulenceModels/incompressible
)

die() { echo "meltdem install-deps: ERROR: $*" >&2; exit 1; }
step() { echo "meltdem install-deps: $*"; }

command -v apt-get >/dev/null || die "apt-get not found: MeltDEM needs Debian bookworm or trixie"
step "Debian $codename: LAMMPS $LAMMPS_BIN_VERSION, OpenFOAM $OPENFOAM_BIN_VERSION"
export DEBIAN_FRONTEND=noninteractive

# ---- 1. binary packages -------------------------------------------------------
missing=()
for p in "${PACKAGES[@]}"; do
  name=${p%%=*}; want=${p#*=}
  have=$(dpkg-query -W -f='${db:Status-Status} ${Version}' "$name" 2>/dev/null || true)
  if [ "$name" = "$p" ]; then
    [[ "$have" == installed* ]] || missing+=("$p")
  else
    [ "$have" = "installed $want" ] || missing+=("$p")
  fi
done
apt_updated=0
need_root() { [ "$(id -u)" = 0 ] || die "must run as root to $1 (rerun with sudo)"; }
if [ ${#missing[@]} -gt 0 ]; then
  need_root "install Debian packages: ${missing[*]}"
  step "installing Debian packages: ${missing[*]}"
  apt-get update -q >/dev/null || die "apt-get update failed"
  apt_updated=1
  apt-get install -y -q --no-install-recommends "${missing[@]}" >/dev/null \
    || die "apt-get install failed for: ${missing[*]} (pinned versions: LAMMPS $LAMMPS_BIN_VERSION, OpenFOAM $OPENFOAM_BIN_VERSION)"
else
  step "Debian packages present"
fi

# ---- 2. pinned source packages --------------------------------------------------
cache=$deps/cache
mkdir -p "$cache"
need_download=0
for f in "${!SHA256[@]}"; do
  [ -f "$cache/$f" ] && echo "${SHA256[$f]}  $cache/$f" | sha256sum -c --status || need_download=1
done
if [ $need_download = 1 ]; then
  need_root "download the pinned source packages"
  # deb-src entries mirroring the machine's own deb entries of this release (no host is named here)
  srcfile=/etc/apt/sources.list.d/meltdem-deb-src.sources
  if [ ! -f "$srcfile" ]; then
    step "adding deb-src entries derived from the configured deb entries"
    tmp=$(mktemp)
    for s in /etc/apt/sources.list.d/*.sources; do
      [ -f "$s" ] && [ "$s" != "$srcfile" ] || continue
      grep -q "^Suites:.*$codename" "$s" || continue
      grep -q '^Types:.*deb-src' "$s" && continue
      sed -e 's/^Types:.*/Types: deb-src/' "$s" >> "$tmp"; echo >> "$tmp"
    done
    if [ -f /etc/apt/sources.list ]; then
      grep -E "^deb\s.*$codename" /etc/apt/sources.list | sed 's/^deb /deb-src /' \
        > /etc/apt/sources.list.d/meltdem-deb-src.list || true
    fi
    [ -s "$tmp" ] && cp "$tmp" "$srcfile"
    rm -f "$tmp"
    apt_updated=0
  fi
  [ $apt_updated = 1 ] || apt-get update -q >/dev/null || die "apt-get update (deb-src) failed"
  step "downloading source packages lammps=$LAMMPS_SRC_VERSION openfoam=$OPENFOAM_SRC_VERSION"
  chmod 777 "$cache"
  (cd "$cache" && apt-get source -q --download-only "lammps=$LAMMPS_SRC_VERSION" "openfoam=$OPENFOAM_SRC_VERSION" >/dev/null 2>&1) \
    || [ -z "${SHA256[lammps_$LAMMPS_SRC_VERSION.dsc]:-}" ] \
    || die "apt-get source failed: is a deb-src entry for $codename configured and does it still carry lammps $LAMMPS_SRC_VERSION / openfoam $OPENFOAM_SRC_VERSION?"
  for f in "${!SHA256[@]}"; do
    [ -f "$cache/$f" ] || die "source file $f missing after download"
    echo "${SHA256[$f]}  $cache/$f" | sha256sum -c --status || die "checksum mismatch for $cache/$f"
  done
else
  step "source packages present, checksums verified"
fi

unpack() { # name version dsc
  local dir=$deps/$1-src stamp=$deps/$1-src.stamp
  if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$2" ] && [ -d "$dir" ]; then
    step "$1 source $2 unpacked"; return
  fi
  step "unpacking $1 source $2"
  rm -rf "$dir"
  if [ -n "${SHA256[$3]:-}" ]; then
    dpkg-source --no-check -x "$cache/$3" "$dir" >/dev/null || die "dpkg-source failed for $3"
  else
    # no .dsc pinned: the upstream tarball, then the Debian tarball and its quilt series if pinned
    local upstream=${2%-*} orig debian
    orig=$(ls "$cache/$1_${upstream#*:}".orig.tar.* 2>/dev/null | head -n 1)
    [ -n "$orig" ] || die "no upstream tarball of $1 $upstream in $cache"
    mkdir -p "$dir"
    tar -xf "$orig" -C "$dir" --strip-components=1 || die "unpacking $orig failed"
    debian=$cache/$1_$2.debian.tar.xz
    if [ -n "${SHA256[$1_$2.debian.tar.xz]:-}" ]; then
      tar -xf "$debian" -C "$dir" || die "unpacking $debian failed"
      if [ -f "$dir/debian/patches/series" ]; then
        grep -v '^\s*#' "$dir/debian/patches/series" | while read -r p _; do
          [ -n "$p" ] || continue
          patch -d "$dir" -p1 -s -N <"$dir/debian/patches/$p" >/dev/null || die "Debian patch $p of $1 does not apply"
        done
      fi
    fi
  fi
  echo "$2" > "$stamp"
  rm -f "$deps/$1-headers.stamp"
}
unpack lammps "$LAMMPS_SRC_VERSION" "lammps_$LAMMPS_SRC_VERSION.dsc"
unpack openfoam "$OPENFOAM_SRC_VERSION" "openfoam_$OPENFOAM_SRC_VERSION.dsc"

# ---- 3. headers -------------------------------------------------------------------
[ -f "$deps/lammps-src/src/version.h" ] || die "LAMMPS source tree incomplete: $deps/lammps-src/src/version.h missing"
lnstamp="$deps/openfoam-headers.stamp"
want_ln="${FOAM_LNINCLUDE_DIRS[*]}"
if [ -f "$lnstamp" ] && [ "$(cat "$lnstamp")" = "$want_ln" ]; then
  step "OpenFOAM lnInclude dirs present"
else
  step "building OpenFOAM lnInclude dirs"
  for d in "${FOAM_LNINCLUDE_DIRS[@]}"; do
    [ -d "$deps/openfoam-src/src/$d" ] || die "OpenFOAM source folder src/$d missing"
    (cd "$deps/openfoam-src/src" && ../wmake/wmakeLnInclude -u -s "$d") >/dev/null 2>&1 \
      || die "wmakeLnInclude failed for src/$d"
  done
  echo "$want_ln" > "$lnstamp"
fi
step "done: dependencies ready in $deps"
