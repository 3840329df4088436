#!/usr/bin/env bash
# Sets up, builds and runs every test (README command 2; .ci/run calls it).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset default
cmake --build --preset default
ctest --preset default
