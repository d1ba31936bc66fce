#!/bin/sh
# Command-line tests of whirl periodic: the shaken pendulum inside Mathieu's first tongue, the
# circle drive's steady shape as a periodic motion, SI units, bad input.
. "$(dirname "$0")/lib.sh"

# N = 1 shaken vertically at omega = 2 (a = 1, q = 0.2): inside the first tongue, a multiplier
# below -1 (the period doubling of the parametric resonance); comment lines, the units line,
# the header, the 2 multipliers of the planar pendulum
expect_ok "periodic Mathieu" periodic --pivot vertical:0.1 --omega 2 --links 1 --dim 2 -o "$tmp/m.csv"
if grep -q '^# verdict=unstable growth=1.3671' "$tmp/m.csv" && grep -q 'edge=-1$' "$tmp/m.csv" \
   && grep -q '^# units: dimensionless' "$tmp/m.csv" \
   && [ "$(grep -v '^#' "$tmp/m.csv" | head -1)" = "index,re,im,modulus,err" ] \
   && [ "$(grep -vc '^#' "$tmp/m.csv")" -eq 3 ] \
   && grep -v '^#' "$tmp/m.csv" | sed -n 2p | awk -F, '{exit !($2 < -1.367 && $2 > -1.368 && $3 == 0)}'; then
  pass "periodic Mathieu: unstable through -1, two multipliers"; else fail "periodic Mathieu: unstable through -1, two multipliers"; fi
# outside the tongue (omega = 1.5): neutral, the multipliers on the unit circle
expect_ok "periodic Mathieu outside" periodic --pivot vertical:0.1 --omega 1.5 --dim 2
if grep -q '^# verdict=neutral' "$tmp/stdout" \
   && grep -v '^#' "$tmp/stdout" | awk -F, 'NR > 1 && ($4 - 1) ^ 2 > 1e-18 {bad = 1} END {exit bad}'; then
  pass "periodic Mathieu outside: neutral on the circle"; else fail "periodic Mathieu outside: neutral on the circle"; fi

# the circle drive's mode-2 shape: Newton from the steady shape, 4 N multipliers in 3D
expect_ok "periodic steady" periodic --pivot circle:0.05 --omega 4 --links 4 --start steady --mode 2 -o "$tmp/c.csv"
if grep -q '^# verdict=unstable' "$tmp/c.csv" && [ "$(grep -vc '^#' "$tmp/c.csv")" -eq 17 ]; then
  pass "periodic steady: unstable mode 2, 16 multipliers"; else fail "periodic steady: unstable mode 2, 16 multipliers"; fi

# the cross-check: the same multipliers by central differences (to 1e-9)
expect_ok "periodic --differences" periodic --pivot vertical:0.1 --omega 2 --links 1 --dim 2 --differences -o "$tmp/d.csv"
if grep -q '^# monodromy by central differences' "$tmp/d.csv" && grep -q '^# monodromy by the variational equations' "$tmp/m.csv" \
   && paste -d, "$tmp/m.csv" "$tmp/d.csv" | grep -v '^#' | awk -F, 'NR > 1 && ($2 - $7) ^ 2 + ($3 - $8) ^ 2 > 1e-18 {bad = 1} END {exit bad}'; then
  pass "periodic --differences: the same multipliers"; else fail "periodic --differences: the same multipliers"; fi

# SI units: the path in cm, the rate in Hz, the period in s
expect_ok "periodic SI" periodic --pivot ellipse:1cm,0.6cm --omega 1.5Hz --length 0.5 --mass 50g --links 2 -o "$tmp/si.csv"
if grep -q '^# period=0.666666666666666[0-9]* s;' "$tmp/si.csv" && grep -q '^# units: length=m' "$tmp/si.csv"; then
  pass "periodic SI: period in s"; else fail "periodic SI: period in s"; fi
expect_ok "periodic --help" periodic --help

