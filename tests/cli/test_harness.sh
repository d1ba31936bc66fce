#!/bin/sh
# tests/run.sh itself: fake test programs that go wrong in each way the harness must catch (a
# pass printed before a non-zero exit, a crash, fewer results than the plan, no plan, a skip in
# cmocka's and in plain TAP form, a "not ok" with exit status 0) each make it exit non-zero with
# at least one failure in its closing line; a well-behaved fake passes, as program and as shell
# test.
. "$(dirname "$0")/lib.sh"
run="$(cd "$(dirname "$0")/.." && pwd)/run.sh"

# fake NAME BODY: an executable shell script $tmp/NAME running BODY
fake() {
  printf '#!/bin/sh\n%s\n' "$2" >"$tmp/$1"
  chmod +x "$tmp/$1"
}
fake good 'echo 1..2; echo "ok 1 - a"; echo "ok 2 - b"'
fake ok_then_exit1 'echo 1..1; echo "ok 1 - a"; exit 1'
fake crash 'echo 1..1; echo "ok 1 - a"; kill -SEGV $$'
fake abort 'echo 1..2; echo "ok 1 - a"; kill -ABRT $$; echo "ok 2 - b"'
fake short_plan 'echo 1..3; echo "ok 1 - a"; echo "ok 2 - b"'
fake long_plan 'echo 1..1; echo "ok 1 - a"; echo "ok 2 - b"'
fake no_plan 'echo "ok 1 - a"'
fake two_plans 'echo 1..1; echo "ok 1 - a"; echo 1..1'
fake no_output 'exit 0'
fake skip_cmocka 'echo 1..2; echo "ok 1 - a"; echo "not ok 2 # SKIP b"'
fake skip_tap 'echo 1..2; echo "ok 1 - a"; echo "ok 2 - b # skip no solver"'
fake not_ok_exit0 'echo 1..2; echo "ok 1 - a"; echo "not ok 2 - b"'
cp "$tmp/good" "$tmp/good.sh"
cp "$tmp/ok_then_exit1" "$tmp/ok_then_exit1.sh"

# harness_run NAME: runs the harness on the fake $tmp/NAME, its output in $tmp/harness.out
harness_run() { sh "$run" "$tmp/nobuild" "$tmp/$1" >"$tmp/harness.out" 2>&1; }

for good in good good.sh; do
  if harness_run $good && grep -qx "tests: 2 passed, 0 failed" "$tmp/harness.out"; then
    pass "harness passes $good"
  else fail "harness fails $good: $(tail -n 3 "$tmp/harness.out")"; fi
done
for bad in ok_then_exit1 ok_then_exit1.sh crash abort short_plan long_plan no_plan two_plans \
           no_output skip_cmocka skip_tap not_ok_exit0; do
  if harness_run $bad; then
    fail "harness passes $bad: $(tail -n 3 "$tmp/harness.out")"
  elif grep -Eq "^tests: [0-9]+ passed, [1-9][0-9]* failed$" "$tmp/harness.out" \
       && grep -q "^== FAILED $tmp/$bad: " "$tmp/harness.out"; then
    pass "harness fails $bad ($(grep "^== FAILED" "$tmp/harness.out" | sed 's/.*: //'))"
  else fail "harness fails $bad without naming it: $(tail -n 3 "$tmp/harness.out")"; fi
done
# several programs: one bad among good ones fails the run
if sh "$run" "$tmp/nobuild" "$tmp/good" "$tmp/crash" "$tmp/good.sh" >"$tmp/harness.out" 2>&1; then
  fail "harness passes a crash among passes"
elif grep -qx "tests: 5 passed, 1 failed" "$tmp/harness.out"; then pass "a crash among passes"
else fail "a crash among passes: $(tail -n 3 "$tmp/harness.out")"; fi
finish
