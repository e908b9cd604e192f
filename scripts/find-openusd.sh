#!/usr/bin/env bash
# Finds the OpenUSD 24.08 that hdHair's plugin builds and tests against, and
# prints its prefix on stdout (nothing when there is none). Says on stderr
# which one it chose and why. In order:
#   1. $PXR_ROOT, when set (it must hold pxrConfig.cmake);
#   2. ../shared/openusd beside the repository, when that folder exists:
#      its install.sh installs OpenUSD's runtime packages and unpacks it once
#      (default prefix /opt/usd-24.08, or $HDHAIR_OPENUSD_PREFIX);
#   3. none: the engine, hdhair-record and the embedded reader are built
#      and tested without the plugin.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [[ -n "${PXR_ROOT:-}" ]]; then
  if [[ ! -f "$PXR_ROOT/pxrConfig.cmake" ]]; then
    echo "hdHair: error: PXR_ROOT=$PXR_ROOT holds no pxrConfig.cmake (expected an OpenUSD 24.08 install prefix)" >&2
    exit 1
  fi
  echo "hdHair: OpenUSD from \$PXR_ROOT: $PXR_ROOT" >&2
  echo "$PXR_ROOT"
  exit 0
fi
shared="$root/../shared/openusd"
if [[ -f "$shared/install.sh" ]]; then
  prefix="$(bash "$shared/install.sh" ${HDHAIR_OPENUSD_PREFIX:+"$HDHAIR_OPENUSD_PREFIX"})"
  echo "hdHair: OpenUSD from $(cd "$shared" && pwd), installed at $prefix" >&2
  echo "$prefix"
  exit 0
fi
echo "hdHair: no OpenUSD (PXR_ROOT is unset and there is no ../shared/openusd): the Hydra plugin and its tests are not built" >&2
