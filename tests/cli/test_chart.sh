#!/bin/sh
# Command-line tests of whirl periodic --chart: the stability chart of the vertically shaken
# chain as CSV curves (shape, blank lines between curves), N = 1 against Mathieu's characteristic
# values, SI units, the progress line, Ctrl-C, bad input.
. "$(dirname "$0")/lib.sh"

# N = 1 hanging about the first tongue (tip at omega = 2): comment lines, the units line, the
# header, one curve of 12 rows: the tongue's left edge a_1 at the rates 1.8 and 1.9, its points
# down to the tip (a row apart, or farther where the edge is steep: at most half a rate's step in
# omega, so 3 of them here, the lowest one row above A = 0), the tip (2, 0), the right edge b_1
# up from the tip at the scan's amplitudes and at the rates 2.1 and 2.2; no blank line (one
# curve)
expect_ok "chart N=1" periodic --chart hanging --omega-min 1.8 --omega-max 2.2 --omega-count 5 --amp-max 0.3 --amp-rows 30 -o "$tmp/c.csv"
if grep -q '^# chart: the hanging chain shaken vertically' "$tmp/c.csv" \
   && grep -q '^# units: dimensionless' "$tmp/c.csv" \
   && grep -q 'points=12 curves=1$' "$tmp/c.csv" \
   && [ "$(grep -v '^#' "$tmp/c.csv" | head -1)" = "curve,edge,omega,amplitude,err" ] \
   && [ "$(grep -v '^#' "$tmp/c.csv" | sed 1d | awk -F, 'NF == 5' | wc -l)" -eq 12 ] \
   && [ "$(grep -c '^$' "$tmp/c.csv")" -eq 0 ] \
   && [ "$(grep -v '^#' "$tmp/c.csv" | sed -n 2p | cut -d, -f1,2,3)" = "1,-1,1.8" ] \
   && [ "$(grep -v '^#' "$tmp/c.csv" | sed -n 7p)" = "1,-1,2,0,0" ] \
   && [ "$(grep -v '^#' "$tmp/c.csv" | sed -n 13p | cut -d, -f1,2,3)" = "1,-1,2.2" ]; then
  pass "chart N=1: header, one curve of 12 rows through the tip"; else fail "chart N=1: header, one curve of 12 rows through the tip"; fi
# the edges against Mathieu: a = 4 / omega^2 = a_1(q) (left edge) or b_1(q) (right edge) with
# q = 2 A, the A here from scipy (1.11) by Brent's method on the characteristic value:
#   /usr/bin/python3 -c 'from scipy.special import mathieu_a, mathieu_b; from scipy.optimize
#   import brentq; [print(w, repr(brentq(lambda q: f(1, q) - 4 / w**2, 1e-9, 1, xtol=1e-15) / 2))
#   for w, f in ((1.8, mathieu_a), (1.9, mathieu_a), (2.1, mathieu_b), (2.2, mathieu_b))]'
# to 1e-8 in A (the issue's tolerance) at those rates; each row's err below 1e-8 as well
cat >"$tmp/ref" <<'REF'
1.8 0.12105968496067503
1.9 0.05477706929929081
2.1 0.045963152613975676
2.2 0.08500835628918853
REF
if grep -v '^#' "$tmp/c.csv" | sed 1d | grep -v '^$' | tr , ' ' \
   | awk -v refs="$tmp/ref" 'BEGIN {while ((getline l < refs) > 0) {split(l, r, " "); w[++k] = r[1]; a[k] = r[2]}}
          {if ($5 > 1e-8) bad = 1
           for (i = 1; i <= k; i++) if (($3 - w[i]) ^ 2 < 1e-24) {d = $4 - a[i]; if (d < 0) d = -d; if (d > 1e-8) bad = 1; n++}}
          END {exit bad || n != 4}'; then
  pass "chart N=1: the edges on a_1 and b_1 to 1e-8"; else fail "chart N=1: the edges on a_1 and b_1 to 1e-8"; fi

