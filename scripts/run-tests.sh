#!/usr/bin/env bash
# Runs each cmocka test program, shows its output, and ends with one summary line "N passed, N failed".
set -u
pass=0; fail=0; failed=()
for t in "$@"; do
  echo "=== $t"
  start=$(date +%s)
  if "$t"; then pass=$((pass+1)); else fail=$((fail+1)); failed+=("$t"); fi
  echo "--- $(basename "$t"): $(( $(date +%s) - start )) s"
done
[ ${#failed[@]} -gt 0 ] && echo "failed programs: ${failed[*]}"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
