#!/usr/bin/env bash
# What accuracy costs (docs/accuracy.md): hdhair-bench --accuracy on the
# examples and converted TressFX assets, then the plots. Writes, under the
# output folder, accuracy.json, accuracy.csv, accuracy.md (the tables),
# accuracy-<stage>.png and accuracy.png (the headline plot), and machine.txt.
#   scripts/accuracy-bench.sh [--build DIR] [--out DIR] [--data DIR] [--imageWidth N] [--repetitions N] [--quick]
#                             [--cycles [--cyclesSamples N] [--grooms] [--lighting key|keyFill|sky]]
#                             [--approximations NAME,...]
# --build: a build folder with bin/hdhair-bench and bin/hdhair-convert (default build/).
# --data: the TressFX samples (default ../shared/data/tressfx beside the repository).
# --quick: the CI matrix on the wavy example only (what the testAccuracyBench ctest runs).
# --cycles: against Blender's Cycles too (docs/accuracy.md, "Against Cycles"),
# 512 pixels wide unless --imageWidth says otherwise, every frame shaded with
# Marschner, on the matrix's stages, the textured dome's, and three grooms at
# production size: the bear in black hair, Ratboy in brown, the ponytail in
# blond (melanin 0.95, 0.5, 0.15 authored over the converted assets).
# --grooms: those three grooms only. --lighting: how they are lit: key (the
# converted assets' key light, the default), keyFill (with a fill light of a
# third of its intensity from the other side), or sky (the textured sky dome
# of examples/dome_sky.exr instead of the key).
# --approximations: only these rows of the matrix (hdhair-bench --approximations;
# "preset" for the presets), e.g. multipleScattering,multipleScattering:high
# for docs/accuracy.md's "Multiple scattering".
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build" out="" data="$root/../shared/data/tressfx" width="" repetitions=3 quick=() cycles=()
grooms=0 lighting=key approximations=()
fail() { echo "accuracy-bench: $*" >&2; exit 1; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --data) data="$2"; shift 2 ;;
    --imageWidth) width="$2"; shift 2 ;;
    --repetitions) repetitions="$2"; shift 2 ;;
    --quick) quick=(--quick); shift ;;
    --cycles) cycles+=(--cycles); shift ;;
    --cyclesSamples) cycles+=(--cyclesSamples "$2"); shift 2 ;;
    --grooms) grooms=1; shift ;;
    --lighting) lighting="$2"; shift 2 ;;
    --approximations) approximations=(--approximations "$2"); shift 2 ;;
    *) fail "unknown argument '$1'" ;;
  esac
