#!/usr/bin/env bash
# docs/performance.md's benchmarks again on a machine with a GPU (made for an NVIDIA GPU
# through EGL's device platform, runs anywhere): first which GL device hdHair
# lands on, then hdhair-bench's complexity, transparency, shading and shadow
# tables on the stages docs/performance.md measured them on, then, when OpenUSD's
# usdrecord is there, scripts/storm-comparison.sh. Everything goes into one
# folder with a summary.md naming the machine, the GPU and the GL renderer.
#
#   scripts/gpu-bench.sh [--build-dir DIR] [--build] [--out DIR] [--openusd PREFIX | --no-storm]
#                        [--storm-display DISPLAY] [--data DIR] [--allow-software] [--quick]
# --build-dir: default build/. --build: build what is missing first (scripts/build.sh, with the
#   plugin when an OpenUSD is given or found).
# --out: default BUILD/gpu-bench. --data: the TressFX samples (default ../shared/data/tressfx).
# --openusd: OpenUSD prefix for the Storm comparison (default $PXR_ROOT, else /opt/usd-24.08 when
#   it holds bin/usdrecord); --no-storm skips it.
# --storm-display: an X display on the GPU (an Xorg on the NVIDIA driver) for Storm; without it
#   Storm runs under Xvfb, whose GLX is Mesa's llvmpipe, not the GPU (see README).
# --allow-software: go on when a GPU is present but hdHair's context is a software renderer
#   (by default that stops the run: the figures would be llvmpipe's).
# --quick: a smoke run (short benchmark times, the dense clump only, low complexity in the
#   comparison) to check the script and the machine before the real run.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build"
out="" prefix="${PXR_ROOT:-}" data="$root/../shared/data/tressfx"
doBuild=false storm=true allowSoftware=false quick=false stormDisplay=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build="$2"; shift 2 ;;
    --build) doBuild=true; shift ;;
    --out) out="$2"; shift 2 ;;
    --openusd) prefix="$2"; shift 2 ;;
    --no-storm) storm=false; shift ;;
    --storm-display) stormDisplay="$2"; shift 2 ;;
    --data) data="$2"; shift 2 ;;
    --allow-software) allowSoftware=true; shift ;;
    --quick) quick=true; shift ;;
    -h|--help) sed -n '2,26p' "$0"; exit 0 ;;
    *) echo "gpu-bench: error: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
fail() { echo "gpu-bench: error: $*" >&2; exit 1; }
say() { echo "gpu-bench: $*" >&2; }

if [[ -z "$prefix" && -x /opt/usd-24.08/bin/usdrecord ]]; then prefix=/opt/usd-24.08; fi
[[ -n "$prefix" && -x "$prefix/bin/usdrecord" ]] || { [[ "$storm" == true ]] && say "no usdrecord (--openusd PREFIX): the Storm comparison is skipped"; storm=false; }
if [[ "$doBuild" == true ]]; then
  targets=(hdhair-record hdhair-convert hdhair-bench)
  if [[ "$storm" == true ]]; then
    bash "$root/scripts/build.sh" --build-dir "$build" --openusd "$prefix" --target "${targets[@]}"
  else
    bash "$root/scripts/build.sh" --build-dir "$build" --target "${targets[@]}"
  fi
fi
[[ -d "$build" ]] || fail "no build folder '$build' (pass --build)"
build="$(cd "$build" && pwd)"
for tool in hdhair-record hdhair-convert hdhair-bench; do
  [[ -x "$build/bin/$tool" ]] || fail "$build/bin/$tool is missing (pass --build, or cmake --build $build --target $tool)"
done
out="${out:-$build/gpu-bench}"
assets="$build/storm-comparison/assets"
mkdir -p "$out" "$assets"
summary="$out/summary.md"

# 1. The machine and the GL device hdHair's EGL context lands on.
gpuNames="none found"
if command -v nvidia-smi >/dev/null; then
  gpuNames="$(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null | paste -sd ';' - || true)"
fi
deviceLog="$out/device.log"
"$build/bin/hdhair-record" --reader embedded --verbose --camera /World/main_cam --imageWidth 256 \
  "$root/examples/dense_clump.usda" "$out/device-check.png" >"$deviceLog" 2>&1 ||
  fail "hdhair-record could not render the dense clump (see $deviceLog)"
