#!/bin/sh
# --resume, one discipline for every long command (src/cli/resume.c): the atlas, the stability map
# and the regime map refuse a file of other options in one line naming the first difference,
# refuse every line that is not a row of theirs (non-finite numbers, a mode not asked for, a chunk
# that is no chunk, a point of no map) with its line number, and lock the file for the whole run.
. "$(dirname "$0")/lib.sh"

# ---- the atlas ----
atl="stability --atlas --modes 2,3 --omega-max 6"
# shellcheck disable=SC2086
"$WHIRL" $atl -o "$tmp/a6.csv" 2>"$tmp/err" || fail "atlas to omega 6 ($(cat "$tmp/err"))"

# a "# done" line of a chunk beyond the atlas wrote one int past the chunks' array (ASan:
# heap-buffer-overflow in read_atlas)
sed '4a # done mode 3 omega 7.6 9' "$tmp/a6.csv" >"$tmp/far.csv"
# shellcheck disable=SC2086
expect_refused "atlas: '# done mode 3 omega 7.6 9' refused with its line number, no overflow" \
  "far.csv:5: omega 7.6 9 is no chunk of this atlas" "$tmp/far.csv" $atl
cp "$tmp/a6.csv" "$tmp/far2.csv"; echo "# done mode 3 omega 7.6 9" >>"$tmp/far2.csv"
# shellcheck disable=SC2086
expect_refused "atlas: the same line after the rows refused" "far2.csv:11: a comment among the rows" \
  "$tmp/far2.csv" $atl
# a "# done" line off a chunk boundary (omega 3 6 marked the chunk 5 6 done)
sed 's/^# done mode 2 omega 5 6$/# done mode 2 omega 3 6/' "$tmp/a6.csv" >"$tmp/off.csv"
# shellcheck disable=SC2086
expect_refused "atlas: a '# done' line off the chunks refused" "off.csv:[0-9]+: omega 3 6 is no chunk" \
  "$tmp/off.csv" $atl
sed 's/^# done mode 2 omega 0 5$/# done mode 7 omega 0 5/' "$tmp/a6.csv" >"$tmp/m7.csv"
# shellcheck disable=SC2086
expect_refused "atlas: a '# done' line of a mode not asked for refused" "m7.csv:[0-9]+: .*mode asked for" \
  "$tmp/m7.csv" $atl
# rows holding nan, inf, 1e999 were kept and written back; a row of a mode not asked for too
for v in nan inf 1e999; do
  sed "s/^2,[0-9.]*,/2,$v,/" "$tmp/a6.csv" >"$tmp/nf.csv"
  # shellcheck disable=SC2086
  expect_refused "atlas: a row holding $v refused" "nf.csv:9: column 2 holds '$v', not a finite number" \
    "$tmp/nf.csv" $atl
done
# a non-finite number that the check of the rows once let through: after 70 zeros (a copy of
# the field cut to 63 characters read 0), or followed by a space
zeros=0000000000000000000000000000000000000000000000000000000000000000000000
sed "s/^2,[0-9.]*,/2,${zeros}1e999,/" "$tmp/a6.csv" >"$tmp/nz.csv"
# shellcheck disable=SC2086
expect_refused "atlas: a row holding 1e999 after 70 zeros refused" "nz.csv:9: column 2 holds '0000.*', not a finite number" \
  "$tmp/nz.csv" $atl
sed 's/^3,/4,/' "$tmp/a6.csv" >"$tmp/m4.csv"
# shellcheck disable=SC2086
expect_refused "atlas: a row of mode 4 (not asked for) refused" "m4.csv:10: mode 4 was not asked for" \
  "$tmp/m4.csv" $atl
sed 's/^\(3,[^,]*,[^,]*\),0,0,/\1,2,0,/' "$tmp/a6.csv" >"$tmp/flag.csv"
# shellcheck disable=SC2086
expect_refused "atlas: a flag of 2 refused" "flag.csv:10: open_from and open_to must be 0 or 1" \
  "$tmp/flag.csv" $atl
# a row of a chunk not done would be computed again: twice in the file
grep -v '^# done mode 3' "$tmp/a6.csv" >"$tmp/undone.csv"
# shellcheck disable=SC2086
expect_refused "atlas: a row in no chunk done refused" "undone.csv:[0-9]+: a window of mode 3 .* in no chunk done" \
  "$tmp/undone.csv" $atl

