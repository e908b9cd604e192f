#!/usr/bin/env bash
# What the farm costs: a frame range of the bear rendered by one hdhair-record
# process (-f) and through hdhair-farm on a single-node Slurm cluster started
# here (scripts/tests/slurm-cluster.sh), with 1 and with 2 tasks at a time,
# and Slurm's own overhead per task (an array of empty tasks). Writes
# results.md into --out. Needs root (the cluster's daemons). docs/farm.md
# holds the figures.
#   bash scripts/farm-bench.sh [--build DIR] [--data DIR] [--frames 1:96] [--width 1280] [--chunk 4] [--out DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build" data="$root/../shared/data/tressfx" frames="1:96" width=1280 chunk=4 out=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --data) data="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --width) width="$2"; shift 2 ;;
    --chunk) chunk="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    *) echo "farm-bench.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
out="${out:-$build/farm-bench}"
record="$build/bin/hdhair-record" farm="$build/bin/hdhair-farm" convert="$build/bin/hdhair-convert"
for tool in "$record" "$farm" "$convert"; do
  [[ -x "$tool" ]] || { echo "farm-bench.sh: $tool is missing (scripts/build.sh)" >&2; exit 1; }
done
[[ $EUID -eq 0 ]] || { echo "farm-bench.sh: the cluster's daemons need root" >&2; exit 1; }
mkdir -p "$out"
out="$(cd "$out" && pwd)"
stage="$out/bear.usda"
[[ -f "$stage" ]] || "$convert" "$data/bear/bear.tfx" "$stage" >/dev/null

cluster="$out/cluster"
rm -rf "$cluster"
trap 'bash "$root/scripts/tests/slurm-cluster.sh" stop "$cluster"' EXIT
eval "$(bash "$root/scripts/tests/slurm-cluster.sh" start "$cluster")"
export HDHAIR_FARM_REGISTRY="$out/registry"
args=(--camera /World/main_cam -w "$width")
count="$("$record" "$stage" "$out/probe.####.exr" -f "$frames" --check "${args[@]}" |
  python3 -c 'import json,sys; print(len(json.load(sys.stdin)["frames"]))')"

now() { date +%s.%N; }
seconds() { python3 -c "print(f'{$2 - $1:.1f}')"; }
summary() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }

echo "farm-bench: $count frames of the bear at $width px, chunks of $chunk" >&2
rm -rf "$out/one" "$out/farm1" "$out/farm2"
mkdir -p "$out/one" "$out/farm1" "$out/farm2"
start=$(now)
"$record" "$stage" "$out/one/bear.####.exr" -f "$frames" "${args[@]}" 2>"$out/one.log"
one=$(seconds "$start" "$(now)")
echo "farm-bench: one process: $one s" >&2

declare -A wall submitted
for at in 1 2; do
  start=$(now)
  job="$("$farm" submit --frames "$frames" --chunk "$chunk" --tasksAtOnce "$at" -- "$stage" \
    "$out/farm$at/bear.####.exr" "${args[@]}" 2>"$out/farm$at.log")"
  submitted[$at]=$(seconds "$start" "$(now)")
  "$farm" status "$job" --wait --poll 0.5 2>>"$out/farm$at.log"
  wall[$at]=$(seconds "$start" "$(now)")
  echo "farm-bench: farm, $at at a time: ${wall[$at]} s (submission ${submitted[$at]} s)" >&2
done
frameSeconds="$(summary "$out/farm1/bear.farm/summary.json" totalSeconds)"
median="$(summary "$out/farm1/bear.farm/summary.json" medianSeconds)"
tasks=$(( (count + chunk - 1) / chunk ))

# Slurm alone: an array of empty tasks, one at a time, from submission to the last one's end.
empty=20
start=$(now)
id="$(sbatch --parsable --array=0-$((empty - 1))%1 -o /dev/null --wrap true)"
while [[ -n "$(squeue -h -j "$id" 2>/dev/null)" ]]; do sleep 0.1; done
slurmPerTask=$(python3 -c "print(f'{($(now) - $start) / $empty:.2f}')")
# hdhair-record's start and stage read: --check reads the stage as a frame does.
start=$(now)
"$record" "$stage" "$out/probe.####.exr" -f 1 --check "${args[@]}" >/dev/null
check=$(seconds "$start" "$(now)")

python3 - "$out/results.md" <<EOF
import sys
one, w1, w2 = $one, ${wall[1]}, ${wall[2]}
count, tasks, chunk = $count, $tasks, $chunk
frame_seconds, median = $frameSeconds, $median
per_frame_one = one / count
task_overhead = (w1 - frame_seconds) / tasks
lines = [
    f"| how | wall time | per frame | against one process |",
    f"|---|---|---|---|",
    f"| one hdhair-record process, -f | {one:.1f} s | {per_frame_one:.2f} s | 1.00x |",
    f"| hdhair-farm, 1 task at a time | {w1:.1f} s | {w1 / count:.2f} s | {w1 / one:.2f}x |",
    f"| hdhair-farm, 2 tasks at a time | {w2:.1f} s | {w2 / count:.2f} s | {w2 / one:.2f}x |",
    "",
    f"- frames: {count} at $width px, chunks of {chunk} ({tasks} tasks); submission (the --check included): "
    f"${submitted[1]} s and ${submitted[2]} s",
    f"- a frame in its own hdhair-record process: median {median:.2f} s, {median / per_frame_one:.2f}x a frame of "
    f"the one process ({per_frame_one:.2f} s): the process start and stage read each frame pays",
    f"- per task, beyond its frames' processes (scheduling, the task's start, its records): "
    f"{task_overhead:.2f} s",
    f"- Slurm alone, an empty array task one at a time, submission to end: $slurmPerTask s a task",
    f"- hdhair-record --check on the bear (start and stage read, no GL): $check s",
]
open(sys.argv[1], "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
EOF
