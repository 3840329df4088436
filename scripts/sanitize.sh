#!/usr/bin/env bash
# Builds everything with AddressSanitizer + UndefinedBehaviorSanitizer (preset "sanitize") and runs the whole
# test suite under them. Leaks inside CLN/GiNaC's own caches are suppressed (fuzz/lsan.supp); any other report fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
cmake --preset sanitize
cmake --build --preset sanitize
ctest --preset sanitize
