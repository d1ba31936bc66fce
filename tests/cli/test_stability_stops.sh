#!/bin/sh
# whirl stability and whirl windows stopped by Ctrl-C (SIGINT): the windows' modes finished are
# kept whole and the others marked, a map keeps its finished rows and the atlas its finished
# chunks, exit 130 within a second or two; --resume then completes a map or an atlas to the file
# of a run without a stop. In tests/slow.list (make check runs it, make check-quick leaves it
# out): each stop waits for a run to be well under way, and the runs it is compared with are
# complete ones.
. "$(dirname "$0")/lib.sh"

# windows_sigint NAME "ARGS" FAST SLOW: Ctrl-C in a --windows run of modes FAST,SLOW (ARGS
# without --modes): the mode finished is written whole (the rows of a run of that mode alone),
# the other marked not done, exit 130 within 2 s. One thread; the signal comes at three times
# the time mode FAST alone just took (SLOW takes five or more times as long, so it is still
# running then, however loaded the machine).
windows_sigint() {
  t0=$(date +%s.%N)
  # shellcheck disable=SC2086
  OMP_NUM_THREADS=1 "$WHIRL" $2 --modes "$3" -o "$tmp/wfast.csv" 2>/dev/null
  wait_fast=$(echo "3 * ($(date +%s.%N) - $t0)" | bc)
  # shellcheck disable=SC2086
  OMP_NUM_THREADS=1 env --default-signal=INT "$WHIRL" $2 --modes "$3,$4" -o "$tmp/wint.csv" \
    >/dev/null 2>"$tmp/wint.err" &
  pid=$!
  sleep "$wait_fast"
  interrupt $pid
  if [ $rc -eq 130 ] && [ "$(echo "$late < 2" | bc)" -eq 1 ] &&
     grep -q "interrupted: 1 of 2 modes done in '$tmp/wint.csv'" "$tmp/wint.err" &&
     grep -q "^# mode $4: interrupted, not done\$" "$tmp/wint.csv" &&
     grep -q "^# mode $3: examined" "$tmp/wint.csv" &&
     [ "$(grep -v '^#' "$tmp/wint.csv")" = "$(grep -v '^#' "$tmp/wfast.csv")" ]; then
    pass "$1: SIGINT stops it in $late s, exit 130, mode $3 kept whole, mode $4 marked not done"
  else fail "$1, SIGINT (rc=$rc, $late s, $(cat "$tmp/wint.err"; grep '^# mode' "$tmp/wint.csv"))"; fi
}
# mode 2 of the damped chain takes about five times as long as mode 8, mode 4 of the continuum
# about six times as long as mode 2
windows_sigint "windows with damping" \
  "stability --windows --links 60 --omega-min 3 --omega-max 14 --scan-step 0.05 --damping 1e-3" 8 2
windows_sigint "continuum windows" "stability --windows --omega-min 1 --omega-max 15" 2 4

# ---- a map stopped by Ctrl-C: exit 130, the finished rows kept, no temporary file; --resume
# computes the rest, and the file equals that of a run without a stop ----
# The stop comes at half the time the whole map took (250 periods a point: 4 s under the
# sanitizers, a second in the plain build), so that it finds the map running on a
# fast machine and on a slow (sanitizer) build alike.
map="--omega-min 2 --omega-max 6 --omega-count 8 --modes 1,2 --links 10 --periods 250"
start=$(date +%s.%N)
"$WHIRL" stability $map -o "$tmp/full.csv"
half=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", (b - a) / 2 }')
"$WHIRL" stability $map -o "$tmp/part.csv" 2>"$tmp/err" &
pid=$!
sleep "$half"
kill -INT $pid
wait $pid
rc=$?
if [ $rc -eq 130 ] && [ -z "$(ls "$tmp" | grep '^part.csv.')" ] &&
   grep -q "interrupted: [0-9]* of 14 points in '.*part.csv' (continue with --resume)" "$tmp/err" &&
   [ "$(grep -vc '^#' "$tmp/part.csv")" -lt 15 ]; then
  pass "map interrupted: exit 130, $(($(grep -vc '^#' "$tmp/part.csv") - 1)) rows kept, no temporary file"
else fail "map interrupted: exit 130, rows kept, no temporary file (rc=$rc, $(cat "$tmp/err"))"; fi
if "$WHIRL" stability $map -o "$tmp/part.csv" --resume && cmp -s "$tmp/part.csv" "$tmp/full.csv"; then
  pass "--resume completes the map: the file of a run without a stop"
else fail "--resume completes the map: the file of a run without a stop"; fi
"$WHIRL" stability --omega-min 2 --omega-max 6 --omega-count 9 --modes 1,2 --links 10 --periods 250 \
  -o "$tmp/full.csv" --resume 2>"$tmp/err"
if [ $? -eq 1 ] && grep -q "was not written by a map with these options" "$tmp/err"; then
  pass "--resume refuses a map of other options"
else fail "--resume refuses a map of other options ($(cat "$tmp/err"))"; fi
expect_error "resume to stdout" "whirl stability: --resume needs --output|--resume needs -o FILE" stability $map --resume

# Ctrl-C: SIGINT in the middle of the atlas stops it within a second (2 s allowed on a loaded
# machine), exit 130, the chunks finished kept as complete rows; --resume then completes it to
# the file of an uninterrupted run. The signal's default disposition is restored for whirl:
# the suite may run in the background, where a shell starts jobs with SIGINT ignored.
atl="stability --atlas --modes 2 --omega-max 30"
# shellcheck disable=SC2086
"$WHIRL" $atl -o "$tmp/afull.csv" 2>/dev/null
# shellcheck disable=SC2086
env --default-signal=INT "$WHIRL" $atl -o "$tmp/aint.csv" >/dev/null 2>"$tmp/aint.err" &
pid=$!
i=0
while ! grep -q '^# done mode 2 omega 5 10' "$tmp/aint.csv" 2>/dev/null && [ $i -lt 1200 ]; do
  sleep 0.02; i=$((i + 1))
done
interrupt $pid
done_chunks=$(grep -c '^# done mode 2' "$tmp/aint.csv" 2>/dev/null)
# every row complete: 13 fields, finite numbers
bad_rows=$(grep -v '^#' "$tmp/aint.csv" | sed 1d | awk -F, 'NF != 13 || /nan|inf/' | wc -l)
if [ $rc -eq 130 ] && [ "$(echo "$late < 2" | bc)" -eq 1 ] && [ "$done_chunks" -ge 2 ] &&
   [ "$done_chunks" -lt 6 ] && [ "$bad_rows" -eq 0 ] && grep -q interrupted "$tmp/aint.err" &&
   [ "$(grep -v '^#' "$tmp/aint.csv" | sed -n 2p)" = "$(grep -v '^#' "$tmp/afull.csv" | sed -n 2p)" ]; then
  pass "atlas: SIGINT stops it in $late s, exit 130, $done_chunks of 6 chunks kept with their windows"
else fail "atlas SIGINT (rc=$rc, $late s, $done_chunks chunks, $bad_rows bad rows, $(head -c 200 "$tmp/aint.err"))"; fi
# shellcheck disable=SC2086
if "$WHIRL" $atl -o "$tmp/aint.csv" --resume 2>"$tmp/err" && cmp -s "$tmp/aint.csv" "$tmp/afull.csv"; then
  pass "atlas --resume after SIGINT: the file of the uninterrupted run"
else fail "atlas --resume after SIGINT: $(cat "$tmp/err"; diff "$tmp/aint.csv" "$tmp/afull.csv" | head -5)"; fi

finish
