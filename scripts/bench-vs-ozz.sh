#!/usr/bin/env bash
# ozz-animation side by side: builds bench/ozz (ozz's SkinningJob and pose pipeline on the same
# kind of data as cga-bench) from an ozz-animation git directory, then runs ozz and cga-bench interleaved
# (each case on both sides back to back, round after round) on one core and prints, per round and as medians
# with their spread, each method's speed as a ratio to ozz measured in the same round. Only such ratios mean
# anything on a shared machine; the absolute figures are printed to say what they rest on.
#   scripts/bench.sh --vs-ozz OZZ_GIT_DIR      (ROUNDS=N alternations, default 4; CPU as in bench.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
ozz_git=${1:?usage: scripts/bench.sh --vs-ozz OZZ_GIT_DIR (a clone or mirror of guillaumeblanc/ozz-animation)}
[ -d "$ozz_git" ] || { echo "bench-vs-ozz: '$ozz_git' is not a directory" >&2; exit 1; }
BUILD_DIR=${BUILD_DIR:-build}
ROUNDS=${ROUNDS:-4}
CPU=${CPU-0}
work="$BUILD_DIR/vs-ozz"
mkdir -p "$work"

cmake --preset default >/dev/null
cmake --build "$BUILD_DIR" --target cga-bench -j "${JOBS:-2}" >&2
ozz_bench=$(bash bench/ozz/build.sh "$ozz_git" "$(realpath "$BUILD_DIR")/ozz" | tail -1)

pin=()
if [ -n "$CPU" ] && command -v taskset >/dev/null; then pin=(taskset -c "$CPU"); fi
# Each case runs on both sides back to back (ozz first in odd rounds, cga-bench first in even ones), so a ratio
# compares runs seconds apart: this shared host's speed drifts over minutes.
cases=("1M:^skinning/random1M/[^@]*$" "64K:^skinning/random64K/" "interleaved:^skinning/interleaved1M/" "pose:^pose/paper$")
run_ozz() { "${pin[@]}" "$ozz_bench" "$1" > "$work/ozz_${r}_$1.txt"; }
# cga-bench takes the statistic ozz_bench takes (bench/ozz/common.h, time_it): the median of 7 samples of at
# least 0.25 s each.
run_cga() {
  "${pin[@]}" "$BUILD_DIR/bench/cga-bench" --benchmark_filter="$2" --benchmark_repetitions=7 --benchmark_min_time=0.25 \
    --benchmark_report_aggregates_only=true --benchmark_out="$work/cga_${r}_$1.json" \
    --benchmark_out_format=json >/dev/null 2>&1
}
for r in $(seq 1 "$ROUNDS"); do
  for c in "${cases[@]}"; do
    part=${c%%:*} filter=${c#*:}
    echo "round $r/$ROUNDS: $part" >&2
    if [ $((r % 2)) = 1 ]; then run_ozz "$part"; run_cga "$part" "$filter"
    else run_cga "$part" "$filter"; run_ozz "$part"; fi
  done
done

python3 - "$work" "$ROUNDS" <<'PY'
import json, re, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])
# The methods: the skinning table's, as cga-bench names its rows (skinning/random1M/positions/NAME), not the
# scalar generated loop (NAME-generated), the batch path pinned to another instruction set (NAME@TARGET, not
# run here) or the plain GLM loops.
def methods_of(work):
    names = [b["run_name"] for b in json.load(open(f"{work}/cga_1_1M.json"))["benchmarks"]
             if b.get("aggregate_name") == "median" and b["run_name"].startswith("skinning/random1M/positions/")]
    ms = [n.split("/")[-1] for n in names]
    return [m for m in ms if not m.startswith("plain_glm") and not m.endswith("-generated")]
methods = methods_of(work)
# (cga-bench scene, ozz line tag, title)
cases = [("random1M", "1M", "1 M random vertices"),
         ("random64K", "64K", "64 K random vertices (cache-resident)"),
         ("interleaved1M", "1M interleaved", "1 M random vertices in one 48-byte interleaved stride")]