# SI units: the same chart with L = 0.5 m (omega_0 = sqrt(9.81 / 0.5) rad/s), the amplitudes
# in cm: the rows are the dimensionless ones scaled, omega in rad/s, A in m (to 1e-9: the
# edges' brackets are 1e-10 L wide)
w0=$(echo 'sqrt(9.81 / 0.5)' | bc -l)
expect_ok "chart SI" periodic --chart hanging --omega-min "$(echo "1.8 * $w0" | bc -l)" --omega-max "$(echo "2.2 * $w0" | bc -l)" --omega-count 5 --amp-max 15cm --amp-rows 30 --length 0.5 --mass 50g --gravity 9.81 -o "$tmp/si.csv"
if grep -q '^# units: length=m' "$tmp/si.csv" && grep -q 'rad/s (5 rates); A from 0.005 to 0.15 m' "$tmp/si.csv" \
   && paste -d, "$tmp/c.csv" "$tmp/si.csv" | grep -v '^#' | sed 1d | grep -v '^,$' \
      | awk -F, -v w0="$w0" '{if (($3 * w0 - $8) ^ 2 > 1e-18 * $8 ^ 2 || ($4 * 0.5 - $9) ^ 2 > 1e-18 * $9 ^ 2) bad = 1; n++} END {exit bad || n != 12}'; then
  pass "chart SI: omega in rad/s, A in m"; else fail "chart SI: omega in rad/s, A in m"; fi

# the inverted pendulum: its stability region's lower edge (+1) near Kapitza's A omega = sqrt 2
expect_ok "chart inverted" periodic --chart inverted --omega-min 20 --omega-max 30 --omega-count 3 --amp-max 0.2 --amp-rows 40 -o "$tmp/i.csv"
if grep -q '^# chart: the inverted chain' "$tmp/i.csv" \
   && grep -v '^#' "$tmp/i.csv" | awk -F, '$2 == 1 {r = $3 * $4 / sqrt(2); if (r < 0.95 || r > 1.05) bad = 1; n++} END {exit bad || n != 3}'; then
  pass "chart inverted: the +1 edge at A omega ~ sqrt 2"; else fail "chart inverted: the +1 edge at A omega ~ sqrt 2"; fi

# linear air drag (--drag 0.1, gamma = 0.1 for the uniform chain): the first tongue lifted off
# A = 0 (its lowest amplitude ~gamma / 2 = 0.05), one curve through its lowest point, a point per
# rate; the drag in the first line. The edges against the pendulum with linear drag on its
# inertial velocity, theta'' + g theta' + (1 + z'' + g z') theta = 0 (z = A cos(w t), g = 0.1),
# its monodromy integrated directly (scipy 1.10's DOP853 at rtol 1e-13, Brent's method on
# |mu|max - 1 in A):
#   /usr/bin/python3 -c 'import numpy as np; from scipy.integrate import solve_ivp; from
#   scipy.optimize import brentq
#   def mod(g, w, A):
#     c = lambda t: 1 - A*w*w*np.cos(w*t) - g*A*w*np.sin(w*t)
#     f = lambda t, y: [y[1], -g*y[1] - c(t)*y[0], y[3], -g*y[3] - c(t)*y[2]]
#     a, c, b, d = solve_ivp(f, (0, 2*np.pi/w), [1, 0, 0, 1], method="DOP853", rtol=1e-13,
#                            atol=1e-14).y[:, -1]
#     tr, det = a + d, a*d - b*c; disc = tr*tr/4 - det
#     return np.sqrt(det) if disc < 0 else abs(tr/2) + np.sqrt(disc)
#   [print(w, repr(brentq(lambda A: mod(0.1, w, A) - 1, 0.01, 0.3, xtol=1e-15)))
#    for w in (1.8, 1.9, 2.0, 2.1, 2.2)]'
expect_ok "chart drag" periodic --chart hanging --drag 0.1 --omega-min 1.8 --omega-max 2.2 --omega-count 5 --amp-max 0.3 --amp-rows 30 -o "$tmp/d.csv"
cat >"$tmp/dref" <<'REF'
1.8 0.13384364144377076
1.9 0.07642148993168389
2.0 0.04996491837562285
2.1 0.0657566434787758
2.2 0.09590719081789069
REF
if head -1 "$tmp/d.csv" | grep -q 'links=1 steps=200 tol=1e-10 L drag=0.1 M sqrt(g/L)/L; ' \
   && grep -q 'points=5 curves=1$' "$tmp/d.csv" \
   && grep -v '^#' "$tmp/d.csv" | sed 1d | tr , ' ' \
   | awk -v refs="$tmp/dref" 'BEGIN {while ((getline l < refs) > 0) {split(l, r, " "); w[++k] = r[1]; a[k] = r[2]}}
          {if ($5 > 1e-8 || $4 < 0.04) bad = 1
           for (i = 1; i <= k; i++) if (($3 - w[i]) ^ 2 < 1e-24) {d = $4 - a[i]; if (d < 0) d = -d; if (d > 1e-8) bad = 1; n++}}
          END {exit bad || n != 5}'; then
  pass "chart drag: the lifted tongue, one curve, on the damped pendulum's edges to 1e-8"; else fail "chart drag: the lifted tongue, one curve, on the damped pendulum's edges to 1e-8"; fi
