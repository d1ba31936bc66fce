#!/bin/sh
# Command-line tests of the progress lines of long phases: the continuations of the N-link chain
# (whirl shape, whirl sweep), the critical rates of a long chain (whirl critical) and the reading
# and writing of a large file (whirl view). The line shows on a terminal only (the command run on
# a pseudo-terminal by util-linux's script), says where the work stands and is erased at the end,
# and the output stays the same; Ctrl-C typed on the terminal while the line shows stops the
# command within 2 s (exit 130, nothing written). The bound on the continuation steps
# (--max-steps) stops a run with one line naming the mode and the rate reached, and no output.
. "$(dirname "$0")/lib.sh"

# Mode 100 of 1000 links (born at omega 156.81) up to 190: some 5000 steps and 160 folds, about
# 2 s. The line starts after a second by default; on the pseudo-terminal it is asked for at once
# (WHIRL_PROGRESS_AFTER=0), so that the lines are there however fast the machine.
shape="shape --links 1000 --mode 100 --omega 190"
sweep="sweep --links 1000 --modes 1,100 --omega-min 170 --omega-max 190 --omega-count 3"
printf '\r\033[K' >"$tmp/erase"

# on_tty NAME REDIRECTIONS ARGS...: runs `whirl ARGS REDIRECTIONS` on a pseudo-terminal, the
# progress line asked for from the first report, what the terminal shows into $tmp/NAME.tty; its
# exit status.
on_tty() {
  name=$1; redir=$2; shift 2
  WHIRL_PROGRESS_AFTER=0 script -qfec "\"$WHIRL\" $* $redir" /dev/null </dev/null >"$tmp/$name.tty"
}

# progress_lines NAME CMD PATTERN: the lines drawn on the terminal (each "\r...\033[K") that
# match "^whirl CMD: PATTERN, Ns elapsed$" (the erase sequences removed), into $tmp/NAME.lines.
progress_lines() {
  tr '\r' '\n' <"$tmp/$1.tty" | sed 's/\x1b\[K$//' \
    | grep -E "^whirl $2: $3, [0-9]+s elapsed\$" >"$tmp/$1.lines"
}

# ---- shape ----
if command -v script >/dev/null 2>&1; then pass "script (util-linux) is installed"
else fail "script (util-linux) is installed"; fi
# the CSV to a file, standard error on the terminal: the line shows, then is erased
on_tty shape ">\"$tmp/shape_tty.csv\"" $shape
rc=$?
progress_lines shape shape \
  'mode 100: omega [0-9.]+ of 190 \(now [0-9.]+\), [0-9]+ steps \(at most 200000\), [0-9]+ folds'
if [ $rc -eq 0 ] && [ -s "$tmp/shape.lines" ]; then pass "shape: a progress line on a terminal"
else fail "shape: a progress line on a terminal (rc=$rc: $(tr '\r\033' '|^' <"$tmp/shape.tty" | head -c 300))"; fi
# what the lines say: the highest rate between the birth and the target, at least the current
# one; steps reported every 256 (from the start, step 0), folds among them, and some later
# report past the first steps and folds
if awk '{split($0, f, /[ (),]+/)
         hi = f[6]; now = f[10]; steps = f[11]; folds = f[16]
         if (!(hi >= 156.8 && hi <= 190 && now <= hi && now >= 156.8 && steps % 256 == 0 &&
               folds >= 0 && (folds < steps || steps == 0 && folds == 0))) bad = 1
         if (steps > 0 && folds > 0) later++}
       END {exit bad || later == 0}' "$tmp/shape.lines"; then
  pass "shape: the line's rates, steps and folds"
