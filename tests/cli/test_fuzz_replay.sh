#!/bin/sh
# Replays the committed fuzz corpus and every past crash or hang reproducer (tests/fuzz/corpus,
# tests/fuzz/regress) through each harness, built with the program (plain, and under the
# sanitizers in the second half of `make check`): a crash or a sanitizer report fails it.
. "$(dirname "$0")/lib.sh"
fuzz="$(dirname "$0")/../fuzz"
bin="$(dirname "$WHIRL")/tests/fuzz"
for h in scene fit_csv options resume; do
  if out=$("$bin/replay_$h" "$fuzz/corpus/$h" "$fuzz/regress/$h" 2>"$tmp/replay.err"); then
    pass "fuzz replay $h: $out"
  else
    fail "fuzz replay $h (stderr: $(tail -c 600 "$tmp/replay.err"))"
  fi
done
finish
