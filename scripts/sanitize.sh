#!/usr/bin/env bash
# Builds everything with AddressSanitizer + UndefinedBehaviorSanitizer (preset "sanitize") and runs the test
# suite under them (all but the two groups named below). Leaks inside CLN/GiNaC's own caches are suppressed (fuzz/lsan.supp); any other report fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
cmake --preset sanitize
cmake --build --preset sanitize
# tests/library is not even built here (tests/CMakeLists.txt says why). Three run in the normal pass only
# (scripts/test.sh): tests/targets (the emitted Python, JavaScript,
# Rust, OpenCL, HLSL, ... run by their own toolchains; under ASan its reference step alone takes 260 s
# against 19 s), gen/test_determinism (21 cgagen processes per bundled script, 87 s each under ASan) and
# test_stage's 1000-random-input sweep over every bundled script (325 s under ASan against 20 s). All three
# repeat generator paths that the sanitized gen/ and kernels/ tests and the fuzz gate already cover; the
# other test_stage cases stay in.
ctest --preset sanitize -E '^targets/|^gen/test_determinism/|^gen/test_stage/prepare then body equals'
