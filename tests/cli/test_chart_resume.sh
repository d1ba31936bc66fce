#!/bin/sh
# whirl periodic --chart --resume (src/cli/chart_file.c; the charts' state after their finished
# rates: src/periodic/chart_state.c, chart_ellipse.c): a chart stopped by Ctrl-C keeps the rates
# it finished, and resumed it is byte for byte the chart never stopped; a finished chart resumed
# is the same file, nothing computed; a file of other options, or with a row or a state line
# that is not the chart's, is refused in one line and left as it was (resume.h's rules).
. "$(dirname "$0")/lib.sh"

# rows: the rows of a chart file (no comment, no blank line)
rows() { grep -v '^#' "$1" | grep -v '^$' | sed 1d; }

# ---- the hanging chain, N = 2: two tongues, each joined at its tip (~0.5 s of processor time on one thread) ----
ch="periodic --chart hanging --links 2 --omega-min 1 --omega-max 6 --omega-count 250 --amp-max 0.8 --amp-rows 20"
# shellcheck disable=SC2086
"$WHIRL" $ch -o "$tmp/full.csv" 2>"$tmp/err" || fail "hanging chart ($(cat "$tmp/err"))"
# the runs below on one thread: the chart is the same on any number (the full one above ran on
# all), and a signal after a processor time then comes after as much work, which threads waiting
# for each other on a busy machine would not do (the stops below after a tenth of the chart, then
# another tenth)
export OMP_NUM_THREADS=1

# stopped once it has used 0.04 s of processor time: the rates finished, their rows those of the
# chart never stopped, the message and the comment line saying where it stopped
# shellcheck disable=SC2086
signal_run INT 0.04 "$WHIRL" $ch -o "$tmp/stop.csv" 2>"$tmp/stderr"
rc=$?
done=$(sed -n 's/^# found: interrupted after \([0-9]*\) of 250 rates: the points found until then (whirl periodic --resume goes on)$/\1/p' "$tmp/stop.csv")
rows "$tmp/stop.csv" >"$tmp/stop.rows"
if [ $rc -eq 130 ] && [ "$(report early)" = 0 ] && [ -n "$done" ] && [ "$done" -gt 0 ] \
   && [ "$done" -lt 250 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] \
   && grep -Eq "^whirl periodic: interrupted after $done of 250 rates: the [0-9]+ points found until then are written \(continue with --resume\)$" "$tmp/stderr" \
   && [ -s "$tmp/stop.rows" ] && [ "$(rows "$tmp/full.csv" | grep -Fxcf "$tmp/stop.rows")" -eq "$(wc -l <"$tmp/stop.rows")" ] \
   && grep -q "^# state: vertical columns=$done " "$tmp/stop.csv"; then
  pass "hanging chart stopped after $done of 250 rates: their rows, the state"
else fail "hanging chart stopped (rc=$rc, done=$done, $(cat "$tmp/stderr"))"; fi

# resumed: the chart never stopped, byte for byte (its rows by curve, the counts, the state)
cp "$tmp/stop.csv" "$tmp/r.csv"
# shellcheck disable=SC2086
if "$WHIRL" $ch -o "$tmp/r.csv" --resume 2>"$tmp/err" && cmp -s "$tmp/r.csv" "$tmp/full.csv"; then
  pass "hanging chart resumed: byte-identical to the chart never stopped"
else fail "hanging chart resumed ($(cat "$tmp/err"); $(diff "$tmp/r.csv" "$tmp/full.csv" | head -5))"; fi

# the rows read back are kept as written, not computed again: one's err changed (to a number the
# chart would not give) comes out so, and every other line is the chart never stopped's
first=$(rows "$tmp/stop.csv" | head -1)
marked=$(echo "$first" | sed 's/,[^,]*$/,0.125/')
sed "s/^$first\$/$marked/" "$tmp/stop.csv" >"$tmp/m.csv"
# shellcheck disable=SC2086
"$WHIRL" $ch -o "$tmp/m.csv" --resume 2>"$tmp/err"
if [ "$(diff "$tmp/m.csv" "$tmp/full.csv" | grep -c '^[<>]')" -eq 2 ] && grep -qFx "$marked" "$tmp/m.csv"; then
  pass "hanging chart resumed: the rows read back kept as they are"
