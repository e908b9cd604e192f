#!/usr/bin/env bash
# The Hydra plugin's own tests (testHdHairPlugin, testProgressiveRendering)
# under AddressSanitizer and UndefinedBehaviorSanitizer, against the prebuilt
# OpenUSD: a job of its own, outside scripts/test.sh, because its build does
# not fit CI's 30 minutes beside the two builds there (docs/testing.md,
# "The plugin under AddressSanitizer", has the measured cost).
#
#   bash scripts/asan-plugin.sh [--build-dir DIR]     (default: build-asan-plugin)
#
# Exit status: 0 when both pass with no sanitizer report.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build-asan-plugin"
[[ "${1:-}" == "--build-dir" ]] && build="$2"
bash "$root/scripts/install-dependencies.sh"
openusd="$(bash "$root/scripts/find-openusd.sh")"
if [[ -z "$openusd" ]]; then
  echo "asan-plugin: no OpenUSD (scripts/find-openusd.sh): the plugin is not built" >&2
  exit 1
fi
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHDHAIR_HYDRA=ON "-Dpxr_DIR=$openusd" \
      -DHDHAIR_SANITIZE=ON >/dev/null
start=$SECONDS
cmake --build "$build" --parallel "$(nproc)" --target hdHair testHdHairPlugin testProgressiveRendering
echo "asan-plugin: built in $((SECONDS - start)) s"
export LSAN_OPTIONS="suppressions=$root/cmake/sanitizers/openusd-leaks.supp:print_suppressions=0"
status=0
for test in testHdHairPlugin testProgressiveRendering; do
  start=$SECONDS
  # OpenImageIOLoadsOnlyForADomeTexture checks which libraries the plugin
  # pulls in, which the sanitizer runtime's link changes (OpenColorIO comes
  # in); it runs in the plain build.
  "$build/bin/$test" --gtest_filter=-HdHairPlugin.OpenImageIOLoadsOnlyForADomeTexture || status=1
  echo "asan-plugin: $test in $((SECONDS - start)) s"
done
exit $status
