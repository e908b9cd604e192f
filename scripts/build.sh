#!/usr/bin/env bash
# Configures (once) and builds hdHair into build/. Warnings are errors when
# CI is set, as in CI. Extra arguments go to `cmake --build` (e.g. --target X).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
werror=OFF
[[ -n "${CI:-}" ]] && werror=ON
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHDHAIR_WERROR=$werror >/dev/null
cmake --build "$root/build" --parallel "$(nproc)" "$@"