# bad input: one line naming the term, nothing written
expect_error "no pivot" "whirl periodic: --pivot .*is required" periodic --omega 2 -o "$tmp/out.csv"
expect_error "no rate" "whirl periodic: --omega .*is required" periodic --pivot circle:0.1 -o "$tmp/out.csv"
expect_error "zero rate" "whirl periodic: --omega must be" periodic --pivot circle:0.1 --omega 0 -o "$tmp/out.csv"
expect_error "unknown path" "whirl periodic: --pivot: pivot path 'square': unknown kind" periodic --pivot square:1 --omega 2 -o "$tmp/out.csv"
expect_error "bad term" "whirl periodic: --pivot: .*term 'x9c'" periodic --pivot fourier:x9c=0.1 --omega 2 -o "$tmp/out.csv"
expect_error "bad length" "whirl periodic: --pivot: .*ellipse B: 'abc' is not a length" periodic --pivot ellipse:0.1,abc --omega 2 -o "$tmp/out.csv"
expect_error "unit without SI" "whirl periodic: --pivot: .*has a unit" periodic --pivot circle:1cm --omega 2 -o "$tmp/out.csv"
expect_error "y term in 2D" "whirl periodic: --pivot: .*y1s moves the pivot out of the x-z plane" periodic --pivot ellipse:0.1,0.1 --omega 2 --dim 2 -o "$tmp/out.csv"
expect_error "infinite amplitude" "whirl periodic: --pivot: .*circle R" periodic --pivot circle:1e999 --omega 2 -o "$tmp/out.csv"
expect_error "bad start" "whirl periodic: --start must be hanging, inverted or steady" periodic --pivot circle:0.1 --omega 2 --start up -o "$tmp/out.csv"
expect_error "steady without circle" "whirl periodic: --start steady needs --pivot circle" periodic --pivot ellipse:0.1,0.05 --omega 2 --start steady -o "$tmp/out.csv"
expect_error "bad dim" "whirl periodic: --dim must be" periodic --pivot vertical:0.1 --omega 2 --dim 4 -o "$tmp/out.csv"
expect_error "few steps" "whirl periodic: --steps must be" periodic --pivot vertical:0.1 --omega 2 --steps 2 -o "$tmp/out.csv"
# the damped pendulum (no drive: a path of zero amplitude): the damped oscillator, theta'' +
# (D / (m l^2)) theta' + theta = 0, |mu| = exp(-D T / 2) with T = 2 pi / 1.3; the multipliers
# not in pairs, said so
expect_ok "periodic damped" periodic --pivot vertical:0 --omega 1.3 --links 1 --dim 2 --damping 0.3 -o "$tmp/damped.csv"
if grep -q '^# verdict=stable' "$tmp/damped.csv" && grep -q '^# dissipation: drag=0 drag_quadratic=0 damping=0.3$' "$tmp/damped.csv" \
   && grep -q 'not in pairs: not an error' "$tmp/damped.csv" \
   && grep -v '^#' "$tmp/damped.csv" | awk -F, 'NR > 1 { d = $4 - exp(-0.15 * 2 * 3.141592653589793 / 1.3); if (d * d > 1e-22) bad = 1; n++ } END {exit bad || n != 2}'; then
  pass "periodic damped: |mu| = exp(-D T / 2)"; else fail "periodic damped: |mu| = exp(-D T / 2)"; fi
# the dragged circle drive's torus (tests/unit/periodic/test_periodic_dissipative.c: at the root of the
# steady linearisation's growth rate, 2.850665362775)
expect_ok "periodic drag torus" periodic --pivot circle:0.05 --omega 2.8 --links 3 --start steady --mode 2 --side -1 --drag 0.05 --omega-min 2.8 --omega-max 2.9 --up --arc-step 0.02 -o "$tmp/torus.csv"
if grep '^# torus omega=' "$tmp/torus.csv" | awk '{sub("omega=", "", $3); d = $3 - 2.850665362775; exit !(d * d < 1e-16)}' \
   && [ "$(grep -c '^# torus' "$tmp/torus.csv")" -eq 1 ]; then
  pass "periodic drag torus: located"; else fail "periodic drag torus: located"; fi