kinds = {"positions": "P", "positions+normals": "PN"}
rows = {(scene, kind): [] for scene, _, _ in cases for kind in kinds}
pose = []
parts = ["1M", "64K", "interleaved", "pose"]
for r in range(1, rounds + 1):
    text = "".join(open(f"{work}/ozz_{r}_{p}.txt").read() for p in parts)
    ozz = {(m.group(2).strip(), m.group(1)): float(m.group(3)) for m in
           re.finditer(r"ozz SkinningJob (PN|P) +(.+?) n=\d+ inf=4: ([0-9.]+) Mvert/s", text)}
    m = re.search(r"ozz pose full: sample x2\+blend\+L2M\+invbind\s+joints=\d+:\s+([0-9.]+) ns/pose", text)
    ozz_pose_ns = float(m.group(1)) if m else None
    cga = {}
    for p in parts:
        for b in json.load(open(f"{work}/cga_{r}_{p}.json"))["benchmarks"]:
            if b.get("aggregate_name") == "median":
                cga[b["run_name"]] = b
    for scene, tag, _ in cases:
        for kind, ozz_kind in kinds.items():
            if (tag, ozz_kind) not in ozz: sys.exit(f"bench-vs-ozz: no '{ozz_kind} {tag}' line in ozz output of round {r}")
            row = {"ozz": ozz[(tag, ozz_kind)]}
            for meth in methods:
                b = cga.get(f"skinning/{scene}/{kind}/{meth}")
                row[meth] = b["items_per_second"] / 1e6 / row["ozz"] if b else None
            rows[(scene, kind)].append(row)
    b = cga.get("pose/paper")
    if b and ozz_pose_ns:
        ns = b["real_time"] * {"ns": 1, "us": 1e3, "ms": 1e6}[b["time_unit"]]
        pose.append((ozz_pose_ns, ns))

def fmt(v): return "–" if v is None else f"{v:.2f}"
summary = []
for scene, _, title in cases:
    for kind in kinds:
        rs = rows[(scene, kind)]
        print(f"\n### Skinning, {kind}: {title}, 64 joints, 4 influences, one core")
        print("| round | ozz (M vertices/s) | " + " | ".join(methods) + " |")
        print("|---|---|" + "---|" * len(methods))
        for i, row in enumerate(rs, 1):
            print(f"| {i} | {row['ozz']:.0f} | " + " | ".join(fmt(row[m]) for m in methods) + " |")
        med = []
        for m in methods:
            v = [row[m] for row in rs if row[m] is not None]
            med.append(f"**{statistics.median(v):.2f}** ({min(v):.2f}–{max(v):.2f})" if v else "–")
        ozz_med = statistics.median(r['ozz'] for r in rs)
        print(f"| median (spread) | {ozz_med:.0f} | " + " | ".join(med) + " |")
        summary.append(f"| {title}, {kind} | {ozz_med:.0f} | " + " | ".join(med) + " |")
print("\n### Summary: median speed ratio to ozz's SkinningJob in the same round (spread over rounds)")
print("| case | ozz (M vertices/s) | " + " | ".join(methods) + " |")
print("|---|---|" + "---|" * len(methods))
print("\n".join(summary))
if pose:
    print("\n### Pose: two clips sampled, blended, to model space, times inverse binds (ozz: 54 joints; cga-bench pose/paper)")
    print("| round | ozz (µs/pose) | cga paper (µs/pose) | speed ratio to ozz |")
    print("|---|---|---|---|")
    for i, (o, c) in enumerate(pose, 1):
        print(f"| {i} | {o/1e3:.2f} | {c/1e3:.2f} | {o/c:.2f} |")
print("\nRatios are speed relative to ozz in the same round (> 1 = faster than ozz).")
PY
