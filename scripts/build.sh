#!/usr/bin/env bash
# Configures and builds hdHair. Warnings are errors when CI is set, as in CI.
#   scripts/build.sh [--build-dir DIR] [--openusd PREFIX | --no-openusd] [cmake --build arguments...]
# --build-dir: default build/ in the repository.
# --openusd PREFIX: build the Hydra plugin against the OpenUSD at PREFIX
#   (scripts/find-openusd.sh finds one); --no-openusd: build without it.
#   Neither: keep what the build folder was configured with (first time: AUTO).
# Other arguments go to `cmake --build` (e.g. --target hdhair-record).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build"
usd=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build="$2"; shift 2 ;;
    --openusd) usd=(-DHDHAIR_HYDRA=ON "-Dpxr_DIR=$2"); shift 2 ;;
    --no-openusd) usd=(-DHDHAIR_HYDRA=OFF); shift ;;
    *) break ;;
  esac
done
werror=OFF
[[ -n "${CI:-}" ]] && werror=ON
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHDHAIR_WERROR=$werror "${usd[@]}" >/dev/null
cmake --build "$build" --parallel "$(nproc)" "$@"