glLine="$(sed -n 's/^hdhair-record: GL //p' "$deviceLog" | sed 's/; read .*//' | head -n 1)"
say "GL $glLine"
if grep -q "warning: gl:" "$deviceLog"; then
  grep "warning: gl:" "$deviceLog" >&2
  [[ "$allowSoftware" == true ]] ||
    fail "a GPU is present but hdHair renders in software (above); fix the driver or pass --allow-software"
fi
{
  echo "# hdHair benchmarks, $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo
  echo "- machine: $(nproc) cores ($(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -n 1)), $(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo)"
  echo "- GPU: $gpuNames; /dev/nvidia0 $([[ -e /dev/nvidia0 ]] && echo present || echo absent)"
  echo "- hdHair's GL: $glLine"
  echo "- load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "- commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
} >"$summary"

# 2. The stages docs/performance.md's tables were measured on.
convertOnce() {  # NAME OUTPUT INPUT... [options]
  local name="$1" output="$2"; shift 2
  if [[ ! -s "$output" ]]; then
    "$build/bin/hdhair-convert" "$@" "$output" >"$out/convert-$name.log" 2>&1 ||
      fail "hdhair-convert failed for $name (see $out/convert-$name.log)"
  fi
}
clump="$root/examples/dense_clump.usda"
stages=(--stage "$clump")
if [[ "$quick" == false ]]; then
  [[ -d "$data" ]] || fail "no TressFX samples at $data (--data DIR)"
  convertOnce ratboy "$assets/ratboy.usda" "$data/ratboy/Ratboy_mohawk.tfx"
  convertOnce bear "$assets/bear.usda" "$data/bear/bear.tfx"
  convertOnce sintel_dense "$assets/sintel_dense.usda" "$data/sintel/sintel_hair.tfx" "$data/sintel/sintel.obj" \
    --followStrands 31
  stages+=(--stage "$assets/ratboy.usda" --stage "$assets/bear.usda")
fi

# 3. hdhair-bench's tables, as README runs them (the figures there are llvmpipe's on 2 cores).
bench() {  # NAME ARGS...
  local name="$1"; shift
  say "hdhair-bench $name"
  "$build/bin/hdhair-bench" "$@" --benchmark_color=false --benchmark_out="$out/$name.json" \
    --benchmark_out_format=json >"$out/$name.txt" 2>"$out/$name.log" ||
    fail "hdhair-bench $name failed (see $out/$name.log)"
  # The tables and their titles, without Google Benchmark's own rows.
  { echo; echo "## hdhair-bench $name"; echo; echo '```'; echo "hdhair-bench $*"; echo '```'
    awk '/^hdhair-bench: / || /^\|/ { print; next } / relative to | against / { print ""; print; print "" }' \
      "$out/$name.txt"; } >>"$summary"
}
if [[ "$quick" == true ]]; then
  bench complexity --table complexity --benchmark_min_time=0.01 --stage "$clump" --imageWidth 256
else
  bench complexity --table complexity --benchmark_min_time=0.5 --stage "$clump" --imageWidth 512
  bench transparency --table transparency --benchmark_min_time=0.3 --imageWidth 512 "${stages[@]}"
  bench shading --table shading --benchmark_min_time=0.2 --benchmark_filter=RenderFrame --stage "$clump" \
    --imageWidth 512
  bench shadows --table shadows --benchmark_filter=ShadowFrame --benchmark_repetitions=3 --imageWidth 512 \
    --stage "$clump" --stage "$assets/sintel_dense.usda"
fi

# 4. Storm beside hdHair, when usdrecord is there.
if [[ "$storm" == true ]]; then
  say "storm-comparison"
  comparison=(--build-dir "$build" --openusd "$prefix" --out "$out/storm" --assets "$assets" --data "$data")
  [[ -n "$stormDisplay" ]] && comparison+=(--display "$stormDisplay")
  [[ "$quick" == true ]] && comparison+=(--stages ratboy --complexities low)
  if bash "$root/scripts/storm-comparison.sh" "${comparison[@]}" >"$out/storm.log" 2>&1; then
    { echo; echo "## Storm comparison"; echo; cat "$out/storm/results.md"; } >>"$summary"
  else
    { echo; echo "## Storm comparison"; echo; echo "failed: see storm.log"; } >>"$summary"
    say "the Storm comparison failed (see $out/storm.log)"
  fi
fi
echo "- load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)" >>"$summary"
say "wrote $summary"