# the same drag in SI units (L = 0.5 m, M = 50 g: C = 0.1 M sqrt(g/L) / L kg/(m s)): the rows the
# dimensionless ones scaled, the drag written back in kg/(m s)
cs=$(echo "0.1 * 0.05 * sqrt(9.81 / 0.5) / 0.5" | bc -l)
expect_ok "chart drag SI" periodic --chart hanging --drag "$cs" --omega-min "$(echo "1.8 * $w0" | bc -l)" --omega-max "$(echo "2.2 * $w0" | bc -l)" --omega-count 5 --amp-max 15cm --amp-rows 30 --length 0.5 --mass 50g --gravity 9.81 -o "$tmp/dsi.csv"
if head -1 "$tmp/dsi.csv" | grep -q ' drag=0.04429[0-9]* kg/(m s); ' \
   && paste -d, "$tmp/d.csv" "$tmp/dsi.csv" | grep -v '^#' | sed 1d | grep -v '^,$' \
      | awk -F, -v w0="$w0" '{if (($3 * w0 - $8) ^ 2 > 1e-18 * $8 ^ 2 || ($4 * 0.5 - $9) ^ 2 > 1e-18 * $9 ^ 2) bad = 1; n++} END {exit bad || n != 5}'; then
  pass "chart drag SI: the drag in kg/(m s), the same rows scaled"; else fail "chart drag SI: the drag in kg/(m s), the same rows scaled"; fi
# a file of one drag is not resumed with another, nor without; with its own, the same file
cp "$tmp/d.csv" "$tmp/dr.csv"
dch="periodic --chart hanging --omega-min 1.8 --omega-max 2.2 --omega-count 5 --amp-max 0.3 --amp-rows 30"
# shellcheck disable=SC2086
expect_refused "chart drag: resumed with another drag" "^whirl periodic: --resume: '.*dr.csv' was not written by a chart with these options: line 1 has 'L drag=0.1' where these options write 'L drag=0.2'$" "$tmp/dr.csv" $dch --drag 0.2
# shellcheck disable=SC2086
expect_refused "chart drag: resumed without the drag" "^whirl periodic: --resume: '.*dr.csv' was not written by a chart with these options: line 1 has " "$tmp/dr.csv" $dch
# shellcheck disable=SC2086
if "$WHIRL" $dch --drag 0.1 -o "$tmp/dr.csv" --resume 2>"$tmp/err" && cmp -s "$tmp/dr.csv" "$tmp/d.csv"; then
  pass "chart drag: resumed with its drag, the same file"; else fail "chart drag: resumed with its drag ($(cat "$tmp/err"))"; fi

