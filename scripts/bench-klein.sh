#!/usr/bin/env bash
# The generated 3D PGA library (libraries/pga3.gal, cgagen --library) against klein (jeremyong/klein, hand-written
# SSE) in one process (bench/klein, cga-klein-bench): both sides checked equal on the same seeded random elements,
# then timed, one call (a dependent chain) and per element of a 2^20-element loop. Prints the Markdown table with
# the machine it ran on and the instructions each side's functions compiled to, and writes the same text to
# $BUILD_DIR/klein-bench.md.
#   KLEIN_DIR=/path/to/klein scripts/bench-klein.sh [Google Benchmark flags...]
#   (klein: a checkout, git clone https://github.com/jeremyong/klein, or a bare git mirror of it; nothing of it
#   enters this repository)
# Environment: BUILD_DIR (default build-klein, configured Release), CPU (the core to pin to with taskset,
#   default 0; empty: no pin), JOBS (build parallelism, default 2), REPETITIONS (runs per figure, the median is
#   kept; default 5), CXXFLAGS (both sides' flags, default "-O3 -march=native").
set -euo pipefail
cd "$(dirname "$0")/.."
klein=${KLEIN_DIR:-}
if [ -z "$klein" ] || [ ! -d "$klein" ]; then
  echo "bench-klein: set KLEIN_DIR to a klein checkout (git clone https://github.com/jeremyong/klein)" >&2
  exit 1
fi
klein=$(cd "$klein" && pwd)
BUILD_DIR=${BUILD_DIR:-build-klein}
JOBS=${JOBS:-2}
CPU=${CPU-0}
flags=${CXXFLAGS:-"-O3 -march=native"}

load_before=$(cut -d' ' -f1-3 /proc/loadavg)  # before the build: the other work on the machine
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DKLEIN_DIR="$klein" \
  -DKLEIN_BENCH_CXX_FLAGS="${flags// /;}" >/dev/null
cmake --build "$BUILD_DIR" --target cga-klein-bench -j "$JOBS" >&2
bin=$BUILD_DIR/bench/klein/cga-klein-bench

pin=()
if [ -n "$CPU" ] && command -v taskset >/dev/null; then pin=(taskset -c "$CPU"); fi
table=$(mktemp)
trap 'rm -f "$table"' EXIT
# The checks and Google Benchmark's lines go to stderr, so stdout is only the Markdown below.
"${pin[@]}" "$bin" --klein_markdown="$table" --klein_repetitions="${REPETITIONS:-5}" --benchmark_color=false \
  "$@" >&2
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

# Instructions of each out-of-line function (bench/klein/counted.cpp) as compiled into the binary: all, the
# floating-point arithmetic among them (an FMA counts once), the shuffles (permutes, blends, inserts,
# extracts, broadcasts, unpacks) and the calls.
count() {
  objdump -d --no-show-raw-insn --disassemble="$1" "$bin" | awk '
    /^ +[0-9a-f]+:\t/ {
      m = $2; n++
      arith = "^v?(add|sub|mul|div|sqrt|rsqrt|rcp|min|max|dp|hadd|hsub|fn?madd|fn?msub|fmaddsub|fmsubadd)"
      shuffle = "^v?(shuf|perm|unpck|blend|insert|extract|broadcast|movhl|movlh|movs[hl]dup|pshuf|movddup)"
      if (m ~ arith && m ~ /(ps|ss|pd|sd)$/) a++
      else if (m ~ shuffle) s++
      else if (m ~ /^call/) c++
    }
    END { if (n) printf "%d / %d / %d / %d", n, a, s, c; else printf "—" }'
}
row() {  # operation, function suffix (klein's, and cgagen's where it differs)
  echo "| $1 | $(count "kb_klein_$2") | $(count "kb_cgagen_${3:-$2}") |"
}

model=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
family=$(lscpu | sed -n 's/^CPU family:[[:space:]]*//p' | head -1)
cpumodel=$(lscpu | sed -n 's/^Model:[[:space:]]*//p' | head -1)
cores=$(nproc --all)
compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$BUILD_DIR/CMakeCache.txt" | head -1)
klein_rev=$(git -C "$klein" rev-parse --short HEAD 2>/dev/null ||
  git --git-dir="$klein" rev-parse --short HEAD 2>/dev/null || echo "(not a git directory)")
{
  echo "## cga-klein-bench results"
  echo
  echo "Machine: $model (family $family, model $cpumodel), $cores cores (run pinned to one core${CPU:+: cpu $CPU});"
  echo "load average (1/5/15 min) before the build $load_before, after the run $load_after (the build and the run"
  echo "count about 1; more is other work beside them, which disturbs the loops in memory most). Compiler:"
  echo "$("$compiler" --version | head -1), \`$flags\` on both sides; klein $klein_rev."
  echo "Date: $(date -u +%Y-%m-%d). Reproduce: \`KLEIN_DIR=... scripts/bench-klein.sh\`. Median of"
  echo "${REPETITIONS:-5} runs; ratio below 1: cgagen faster."
  echo
  cat "$table"
  echo
  echo "Instructions each function compiled to (all / floating-point arithmetic, an FMA once / shuffles / calls;"
  echo "objdump of the out-of-line functions of bench/klein/counted.cpp, loads and stores of the arguments included):"
  echo
  echo "| operation | klein | cgagen |"
  echo "|---|---|---|"
  row "rotor * rotor" gp_rotor_rotor
  row "motor * motor" gp_motor_motor
  row "motor(point)" sandwich_motor_point
  row "motor(line)" sandwich_motor_line
  row "motor(plane)" sandwich_motor_plane
  row "motor -> mat3x4" motor_to_mat3x4 motor_to_matrix
  row "exp(line)" exp_line
  row "log(motor)" log_motor
} | tee "$BUILD_DIR/klein-bench.md"