else fail "hanging chart resumed: rows kept ($(cat "$tmp/err"))"; fi

# stopped again while resumed, and resumed once more: still the chart never stopped
cp "$tmp/stop.csv" "$tmp/r2.csv"
# shellcheck disable=SC2086
signal_run INT 0.04 "$WHIRL" $ch -o "$tmp/r2.csv" --resume 2>"$tmp/stderr"
rc=$?
again=$(sed -n 's/^# found: interrupted after \([0-9]*\) of 250.*/\1/p' "$tmp/r2.csv")
# shellcheck disable=SC2086
if [ $rc -eq 130 ] && [ "$(report early)" = 0 ] && [ "$again" -gt "$done" ] \
   && "$WHIRL" $ch -o "$tmp/r2.csv" --resume 2>"$tmp/err" && cmp -s "$tmp/r2.csv" "$tmp/full.csv"; then
  pass "hanging chart stopped twice ($done, then $again rates), resumed: byte-identical"
else fail "hanging chart stopped twice (rc=$rc, $done then $again; $(cat "$tmp/stderr" "$tmp/err"))"; fi

# a finished chart resumed: the same file, nothing computed (a row's changed err stays)
sed "s/^$(rows "$tmp/full.csv" | tail -1)\$/$(rows "$tmp/full.csv" | tail -1 | sed 's/,[^,]*$/,0.125/')/" \
  "$tmp/full.csv" >"$tmp/f.csv"
cp "$tmp/f.csv" "$tmp/f0.csv"
# shellcheck disable=SC2086
if "$WHIRL" $ch -o "$tmp/f.csv" --resume 2>"$tmp/err" && cmp -s "$tmp/f.csv" "$tmp/f0.csv" \
   && ! cmp -s "$tmp/f.csv" "$tmp/full.csv"; then
  pass "finished chart resumed: the same file, its rows not computed again"
else fail "finished chart resumed ($(cat "$tmp/err"))"; fi

# other options: refused, naming the first difference (more amplitudes scanned move the default
# lowest one first: --amp-max / --amp-rows)
s="$tmp/stop.csv"
# shellcheck disable=SC2086
{
expect_refused "resume: other --steps" "^whirl periodic: --resume: '.*stop.csv' was not written by a chart with these options: line 1 has 'links=2 steps=200' where these options write 'links=2 steps=300'$" "$s" $ch --steps 300
expect_refused "resume: other --omega-max" "line 2 has 'to 6' where these options write 'to 7'" "$s" periodic --chart hanging --links 2 --omega-min 1 --omega-max 7 --omega-count 250 --amp-max 0.8 --amp-rows 20
expect_refused "resume: other --amp-rows" "line 2 has 'from 0.04' where these options write 'from 0.0380952380952381'" "$s" periodic --chart hanging --links 2 --omega-min 1 --omega-max 6 --omega-count 250 --amp-max 0.8 --amp-rows 21
expect_refused "resume: other --edge-tol" "line 1 has 'steps=200 tol=1e-10' where these options write 'steps=200 tol=1e-09'" "$s" $ch --edge-tol 1e-9
expect_refused "resume: the inverted chain" "line 1 has 'the hanging' where these options write 'the inverted'" "$s" periodic --chart inverted --links 2 --omega-min 1 --omega-max 6 --omega-count 250 --amp-max 0.8 --amp-rows 20
expect_refused "resume: SI units" "line 1 has 'tol=1e-10 L;' where these options write 'tol=1e-10 m;'" "$s" $ch --length 1
}
expect_error "resume: standard output" "^whirl periodic: --resume needs -o FILE, not standard output$" periodic --chart hanging --omega-min 1 --omega-max 2 --amp-max 0.5 -o - --resume
expect_error "resume: no file" "^whirl periodic: --resume: cannot read '.*/out.csv': No such file or directory$" periodic --chart hanging --omega-min 1 --omega-max 2 --amp-max 0.5 -o "$tmp/out.csv" --resume

