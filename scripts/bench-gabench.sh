#!/usr/bin/env bash
# ga-benchmark's operation set (bench/gabench): cgagen -O2 kernels and, with GATL_DIR, GATL's versions of the
# same operations on the same seeded random blades, checked equal against each other's oracle and timed in one
# process, each case's two sides back to back. Prints a short line per case and side and the table of geomean
# ratios cgagen/GATL per operation and model; writes Google Benchmark's JSON with ga-benchmark's benchmark
# names to $BUILD_DIR/gabench/GABenchmark_cgagen.json (the shape ga-benchmark's gabm.py reads).
#   GATL_DIR=/path/to/gatl bash scripts/bench-gabench.sh            (GATL: a checkout or a bare git mirror)
#   MODELS="c3ga;e3ga" OPS="GeometricProduct;OuterProduct" REPETITIONS=30 bash scripts/bench-gabench.sh
# Without GATL_DIR, cgagen's kernels alone are checked (against the oracle) and timed. Flags of both sides:
# CXXFLAGS (default -O3 -march=native, as a ;-list for CMake). GATL (header-only, GPL) is the user's checkout;
# nothing of it enters this repository.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
models=${MODELS:-c3ga;e3ga;h3ga}
ops=${OPS:-}
flags=${CXXFLAGS:-"-O3 -march=native"}
gatl=${GATL_DIR:-}
if [ -n "$gatl" ] && [ ! -d "$gatl" ]; then
  echo "bench-gabench: GATL_DIR '$gatl' is not a directory" >&2
  exit 1
fi

cmake --preset default >/dev/null
cmake "$BUILD_DIR" -DGATL_DIR="$gatl" -DGABENCH_MODELS="$models" -DGABENCH_OPS="$ops" \
  -DGABENCH_CXX_FLAGS="${flags// /;}" >/dev/null
cmake --build "$BUILD_DIR" --target cga-gabench -j "${JOBS:-2}" >&2
mkdir -p "$BUILD_DIR/gabench"
echo "compiler: $(g++ --version | head -1); flags: $flags; CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
"$BUILD_DIR/bench/gabench/cga-gabench" --gabench_repetitions="${REPETITIONS:-30}" \
  --benchmark_out="$BUILD_DIR/gabench/GABenchmark_cgagen.json" --benchmark_out_format=json "$@"
