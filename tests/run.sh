#!/bin/sh
# Runs every test program (cmocka, TAP output) and every shell test in tests/,
# then prints the closing line "N passed, N failed".
build=${1:-build}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
export CMOCKA_MESSAGE_OUTPUT=TAP
status=0
for t in "$build"/tests/test_*; do
  [ -x "$t" ] || continue
  echo "== $t"
  "$t" 2>&1 | tee -a "$log" || status=1
done
for t in tests/test_*.sh; do
  [ -f "$t" ] || continue
  echo "== $t"
  WHIRL="$build/whirl" sh "$t" 2>&1 | tee -a "$log" || status=1
done
passed=$(grep -c '^ok ' "$log")
failed=$(grep -c '^not ok ' "$log")
echo "tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$status" -eq 0 ] && [ "$passed" -gt 0 ]
