#!/usr/bin/env bash
# Sets up, builds and runs the main job (README command 1): the demo on a real character; it also writes the
# interactive page out/web/index.html (docs/web.md; a later --web DIR given here wins).
# Builds only cga-demo and what it is made of (the generator, the kernels it generates, the runtime, the GL
# path and the page template, which cga-demo compiles in: it reads no build output at run time), not the
# tests and benchmarks; scripts/test.sh builds everything.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset default
cmake --build --preset default --target cga-demo
exec ./build/examples/demo/cga-demo --web out/web "$@"
