#!/usr/bin/env bash
# Sets up, builds and runs the main job (README command 1): the demo on a real character; it also writes the
# interactive page out/web/index.html (docs/web.md; a later --web DIR given here wins).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset default
cmake --build --preset default
exec ./build/examples/demo/cga-demo --web out/web "$@"