else fail "shape: the line's rates, steps and folds ($(head -n 2 "$tmp/shape.lines"))"; fi
if grep -q 'left' "$tmp/shape.tty"; then fail "shape: no estimate of the time left"
else pass "shape: no estimate of the time left"; fi
if tail -c 4 "$tmp/shape.tty" | cmp -s - "$tmp/erase"; then pass "shape: the line is erased at the end"
else fail "shape: the line is erased at the end ($(tail -c 40 "$tmp/shape.tty" | tr '\r\033' '|^'))"; fi
# the CSV to the terminal, standard error to a file: no line anywhere, the same CSV
on_tty shape_err "2>\"$tmp/shape.err\"" $shape
rc=$?
tr -d '\r' <"$tmp/shape_err.tty" >"$tmp/shape_err.csv"
if [ $rc -eq 0 ] && [ ! -s "$tmp/shape.err" ] && ! grep -q 'whirl' "$tmp/shape_err.tty" \
   && [ "$(grep -c '^[0-9]' "$tmp/shape_err.csv")" -eq 1001 ]; then
  pass "shape: no progress line when standard error is not a terminal"
else fail "shape: no progress line when standard error is not a terminal (rc=$rc, $(head -c 200 "$tmp/shape.err"))"; fi
if cmp -s "$tmp/shape_tty.csv" "$tmp/shape_err.csv" && ! grep -q "$(printf '[\r\033]')" "$tmp/shape_tty.csv"
then pass "shape: the CSV is the same, with or without the line"
else fail "shape: the CSV is the same, with or without the line"; fi

# ---- sweep: the same line, with the mode's place in the list ----
on_tty sweep ">\"$tmp/sweep_tty.csv\"" $sweep
rc=$?
progress_lines sweep sweep \
  'mode 100 \(2 of 2\): omega [0-9.]+ of 190 \(now [0-9.]+\), [0-9]+ steps \(at most 200000\), [0-9]+ folds'
if [ $rc -eq 0 ] && [ -s "$tmp/sweep.lines" ] && ! grep -q 'left' "$tmp/sweep.tty" \
   && tail -c 4 "$tmp/sweep.tty" | cmp -s - "$tmp/erase"; then
  pass "sweep: a progress line on a terminal, erased at the end"
else fail "sweep: a progress line on a terminal, erased at the end (rc=$rc: $(tr '\r\033' '|^' <"$tmp/sweep.tty" | head -c 300))"; fi
on_tty sweep_err "2>\"$tmp/sweep.err\"" $sweep
rc=$?
tr -d '\r' <"$tmp/sweep_err.tty" >"$tmp/sweep_err.csv"
if [ $rc -eq 0 ] && [ ! -s "$tmp/sweep.err" ] && ! grep -q 'whirl' "$tmp/sweep_err.tty" \
   && cmp -s "$tmp/sweep_tty.csv" "$tmp/sweep_err.csv" \
   && [ "$(grep -c '^1[0-9]*,100,' "$tmp/sweep_tty.csv")" -ge 3 ]; then
  pass "sweep: no progress line when standard error is not a terminal, the same CSV"
else fail "sweep: no progress line when standard error is not a terminal, the same CSV (rc=$rc)"; fi

# ctrl_c PATTERN ARGS...: runs `whirl ARGS` on a pseudo-terminal (the line asked for at once),
# types Ctrl-C once the terminal shows PATTERN (the terminal's line discipline sends SIGINT),
# and sets cc_rc (the exit status) and cc_late (seconds from the Ctrl-C to the exit); the
# terminal's text in $tmp/cc.tty.
ctrl_c() {
  pattern=$1; shift
  rm -f "$tmp/cc.tty" "$tmp/cc.rc" "$tmp/cc.t0" "$tmp/cc.t1"
  { i=0
    until grep -q "$pattern" "$tmp/cc.tty" 2>/dev/null || [ $i -ge 600 ]; do sleep 0.05; i=$((i + 1)); done
    date +%s.%N >"$tmp/cc.t0"; printf '\003'
    i=0; until [ -e "$tmp/cc.rc" ] || [ $i -ge 100 ]; do sleep 0.05; i=$((i + 1)); done; } |
    { WHIRL_PROGRESS_AFTER=0 script -qfec "exec \"$WHIRL\" $*" /dev/null >"$tmp/cc.tty"
      echo $? >"$tmp/cc.rc.new"; date +%s.%N >"$tmp/cc.t1"; mv "$tmp/cc.rc.new" "$tmp/cc.rc"; }
  cc_rc=$(cat "$tmp/cc.rc")
  cc_late=$(echo "$(cat "$tmp/cc.t1") - $(cat "$tmp/cc.t0")" | bc)
}

