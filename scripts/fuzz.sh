#!/usr/bin/env bash
# Fuzzing of the generator (front end, expander, optimizer) with libFuzzer under ASan + UBSan.
#
#   scripts/fuzz.sh                      CI gate: the same verdict for the same commit on every machine.
#                                        Replays every committed regression (fuzz/regressions/, and the bad
#                                        scripts of the test suite), then fuzzes from the bundled scripts with a
#                                        fixed seed and a fixed number of runs (FUZZ_SEED, FUZZ_RUNS).
#   scripts/fuzz.sh --explore SECONDS    Open-ended exploration outside CI: random seed, a corpus kept across
#                                        runs in build-fuzz/explore-corpus, finds written to build-fuzz/finds/.
#                                        Each find is to be minimized (the command is printed), fixed, and
#                                        committed under fuzz/regressions/ (CI replays that folder).
# Exits non-zero on any crash, timeout, leak or sanitizer report.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=ci
seconds=0
case "${1:-}" in
  "") ;;
  --explore)
    [ $# -ge 2 ] || { echo "fuzz.sh: --explore needs a number of seconds" >&2; exit 2; }
    mode=explore; seconds=$2 ;;
  *) echo "usage: scripts/fuzz.sh [--explore SECONDS]" >&2; exit 2 ;;
esac
seed=${FUZZ_SEED:-1}
runs=${FUZZ_RUNS:-3000}

cmake -S fuzz -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz --target fuzz_script
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
# Per input: the generator's work budget keeps every input far below this (the slowest known take about 0.1 s
# of CPU unsanitized and 1 s under ASan); the margin is for a loaded machine, whose wall clock is what counts.
limits=(-timeout=25 -rss_limit_mb=2048 -max_len=4096)

seeds() {  # a fresh corpus of the bundled scripts in $1
  rm -rf "$1"
  mkdir -p "$1"
  for f in runtime/scripts/*.clu tests/gen/scripts/*.clu examples/*/*.clu; do [ -f "$f" ] && cp "$f" "$1/"; done
}

if [ "$mode" = ci ]; then
  replay=(tests/gen/scripts/bad/*.clu)
  if compgen -G "fuzz/regressions/*" >/dev/null; then replay+=(fuzz/regressions/*); fi
  echo "fuzz.sh: replaying ${#replay[@]} regression inputs"
  ./build-fuzz/fuzz_script "${limits[@]}" "${replay[@]}"
  seeds build-fuzz/ci-corpus
  echo "fuzz.sh: fuzzing with -seed=$seed -runs=$runs"
  # Without address randomization: GiNaC orders terms by hashes that mix in addresses, so with ASLR the
  # coverage, and with it the fuzzer's path, would differ from run to run. This way two runs of the same
  # commit in the same checkout folder execute the same inputs (their coverage lines match; only the timings
  # differ). From another folder the path differs (the binary's layout moves with it), the verdict does not.
  # -reload=0: by default libFuzzer rereads the corpus folder on a wall-clock timer, which makes the path timing-dependent.
  setarch "$(uname -m)" -R ./build-fuzz/fuzz_script build-fuzz/ci-corpus "${limits[@]}" -seed="$seed" -runs="$runs" -reload=0 \
    -artifact_prefix=build-fuzz/ -print_final_stats=1
else
  corpus=build-fuzz/explore-corpus
  [ -d "$corpus" ] || seeds "$corpus"
  mkdir -p build-fuzz/finds
  echo "fuzz.sh: exploring for $seconds s; finds go to build-fuzz/finds/"
  status=0
  # Fork mode keeps exploring after a find (each one is written to build-fuzz/finds/ and listed below).
  ./build-fuzz/fuzz_script "$corpus" "${limits[@]}" -max_total_time="$seconds" -fork=1 -ignore_crashes=1 \
    -ignore_timeouts=1 -ignore_ooms=1 -artifact_prefix=build-fuzz/finds/ -print_final_stats=1 || status=$?
  if compgen -G "build-fuzz/finds/*" >/dev/null; then
    echo "fuzz.sh: finds (minimize each with: ./build-fuzz/fuzz_script -minimize_crash=1 -runs=20000" \
         "-exact_artifact_path=fuzz/regressions/NAME.clu FIND; fix; commit it):"
    ls -l build-fuzz/finds/
  fi
  exit "$status"
fi
