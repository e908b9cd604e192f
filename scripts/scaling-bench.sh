#!/usr/bin/env bash
# How a frame's cost grows with the groom: the TressFX bear (144k spans) cut
# down with hdhair-convert --maxStrands and grown with --followStrands, from
# about 10 thousand to 2 million spans, each rendered by hdhair-record in its
# own process at one size and complexity. Writes, under the output folder,
# scaling.md (the table docs/performance.md shows), scaling.csv and, with python3-matplotlib,
# scaling.png (frame time and peak memory against spans, log-log).
#   scripts/scaling-bench.sh [--build DIR] [--out DIR] [--imageWidth N] [--complexity LEVEL]
#                            [--setting NAME=VALUE ...]
# --setting: a renderer setting for every render (repeatable), as hdhair-record's -s,
#   e.g. --setting strandRaster=compute; the table's heading names them.
# Figures are one run each on whatever machine runs it: read the ratios
# (time and bytes a span against the smallest groom), not the seconds.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build"
out="$root/build/scaling"
width=512
complexity=high
settings=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --imageWidth) width="$2"; shift 2 ;;
    --complexity) complexity="$2"; shift 2 ;;
    --setting) settings+=(-s "$2"); shift 2 ;;
    *) echo "scaling-bench: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
bear="$root/../shared/data/tressfx/bear/bear.tfx"
[[ -f "$bear" ]] || { echo "scaling-bench: no TressFX bear at $bear" >&2; exit 1; }
for tool in hdhair-convert hdhair-record; do
  [[ -x "$build/bin/$tool" ]] || { echo "scaling-bench: build $tool first (scripts/build.sh --target $tool)" >&2; exit 1; }
done
mkdir -p "$out"

# name, hdhair-convert options: the bear has 48,113 strands of 4 points
# (3 spans each); follow strands copy a guide's spans.
grooms=(
  "10k|--maxStrands 3333"
  "30k|--maxStrands 10000"
  "100k|--maxStrands 33333"
  "290k|--followStrands 1"
  "1.0M|--followStrands 6"
  "2.0M|--followStrands 13"
)
echo "groom,spans,frame_ms,strand_pass_ms,triangles,peak_rss_mb" > "$out/scaling.csv"
for entry in "${grooms[@]}"; do
  name="${entry%%|*}"
  options="${entry#*|}"
  stage="$out/bear-$name.usda"
  if [[ ! -f "$stage" ]]; then
    echo "scaling-bench: converting the bear ($options)"
    # shellcheck disable=SC2086
    "$build/bin/hdhair-convert" $options "$bear" "$stage.tmp.usda" >/dev/null
    mv "$stage.tmp.usda" "$stage"
  fi
  echo "scaling-bench: rendering $name spans"
  /usr/bin/time -f "%M" -o "$out/rss-$name.txt" \
    "$build/bin/hdhair-record" --imageWidth "$width" --complexity "$complexity" --stats "$out/stats-$name.json" \
    "${settings[@]}" -- "$stage" "$out/bear-$name.exr" >/dev/null
  python3 - "$out" "$name" >> "$out/scaling.csv" <<'EOF'
import json, sys
out, name = sys.argv[1], sys.argv[2]
frame = json.load(open(f"{out}/stats-{name}.json"))["frames"][0]
passes = {p["name"]: p["milliseconds"] for p in frame["passes"]}
strands = sum(ms for pass_name, ms in passes.items() if pass_name.startswith("strands"))
rss_kb = int(open(f"{out}/rss-{name}.txt").read().split()[-1])
render_ms = frame["totalMilliseconds"]
print(f"{name},{frame['segments']},{render_ms:.1f},{strands:.1f},{frame.get('strandTriangles', 0)},{rss_kb / 1024:.0f}")
EOF
done

# Debian's python3, where python3-matplotlib is (a python3 earlier on PATH,
# such as pyenv's for OpenUSD, may not have it).
/usr/bin/python3 - "$out" "$width" "$complexity" "${settings[@]}" <<'EOF'
import csv, sys
out, width, complexity = sys.argv[1], sys.argv[2], sys.argv[3]
assignments = [a for a in sys.argv[4:] if a != "-s"]
rows = list(csv.DictReader(open(f"{out}/scaling.csv")))
base = rows[0]
base_ms_per_span = float(base["frame_ms"]) / int(base["spans"])
lines = [f"| groom | spans | frame | strand passes | triangles | frame per span (x smallest) | peak RSS | RSS beyond the smallest, bytes a span |",
         "|---|---|---|---|---|---|---|---|"]
for r in rows:
    spans = int(r["spans"])
    per_span = float(r["frame_ms"]) / spans / base_ms_per_span
    rss = float(r["peak_rss_mb"])
    extra_spans = spans - int(base["spans"])
    marginal = f"{(rss - float(base['peak_rss_mb'])) * 2**20 / extra_spans:.0f}" if extra_spans > 0 else "-"
    lines.append(f"| {r['groom']} | {spans:,} | {float(r['frame_ms']) / 1000:.2f} s | {float(r['strand_pass_ms']) / 1000:.2f} s "
                 f"| {int(r['triangles']):,} | {per_span:.2f}x | {rss:.0f} MB | {marginal} |")
with_settings = f", {' '.join(assignments)}" if assignments else ""
open(f"{out}/scaling.md", "w").write(f"hdhair-record at {width} px, complexity {complexity}{with_settings}, one process a groom:\n\n" +
                                     "\n".join(lines) + "\n")
print(open(f"{out}/scaling.md").read())
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("scaling-bench: python3-matplotlib is not installed: no scaling.png")
    sys.exit(0)
spans = [int(r["spans"]) for r in rows]
fig, axes = plt.subplots(1, 2, figsize=(10, 4))
axes[0].loglog(spans, [float(r["frame_ms"]) / 1000 for r in rows], "o-", label="frame")
axes[0].loglog(spans, [float(r["strand_pass_ms"]) / 1000 for r in rows], "s-", label="strand passes")
axes[0].loglog(spans, [float(base["frame_ms"]) / 1000 * s / int(base["spans"]) for s in spans], "k:", label="linear")
axes[0].set_xlabel("spans"); axes[0].set_ylabel("seconds"); axes[0].legend(); axes[0].set_title("frame time")
axes[1].loglog(spans, [float(r["peak_rss_mb"]) for r in rows], "o-")
axes[1].set_xlabel("spans"); axes[1].set_ylabel("MB"); axes[1].set_title("peak RSS")
fig.tight_layout()
fig.savefig(f"{out}/scaling.png", dpi=100)
print(f"scaling-bench: wrote {out}/scaling.png")
EOF
