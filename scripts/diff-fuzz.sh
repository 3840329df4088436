#!/usr/bin/env bash
# The differential fuzzer (tests/diff): random CluScripts through cgagen at -O0/-O1/-O2 against an oracle
# interpreter.
#
#   scripts/diff-fuzz.sh                 what CI runs: seed 1, 200 programs, a sample of the C++ compiled.
#   scripts/diff-fuzz.sh --explore N     N programs from a random seed (printed); finds are written to
#                                        build/tests/diff/explore/finds/. Each find is to be reduced, fixed, and
#                                        committed to tests/diff/regressions/ (its first line keeps the
#                                        "// inputs: ..." line), which every run replays.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build --target diff_fuzz >/dev/null
exe=build/tests/diff/diff_fuzz
case "${1:-}" in
  "") exec "$exe" --seed 1 --count 200 --compile-every 40 --work-dir build/tests/diff/work --regressions tests/diff/regressions ;;
  --explore)
    [ $# -ge 2 ] || { echo "diff-fuzz.sh: --explore needs a number of programs" >&2; exit 2; }
    seed=${DIFF_SEED:-$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')}
    echo "diff-fuzz.sh: seed $seed"
    exec "$exe" --seed "$seed" --count "$2" --compile-every 50 --work-dir build/tests/diff/explore --regressions tests/diff/regressions ;;
  *) echo "usage: scripts/diff-fuzz.sh [--explore N]" >&2; exit 2 ;;
esac