done
[[ ${#cycles[@]} -eq 0 || "${cycles[0]}" == --cycles ]] || fail "--cyclesSamples needs --cycles before it"
[[ $grooms -eq 0 || ${#cycles[@]} -gt 0 ]] || fail "--grooms needs --cycles"
[[ "$lighting" =~ ^(key|keyFill|sky)$ ]] || fail "--lighting must be key, keyFill or sky, not '$lighting'"
width="${width:-$([[ ${#cycles[@]} -gt 0 ]] && echo 512 || echo 128)}"
out="${out:-$build/accuracy}"
bench="$build/bin/hdhair-bench" convert="$build/bin/hdhair-convert"
[[ -x "$bench" && -x "$convert" ]] || fail "$build has no bin/hdhair-bench or bin/hdhair-convert (scripts/build.sh --target hdhair-bench hdhair-convert)"
[[ "$width" =~ ^[0-9]+$ ]] || fail "--imageWidth must be a number of pixels, not '$width'"
[[ "$repetitions" =~ ^[1-9][0-9]*$ ]] || fail "--repetitions must be a positive number, not '$repetitions'"
mkdir -p "$out/assets"

stages=()
[[ $grooms -eq 1 ]] || stages+=(--stage "$root/examples/wavy_strands.usda")
if [[ ${#quick[@]} -eq 0 ]]; then
  [[ $grooms -eq 1 ]] || stages+=(--stage "$root/examples/straight_strands.usda" --stage "$root/examples/dense_clump.usda")
  # TressFX samples through hdhair-convert, as scripts/storm-comparison.sh converts them:
  # Sintel's guide strands with her head (a mesh occluding hair), and Ratboy's mohawk.
  sintel="$out/assets/sintel.usda" ratboy="$out/assets/ratboy.usda"
  for tfx in "$data/sintel/sintel_hair.tfx" "$data/sintel/sintel.obj" "$data/ratboy/Ratboy_mohawk.tfx"; do
    [[ -f "$tfx" ]] || fail "missing $tfx (--data names the TressFX folder)"
  done
  [[ "$sintel" -nt "$data/sintel/sintel_hair.tfx" ]] ||
    "$convert" "$data/sintel/sintel_hair.tfx" "$data/sintel/sintel.obj" "$sintel" >/dev/null
  [[ "$ratboy" -nt "$data/ratboy/Ratboy_mohawk.tfx" ]] ||
    "$convert" "$data/ratboy/Ratboy_mohawk.tfx" "$ratboy" >/dev/null
  if [[ ${#cycles[@]} -eq 0 ]]; then
    stages+=(--stage "$sintel" --stage "$ratboy")
  else
    # A groom in one hair colour: the converted asset with its strands'
    # melanin authored over it (the embedded reader composes the sublayer).
    groom() {  # NAME ASSET MELANIN PRIM...
      local name="$1" asset="$2" melanin="$3"; shift 3
      {
        printf '#usda 1.0\n(\n    subLayers = [@%s@]\n    defaultPrim = "World"\n)\n\nover "World"\n{\n' "$(basename "$asset")"
        for prim in "$@"; do
          printf '    over "%s"\n    {\n' "$prim"
          printf '        float[] primvars:hdHair:melanin = [%s] (\n            interpolation = "constant"\n        )\n' "$melanin"
          printf '        token primvars:hdHair:shadingModel = "marschner" (\n            interpolation = "constant"\n        )\n    }\n'
        done
        case "$lighting" in
          keyFill)
            printf '    def DistantLight "fill_light"\n    {\n        float inputs:angle = 1\n'
            printf '        float inputs:intensity = 0.7\n        float3 xformOp:rotateXYZ = (-15, -70, 0)\n'
            printf '        uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]\n    }\n' ;;
          sky)
            printf '    over "key_light"\n    {\n        float inputs:intensity = 0\n    }\n'
            printf '    def DomeLight "sky"\n    {\n        float inputs:intensity = 1\n'
            printf '        asset inputs:texture:file = @%s@\n' "$root/examples/dome_sky.exr"
            printf '        token inputs:texture:format = "latlong"\n    }\n' ;;
        esac
        printf '}\n'
      } > "$out/assets/$name.usda"
      stages+=(--stage "$out/assets/$name.usda")
    }
    bear="$out/assets/bear.usda" ponytail="$out/assets/ponytail.usda"
    [[ -f "$data/bear/bear.tfx" && -f "$data/ponytail/tail.tfx" ]] || fail "missing the bear or ponytail samples in $data"
    [[ "$bear" -nt "$data/bear/bear.tfx" ]] || "$convert" "$data/bear/bear.tfx" "$bear" >/dev/null
    [[ "$ponytail" -nt "$data/ponytail/tail.tfx" ]] ||
      "$convert" "$data"/ponytail/{back,front_top,side,tail}.tfx "$ponytail" >/dev/null
    [[ $grooms -eq 1 ]] || stages+=(--stage "$root/examples/dome_lit_strands.usda" --stage "$sintel")
    groom bear_black "$bear" 0.95 bear
    groom ratboy_brown "$ratboy" 0.5 Ratboy_mohawk
    groom ponytail_blond "$ponytail" 0.15 back front_top side tail
  fi
fi

{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
  echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
  [[ ${#cycles[@]} -eq 0 ]] || echo "lighting of the grooms: $lighting"
} > "$out/machine.txt"
start=$(date +%s)
status=0
"$bench" --accuracy "${quick[@]}" "${cycles[@]}" "${approximations[@]}" --imageWidth "$width" --repetitions "$repetitions" --out "$out" "${stages[@]}" \
  > "$out/bench.log" 2>&1 || status=$?
{
  echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "wall time: $(( $(date +%s) - start )) s"
} >> "$out/machine.txt"
[[ -f "$out/accuracy.json" ]] || fail "hdhair-bench wrote no report (see $out/bench.log)"
/usr/bin/python3 "$root/scripts/accuracy-plots.py" "$out/accuracy.json" "$out"
cat "$out/machine.txt"
grep "check failed\|accuracy matrix in" "$out/bench.log" || true
exit "$status"