# ---- critical: the eigenvalues of a long chain, counted ----
on_tty critical ">\"$tmp/crit_tty.csv\"" critical --links 2000 --modes 2000
rc=$?
# the lines drawn: the count of rates, the time and the time left (none in the last line,
# drawn once every rate is found); any other line starting "whirl critical" is wrong
tr '\r' '\n' <"$tmp/critical.tty" | sed 's/\x1b\[K$//' | grep '^whirl critical' >"$tmp/critical.all"
grep -E '^whirl critical: critical rates [0-9]+/2000 \([0-9]+%\), [0-9]+s elapsed(, about [0-9hms]+ left)?$' \
  "$tmp/critical.all" >"$tmp/critical.lines"
grep -Ev '^whirl critical: critical rates [0-9]+/2000 \([0-9]+%\), [0-9]+s elapsed(, about [0-9hms]+ left)?$' \
  "$tmp/critical.all" >"$tmp/critical.other"
if [ $rc -eq 0 ] && [ -s "$tmp/critical.lines" ] && [ ! -s "$tmp/critical.other" ] &&
   tail -c 4 "$tmp/critical.tty" | cmp -s - "$tmp/erase"; then
  pass "critical: a progress line on a terminal ($(wc -l <"$tmp/critical.lines") drawn), erased at the end"
else fail "critical: a progress line on a terminal (rc=$rc: $(tr '\r\033' '|^' <"$tmp/critical.tty" | head -c 300))"; fi
# the counts grow, in blocks of dstebz, up to the modes asked for
if awk '{split($0, f, /[ /]+/); k = f[5]; if (k <= last || k > 2000) bad = 1; last = k}
        END {exit bad || NR == 0}' "$tmp/critical.lines"; then pass "critical: the count of rates grows to 2000"
else fail "critical: the count of rates ($(head -n 3 "$tmp/critical.lines"))"; fi
"$WHIRL" critical --links 2000 --modes 2000 >"$tmp/crit.csv" 2>"$tmp/crit.err"
if cmp -s "$tmp/crit.csv" "$tmp/crit_tty.csv" && [ ! -s "$tmp/crit.err" ] &&
   [ "$(grep -c '^[0-9]' "$tmp/crit.csv")" -eq 2000 ]; then
  pass "critical: the same 2000 rates with or without the line, none on a file"
else fail "critical: the same rates with or without the line ($(head -c 200 "$tmp/crit.err"))"; fi
# a run shorter than a second shows nothing by default
script -qfec "\"$WHIRL\" critical --links 300 --modes 300 >/dev/null" /dev/null </dev/null \
  >"$tmp/crit_short.tty"
if ! grep -q whirl "$tmp/crit_short.tty"; then pass "critical: no line for a run under a second"
else fail "critical: no line for a run under a second ($(tr '\r\033' '|^' <"$tmp/crit_short.tty" | head -c 200))"; fi
# Ctrl-C while the line shows: the eigenvalues of 60000 links (minutes) stop at once
rm -rf "$tmp/cc_out"; mkdir "$tmp/cc_out"
ctrl_c 'critical rates [0-9]' critical --links 60000 --modes 60000 -o "$tmp/cc_out/c.csv"
if [ "$cc_rc" -eq 130 ] && [ "$(echo "$cc_late < 2" | bc)" -eq 1 ] && [ -z "$(ls -A "$tmp/cc_out")" ] &&
   tr '\r' '\n' <"$tmp/cc.tty" | grep -q 'whirl critical: stopped after [0-9]* of 60000 critical rates'; then
  pass "critical: Ctrl-C on the terminal stops 60000 links in $cc_late s (exit 130, no file)"
else fail "critical: Ctrl-C (rc=$cc_rc, $cc_late s, $(ls -A "$tmp/cc_out"), $(tr '\r\033' '|^' <"$tmp/cc.tty" | tail -c 200))"; fi

