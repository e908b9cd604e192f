#!/usr/bin/env bash
# hdHair beside Storm on the same TressFX grooms: for each asset at every
# complexity, in one run, the whole process of
#   usdrecord --renderer GL           (Storm, under xvfb-run or on --display),
#   usdrecord --renderer HdHair --disableGpu   (the plugin),
#   hdhair-record                     (its default reader),
# at the same camera and width, each timed by /usr/bin/time (wall seconds and
# peak RSS), with the frame's own time (through usdrecord, the
# FrameRecorder.Record() call, timed alike for both renderers by
# usdrecord-timed.py; hdhair-record, its passes from --stats), --runs
# times each in turn (the three renderers one after the other, then again),
# reporting medians. Writes results.csv (a row a run) and results.md (a
# Markdown table with hdHair/Storm ratios per row: runs on a shared machine
# are noisy, so ratios of medians measured side by side are what we report;
# and a memory table: hdhair-record's peak RSS beside the GPU
# memory its --stats report, per authored control vertex) into the output
# folder, and prints the tables.
#
#   scripts/storm-comparison.sh [--build-dir DIR] [--openusd PREFIX] [--assets DIR] [--out DIR]
#                               [--data DIR] [--width N] [--complexities "low medium high veryhigh"]
#                               [--stages "ratboy bear"] [--display DISPLAY] [--runs N]
# --build-dir: an hdHair build with the plugin (scripts/build.sh --openusd ...; default build/):
#   bin/hdhair-record, bin/hdhair-convert and plugin/usd/hdHair/resources are used from it.
# --openusd: the OpenUSD prefix whose bin/usdrecord runs (default $PXR_ROOT, else scripts/find-openusd.sh).
# --assets: where the converted stages are cached (default BUILD/storm-comparison/assets): converted
#   once with hdhair-convert, reused while newer than their .tfx.
# --out: results, logs and images (default BUILD/storm-comparison).
# --data: the TressFX samples (default ../shared/data/tressfx beside the repository).
# --runs: runs of each renderer per stage and complexity, interleaved (default 1); the table
#   gives the median of each figure.
# --display: an X display for Storm (one on a GPU's driver) instead of a fresh Xvfb per run, whose
#   GLX is Mesa's llvmpipe: on a headless GPU machine Storm under Xvfb renders in software.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build"
prefix="${PXR_ROOT:-}"
assets="" out="" data="$root/../shared/data/tressfx"
width=1280
complexities="low medium high veryhigh"
stages="ratboy bear"
display=""
runs=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build="$2"; shift 2 ;;
    --openusd) prefix="$2"; shift 2 ;;
    --assets) assets="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --data) data="$2"; shift 2 ;;
    --width) width="$2"; shift 2 ;;
    --complexities) complexities="$2"; shift 2 ;;
    --stages) stages="$2"; shift 2 ;;
    --display) display="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    -h|--help) sed -n '2,30p' "$0"; exit 0 ;;
    *) echo "storm-comparison: error: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
fail() { echo "storm-comparison: error: $*" >&2; exit 1; }

[[ -d "$build" ]] || fail "no build folder '$build' (build with scripts/build.sh --openusd PREFIX)"
build="$(cd "$build" && pwd)"
assets="${assets:-$build/storm-comparison/assets}"
out="${out:-$build/storm-comparison}"
[[ -n "$prefix" ]] || prefix="$(bash "$root/scripts/find-openusd.sh")"
[[ -n "$prefix" ]] || fail "no OpenUSD: pass --openusd PREFIX or set PXR_ROOT"
record="$build/bin/hdhair-record" convert="$build/bin/hdhair-convert"
plugin="$build/plugin/usd/hdHair/resources"
usdrecord="$prefix/bin/usdrecord"
[[ -x "$record" && -x "$convert" ]] || fail "$build has no bin/hdhair-record or bin/hdhair-convert (cmake --build $build --target hdhair-record hdhair-convert)"
[[ -f "$plugin/plugInfo.json" ]] || fail "$build has no plugin at $plugin (build with --openusd so that the HdHair plugin is built)"
[[ -x "$usdrecord" ]] || fail "no usdrecord at $usdrecord"
[[ -x /usr/bin/time ]] || fail "/usr/bin/time is missing (Debian package 'time'; scripts/install-dependencies.sh installs it)"
[[ -n "$display" ]] || command -v xvfb-run >/dev/null || fail "xvfb-run is missing (Debian packages 'xvfb' and 'xauth'; scripts/install-dependencies.sh installs them)"
for level in $complexities; do
  case "$level" in low|medium|high|veryhigh) ;; *) fail "--complexities: '$level' is not low, medium, high or veryhigh" ;; esac
