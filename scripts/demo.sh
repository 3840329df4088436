#!/usr/bin/env bash
# Sets up, builds and runs the main job (README command 1): the demo on a real character.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset default
cmake --build --preset default
exec ./build/examples/demo/cga-demo "$@"