# ---- view: the reading and the writing of a large file ----
# a shape of 2e6 points (84 MB): some seconds to read, one to write
awk 'BEGIN {print "# omega=3 mode=2"; print "s,r,z,tension"
            for (i = 0; i < 2000000; i++) printf "%.15g,%.15g,%.15g,1\n", i * 1e-7, 0.1 * sin(i * 1e-6), -i * 3.3e-7}' \
  >"$tmp/big.csv"
on_tty view ">/dev/null" view "$tmp/big.csv" -o "$tmp/big_tty.html"
rc=$?
progress_lines view view 'reading .*big\.csv: [0-9]+/[0-9]+ MiB \([0-9]+%\)'
cp "$tmp/view.lines" "$tmp/view_r.lines"
progress_lines view view 'writing the page: [0-9]+/2000000 points \([0-9]+%\)'
if [ $rc -eq 0 ] && [ -s "$tmp/view_r.lines" ] && [ -s "$tmp/view.lines" ] &&
   tail -c 4 "$tmp/view.tty" | cmp -s - "$tmp/erase"; then
  pass "view: progress lines for the reading and the writing, erased at the end"
else fail "view: progress lines (rc=$rc: $(tr '\r\033' '|^' <"$tmp/view.tty" | head -c 300))"; fi
"$WHIRL" view "$tmp/big.csv" -o "$tmp/big.html" 2>"$tmp/view.err"
if cmp -s "$tmp/big.html" "$tmp/big_tty.html" && [ ! -s "$tmp/view.err" ]; then
  pass "view: the same page with or without the line"
else fail "view: the same page with or without the line ($(head -c 200 "$tmp/view.err"))"; fi
rm -f "$tmp/big.html" "$tmp/big_tty.html"
for phase in reading 'writing the page'; do
  rm -rf "$tmp/cc_out"; mkdir "$tmp/cc_out"
  ctrl_c "view: $phase" view "$tmp/big.csv" -o "$tmp/cc_out/big.html"
  case $phase in reading) said='big.csv:[0-9]+: interrupted while reading' ;;
                 *) said='interrupted while writing the page: nothing written' ;; esac
  if [ "$cc_rc" -eq 130 ] && [ "$(echo "$cc_late < 2" | bc)" -eq 1 ] && [ -z "$(ls -A "$tmp/cc_out")" ] &&
     tr '\r' '\n' <"$tmp/cc.tty" | grep -Eq "whirl view: (.*/)?$said"; then
    pass "view: Ctrl-C while $phase stops it in $cc_late s (exit 130, no file)"
  else fail "view: Ctrl-C while $phase (rc=$cc_rc, $cc_late s, $(ls -A "$tmp/cc_out"), $(tr '\r\033' '|^' <"$tmp/cc.tty" | tail -c 200))"; fi
done
rm -f "$tmp/big.csv"

# ---- --max-steps: a bound on the continuation steps of each branch ----
expect_error "shape: --max-steps 10 stops a long continuation, no file" \
  '^whirl shape: mode 100: 10 continuation steps from the birth at omega=156\.8[0-9]* .*reached omega=15[6-9]\.[0-9]+ at most .*--max-steps' \
  $shape --max-steps 10 -o "$tmp/out.csv"
expect_error "sweep: --max-steps 10 stops a long continuation, no file" \
  '^whirl sweep: mode 100: 10 continuation steps from the birth at omega=156\.8[0-9]* .*reached omega=15[6-9]\.[0-9]+ at most .*--max-steps' \
  sweep --links 1000 --modes 100 --omega-min 170 --omega-max 190 --omega-count 3 --max-steps 10 \
  -o "$tmp/out.csv"
expect_error "sweep: --max-steps 10 in the first mode of two, nothing on standard output" \
  '^whirl sweep: mode 1: 10 continuation steps from the birth at omega=1\.202' $sweep --max-steps 10
# a bound the run stays within changes nothing
expect_ok "shape: --max-steps within the run's needs" \
  shape --links 40 --mode 12 --omega 30 --max-steps 1000 -o "$tmp/bounded.csv"
