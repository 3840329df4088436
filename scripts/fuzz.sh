#!/usr/bin/env bash
# Builds the libFuzzer target over the script front end (clang, ASan, UBSan) and runs it for a bounded time
# on a seed corpus of the bundled scripts. Exits non-zero on any crash, hang, leak or sanitizer report.
# Usage: bash scripts/fuzz.sh [SECONDS]   (default 60)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
cmake -S fuzz -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz --target fuzz_script
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
corpus=build-fuzz/corpus
mkdir -p "$corpus"
for f in runtime/scripts/*.clu tests/gen/scripts/*.clu; do [ -f "$f" ] && cp "$f" "$corpus/"; done
# Crashes found earlier live in fuzz/regressions and are replayed first (they are also regression tests).
if compgen -G "fuzz/regressions/*" >/dev/null; then
  ./build-fuzz/fuzz_script fuzz/regressions/*
fi
./build-fuzz/fuzz_script "$corpus" -max_total_time="$seconds" -max_len=2048 -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix=build-fuzz/ -print_final_stats=1
