#!/usr/bin/env bash
# Builds cga-bench (preset default) and runs it on one core; prints the summary as Markdown with the
# machine it ran on, and writes the same text to build/bench.md (the table README carries).
#   scripts/bench.sh [--quick] [Google Benchmark flags...]
#   --quick   shorter runs (--benchmark_min_time=0.1), for a smoke check rather than figures to publish
#   scripts/bench.sh --vs-ozz OZZ_GIT_DIR: ozz-animation and cga-bench interleaved (scripts/bench-vs-ozz.sh)
# Environment: BUILD_DIR (default build), CPU (the core to pin to with taskset, default 0; empty: no pin),
#              JOBS (build parallelism, default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1-}" = --vs-ozz ]; then shift; exec bash scripts/bench-vs-ozz.sh "$@"; fi

BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-2}
CPU=${CPU-0}
args=()
for a in "$@"; do
  if [ "$a" = --quick ]; then args+=(--benchmark_min_time=0.1); else args+=("$a"); fi
done

if [ "$BUILD_DIR" = build ]; then
  cmake --preset default >/dev/null
else
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$BUILD_DIR" --target cga-bench -j "$JOBS" >&2

pin=()
if [ -n "$CPU" ] && command -v taskset >/dev/null; then pin=(taskset -c "$CPU"); fi

table=$(mktemp)
trap 'rm -f "$table"' EXIT
# Google Benchmark's own report goes to stderr, so stdout is only the Markdown below.
"${pin[@]}" "$BUILD_DIR/bench/cga-bench" --cga_markdown="$table" --benchmark_color=false "${args[@]}" >&2

model=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
cores=$(nproc --all)
load=$(cut -d' ' -f1-3 /proc/loadavg)
compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$BUILD_DIR/CMakeCache.txt" | head -1)
compiler_version=$("$compiler" --version | head -1)
{
  echo "## cga-bench results"
  echo
  echo "Machine: $model, $cores cores (run pinned to one core${CPU:+: cpu $CPU}); load average (1/5/15 min)"
  echo "at the end of the run: $load (above ~1 the figures are disturbed by other work)."
  echo "Compiler: $compiler_version, $(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$BUILD_DIR/CMakeCache.txt")."
  echo "Date: $(date -u +%Y-%m-%d). Reproduce: \`scripts/bench.sh\`."
  cat "$table"
} | tee "$BUILD_DIR/bench.md"
