#!/usr/bin/env bash
# Reads a CTest log and fails for every skipped test that
# scripts/allowed-skips.txt (or the list given as $2) does not allow, with
# one line each; prints the allowed ones. scripts/test.sh runs it after each
# suite: a test that cannot run is not a pass.
#
#   scripts/check-skips.sh CTEST_LOG [ALLOWED_SKIPS]
#
# Exit status: 0 when every skip is allowed, 1 otherwise; the last line says
# "skipped: N" for the caller's totals.
set -euo pipefail
log="$1"
allowed="${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/allowed-skips.txt}"

# Whether the allow-list lets test $1 skip.
skip_allowed() {
  local name="$1" line pattern
  while IFS= read -r line; do
    [[ -z "$line" || "$line" == \#* ]] && continue
    pattern="${line%%:*}"
    # shellcheck disable=SC2053  # the pattern is a glob on purpose
    [[ "$name" == $pattern ]] && return 0
  done < "$allowed"
  return 1
}

status=0
count=0
# CTest lists them after "The following tests did not run:" as
# "  12 - Suite.Name (Skipped)".
while IFS= read -r name; do
  count=$((count + 1))
  if skip_allowed "$name"; then
    echo "hdHair: $name skipped (allowed: $(basename "$allowed"))"
  else
    echo "hdHair: $name skipped, and $(basename "$allowed") does not allow it: a skip is not a pass" >&2
    status=1
  fi
done < <(sed -nE 's/^[[:space:]]*[0-9]+ - (.+) \(Skipped\)$/\1/p' "$log")
echo "skipped: $count"
exit $status