done
[[ "$width" =~ ^[0-9]+$ ]] || fail "--width must be a number of pixels, not '$width'"
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || fail "--runs must be a whole number of runs, at least 1, not '$runs'"

# The TressFX sample of each stage name.
tfxOf() {
  case "$1" in
    ratboy) echo "$data/ratboy/Ratboy_mohawk.tfx" ;;
    bear) echo "$data/bear/bear.tfx" ;;
    sintel) echo "$data/sintel/sintel_hair.tfx" ;;
    *) fail "--stages: no TressFX sample called '$1' (ratboy, bear, sintel)" ;;
  esac
}

mkdir -p "$assets" "$out/logs" "$out/images"
for stage in $stages; do
  tfx="$(tfxOf "$stage")"
  [[ -f "$tfx" ]] || fail "missing $tfx (--data names the TressFX folder)"
  if [[ ! "$assets/$stage.usda" -nt "$tfx" ]]; then
    "$convert" "$tfx" "$assets/$stage.usda" >"$out/logs/convert-$stage.log" 2>&1 ||
      fail "hdhair-convert failed on $tfx (see $out/logs/convert-$stage.log)"
  fi
done

export PYTHONPATH="$prefix/lib/python${PYTHONPATH:+:$PYTHONPATH}"
export HOME="${HOME:-/tmp}"
csv="$out/results.csv"
echo "stage,spans,complexity,renderer,seconds,peak_kb,frame_ms,status,gpu_bytes,strand_bytes,authored_points,run" >"$csv"
failures=()

# run NAME LOG -- COMMAND...: times COMMAND's whole process; sets seconds, peakKb, status.
run() {
  local name="$1" log="$2"; shift 3
  local timing="$out/logs/$name.time"
  rm -f "$timing"
  if /usr/bin/time -f '%e %M' -o "$timing" "$@" >"$log" 2>&1; then status=ok; else status=failed; failures+=("$name"); fi
  read -r seconds peakKb < <(tail -n 1 "$timing" 2>/dev/null || echo "nan nan")
}

timedUsdrecord="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/usdrecord-timed.py"
# recordedFrame LOG: the milliseconds usdrecord-timed.py printed for the frame.
recordedFrame() { sed -n 's/^usdrecord-timed: frame .* took \([0-9.]*\) ms$/\1/p' "$1" | tail -n 1; }

started="$(date -u '+%Y-%m-%d %H:%M UTC')"
loadStart="$(cut -d' ' -f1-3 /proc/loadavg)"
glRenderer=""
for stage in $stages; do
  for level in $complexities; do
   for ((rep = 1; rep <= runs; ++rep)); do
    name="$stage-$level"
    echo "storm-comparison: $name (run $rep of $runs)" >&2
    # hdhair-record first: its --stats give the span count and the GL renderer.
    stats="$out/logs/$name.hdhair-record.json"
    run "$name.hdhair-record" "$out/logs/$name.hdhair-record.log" -- \
      env PXR_PLUGINPATH_NAME="$plugin" "$record" --camera /World/main_cam --imageWidth "$width" \
      --complexity "$level" --stats "$stats" "$assets/$stage.usda" "$out/images/$name.hdhair-record.png"
    spans="$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["frames"][0].get("segments", ""))' "$stats" 2>/dev/null || true)"
    [[ -n "$glRenderer" ]] || glRenderer="$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["frames"][0].get("gl", ""))' "$stats" 2>/dev/null || true)"
    # The frame: the renderer's own passes, without reading the stage, the
    # CPU display transform and writing the image.
    frame="$(/usr/bin/python3 -c '
