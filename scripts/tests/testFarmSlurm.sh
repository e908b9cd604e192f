#!/usr/bin/env bash
# hdhair-farm on a real Slurm: starts a single-node cluster (munged, slurmctld,
# slurmd: scripts/tests/slurm-cluster.sh) in a temporary folder, renders
# testenv/farm's stages through it, and stops every daemon it started when it
# ends, whatever happened. Needs root (the daemons) and Debian's slurm-wlm and
# munge (scripts/debian-packages.txt).
#   testFarmSlurm.sh HDHAIR_FARM HDHAIR_RECORD
# Checks (docs/farm.md, "Tests"):
#  1. 24 frames through the farm equal the same frames rendered locally by
#     hdhair-record, pixel for pixel in the EXR; --wait prints progress;
#     `status JOB` reports the ended job; every frame has its --stats.
#  2. A second job into a running job's folder is refused. A job cancelled
#     partway (scancel) and resubmitted renders only the missing frames, and
#     the final set is complete and equal.
#  3. A stage whose frame 7 has a broken camera: the job ends non-zero, frame 7
#     is named with its task, log and error, the other 23 frames are written.
#  4. Bad input (frame spec, missing stage, output without '#', --frames given
#     to hdhair-record, an unreachable controller): one error line, exit 1,
#     nothing submitted.
set -euo pipefail
farm="$(realpath "$1")"
record="$(realpath "$2")"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
stages="$root/testenv/farm"
cluster_script="$root/scripts/tests/slurm-cluster.sh"

if [[ $EUID -ne 0 ]]; then
  echo "FAIL: starting munged, slurmctld and slurmd needs root" >&2
  exit 1
fi
for tool in munged slurmctld slurmd sbatch squeue scancel scontrol idiff; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool is missing (scripts/install-dependencies.sh)" >&2; exit 1; }
done

work="$(mktemp -d /tmp/hdhair-farm-slurm.XXXXXX)"
cleanup() {
  bash "$cluster_script" stop "$work/cluster" || true
  rm -rf "$work"
}
trap cleanup EXIT
started_all=$SECONDS
started=$SECONDS
eval "$(bash "$cluster_script" start "$work/cluster")"
echo "cluster up in $((SECONDS - started)) s ($SLURM_CONF)"
export HDHAIR_FARM_REGISTRY="$work/registry"
cd "$work"

failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
# The jobs Slurm knows of (ended ones stay for MinJobAge): a refused
# submission must not add one.
job_count() { scontrol -o show jobs 2>/dev/null | grep -c '^JobId=' || true; }
# Every frame of $1 equals the local render's, pixel for pixel.
same_as_local() {
  local folder="$1" frame name
  for frame in $(seq 1 24); do
    name="$(printf 'frame.%04d.exr' "$frame")"
    if [[ ! -f "$folder/$name" ]]; then fail "$folder/$name was not written"; continue; fi
    idiff -q -fail 0 -failpercent 0 -warn 0 "local/$name" "$folder/$name" >/dev/null ||
      fail "$folder/$name differs from the local render"
  done
}
record_args=(--reader embedded --camera /World/main_cam -w 64)

# The reference: one hdhair-record process, every frame.
mkdir -p local bad
"$record" "$stages/animated.usda" local/frame.####.exr -f 1:24 "${record_args[@]}"

# 1. The whole range, waited for.
mkdir -p whole
rc=0
"$farm" submit --frames 1:24 --chunk 4 --wait --poll 0.5 -- "$stages/animated.usda" whole/frame.####.exr \
  "${record_args[@]}" 2>whole.log || rc=$?
