#!/usr/bin/env bash
# Installs the build (default build/, as scripts/test.sh leaves it) into a temporary prefix, moves the prefix
# elsewhere (nothing may depend on the install path), then configures, builds and tests the out-of-tree
# project examples/consumer against it: find_package(cgagen 0.2), cgagen_generate() with the installed cgagen
# and templates, cgagen::runtime. .ci/run calls it after scripts/test.sh; about 10 s.
# Environment: BUILD_DIR (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
[ -f "$BUILD_DIR/CMakeCache.txt" ] || { echo "test-install: no $BUILD_DIR (run scripts/test.sh first)" >&2; exit 2; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/cgagen-install.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

cmake --install "$BUILD_DIR" --prefix "$tmp/prefix" >/dev/null
mv "$tmp/prefix" "$tmp/moved"   # relocation: the package and cgagen's template lookup are prefix-relative
prefix=$tmp/moved
version=$("$prefix/bin/cgagen" --version)
echo "test-install: $version installed and moved to $prefix"
# A marker in the relocated templates shows that the installed cgagen reads them, not the source tree's.
marker="// test-install: relocated templates"
printf '%s\n' "$marker" >>"$prefix/share/cgagen/templates/cpp/file.hpp.in"

cmake -S examples/consumer -B "$tmp/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$tmp/consumer"
grep -qxF "$marker" "$tmp/consumer/generated/reflect.hpp" ||
  { echo "test-install: the installed cgagen did not use $prefix/share/cgagen/templates" >&2; exit 1; }
ctest --test-dir "$tmp/consumer" --output-on-failure