import json, sys
passes = json.load(open(sys.argv[1]))["frames"][0]["passes"]
print(round(sum(p["milliseconds"] for p in passes
                if p["name"] not in ("readScene", "writeImage", "displayTransform (cpu)")), 1))' "$stats" 2>/dev/null || true)"
    # The GPU memory the frame holds (hdHair/gl/GpuMemory.h) and the points
    # the stage authors, for bytes per control vertex.
    memory="$(/usr/bin/python3 -c '
import json, sys
frame = json.load(open(sys.argv[1]))["frames"][0]
gpu = frame.get("gpuMemory", {})
print(",".join(str(v) for v in (gpu.get("total", ""), gpu.get("strandGeometry", ""),
                                 frame.get("authoredPoints", ""))))' "$stats" 2>/dev/null || echo ",,")"
    echo "$stage,$spans,$level,hdhair-record,$seconds,$peakKb,$frame,$status,$memory,$rep" >>"$csv"

    # Through usdrecord, either renderer's frame is its FrameRecorder.Record()
    # call, timed alike by usdrecord-timed.py: sync, render, read back, write.
    log="$out/logs/$name.usdrecord-hdhair.log"
    run "$name.usdrecord-hdhair" "$log" -- \
      env PXR_PLUGINPATH_NAME="$plugin" /usr/bin/python3 "$timedUsdrecord" "$usdrecord" --renderer HdHair \
      --disableGpu --camera /World/main_cam --imageWidth "$width" --complexity "$level" "$assets/$stage.usda" \
      "$out/images/$name.usdrecord-hdhair.png"
    frame="$(recordedFrame "$log")"
    echo "$stage,$spans,$level,usdrecord-hdhair,$seconds,$peakKb,$frame,$status,,,,$rep" >>"$csv"

    # Storm needs an X display for its GL context: --display's, or one that
    # xvfb-run starts, with /usr/bin/time inside it timing usdrecord alone,
    # not Xvfb's start.
    storm=(/usr/bin/python3 "$timedUsdrecord" "$usdrecord" --renderer GL --camera /World/main_cam
           --imageWidth "$width" --complexity "$level" "$assets/$stage.usda" "$out/images/$name.usdrecord-storm.png")
    if [[ -n "$display" ]]; then
      run "$name.usdrecord-storm" "$out/logs/$name.usdrecord-storm.log" -- env DISPLAY="$display" "${storm[@]}"
    else
      run "$name.usdrecord-storm" "$out/logs/$name.usdrecord-storm.log" -- \
        xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/time -f '%e %M' -o "$out/logs/$name.storm.time" "${storm[@]}"
      [[ "$status" == ok ]] && read -r seconds peakKb < <(tail -n 1 "$out/logs/$name.storm.time")
    fi
    echo "$stage,$spans,$level,usdrecord-storm,$seconds,$peakKb,$(recordedFrame "$out/logs/$name.usdrecord-storm.log"),$status,,,,$rep" >>"$csv"
   done
  done
done
loadEnd="$(cut -d' ' -f1-3 /proc/loadavg)"

/usr/bin/python3 - "$csv" "$out/results.md" "$started" "$loadStart" "$loadEnd" "$width" "$glRenderer" "$runs" <<'EOF'
import csv, os, platform, statistics, sys
path, markdown, started, loadStart, loadEnd, width, gl, runCount = sys.argv[1:9]
# One row per stage, complexity and renderer: the median of its runs' time,
# peak RSS and frame (a run that failed fails the row).
grouped = {}
for r in csv.DictReader(open(path)):
    grouped.setdefault((r["stage"], r["complexity"], r["renderer"]), []).append(r)
