#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and renders
# an example stage. Usage: scripts/render-example.sh [stage.usda [output.png]]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
stage="${1:-$root/examples/dense_clump.usda}"
output="${2:-$root/build/dense_clump.png}"
bash "$root/scripts/install-dependencies.sh"
bash "$root/scripts/build.sh" --target hdhair-record
"$root/build/bin/hdhair-record" --camera /World/main_cam --imageWidth 960 --complexity high --verbose \
  "$stage" "$output"
echo "hdHair: rendered $output"
