#!/usr/bin/env bash
# Value + Jacobian of a joint chain's end point, three ways in one process (bench/jacobian, cga-jacobian-bench):
# cgagen's derivative kernel (#pragma jacobian), ceres::Jet autodiff of plain C++ kinematics, and forward and
# central differences of cgagen's value kernel; for the 5-joint arm (bench/ik_arm/arm5.clu) and the 10- and
# 20-joint chains (cga::testing::joint_chain_script). All ways are checked equal on the same seeded angle
# sets before anything is timed. Prints the Markdown table with the machine it ran on and writes the same
# text to $BUILD_DIR/jacobian-bench.md. Installs nothing: Ceres (its headers, e.g. Debian's libceres-dev) and
# Eigen3 are the user's.
#   scripts/bench-jacobian.sh            (Ceres in the default prefix)
#   CERES_DIR=/opt/ceres scripts/bench-jacobian.sh
# Environment: BUILD_DIR (default build-jacobian; a new one is configured Release), CPU (the core to pin to
#   with taskset, default 0; empty: no pin), JOBS (build parallelism, default 2), CXXFLAGS (the benchmark's
#   flags, default "-O3 -march=native").
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build-jacobian}
JOBS=${JOBS:-2}
CPU=${CPU-0}
flags=${CXXFLAGS:-"-O3 -march=native"}

config=(-DCGA_BENCH_JACOBIAN=ON -DJACOBIAN_BENCH_CXX_FLAGS="${flags// /;}")
[ -n "${CERES_DIR:-}" ] && config+=(-DCERES_DIR="$CERES_DIR")
[ -f "$BUILD_DIR/CMakeCache.txt" ] || config+=(-G Ninja -DCMAKE_BUILD_TYPE=Release)
load_before=$(cut -d' ' -f1-3 /proc/loadavg)  # before the build: the other work on the machine
cmake -S . -B "$BUILD_DIR" "${config[@]}" >/dev/null
cmake --build "$BUILD_DIR" --target cga-jacobian-bench -j "$JOBS" >&2
bin=$BUILD_DIR/bench/jacobian/cga-jacobian-bench

pin=()
if [ -n "$CPU" ] && command -v taskset >/dev/null; then pin=(taskset -c "$CPU"); fi
table=$(mktemp)
trap 'rm -f "$table"' EXIT
# The checks and the per-round figures go to stderr, so stdout is only the Markdown below.
"${pin[@]}" "$bin" --markdown "$table" >&2
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

model=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$BUILD_DIR/CMakeCache.txt" | head -1)
ceres_version=$(sed -n 's/^#define CERES_VERSION_\(MAJOR\|MINOR\|REVISION\) \([0-9]*\)/\2/p' \
  "$(sed -n 's/^CGA_CERES_INCLUDE_DIR:[A-Z]*=//p' "$BUILD_DIR/CMakeCache.txt")/ceres/version.h" | paste -sd.)
{
  echo "## cga-jacobian-bench results"
  echo
  echo "Machine: $model, $(nproc --all) cores (run pinned to one core${CPU:+: cpu $CPU}); load average"
  echo "(1/5/15 min) before the build $load_before, after the run $load_after. Compiler:"
  echo "$("$compiler" --version | head -1), \`$flags\`; Ceres ${ceres_version:-?} (ceres/jet.h)."
  echo "Date: $(date -u +%Y-%m-%d). Reproduce: \`scripts/bench-jacobian.sh\`. ns per value + Jacobian (5 x n),"
  echo "median of 7 rounds over 1024 seeded angle sets; ratio below 1: cgagen faster."
  echo
  cat "$table"
} | tee "$BUILD_DIR/jacobian-bench.md"
