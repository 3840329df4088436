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
# The bad scripts of the test suite (fuzzer finds among them: abs_of_quotient.clu was a timeout) and any
# crash kept in fuzz/regressions are replayed first, under the same time limit as the fuzzing run.
replay=(tests/gen/scripts/bad/*.clu)
if compgen -G "fuzz/regressions/*" >/dev/null; then replay+=(fuzz/regressions/*); fi
./build-fuzz/fuzz_script -timeout=10 -rss_limit_mb=2048 "${replay[@]}"
./build-fuzz/fuzz_script "$corpus" -max_total_time="$seconds" -max_len=2048 -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix=build-fuzz/ -print_final_stats=1
