#!/usr/bin/env bash
# hdHair's quality presets against Blender's Cycles on the same stage
# (docs/cycles-reference.md, "Against the path-traced frame"): every preset's
# error against Cycles with full path tracing and with single scattering, the
# noise floor (two Cycles seeds), and each frame's wall time, in one run.
#   scripts/cycles-comparison.sh [--build DIR] [--out DIR] [--imageWidth N] [--samples N] STAGE[:CAMERA] ...
# Every stage is shaded with shadingModel=marschner in both renderers (Kajiya-Kay
# has no physical counterpart). Writes OUT/comparison.md and the images.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build" out="" width=256 samples=128 stages=()
fail() { echo "cycles-comparison: $*" >&2; exit 1; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --imageWidth) width="$2"; shift 2 ;;
    --samples) samples="$2"; shift 2 ;;
    -*) fail "unknown option '$1'" ;;
    *) stages+=("$1"); shift ;;
  esac
done
[[ ${#stages[@]} -gt 0 ]] || fail "name at least one stage"
out="${out:-$build/cycles-comparison}"
record="$build/bin/hdhair-record" compare="$build/bin/hdhair-compare"
[[ -x "$record" && -x "$compare" ]] || fail "$build has no bin/hdhair-record or bin/hdhair-compare"
mkdir -p "$out"
seconds() { local ms=$(( ($(date +%s%N) - $1) / 1000000 )); printf '%d.%03d' $((ms / 1000)) $((ms % 1000)); }
error() { "$compare" "$1" "$2" | python3 -c 'import json,sys; e=json.loads(sys.stdin.read()); print("%.4f (sum %.3f)" % (e["relativeRmse"], e["sumRatio"]))'; }

report="$out/comparison.md"
{
  echo "# hdHair against Cycles"
  echo
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'), commit $(git -C "$root" rev-parse --short HEAD), $(nproc) cores, ${width} px,"
  echo "Cycles ${samples} samples; relative RMSE over covered pixels (relativeColorError) and the ratio of sums."
  echo
  echo "| stage | frame | time (s) | vs Cycles full | vs Cycles single scattering |"
  echo "|---|---|---|---|---|"
} > "$report"
for entry in "${stages[@]}"; do
  stage="${entry%%:*}" camera=()
  [[ "$entry" == *:* ]] && camera=(--camera "${entry#*:}")
  name="$(basename "$stage" .usda)"
  common=(-w "$width" --exrFloat32 "${camera[@]}" -s shadingModel=marschner)
  start=$(date +%s%N)
  "$record" --reference cycles --samples "$samples" --seed 0 "${common[@]}" -- "$stage" "$out/$name.cycles.exr" 2>/dev/null
  full_time=$(seconds "$start")
  "$record" --reference cycles --samples "$samples" --seed 1 "${common[@]}" -- "$stage" "$out/$name.cycles-seed1.exr" 2>/dev/null
  start=$(date +%s%N)
  "$record" --reference cycles --samples "$samples" --maxBounces 0 "${common[@]}" -- "$stage" "$out/$name.cycles-single.exr" 2>/dev/null
  single_time=$(seconds "$start")
  echo "| $name | Cycles, full, seed 1 (noise floor) | $full_time | $(error "$out/$name.cycles.exr" "$out/$name.cycles-seed1.exr") | |" >> "$report"
  echo "| $name | Cycles, single scattering | $single_time | $(error "$out/$name.cycles.exr" "$out/$name.cycles-single.exr") | 0 |" >> "$report"
  for quality in preview default high reference; do
    start=$(date +%s%N)
    "$record" --reader embedded --quality "$quality" "${common[@]}" -- "$stage" "$out/$name.$quality.exr" 2>/dev/null
    time=$(seconds "$start")
    echo "| $name | hdHair $quality | $time | $(error "$out/$name.cycles.exr" "$out/$name.$quality.exr") | $(error "$out/$name.cycles-single.exr" "$out/$name.$quality.exr") |" >> "$report"
  done
done
cat "$report"