# other options: refused in one line naming the first difference. --modes 2 then 2,3 wrote
# every window of mode 3 twice; a larger --omega-max lost the windows beyond the first run's
expect_refused "atlas: --modes 2 on an atlas of 2,3 refused, the modes named" \
  "'.*a6.csv' was not written by an atlas with these options: line 1 has 'modes 2,3,' where these options write 'modes 2,'" \
  "$tmp/a6.csv" stability --atlas --modes 2 --omega-max 6
"$WHIRL" stability --atlas --modes 2,3 --omega-max 10 -o "$tmp/a6x.csv" --resume 2>/dev/null # (no file)
cp "$tmp/a6.csv" "$tmp/ext.csv"
"$WHIRL" stability --atlas --modes 2,3 --omega-max 10 -o "$tmp/ext.csv" --resume 2>"$tmp/err"
rc=$?
if [ $rc -eq 1 ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "line 1 has 'omega 6;' where these options write 'omega 10;'" "$tmp/err" &&
   cmp -s "$tmp/ext.csv" "$tmp/a6.csv"; then
  pass "atlas: a larger --omega-max refused, the rate named (not silently incomplete)"
elif [ $rc -eq 0 ] && "$WHIRL" stability --atlas --modes 2,3 --omega-max 10 -o "$tmp/a10.csv" &&
     cmp -s "$tmp/ext.csv" "$tmp/a10.csv"; then
  pass "atlas: a larger --omega-max computes exactly the missing part"
else fail "atlas: a larger --omega-max (rc=$rc, $(cat "$tmp/err"), $(diff "$tmp/ext.csv" "$tmp/a10.csv" 2>&1 | head -3))"; fi
# --degree, --tol, --scan-step change the rows: recorded in the header and compared
for p in "degree=16/degree=20" "tol=1e-09/tol=1e-08" "scan_step=0.25/scan_step=0.2"; do
  sed "2s/$p/" "$tmp/a6.csv" >"$tmp/opt.csv"
  # shellcheck disable=SC2086
  expect_refused "atlas: a file of ${p#*/} refused, named" \
    "line 2 has '[^ ]* ${p#*/}' where these options write '[^ ]* ${p%/*}'" "$tmp/opt.csv" $atl
done
# a file of 2.1.0 (no parameter line) is refused, not taken for one of these options
sed 2d "$tmp/a6.csv" >"$tmp/old.csv"
# shellcheck disable=SC2086
expect_refused "atlas: a file without the parameter line refused" "old.csv' was not written by an atlas with these options: line 2" \
  "$tmp/old.csv" $atl
# the rows of a good file kept, the missing chunk computed: the file of a fresh run
grep -v '^# done mode 2 omega 5 6' "$tmp/a6.csv" >"$tmp/part.csv"
# shellcheck disable=SC2086
if "$WHIRL" $atl -o "$tmp/part.csv" --resume 2>"$tmp/err" && cmp -s "$tmp/part.csv" "$tmp/a6.csv"; then
  pass "atlas: --resume of a good file completes it to the fresh run's file"
else fail "atlas: --resume of a good file ($(cat "$tmp/err"))"; fi
# an unfinished last line (a run killed while writing) is dropped, not refused
{ cat "$tmp/a6.csv"; printf '3,5.5,5.6'; } >"$tmp/cut.csv"
# shellcheck disable=SC2086
if "$WHIRL" $atl -o "$tmp/cut.csv" --resume 2>"$tmp/err" && cmp -s "$tmp/cut.csv" "$tmp/a6.csv"; then
  pass "atlas: an unfinished last line dropped"
else fail "atlas: an unfinished last line ($(cat "$tmp/err"))"; fi

# one run at a time: a second run on the file of a running atlas is refused (it replaced the
# complete atlas of the first with its partial one)
long="stability --atlas --modes 2 --omega-max 60"
# shellcheck disable=SC2086
env --default-signal=INT "$WHIRL" $long -o "$tmp/run.csv" >/dev/null 2>"$tmp/run.err" &
pid=$!
i=0
while ! grep -q '^# done mode 2 omega 0 5' "$tmp/run.csv" 2>/dev/null && [ $i -lt 1500 ]; do
  sleep 0.02; i=$((i + 1))
done
# shellcheck disable=SC2086
expect_refused "atlas: --resume on an atlas another run writes refused (locked)" \
  "run.csv' is being written by another run \(locked\)" "$tmp/run.csv" $long
# shellcheck disable=SC2086
"$WHIRL" $long -o "$tmp/run.csv" >/dev/null 2>"$tmp/err"
rc2=$?
interrupt $pid
if [ $rc2 -eq 1 ] && grep -q "is being written by another run" "$tmp/err" && [ $rc -eq 130 ] &&
   [ "$(grep -c '^# done mode 2' "$tmp/run.csv")" -ge 1 ]; then
  pass "atlas: a fresh run on it refused too; the first kept its chunks (exit 130)"
else fail "atlas: the lock (second rc=$rc2, first rc=$rc, $(cat "$tmp/err"))"; fi

# ---- the stability map ----
map="stability --omega-min 2 --omega-max 4 --omega-count 3 --modes 1,2 --links 6 --linear"
# shellcheck disable=SC2086
"$WHIRL" $map -o "$tmp/smap.csv" 2>"$tmp/err" || fail "stability map ($(cat "$tmp/err"))"
expect_refused "stability map: other options refused, the first difference named" \
  "not written by a map with these options: line 2 has 'to 4,' where these options write 'to 5,'" \
  "$tmp/smap.csv" stability --omega-min 2 --omega-max 5 --omega-count 3 --modes 1,2 --links 6 --linear
sed 's/^3,2,/3,5,/' "$tmp/smap.csv" >"$tmp/sm5.csv"
# shellcheck disable=SC2086
expect_refused "stability map: a row of mode 5 (not asked for) refused" "sm5.csv:[0-9]+: .*no point of this map" \
  "$tmp/sm5.csv" $map
sed 's/^3,2,/3.5,2,/' "$tmp/smap.csv" >"$tmp/sm35.csv"
# shellcheck disable=SC2086
expect_refused "stability map: a row of a rate off the grid refused" "sm35.csv:[0-9]+: .*no point of this map" \
  "$tmp/sm35.csv" $map
for v in nan inf 1e999; do
  sed "s/^\(3,2,6\),[^,]*,/\1,$v,/" "$tmp/smap.csv" >"$tmp/smn.csv"
  # shellcheck disable=SC2086
  expect_refused "stability map: a row holding $v refused" "smn.csv:[0-9]+: column 4 holds '$v'" \
    "$tmp/smn.csv" $map
done

# ---- the regime map ----
rmap="regime --omega-min 1 --omega-max 2 --omega-count 3 --eps 0.05 --links 5 --drag 0.25 --t-max 150 --t-ramp 10"
# shellcheck disable=SC2086
"$WHIRL" $rmap -o "$tmp/rmap.csv" 2>"$tmp/err" || fail "regime map ($(cat "$tmp/err"))"
expect_refused "regime map: other parameters refused, the first difference named" \
  "not written by a map with these parameters: line 2 has 'links=5 drag=0.25' where these parameters write 'links=5 drag=0.3'" \
  "$tmp/rmap.csv" regime --omega-min 1 --omega-max 2 --omega-count 3 --eps 0.05 --links 5 --drag 0.3 --t-max 150 --t-ramp 10
sed 's/^2,2,/7,2,/' "$tmp/rmap.csv" >"$tmp/ri.csv"
# shellcheck disable=SC2086
expect_refused "regime map: a row of index 7 (of 3 points) refused" "ri.csv:[0-9]+: .*no point of this map" \
  "$tmp/ri.csv" $rmap
sed 's/^2,2,/2,1.7,/' "$tmp/rmap.csv" >"$tmp/ro.csv"
# shellcheck disable=SC2086
expect_refused "regime map: a row whose rate is not its index's refused" "ro.csv:[0-9]+: .*no point of this map" \
  "$tmp/ro.csv" $rmap
for v in "nan " "infx" "${zeros}1e999"; do
  awk -F, -v v="$v" 'BEGIN { OFS = "," } /^1,/ { $9 = v } { print }' "$tmp/rmap.csv" >"$tmp/rv.csv"
  # shellcheck disable=SC2086
  expect_refused "regime map: a row with '$(echo "$v" | cut -c1-12)' in column 9 refused" "rv.csv:[0-9]+: column 9 holds" \
    "$tmp/rv.csv" $rmap
done
sed 's/^\(1,.*\)$/# note\n\1/' "$tmp/rmap.csv" >"$tmp/rc.csv"
# shellcheck disable=SC2086
expect_refused "regime map: a comment among the rows refused" "rc.csv:[0-9]+: a comment among the rows" \
  "$tmp/rc.csv" $rmap

finish
