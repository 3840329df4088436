#!/usr/bin/env bash
# Sets up, builds and runs every test (README command 2; .ci/run calls it).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset default
cmake --build --preset default
ctest --preset default
# Figures the tests measure but do not assert (timings belong in the log, not in verdicts): NumPy against the
# C++ kernel on 10^6 inputs, and the headless-Chromium runs, labelled there as SwiftShader CPU emulation.
log=build/Testing/Temporary/LastTest.log
if [ -f "$log" ]; then
  echo "== timings printed by the tests (build/Testing/Temporary/LastTest.log)"
  grep -E '^(speed |time )|SwiftShader' "$log" || echo "(none found)"
fi