[[ $rc -eq 0 ]] || fail "the whole range exited $rc: $(tail -n 3 whole.log)"
grep -q 'frames done' whole.log || fail "--wait printed no progress line"
grep -q 'all 24 frames complete' whole.log || fail "no 'all 24 frames complete' at the end: $(tail -n 3 whole.log)"
same_as_local whole
[[ $(ls whole/frame.farm/stats/*.json 2>/dev/null | wc -l) -eq 24 ]] || fail "not every frame has its --stats JSON"
jq_frames="$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["framesRendered"])' whole/frame.farm/summary.json)"
[[ "$jq_frames" == 24 ]] || fail "summary.json says $jq_frames frames rendered, not 24"
whole_job="$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["slurmJobIds"][-1])' whole/frame.farm/job.json)"
rc=0
"$farm" status "$whole_job" >/dev/null 2>status.log || rc=$?
[[ $rc -eq 0 ]] && grep -q '24/24 frames done' status.log || fail "status $whole_job: exit $rc, $(cat status.log)"
rc=0
"$farm" submit --frames 1:24 -- "$stages/animated.usda" whole/frame.####.exr "${record_args[@]}" \
  >/dev/null 2>again.log || rc=$?
[[ $rc -eq 0 ]] && grep -q 'nothing to submit' again.log || fail "a complete range was submitted again: $(cat again.log)"

# 2. Cancelled partway, then resubmitted: only the missing frames render.
mkdir -p resumed
first_job="$("$farm" submit --frames 1:24 --chunk 2 --tasksAtOnce 1 -- "$stages/animated.usda" \
  resumed/frame.####.exr "${record_args[@]}" 2>/dev/null)"
for _ in $(seq 1 600); do
  [[ $(grep -l '"state": "done"' resumed/frame.farm/frames/*.json 2>/dev/null | wc -l) -ge 5 ]] && break
  sleep 0.1
done
# A second job into the same folder while the first runs is refused.
rc=0
"$farm" submit --frames 1:24 -- "$stages/animated.usda" resumed/frame.####.exr "${record_args[@]}" \
  >/dev/null 2>twice.log || rc=$?
[[ $rc -eq 1 ]] && grep -q "job $first_job still renders into" twice.log ||
  fail "a second job into a running job's folder: exit $rc, $(cat twice.log)"
scancel "$first_job"
for _ in $(seq 1 300); do
  [[ -z "$(squeue -h -j "$first_job" 2>/dev/null)" ]] && break
  sleep 0.1
done
kept=$(ls resumed/frame.*.exr 2>/dev/null | wc -l)
echo "cancelled job $first_job with $kept of 24 frames written"
if [[ $kept -lt 5 || $kept -ge 24 ]]; then fail "the cancelled job wrote $kept frames, not 5 to 23"; fi
rc=0
"$farm" status "$first_job" >/dev/null 2>cancelled.log || rc=$?
[[ $rc -eq 1 ]] && grep -q 'were not rendered' cancelled.log && grep -q -- '--frames' cancelled.log ||
  fail "status of the cancelled job: exit $rc, $(cat cancelled.log)"
rc=0
"$farm" submit --frames 1:24 --chunk 2 --wait --poll 0.5 -- "$stages/animated.usda" resumed/frame.####.exr \
  "${record_args[@]}" 2>resumed.log || rc=$?
[[ $rc -eq 0 ]] || fail "the resubmission exited $rc: $(tail -n 3 resumed.log)"
second_rendered="$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["framesRendered"])' \
  resumed/frame.farm/summary.json)"
[[ "$second_rendered" -eq $((24 - kept)) ]] ||
  fail "the resubmission rendered $second_rendered frames, not the $((24 - kept)) missing"
grep -q "$((24 - kept)) frames in" resumed.log || fail "the resubmission did not submit only the missing frames"
same_as_local resumed

# 3. Frame 7 fails; the rest are written.
mkdir -p broken
rc=0
# With a registry that cannot be written: a warning, and the job runs.
HDHAIR_FARM_REGISTRY=/proc/hdhair-farm-registry \
  "$farm" submit --frames 1:24 --chunk 4 --wait --poll 0.5 -- "$stages/broken-camera-at-7.usda" \
  broken/frame.####.exr "${record_args[@]}" 2>broken.log || rc=$?
[[ $rc -eq 1 ]] || fail "a job with a failed frame exited $rc"
grep -q 'warning: job .* is not in the job registry' broken.log || fail "no warning for the unwritable registry"
grep -q 'frame 7 failed in task 1 (log .*/logs/task-1.log): .*main_cam.focalLength' broken.log ||
  fail "frame 7's failure is not named with its task, log and error: $(grep -i fail broken.log || true)"
grep -q -- '--frames 7 ' broken.log || fail "no --frames 7 to resubmit: $(tail -n 2 broken.log)"
grep -q 'focalLength' broken/frame.farm/logs/task-1.log || fail "task 1's log lacks hdhair-record's error"
[[ ! -e broken/frame.0007.exr ]] || fail "frame 7 was written"
[[ $(ls broken/frame.*.exr | wc -l) -eq 23 ]] || fail "not the 23 other frames written"

# 4. Refused before anything is submitted.
before=$(job_count)
refused() {
  local what="$1" expected="$2" rc=0
  shift 2
  "$farm" submit "$@" >/dev/null 2>refused.log || rc=$?
  if [[ $rc -ne 1 ]]; then fail "$what: exit $rc, not 1"; fi
  [[ $(wc -l <refused.log) -eq 1 ]] && grep -q "^hdhair-farm: error: .*$expected" refused.log ||
    fail "$what: not one error line with '$expected': $(cat refused.log)"
}
refused "a bad frame spec" "bad frame spec" --frames 1:x -- "$stages/animated.usda" bad/frame.####.exr "${record_args[@]}"
refused "a missing stage" "missing.usda" --frames 1:4 -- "$work/missing.usda" bad/frame.####.exr "${record_args[@]}"
refused "an output without '#'" "no '#'" --frames 1 -- "$stages/animated.usda" bad/frame.exr "${record_args[@]}"
refused "--frames given to hdhair-record" "give the frames to hdhair-farm" --frames 1:4 -- "$stages/animated.usda" \
  bad/frame.####.exr -f 1:4 "${record_args[@]}"
unreachable="$(bash "$cluster_script" conf-unreachable "$work/unreachable")"
started=$SECONDS
conf="$SLURM_CONF"
eval "$unreachable"
refused "an unreachable controller" "Unable to contact slurm controller" --frames 1:4 -- \
  "$stages/animated.usda" bad/frame.####.exr "${record_args[@]}"
export SLURM_CONF="$conf"
echo "an unreachable controller was reported in $((SECONDS - started)) s"
[[ $(job_count) -eq $before ]] || fail "a refused submission reached Slurm ($before jobs before, $(job_count) after)"
[[ ! -e bad/frame.farm ]] || fail "a refused submission left its job folder"

echo "farm tests done in $((SECONDS - started_all)) s with $failures failures"
[[ $failures -eq 0 ]]
