#!/usr/bin/env bash
# Builds the Debian package from the build (default build/, as scripts/test.sh leaves it: `cpack -G DEB`),
# installs it with apt, runs `cgagen --version`, builds and tests examples/consumer against it (prefix /usr),
# and removes the package again, on failure too. Needs root (or sudo); .ci/run calls it after
# scripts/test-install.sh; about 30 s.
# Safety: it refuses to run when /usr/bin/cgagen exists and belongs to no package `cgagen` (a hand-made
# install it would overwrite); a `cgagen` package left by an interrupted earlier run is removed first; the
# package depends only on packages scripts/setup.sh installs, so apt needs no download.
# Environment: BUILD_DIR (default build). Prints the .deb's path and control fields.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
[ -f "$BUILD_DIR/CMakeCache.txt" ] || { echo "test-deb: no $BUILD_DIR (run scripts/test.sh first)" >&2; exit 2; }

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "test-deb: needs root (apt-get install); not run" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
apt=($SUDO apt-get -y -q -o DPkg::Lock::Timeout=120)

installed() { dpkg-query -W -f='${Status}' cgagen 2>/dev/null | grep -q "install ok installed"; }
# Any trace of the package in dpkg's database (installed, half-installed, config files left).
known() { dpkg-query -W -f='${Status}\n' cgagen 2>/dev/null | grep -qv 'not-installed'; }
remove_package() {
  if installed; then "${apt[@]}" remove cgagen >/dev/null || true; fi
  if known; then $SUDO dpkg --purge cgagen >/dev/null || true; fi
  ! known
}
if [ -e /usr/bin/cgagen ] && ! dpkg -S /usr/bin/cgagen 2>/dev/null | grep -q '^cgagen:'; then
  echo "test-deb: /usr/bin/cgagen exists and is not from the cgagen package; not overwriting it" >&2
  exit 1
fi
if known; then
  echo "test-deb: removing the cgagen package left by an earlier run"
  remove_package
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/cgagen-deb.XXXXXX")
cleanup() {
  local status=$?
  remove_package || { echo "test-deb: could not remove the cgagen package" >&2; status=1; }
  rm -rf "$tmp"
  if [ -e /usr/bin/cgagen ]; then echo "test-deb: /usr/bin/cgagen still there after removing the package" >&2; status=1; fi
  if [ "$status" = 0 ]; then echo "test-deb: package installed, used and removed"; fi
  exit $status
}
trap cleanup EXIT

rm -f "$BUILD_DIR"/packages/cgagen_*.deb
(cd "$BUILD_DIR" && cpack -G DEB >/dev/null)
debs=("$BUILD_DIR"/packages/cgagen_*.deb)
[ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ] || { echo "test-deb: cpack made no single .deb: ${debs[*]}" >&2; exit 1; }
deb=$(realpath "${debs[0]}")
echo "test-deb: $deb"
dpkg-deb -f "$deb" Package Version Depends Recommends

"${apt[@]}" --no-install-recommends install "$deb" >/dev/null
installed || { echo "test-deb: apt did not install cgagen" >&2; exit 1; }
[ "$(command -v cgagen)" = /usr/bin/cgagen ] || { echo "test-deb: cgagen on PATH is $(command -v cgagen)" >&2; exit 1; }
version=$(cgagen --version)
echo "test-deb: installed: $version"
[ "$version" = "cgagen $(dpkg-deb -f "$deb" Version)" ] || { echo "test-deb: --version says '$version'" >&2; exit 1; }
[ -f /usr/share/man/man1/cgagen.1 ] && [ -d /usr/share/cgagen/templates ]

cmake -S examples/consumer -B "$tmp/consumer" -G Ninja >/dev/null
grep -qx 'cgagen_DIR:PATH=/usr/share/cgagen/cmake' "$tmp/consumer/CMakeCache.txt" ||
  { echo "test-deb: the consumer found cgagen elsewhere: $(grep '^cgagen_DIR' "$tmp/consumer/CMakeCache.txt")" >&2; exit 1; }
cmake --build "$tmp/consumer"
ctest --test-dir "$tmp/consumer" --output-on-failure
