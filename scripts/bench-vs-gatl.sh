#!/usr/bin/env bash
# GATL side by side: times the 5-joint arm chain (bench/ik_arm/arm5.clu, ga-benchmark's "inverse kinematics"
# algorithm) as cgagen -O2 compiles it (double and float) and as GATL computes it, in one process, alternating
# rounds, and prints the ratio. GATL (laffernandes/gatl, header-only, GPL) is the user's checkout; nothing of it
# enters this repository or its build.
#   GATL_DIR=/path/to/gatl bash scripts/bench-vs-gatl.sh     (or: scripts/bench-vs-gatl.sh /path/to/gatl)
# GATL_DIR may be a checkout (with cpp/include/gatl) or a bare/mirror git directory of it.
# With GABENCH_DIR (a checkout or bare mirror of ga-developers/ga-benchmark), ga-benchmark's own script of the
# algorithm is timed too, as its source publishes it: the CluCalc block of
# source/Gaalop/SpecializedAlgorithmInverseKinematics.hpg, with only its basis names eo/ei spelt e0/einf.
# Both sides are compiled by the same compiler with the same flags: g++ -O3 -march=native (CXXFLAGS overrides).
set -euo pipefail
cd "$(dirname "$0")/.."
gatl=${1:-${GATL_DIR:-}}
[ -n "$gatl" ] || { echo "usage: GATL_DIR=DIR scripts/bench-vs-gatl.sh (a checkout of laffernandes/gatl)" >&2; exit 2; }
[ -d "$gatl" ] || { echo "bench-vs-gatl: '$gatl' is not a directory" >&2; exit 1; }
BUILD_DIR=${BUILD_DIR:-build}
work="$BUILD_DIR/vs-gatl"
mkdir -p "$work"
include="$gatl/cpp/include"
if [ ! -f "$include/gatl/ga3c.hpp" ]; then
  # A bare or mirror git directory: take the headers out of its HEAD.
  git --git-dir="$gatl" archive HEAD cpp/include | tar -x -C "$work" || { echo "bench-vs-gatl: no cpp/include/gatl/ga3c.hpp in '$gatl'" >&2; exit 1; }
  include="$work/cpp/include"
fi

cmake --preset default >/dev/null
cmake --build "$BUILD_DIR" --target cgagen -j "${JOBS:-2}" >&2
"$BUILD_DIR/gen/cgagen" -O2 --target cpp -o "$work/arm5.hpp" bench/ik_arm/arm5.clu
defs="-DCGA_WITH_GATL"
gabench=${GABENCH_DIR:-}
if [ -n "$gabench" ]; then
  hpg=source/Gaalop/SpecializedAlgorithmInverseKinematics.hpg
  if [ -f "$gabench/$hpg" ]; then text=$(cat "$gabench/$hpg"); else text=$(git --git-dir="$gabench" show "HEAD:$hpg"); fi \
    || { echo "bench-vs-gatl: no $hpg in '$gabench'" >&2; exit 1; }
  printf '%s\n' "$text" | sed -n '/#pragma clucalc begin/,/#pragma clucalc end/p' | sed '1d;$d' \
    | sed -E 's/\beo\b/e0/g; s/\bei\b/einf/g' > "$work/gabench_ik.clu"
  "$BUILD_DIR/gen/cgagen" -O2 --stats "$work/gabench_ik.clu" | grep -E '^(total|product)' | sed 's/^/gabench_ik.clu -O2 /'
  "$BUILD_DIR/gen/cgagen" -O2 --stats bench/ik_arm/arm5.clu | grep '^total' | sed 's/^/arm5.clu -O2 /'
  "$BUILD_DIR/gen/cgagen" -O2 --target cpp -o "$work/gabench_ik.hpp" "$work/gabench_ik.clu"
  defs="$defs -DCGA_WITH_GABENCH_IK"
fi
flags=${CXXFLAGS:-"-O3 -march=native"}
g++ -std=c++17 $flags $defs -I"$work" -Ibench/ik_arm -c bench/ik_arm/ik_bench.cpp -o "$work/ik_bench.o"
g++ -std=c++17 $flags -I"$include" -Ibench/ik_arm -c bench/ik_arm/ik_gatl.cpp -o "$work/ik_gatl.o"
g++ "$work/ik_bench.o" "$work/ik_gatl.o" -o "$work/ik_vs_gatl"
echo "compiler: $(g++ --version | head -1); flags: $flags; CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
"$work/ik_vs_gatl"
