#!/usr/bin/env bash
# scripts/check-skips.sh on CTest logs written here: an allowed skip passes,
# an unexpected one fails naming the test, a log without skips passes.
set -euo pipefail
check="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/check-skips.sh"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cat > "$work/allowed.txt" <<'LIST'
# comment
Data.Shared*: the data lives outside the repository
LIST
fail() { echo "testCheckSkips: $*" >&2; exit 1; }

printf '100%% tests passed, 0 tests failed out of 3\n\nThe following tests did not run:\n\t  2 - Data.SharedAssets (Skipped)\n' > "$work/allowed.log"
out="$(bash "$check" "$work/allowed.log" "$work/allowed.txt" 2>&1)" || fail "an allowed skip failed: $out"
[[ "$out" == *"skipped: 1"* ]] || fail "the allowed skip was not counted: $out"

printf '100%% tests passed, 0 tests failed out of 3\n\nThe following tests did not run:\n\t  2 - Data.SharedAssets (Skipped)\n\t  3 - Stages.Missing (Skipped)\n' > "$work/unexpected.log"
if out="$(bash "$check" "$work/unexpected.log" "$work/allowed.txt" 2>&1)"; then
  fail "an unexpected skip passed: $out"
fi
[[ "$out" == *"Stages.Missing skipped, and allowed.txt does not allow it"* ]] || fail "the skip was not named: $out"
[[ "$out" == *"skipped: 2"* ]] || fail "the skips were not counted: $out"

printf '100%% tests passed, 0 tests failed out of 3\n' > "$work/none.log"
out="$(bash "$check" "$work/none.log" "$work/allowed.txt" 2>&1)" || fail "a log without skips failed: $out"
[[ "$out" == *"skipped: 0"* ]] || fail "$out"
echo "testCheckSkips: passed"