expect_error "joint damping on a chart" "whirl periodic: --chart .*--damping" periodic --chart hanging --omega-min 1 --omega-max 2 --amp-max 0.1 --damping 0.1 -o "$tmp/out.csv"
expect_error "negative damping" "whirl periodic: --damping must be" periodic --pivot vertical:0.1 --omega 2 --damping -1 -o "$tmp/out.csv"
# Newton that cannot converge: the residual named, no multipliers
expect_error "Newton fails" "whirl periodic: Newton's method on the period map did not converge in 1 iterations: residual [0-9.e-]+" periodic --pivot ellipse:0.1,0.05 --omega 3 --links 3 --max-iter 1 --tol 1e-14 -o "$tmp/out.csv"
# the progress line on a terminal (util-linux's script; asked for at once): which solve, Newton's
# iteration and residual, the monodromy's part when a tick falls within it (a short run may end
# first: no timing is assumed); erased at the end, the same multipliers written
printf '\r\033[K' >"$tmp/erase"
WHIRL_PROGRESS_AFTER=0 script -qfec "\"$WHIRL\" periodic --pivot ellipse:0.02,0.01 --omega 3 --links 4 -o $tmp/tty.csv" /dev/null </dev/null >"$tmp/p.tty"
rc=$?
"$WHIRL" periodic --pivot ellipse:0.02,0.01 --omega 3 --links 4 -o "$tmp/plain.csv"
if [ $rc -eq 0 ] && tr '\r' '\n' <"$tmp/p.tty" | sed 's/\x1b\[K$//' \
     | grep -Eq '^whirl periodic: solve [12] of 2, Newton iteration [0-9]+ \(residual [0-9.e+-]+\)(, monodromy [0-9]+%)?, [0-9]+s elapsed$' \
   && [ "$(tail -c 4 "$tmp/p.tty" | od -An -c | tr -d ' ')" = "$(od -An -c <"$tmp/erase" | tr -d ' ')" ] \
   && cmp -s "$tmp/tty.csv" "$tmp/plain.csv"; then
  pass "periodic progress line: shown, erased, the same CSV"; else fail "periodic progress line: shown, erased, the same CSV (rc=$rc)"; fi

# Ctrl-C during a long solve (60 links): exit status 130, one line, no file
env --default-signal=INT "$WHIRL" periodic --pivot ellipse:0.02,0.01 --omega 3 --links 60 -o "$tmp/out.csv" 2>"$tmp/stderr" &
pid=$!
sleep 1
interrupt $pid
if [ $rc -eq 130 ] && [ ! -e "$tmp/out.csv" ] && grep -q '^whirl periodic: interrupted' "$tmp/stderr"; then
  pass "periodic interrupted: 130, no file"; else fail "periodic interrupted: 130, no file (rc=$rc)"; fi
# a branch in the amplitude (N = 1 hanging at omega = 1.8, A from 0.01 up): the period doubling
# at Mathieu's a_1(q) = 4 / omega^2, q = 2 A; scipy 1.10.1's root (the command in
# tests/unit/periodic/test_cycle_path.c): A = 0.12105968496067503, to 1e-8
expect_ok "periodic branch amplitude" periodic --pivot vertical:0.01 --omega 1.8 --links 1 --dim 2 --amp-max 0.3 --up -o "$tmp/b.csv"
if grep -q '^# periodic branch: pivot vertical:0.01, links=1 dim=2 start=hanging; followed in the amplitude from 0.01 towards larger values, [0-9]* rows (1 events), left the range$' "$tmp/b.csv" \
   && grep -q '^# units: dimensionless' "$tmp/b.csv" \
   && [ "$(grep -v '^#' "$tmp/b.csv" | head -1)" = "event,omega,amplitude,max_modulus,verdict,edge,fold_test,flip_test,torus_test,err" ] \
   && [ "$(grep -c '^# period-doubling' "$tmp/b.csv")" -eq 1 ] && [ "$(grep -c '^# fold\|^# branch ' "$tmp/b.csv")" -eq 0 ] \
   && grep '^# period-doubling' "$tmp/b.csv" | sed 's/.*amplitude=\([^ ]*\) err=\(.*\)/\1 \2/' \
      | awk '{d = $1 - 0.12105968496067503; if (d < 0) d = -d; exit !(d < 1e-8 && $2 < 1e-8)}' \
   && grep '^period-doubling,1.8,' "$tmp/b.csv" >/dev/null \
   && grep -v '^#' "$tmp/b.csv" | awk -F, 'NR > 1 && $1 == "point" {if ($3 < 0.121 && $5 != "neutral" || $3 > 0.122 && $5 != "unstable") bad = 1; n++} END {exit bad || n < 5}'; then
  pass "periodic branch amplitude: period doubling on a_1 to 1e-8"; else fail "periodic branch amplitude: period doubling on a_1 to 1e-8"; fi

# a branch in the rate: the circle drive's shape of mode 1 opposite the pivot (N = 2, eps 0.05)
# folds where whirl driven's steady branch folds, to 1e-8
expect_ok "driven fold" driven --links 2 --eps 0.05 --omega-min 1.1 --omega-max 1.5 --omega 1.3 --mode 1 --side -1 -o "$tmp/d.csv"
expect_ok "periodic branch rate" periodic --pivot circle:0.05 --omega 1.3 --links 2 --start steady --side -1 --omega-min 1.1 --omega-max 1.5 -o "$tmp/f.csv"
steady=$(sed -n 's/^# fold omega=//p' "$tmp/d.csv")
if [ "$(grep -c '^# fold omega=' "$tmp/f.csv")" -eq 1 ] && [ -n "$steady" ] \
   && grep '^# fold' "$tmp/f.csv" | sed 's/.*omega=\([^ ]*\) .*/\1/' \
      | awk -v s="$steady" '{d = $1 - s; if (d < 0) d = -d; exit !(d < 1e-8)}'; then
  pass "periodic branch rate: the fold of cycles at whirl driven's fold to 1e-8"; else fail "periodic branch rate: the fold of cycles at whirl driven's fold to 1e-8 (steady $steady)"; fi