# crafted lines: each refused in one line naming it, the file left as it was, no crash (the
# sanitizers' reports would be more lines)
line=$(grep -n -v '^#' "$s" | sed -n 3p | cut -d: -f1) # the second row
crafted() { # crafted NAME PATTERN SED-SCRIPT
  sed "$3" "$s" >"$tmp/x.csv"
  # shellcheck disable=SC2086
  expect_refused "resume refuses $1" "$2" "$tmp/x.csv" $ch
}
crafted "a field too many" "x.csv:$line: 6 columns, the header has 5" "${line}s/\$/,1/"
crafted "a NaN" "x.csv:$line: column 4 holds 'nan', not a finite number" "${line}s/,[^,]*,\([^,]*\)\$/,nan,\1/"
crafted "an overflow" "x.csv:$line: column 4 holds '1e999', not a finite number" "${line}s/,[^,]*,\([^,]*\)\$/,1e999,\1/"
crafted "a huge amplitude" "x.csv:$line: an amplitude outside the chart" "${line}s/,[^,]*,\([^,]*\)\$/,1e300,\1/"
crafted "a rate outside the chart" "x.csv:$line: a rate outside the chart" "${line}s/^\([^,]*\),\([^,]*\),[^,]*,/\1,\2,7,/"
crafted "a rate not finished" "x.csv:$line: a rate beyond those the state has finished" "${line}s/^\([^,]*\),\([^,]*\),[^,]*,/\1,\2,5.9,/"
crafted "an edge of 0" "x.csv:$line: an edge other than 1 or -1" "${line}s/^\([^,]*\),[^,]*,/\1,0,/"
crafted "a curve not begun" "x.csv:$line: a curve the chart's state has not begun" "${line}s/^[^,]*,/99,/"
crafted "a text field" "x.csv:$line: not a row curve,edge,omega,amplitude,err" "${line}s/^[^,]*,/one,/"
crafted "a row twice" "holds [0-9]+ rows where its '# found: points=' line says [0-9]+: rows were removed or added" "${line}p"
points=$(sed -n 's/^# found: points=\([0-9]*\) .*/\1/p' "$s")
crafted "a row twice, counted" "x.csv:$((line + 1)): the row of line $line again" "${line}p; s/^# found: points=$points /# found: points=$((points + 1)) /"
crafted "a row removed" "holds [0-9]+ rows where its '# found: points=' line says $points" "${line}d"
crafted "a comment among the rows" "x.csv:$line: a comment among the rows" "${line}s/^/# note\n/"
# the state's curves crafted in the finished chart's state (the stopped one has none when the stop
# fell between two curves), which --resume reads and checks as well
s="$tmp/full.csv"
crafted "a mode the chain has not" "the chart's state line 2: an integer out of range: the file cannot be trusted$" '/^# state: curve/{s/^\(# state: curve [0-9]* [0-3]\) [0-9]*/\1 9/;}'
crafted "a NaN in the state" "the chart's state line 2: a number not finite or out of range" '0,/^# state: curve/s/^\(# state: curve\( [^ ]*\)\{6\}\) [^ ]*/\1 nan/'
s="$tmp/stop.csv"
crafted "rates beyond the chart in the state" "the chart's state line 1: an integer out of range" 's/^# state: vertical columns=[0-9]*/# state: vertical columns=251/'
crafted "a state line too many" "the chart's state line [0-9]+: a line too many" '$p'
crafted "no state" "holds no chart state" '/^# state: /d'
head -c -12 "$s" >"$tmp/x.csv"
# shellcheck disable=SC2086
expect_refused "resume refuses a state cut short (its last line unfinished)" "the chart's state line [0-9]+: missing" "$tmp/x.csv" $ch
head -c "$(grep -b -v '^#' "$s" | sed -n 5p | cut -d: -f1)" "$s" | head -c -3 >"$tmp/x.csv"
# shellcheck disable=SC2086
expect_refused "resume refuses a file cut among its rows" "holds no chart state" "$tmp/x.csv" $ch

