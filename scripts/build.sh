#!/usr/bin/env bash
# Configures and builds hdHair. Warnings are errors when CI is set, as in CI.
#   scripts/build.sh [--build-dir DIR] [--openusd PREFIX | --no-openusd] [--sanitize] [cmake --build arguments...]
# --build-dir: default build/ in the repository.
# --openusd PREFIX: build the Hydra plugin against the OpenUSD at PREFIX
#   (scripts/find-openusd.sh finds one); --no-openusd: build without it.
#   Neither: keep what the build folder was configured with (first time: AUTO).
# --sanitize: clang with AddressSanitizer, UndefinedBehaviorSanitizer and the
#   libFuzzer targets (HDHAIR_FUZZ), without OpenUSD (a folder of its own).
# Other arguments go to `cmake --build` (e.g. --target hdhair-record).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build"
usd=()
sanitize=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir) build="$2"; shift 2 ;;
    --openusd) usd=(-DHDHAIR_HYDRA=ON "-Dpxr_DIR=$2"); shift 2 ;;
    --no-openusd) usd=(-DHDHAIR_HYDRA=OFF); shift ;;
    # hdhair-farm's Slurm test runs once, in the plain build: under the
    # sanitizers it would start a second cluster for the same checks.
    --sanitize) sanitize=(-DHDHAIR_FUZZ=ON -DHDHAIR_SLURM_TESTS=OFF -DCMAKE_C_COMPILER=clang
                          -DCMAKE_CXX_COMPILER=clang++); shift ;;
    *) break ;;
  esac
done
werror=OFF
[[ -n "${CI:-}" ]] && werror=ON
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHDHAIR_WERROR=$werror "${usd[@]}" \
      "${sanitize[@]}" >/dev/null
cmake --build "$build" --parallel "$(nproc)" "$@"