# bad input of a branch: one line, nothing written
expect_error "branch in both" "whirl periodic: a branch follows one parameter" periodic --pivot vertical:0.01 --omega 1.8 --dim 2 --omega-min 1 --omega-max 2 --amp-max 0.3 -o "$tmp/out.csv"
expect_error "branch --up alone" "whirl periodic: --up, --arc-step and --max-points need a branch" periodic --pivot vertical:0.01 --omega 1.8 --dim 2 --up -o "$tmp/out.csv"
expect_error "branch empty range" "whirl periodic: --amp-max must exceed --amp-min" periodic --pivot vertical:0.01 --omega 1.8 --dim 2 --amp-min 0.3 --amp-max 0.2 -o "$tmp/out.csv"
expect_error "branch start outside" "whirl periodic: --omega .*outside" periodic --pivot vertical:0.01 --omega 3 --dim 2 --omega-min 1 --omega-max 2 -o "$tmp/out.csv"
expect_error "branch start amplitude outside" "whirl periodic: the start's amplitude" periodic --pivot vertical:0.5 --omega 1.8 --dim 2 --amp-max 0.3 -o "$tmp/out.csv"
expect_error "branch --differences" "whirl periodic: --differences is for one motion" periodic --pivot vertical:0.01 --omega 1.8 --dim 2 --amp-max 0.3 --differences -o "$tmp/out.csv"
expect_error "branch bad side" "whirl periodic: --side must be 1 or -1" periodic --pivot circle:0.05 --omega 1.3 --start steady --side 0 --omega-min 1 --omega-max 2 -o "$tmp/out.csv"
[ ! -e "$tmp/out.csv" ] && pass "branch bad input: no file" || fail "branch bad input: no file"

# the branch's progress line on a terminal (asked for at once): the points, the events, the
# parameter, the step, the corrector's iteration and residual; erased at the end, the same CSV
WHIRL_PROGRESS_AFTER=0 script -qfec "\"$WHIRL\" periodic --pivot vertical:0.01 --omega 1.8 --links 1 --dim 2 --amp-max 0.3 --up -o $tmp/btty.csv" /dev/null </dev/null >"$tmp/b.tty"
rc=$?
if [ $rc -eq 0 ] && tr '\r' '\n' <"$tmp/b.tty" | sed 's/\x1b\[K$//' \
     | grep -Eq '^whirl periodic: [0-9]+ points, [0-9]+ events, A [0-9.e-]+, step [0-9.e-]+, corrector iteration [0-9]+ \(residual [0-9.e+-]+\), [0-9]+s elapsed$' \
   && [ "$(tail -c 4 "$tmp/b.tty" | od -An -c | tr -d ' ')" = "$(od -An -c <"$tmp/erase" | tr -d ' ')" ] \
   && cmp -s "$tmp/btty.csv" "$tmp/b.csv"; then
  pass "periodic branch progress line: shown, erased, the same CSV"; else fail "periodic branch progress line: shown, erased, the same CSV (rc=$rc)"; fi

# Ctrl-C during a long branch (tiny steps): exit status 130, the rows so far written with a
# comment line saying where it stopped
env --default-signal=INT "$WHIRL" periodic --pivot vertical:0.01 --omega 1.8 --links 1 --dim 2 --amp-max 0.3 --up --arc-step 1e-6 --max-points 10000000 -o "$tmp/int.csv" 2>"$tmp/stderr" &
pid=$!
sleep 1
interrupt $pid
if [ $rc -eq 130 ] && grep -q '^# stopped (.*stopped at A=' "$tmp/int.csv" \
   && [ "$(grep -v '^#' "$tmp/int.csv" | sed 1d | wc -l)" -ge 2 ] \
   && grep -q '^whirl periodic: interrupted: the [0-9]* rows found until then are written' "$tmp/stderr"; then
  pass "periodic branch interrupted: 130, the rows kept"; else fail "periodic branch interrupted: 130, the rows kept (rc=$rc)"; fi
finish