# ---- the ellipse chart: N = 2, mode 2 about the end of its curve on e = 0 (~1 s) ----
el="periodic --chart ellipse --links 2 --eps 0.05 --mode 2 --side -1 --omega-min 3.9 --omega-max 4.2 --omega-count 8"
# shellcheck disable=SC2086
"$WHIRL" $el -o "$tmp/efull.csv" 2>"$tmp/err" || fail "ellipse chart ($(cat "$tmp/err"))"
# shellcheck disable=SC2086
signal_run INT 0.4 "$WHIRL" $el -o "$tmp/estop.csv" 2>"$tmp/stderr"
rc=$?
edone=$(sed -n 's/^# found: interrupted after \([0-9]*\) of 8 rates.*/\1/p' "$tmp/estop.csv")
cp "$tmp/estop.csv" "$tmp/er.csv"
# shellcheck disable=SC2086
if [ $rc -eq 130 ] && [ "$(report early)" = 0 ] && [ -n "$edone" ] && [ "$edone" -lt 8 ] \
   && grep -Eq "^whirl periodic: interrupted after $edone of 8 rates: the [0-9]+ points found until then are written \(continue with --resume\)$" "$tmp/stderr" \
   && grep -q "^# state: ellipse columns=$edone " "$tmp/estop.csv" \
   && "$WHIRL" $el -o "$tmp/er.csv" --resume 2>"$tmp/err" && cmp -s "$tmp/er.csv" "$tmp/efull.csv"; then
  pass "ellipse chart stopped after $edone of 8 rates, resumed: byte-identical"
else fail "ellipse chart stopped and resumed (rc=$rc, $edone; $(cat "$tmp/stderr" "$tmp/err"))"; fi
cp "$tmp/efull.csv" "$tmp/ef.csv"
# shellcheck disable=SC2086
if "$WHIRL" $el -o "$tmp/ef.csv" --resume 2>"$tmp/err" && cmp -s "$tmp/ef.csv" "$tmp/efull.csv"; then
  pass "finished ellipse chart resumed: the same file"
else fail "finished ellipse chart resumed ($(cat "$tmp/err"))"; fi

s="$tmp/efull.csv"
line=$(grep -n -v '^#' "$s" | sed -n 3p | cut -d: -f1)
ecrafted() { # ecrafted NAME PATTERN SED-SCRIPT
  sed "$3" "$s" >"$tmp/x.csv"
  # shellcheck disable=SC2086
  expect_refused "ellipse resume refuses $1" "$2" "$tmp/x.csv" $el
}
# shellcheck disable=SC2086
expect_refused "ellipse resume: other --arc-step" "line 1 has 'steps=400 arc_step=0.01' where these options write 'steps=400 arc_step=0.02'" "$s" $el --arc-step 0.02
ecrafted "a rate off the grid" "x.csv:$line: a rate not on the grid" "${line}s/^\([^,]*\),\([^,]*\),[^,]*,/\1,\2,3.91,/"
ecrafted "an unknown event" "x.csv:$line: an event not fold, branch, period-doubling, torus or none" "${line}s/^\([^,]*\),[^,]*,/\1,tours,/"
ecrafted "a second row of a rate" "x.csv:$((line + 1)): a second row of its rate" "${line}{p;s/,[^,]*\$/,0.125/;}; s/^# found: points=5 /# found: points=6 /"
ecrafted "an ellipticity above e_max" "x.csv:$line: an ellipticity outside 0..e_max" "${line}s/^\([^,]*,[^,]*,[^,]*\),[^,]*,/\1,1.5,/"
ecrafted "a state of another kind" "the chart's state line 1: not 'ellipse columns=J prev=P curve=C failed=F'" 's/^# state: ellipse/# state: vertical/'
ecrafted "a state out of range" "the chart's state line 1: a count out of range" 's/prev=0/prev=7/'

finish
