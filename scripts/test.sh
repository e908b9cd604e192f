#!/usr/bin/env bash
# The README's second command: installs what is missing, builds, and runs the
# whole test suite with CTest. .ci/run calls this. Extra arguments go to ctest
# (e.g. -R Baseline).
#
# With an OpenUSD (scripts/find-openusd.sh: $PXR_ROOT, else ../shared/openusd)
# build/ has the Hydra plugin, whose tests (plugin, usdrecord, usdview,
# OpenUSD's own curve stages) run with everything else; without one, build/
# has no plugin. Then build-sanitize/: clang with AddressSanitizer and
# UndefinedBehaviorSanitizer and without OpenUSD, as users without it get
# hdHair: the engine's and tools' tests under them (the Debian package
# included), and the libFuzzer targets for a bounded time each. A third,
# plain build without OpenUSD ran the same tests as these two together and
# cost CI 8 of its 30 minutes, so there is none.
#
# A test that skips fails the run unless scripts/allowed-skips.txt names it
# with a reason (a skip is not a pass), and a -R filter that matches no test
# fails (ctest --no-tests=error).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-dependencies.sh"
openusd="$(bash "$root/scripts/find-openusd.sh")"

passed=0
failed=0
skipped=0
status=0
# Runs CTest in a build folder and adds its counts to the totals.
run_suite() {
  local label="$1" dir="$2"
  shift 2
  echo "hdHair: running the tests $label ($dir)"
  local log="$dir/Testing/hdhair-ctest.log"
  mkdir -p "$dir/Testing"
  local rc=0
  (cd "$dir" && ctest --output-on-failure --no-tests=error --parallel "$(nproc)" --timeout 600 "$@") 2>&1 | tee "$log" || rc=$?
  [[ $rc -eq 0 ]] || status=$rc
  local line
  line="$(grep -E '^[0-9]+% tests passed, [0-9]+ tests? failed out of [0-9]+' "$log" | tail -n 1 || true)"
  if [[ "$line" =~ ([0-9]+)\ tests?\ failed\ out\ of\ ([0-9]+) ]]; then
    failed=$((failed + BASH_REMATCH[1]))
    passed=$((passed + BASH_REMATCH[2] - BASH_REMATCH[1]))
  elif [[ $rc -ne 0 ]]; then
    failed=$((failed + 1))  # ctest itself failed (no tests found, a build step)
  fi
  # Skipped tests were counted as passed above; each one that
  # scripts/allowed-skips.txt does not allow fails the run.
  local skips=0 report
  report="$(bash "$root/scripts/check-skips.sh" "$log")" || { status=1; skips=-1; }
  echo "$report" | grep -v '^skipped: ' || true
  local count
  count="$(echo "$report" | sed -nE 's/^skipped: ([0-9]+)$/\1/p')"
  skipped=$((skipped + ${count:-0}))
  passed=$((passed - ${count:-0}))
  [[ $skips -ge 0 ]] || failed=$((failed + 1))
}

start=$SECONDS
if [[ -n "$openusd" ]]; then
  bash "$root/scripts/build.sh" --openusd "$openusd"
  run_suite "with the Hydra plugin (OpenUSD at $openusd)" "$root/build" "$@"
else
  bash "$root/scripts/build.sh" --no-openusd
  run_suite "without OpenUSD (no plugin)" "$root/build" "$@"
fi
bash "$root/scripts/build.sh" --build-dir "$root/build-sanitize" --no-openusd --sanitize
run_suite "without OpenUSD, under AddressSanitizer and UndefinedBehaviorSanitizer, with the fuzzers" "$root/build-sanitize" "$@"
echo "hdHair: built and tested in $((SECONDS - start)) s"
echo "tests: $passed passed, $failed failed, $skipped skipped"
exit $status