# the progress line on a terminal (util-linux's script; asked for at once): the rate, the
# curves, the monodromies; erased at the end, the same CSV written
printf '\r\033[K' >"$tmp/erase"
WHIRL_PROGRESS_AFTER=0 script -qfec "\"$WHIRL\" periodic --chart hanging --omega-min 1.8 --omega-max 2.2 --omega-count 5 --amp-max 0.3 --amp-rows 30 -o $tmp/tty.csv" /dev/null </dev/null >"$tmp/p.tty"
rc=$?
if [ $rc -eq 0 ] && tr '\r' '\n' <"$tmp/p.tty" | sed 's/\x1b\[K$//' \
     | grep -Eq '^whirl periodic: rate [1-5] of 5, [0-9]+ curves, [0-9]+ monodromies, [0-9]+s elapsed$' \
   && [ "$(tail -c 4 "$tmp/p.tty" | od -An -c | tr -d ' ')" = "$(od -An -c <"$tmp/erase" | tr -d ' ')" ] \
   && cmp -s "$tmp/tty.csv" "$tmp/c.csv"; then
  pass "chart progress line: shown, erased, the same CSV"; else fail "chart progress line: shown, erased, the same CSV (rc=$rc)"; fi

# Ctrl-C during a long chart (10 links, 1000 rates: minutes of processor time), sent once it has
# used a second of processor time: exit status 130 with under a second of processor time after
# the signal, one line, the file written with the points of the rates finished and a comment
# saying where it stopped (--resume goes on: tests/cli/test_chart_resume.sh)
signal_run INT 1 "$WHIRL" periodic --chart hanging --links 10 --omega-min 1 --omega-max 8 --omega-count 1000 --amp-max 0.5 --amp-rows 200 -o "$tmp/stop.csv" 2>"$tmp/stderr"
rc=$?
late="$(report cpu_after) s of processor time, $(report wall) s wall"
if [ $rc -eq 130 ] && [ "$(report early)" = 0 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] \
   && grep -Eq '^whirl periodic: interrupted after [0-9]+ of 1000 rates: the [0-9]+ points found until then are written \(continue with --resume\)$' "$tmp/stderr" \
   && grep -Eq '^# found: interrupted after [0-9]+ of 1000 rates' "$tmp/stop.csv" \
   && [ "$(grep -v '^#' "$tmp/stop.csv" | head -1)" = "curve,edge,omega,amplitude,err" ] \
   && [ "$(echo "$(report cpu_after) < 1" | bc)" -eq 1 ]; then
  pass "chart interrupted: 130, the points kept ($late)"; else fail "chart interrupted: 130, the points kept (rc=$rc, $late, $(cat "$tmp/stderr"))"; fi

# whirl plot of a chart: recognised by its header, a PNG and an SVG; plots/plot.gp by hand with
# nothing on gnuplot's stderr; the title, the axes in the file's units, the edges' legend; a
# chart without edges drawn and saying so
gp=$(dirname "$0")/../../plots/plot.gp
"$WHIRL" periodic --chart hanging --omega-min 1.2 --omega-max 1.4 --omega-count 3 --amp-max 0.01 --amp-rows 4 -o "$tmp/e.csv"
[ "$(grep -v '^#' "$tmp/e.csv" | wc -l)" -eq 1 ] && pass "chart 1.2..1.4, A <= 0.01: no edge" ||
  fail "chart 1.2..1.4, A <= 0.01: edges: $(cat "$tmp/e.csv")"
for f in c si i e d; do
  expect_ok "plot: chart $f.csv to PNG" plot "$tmp/$f.csv" -o "$tmp/$f.png"
  [ "$(head -c 8 "$tmp/$f.png" | od -An -c | tr -d ' ')" = '211PNG\r\n032\n' ] &&
    pass "plot: chart $f.png is a PNG" || fail "plot: chart $f.png is not a PNG"
  expect_ok "plot: chart $f.csv to SVG" plot "$tmp/$f.csv" -o "$tmp/$f.svg"
  gnuplot -e "file='$tmp/$f.csv'; out='$tmp/g.svg'" "$gp" >"$tmp/gp.out" 2>&1
  [ ! -s "$tmp/gp.out" ] && [ -s "$tmp/g.svg" ] && pass "plots/plot.gp: chart $f.csv without a warning" ||
    fail "plots/plot.gp: chart $f.csv: $(head -3 "$tmp/gp.out")"
