#!/usr/bin/env bash
# Builds bench/ozz/ozz_bench.cc (ozz-animation SkinningJob + pose pipeline, AVX2+FMA, -O3) against the sources
# of ozz-animation taken from a clone or mirror of guillaumeblanc/ozz-animation; scripts/bench.sh --vs-ozz runs it.
# usage: build.sh MIRROR_GIT_DIR OUTDIR   -> OUTDIR/ozz_bench (run: ozz_bench [skin|pose|1M|64K|interleaved])
set -euo pipefail
mirror=$1; out=$2; here=$(cd "$(dirname "$0")" && pwd)
src=$out/ozz-src; mkdir -p "$src" "$out/ozz-build"
[ -f "$src/CMakeLists.txt" ] || git --git-dir="$mirror" archive HEAD CMakeLists.txt build-utils include src extern LICENSE.md | tar -x -C "$src"
flags="-O3 -mavx2 -mfma -DNDEBUG"
cmake -S "$src" -B "$out/ozz-build" -G Ninja -DCMAKE_BUILD_TYPE=Release -Dozz_build_tools=OFF -Dozz_build_fbx=OFF \
  -Dozz_build_gltf=OFF -Dozz_build_samples=OFF -Dozz_build_howtos=OFF -Dozz_build_tests=OFF -Dozz_build_postfix=OFF \
  -DCMAKE_CXX_FLAGS="$flags" >/dev/null
cmake --build "$out/ozz-build" --target ozz_animation ozz_animation_offline ozz_geometry ozz_base >/dev/null
libs=$(find "$out/ozz-build" -name 'libozz_animation_offline.a' -o -name 'libozz_animation.a' -o -name 'libozz_geometry.a' -o -name 'libozz_base.a' | sort -r)
g++ -std=c++17 $flags -I"$src/include" -I"$here" "$here/ozz_bench.cc" \
  $(find "$out/ozz-build" -name 'libozz_animation_offline.a') $(find "$out/ozz-build" -name 'libozz_animation.a') \
  $(find "$out/ozz-build" -name 'libozz_geometry.a') $(find "$out/ozz-build" -name 'libozz_base.a') -o "$out/ozz_bench"
echo "$out/ozz_bench"
