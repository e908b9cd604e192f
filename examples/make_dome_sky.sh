#!/usr/bin/env bash
# Writes examples/dome_sky.exr, the DomeLight texture of dome_lit_strands.usda:
# a 128 x 64 half-float latlong sky (Storm's orientation: +Y at the top row,
# +Z at the centre column), blue above, warm at the horizon, dark ground
# below, and a 3 x 3 texel sun of radiance about 150 some 34 degrees up
# towards +Z. Procedural: the committed file is what this writes, but for
# the DateTime header OpenEXR adds.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# oiiotool 2.4's --paste takes the foreground first, then the background.
oiiotool \
  --pattern constant:color=160,140,115 3x3 3 \
  --pattern fill:top=0.30,0.45,0.90:bottom=0.90,0.85,0.75 128x32 3 \
  --pattern fill:top=0.20,0.16,0.12:bottom=0.04,0.035,0.03 128x32 3 \
  --mosaic 1x2 \
  --paste +63+19 \
  --nosoftwareattrib \
  -d half --compression zip -o "$here/dome_sky.exr"