done
has() { grep -qF ">$2<" "$tmp/$1.svg" && pass "plot: $1.svg shows '$2'" || fail "plot: $1.svg lacks '$2'"; }
has c 'the hanging chain of 1 link shaken vertically, A cos(omega t)'
has c 'shaking rate omega [sqrt(g/L)]'
has c 'amplitude A [L]'
has c 'edge -1: a multiplier pair through -1 (period doubling)'
has si 'shaking rate omega [rad/s]'
has si 'amplitude A [m]'
has i 'the inverted chain of 1 link shaken vertically, A cos(omega t)'
has i 'edge +1: a pair through +1'
has e 'no edge in the range'
has d 'the hanging chain of 1 link shaken vertically, A cos(omega t), linear air drag 0.1 M sqrt(g/L)/L'

# bad input: one line naming the option, nothing written
expect_error "chart kind" "whirl periodic: --chart must be hanging, inverted or ellipse, got 'up'" periodic --chart up --omega-min 1 --omega-max 2 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "chart rates reversed" "whirl periodic: --omega-max must exceed --omega-min" periodic --chart hanging --omega-min 2 --omega-max 1 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "chart amplitudes reversed" "whirl periodic: --amp-max must exceed --amp-min" periodic --chart hanging --omega-min 1 --omega-max 2 --amp-min 0.2 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "chart no amplitude" "whirl periodic: --chart needs --amp-max" periodic --chart hanging --omega-min 1 --omega-max 2 -o "$tmp/out.csv"
expect_error "chart zero rate" "whirl periodic: --omega-min must be" periodic --chart hanging --omega-min 0 --omega-max 2 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "chart one rate" "whirl periodic: --omega-count must be" periodic --chart hanging --omega-min 1 --omega-max 2 --omega-count 1 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "chart NaN amplitude" "whirl periodic: option --amp-max needs a finite number" periodic --chart hanging --omega-min 1 --omega-max 2 --amp-max nan -o "$tmp/out.csv"
expect_error "chart with a pivot" "whirl periodic: --chart cannot be given with --pivot" periodic --chart hanging --pivot vertical:0.1 --omega-min 1 --omega-max 2 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "chart options alone" "whirl periodic: --pivot or --chart is required" periodic --omega-min 1 --omega-max 2 --amp-max 0.1 -o "$tmp/out.csv"
# dissipation other than linear air drag: one line saying why
expect_error "chart damping" "whirl periodic: --chart hanging takes linear air drag \\(--drag\\) alone: it keeps the modes apart; the joints' --damping couples them \\(from 3 links on\\), and quadratic drag damps at a rate that changes along the period$" periodic --chart hanging --damping 0.01 --omega-min 1 --omega-max 2 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "chart quadratic drag" "whirl periodic: --chart inverted takes linear air drag \\(--drag\\) alone" periodic --chart inverted --drag-quadratic 0.01 --omega-min 1 --omega-max 2 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "chart ellipse drag" "whirl periodic: --chart ellipse is of the conservative chain: no --drag, --drag-quadratic, --drag-cd or --damping" periodic --chart ellipse --eps 0.05 --drag 0.1 --omega-min 3.9 --omega-max 4 -o "$tmp/out.csv"
expect_error "chart negative drag" "whirl periodic: --drag must be" periodic --chart hanging --drag -0.1 --omega-min 1 --omega-max 2 --amp-max 0.1 -o "$tmp/out.csv"
# a period too long for the modes' integrator (1e-9: 1e11 steps per period)
expect_error "chart rate too low" "whirl periodic: the chart's slowest rate or largest amplitude is beyond the integrator: 1[.]01e[+]11 steps per period needed" periodic --chart hanging --omega-min 1e-9 --omega-max 1 --amp-max 0.1 -o "$tmp/out.csv"
finish