expect_ok "shape: the default bound" shape --links 40 --mode 12 --omega 30 -o "$tmp/default.csv"
if cmp -s "$tmp/bounded.csv" "$tmp/default.csv"; then pass "shape: a bound not reached changes nothing"
else fail "shape: a bound not reached changes nothing"; fi
for bad in 0 -3; do
  expect_error "shape: --max-steps $bad" "^whirl shape: --max-steps must be >= 1, got $bad\$" \
    shape --links 40 --mode 12 --omega 30 --max-steps $bad -o "$tmp/out.csv"
done
for bad in 2.5 1e3 ten ''; do
  expect_error "sweep: --max-steps '$bad'" "^whirl sweep: option --max-steps needs an integer" \
    sweep --links 40 --modes 12 --omega-min 20 --omega-max 30 --omega-count 2 --max-steps "$bad" \
    -o "$tmp/out.csv"
done
expect_error "shape: --max-steps needs --links" "^whirl shape: --max-steps needs --links\$" \
  shape --mode 2 --omega 4 --max-steps 100 -o "$tmp/out.csv"
# ---- stability --windows of the continuum: the modes done and the rate each search reached ----
cwin="stability --windows --modes 2 --omega-min 5 --omega-max 8"
on_tty cwin "-o \"$tmp/cwin_tty.csv\"" $cwin
rc=$?
progress_lines cwin stability \
  'windows: [01] of 1 modes done(; mode 2: omega [0-9.]+ of 8 \(now [0-9.]+\))?'
# shellcheck disable=SC2086
"$WHIRL" $cwin -o "$tmp/cwin.csv" 2>"$tmp/cwin.err"
if [ $rc -eq 0 ] && [ -s "$tmp/cwin.lines" ] && ! grep -q 'left' "$tmp/cwin.tty" &&
   awk '/mode 2:/ {split($0, f, /[ (),]+/); hi = f[12]; now = f[16]
                   if (!(hi >= 5 && hi <= 8 && now >= 5 && now <= hi && hi >= last)) bad = 1
                   last = hi; n++}
        END {exit bad || n == 0}' "$tmp/cwin.lines" &&
   tail -c 4 "$tmp/cwin.tty" | cmp -s - "$tmp/erase" &&
   [ ! -s "$tmp/cwin.err" ] &&
   [ "$(grep -v '^# mode' "$tmp/cwin_tty.csv")" = "$(grep -v '^# mode' "$tmp/cwin.csv")" ]; then
  pass "stability --windows (continuum): a progress line with the rate reached, erased at the end, the same CSV"
else fail "stability --windows progress (rc=$rc: $(head -n 2 "$tmp/cwin.lines"; tr '\r\033' '|^' <"$tmp/cwin.tty" | head -c 300))"; fi

if "$WHIRL" shape --help | grep -q -- '--max-steps S .*(default max(100000, 200 N))' \
   && "$WHIRL" sweep --help | grep -q -- '--max-steps S '; then pass "--max-steps in the help"
else fail "--max-steps in the help"; fi

# ---- stability --eigenvalues: the dense eigen-solve (minutes at thousands of links) ----
eig="stability --omega 4 --mode 2 --links 150 --eigenvalues"
on_tty eig "-o \"$tmp/eig_tty.csv\"" $eig
rc=$?
progress_lines eig stability 'eigen-solve of 150 links'
# shellcheck disable=SC2086
"$WHIRL" $eig -o "$tmp/eig.csv" 2>"$tmp/eig.err"
if [ $rc -eq 0 ] && [ -s "$tmp/eig.lines" ] && tail -c 4 "$tmp/eig.tty" | cmp -s - "$tmp/erase" &&
   [ ! -s "$tmp/eig.err" ] && cmp -s "$tmp/eig_tty.csv" "$tmp/eig.csv"; then
  pass "stability --eigenvalues: a progress line while the eigen-solve runs, erased at the end, the same CSV"
else fail "stability --eigenvalues: progress (rc=$rc, $(wc -l <"$tmp/eig.lines") lines, $(tail -c 80 "$tmp/eig.tty" | od -c | head -3))"; fi

finish