rows = []
for group in grouped.values():
    row = dict(group[0])
    row["status"] = "ok" if all(r["status"] == "ok" for r in group) else "failed"
    for key in ("seconds", "peak_kb", "frame_ms"):
        values = [float(r[key]) for r in group if r[key] not in ("", "nan")]
        row[key] = str(statistics.median(values)) if values else ""
    rows.append(row)
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
runs = {}
for r in rows:
    runs[(r["stage"], r["complexity"], r["renderer"])] = r

def cell(r, frame=False):
    if r is None or r["status"] != "ok":
        return "failed"
    text = f'{float(r["seconds"]):.2f} s, {float(r["peak_kb"]) / 1024:.0f} MB'
    if frame and r["frame_ms"]:
        text += f' ({float(r["frame_ms"]) / 1000:.2f} s frame)'
    return text

def ratio(r, storm, key):
    if r is None or storm is None or r["status"] != "ok" or storm["status"] != "ok":
        return "-"
    return f'{float(r[key]) / float(storm[key]):.2f}x'

lines = [
    f"Measured {started} on {os.cpu_count()} cores ({cpu}), GL {gl or '?'}; load average "
    f"{loadStart} at the start, {loadEnd} at the end; {width} px wide, "
    + ("one run each." if runCount == "1" else f"the median of {runCount} runs each, the renderers in turn."),
    "",
    "| stage (spans) | complexity | Storm via usdrecord | HdHair via usdrecord | hdhair-record "
    "| time HdHair/Storm (usdrecord, hdhair-record) | frame HdHair/Storm (usdrecord) "
    "| peak RSS HdHair/Storm (usdrecord, hdhair-record) |",
    "|---|---|---|---|---|---|---|---|",
]
seen = []
for r in rows:
    key = (r["stage"], r["complexity"])
    if key in seen:
        continue
    seen.append(key)
    storm = runs.get(key + ("usdrecord-storm",))
    plugin = runs.get(key + ("usdrecord-hdhair",))
    record = runs.get(key + ("hdhair-record",))
    spans = f'{int(r["spans"]):,}' if r["spans"] else "?"
    lines.append(
        f"| {r['stage']} ({spans}) | {r['complexity']} | {cell(storm, True)} | {cell(plugin, True)} "
        f"| {cell(record, True)} | {ratio(plugin, storm, 'seconds')}, {ratio(record, storm, 'seconds')} "
        f"| {ratio(plugin, storm, 'frame_ms') if plugin and storm and plugin['frame_ms'] and storm['frame_ms'] else '-'} "
        f"| {ratio(plugin, storm, 'peak_kb')}, {ratio(record, storm, 'peak_kb')} |")
lines += [
    "",
    "| stage (authored points) | complexity | hdhair-record peak RSS | GPU memory (strand geometry) "
    "| GPU bytes per authored point (strand geometry) | peak RSS per authored point |",
    "|---|---|---|---|---|---|",
]
for stage, complexity in seen:
    r = runs.get((stage, complexity, "hdhair-record"))
    if r is None or r["status"] != "ok" or not r["gpu_bytes"] or not r["authored_points"]:
        lines.append(f"| {stage} | {complexity} | - | - | - | - |")
        continue
    points, gpu, strands = int(r["authored_points"]), int(r["gpu_bytes"]), int(r["strand_bytes"] or 0)
    rss = float(r["peak_kb"]) * 1024
    lines.append(
        f"| {stage} ({points:,}) | {complexity} | {rss / 2**20:.0f} MB | {gpu / 2**20:.1f} MB ({strands / 2**20:.1f} MB) "
        f"| {gpu / points:.0f} ({strands / points:.0f}) | {rss / points:.0f} |")
open(markdown, "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
EOF
echo "storm-comparison: wrote $csv and $out/results.md" >&2
if [[ ${#failures[@]} -gt 0 ]]; then
  echo "storm-comparison: error: ${#failures[@]} run(s) failed: ${failures[*]} (logs in $out/logs)" >&2
  exit 1
fi
