#!/bin/sh
# Command-line tests of whirl periodic --chart ellipse: the ellipticity chart of the hand-swung
# chain as CSV curves (rows per rate and the curve's end on e = 0), SI units, the progress line,
# Ctrl-C, whirl plot, bad input. The end's location against the steady linearisation and the
# verdicts against perturbed runs: tests/unit/periodic/test_chart_ellipse.c.
. "$(dirname "$0")/lib.sh"

# N = 2, a = 0.05, mode 2 (side -1) at 3.95, 4.0, 4.05, 4.1: stable on the circle at the first
# two (a row each: a torus at e_crit), the end on e = 0 between 4.0 and 4.05 where the circle's
# shape meets the torus itself (whirl periodic's branch in the rate at e = 0 finds it there:
# docs/guide/periodic.md), none at the last two
expect_ok "ellipse chart" periodic --chart ellipse --links 2 --eps 0.05 --mode 2 --side -1 --omega-min 3.95 --omega-max 4.1 --omega-count 4 -o "$tmp/e.csv"
"$WHIRL" periodic --pivot circle:0.05 --omega 3.95 --links 2 --start steady --mode 2 --side -1 --omega-min 3.9 --omega-max 4.1 --up -o "$tmp/b.csv"
torus=$(sed -n 's/^# torus omega=\([^ ]*\) .*/\1/p' "$tmp/b.csv")
if grep -q '^# chart: the ellipticity of the hand-swung chain' "$tmp/e.csv" \
   && grep -q '^# units: dimensionless' "$tmp/e.csv" \
   && grep -q 'points=3 curves=1;' "$tmp/e.csv" \
   && [ "$(grep -v '^#' "$tmp/e.csv" | head -1)" = "curve,event,omega,ellipticity,err" ] \
   && [ "$(grep -v '^#' "$tmp/e.csv" | sed -n 2p | cut -d, -f1-3)" = "1,torus,3.95" ] \
   && [ "$(grep -v '^#' "$tmp/e.csv" | sed -n 3p | cut -d, -f1-3)" = "1,torus,4" ] \
   && grep -v '^#' "$tmp/e.csv" | sed -n 4p | awk -F, -v t="$torus" '{exit !($2 == "torus" && $4 == 0 && ($3 - t) ^ 2 < 1e-20 && $5 < 1e-8)}' \
   && grep -v '^#' "$tmp/e.csv" | sed 1d | awk -F, '{if (!($4 >= 0 && $4 < 1 && $5 < 1e-8)) bad = 1} END {exit bad}'; then
  pass "ellipse chart: two rows and the end on e = 0 at the circle's torus ($torus)"; else fail "ellipse chart: $(cat "$tmp/e.csv")"; fi

# a branch in the ellipticity from the circle's steady shape at 4 (--e-max): its torus is the
# chart's row at 4, the rows carry the ellipticity as a column
expect_ok "ellipticity branch" periodic --pivot circle:0.05 --omega 4 --links 2 --start steady --mode 2 --side -1 --e-max 0.3 -o "$tmp/eb.csv"
ec=$(grep -v '^#' "$tmp/e.csv" | sed -n 3p | cut -d, -f4)
if grep -q 'followed in the ellipticity (the path.s y terms scaled by 1 - e) from 0 towards larger values' "$tmp/eb.csv" \
   && [ "$(grep -v '^#' "$tmp/eb.csv" | head -1)" = "event,omega,amplitude,ellipticity,max_modulus,verdict,edge,fold_test,flip_test,torus_test,err" ] \
   && grep -v '^#' "$tmp/eb.csv" | awk -F, -v ec="$ec" '$1 == "torus" {n++; if (($4 - ec) ^ 2 > 1e-20) bad = 1} END {exit bad || n != 1}' \
   && grep -v '^#' "$tmp/eb.csv" | awk -F, 'NR > 1 && $1 == "point" {if (($4 < 0.2689) != ($6 == "neutral")) bad = 1} END {exit bad}'; then
  pass "ellipticity branch: the torus at the chart's e_crit ($ec), neutral before, unstable after"; else fail "ellipticity branch: $(cat "$tmp/eb.csv")"; fi
expect_error "ellipticity branch without y" "whirl periodic: an ellipticity continuation needs a path that moves along y" periodic --pivot line:0.05 --omega 4 --links 2 --e-max 0.3 -o "$tmp/out.csv"
expect_error "two branches" "whirl periodic: a branch follows one parameter" periodic --pivot circle:0.05 --omega 4 --omega-min 3 --omega-max 4 --e-max 0.3 -o "$tmp/out.csv"

# SI units: L = 0.5 m, a = 2.5 cm (0.05 L), the rates in rad/s: the same rows scaled
w0=$(echo 'sqrt(9.81 / 0.5)' | bc -l)
expect_ok "ellipse chart SI" periodic --chart ellipse --links 2 --eps 2.5cm --mode 2 --side -1 --omega-min "$(echo "3.95 * $w0" | bc -l)" --omega-max "$(echo "4.1 * $w0" | bc -l)" --omega-count 4 --length 0.5 --mass 50g --gravity 9.81 -o "$tmp/si.csv"
if grep -q '^# units: length=m' "$tmp/si.csv" && grep -q 'a=0.025 m;' "$tmp/si.csv" \
   && paste -d, "$tmp/e.csv" "$tmp/si.csv" | grep -v '^#' | sed 1d \
      | awk -F, -v w0="$w0" '{if (($3 * w0 - $8) ^ 2 > 1e-16 * $8 ^ 2 || ($4 - $9) ^ 2 > 1e-14) bad = 1; n++} END {exit bad || n != 3}'; then
  pass "ellipse chart SI: omega in rad/s, e the same"; else fail "ellipse chart SI: $(cat "$tmp/si.csv")"; fi

# the progress line on a terminal: the rate, the curves, the points; erased at the end
WHIRL_PROGRESS_AFTER=0 script -qfec "\"$WHIRL\" periodic --chart ellipse --links 2 --eps 0.05 --mode 2 --side -1 --omega-min 3.95 --omega-max 4.1 --omega-count 4 -o $tmp/tty.csv" /dev/null </dev/null >"$tmp/p.tty"
rc=$?
if [ $rc -eq 0 ] && tr '\r' '\n' <"$tmp/p.tty" | sed 's/\x1b\[K$//' \
     | grep -Eq '^whirl periodic: rate [1-4] of 4, [0-9]+ curves, [0-9]+ points, e [0-9.e-]+, [0-9]+s elapsed$' \
   && cmp -s "$tmp/tty.csv" "$tmp/e.csv"; then
  pass "ellipse chart progress line: shown, the same CSV"; else fail "ellipse chart progress line (rc=$rc)"; fi

# Ctrl-C during a long chart (2000 rates: a quarter of a minute of processor time), sent once it
# has used a second of processor time: exit status 130 with under a second of processor time
# after the signal, one line, the rows of the rates finished written
signal_run INT 1 "$WHIRL" periodic --chart ellipse --links 3 --eps 0.05 --omega-min 3 --omega-max 9 --omega-count 2000 -o "$tmp/stop.csv" 2>"$tmp/stderr"
rc=$?
late="$(report cpu_after) s of processor time, $(report wall) s wall"
if [ $rc -eq 130 ] && [ "$(report early)" = 0 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] \
   && grep -Eq '^whirl periodic: interrupted after [0-9]+ of 2000 rates: the [0-9]+ points found until then are written \(continue with --resume\)$' "$tmp/stderr" \
   && grep -Eq '^# found: interrupted after [0-9]+ of 2000 rates' "$tmp/stop.csv" \
   && [ "$(grep -v '^#' "$tmp/stop.csv" | head -1)" = "curve,event,omega,ellipticity,err" ] \
   && [ "$(echo "$(report cpu_after) < 1" | bc)" -eq 1 ]; then
  pass "ellipse chart interrupted: 130, the rows kept ($late)"; else fail "ellipse chart interrupted (rc=$rc, $late, $(cat "$tmp/stderr"))"; fi

# whirl plot: recognised by its header, a PNG and an SVG with the title and the axes;
# plots/plot.gp by hand with nothing on gnuplot's stderr
gp=$(dirname "$0")/../../plots/plot.gp
for f in e si; do
  expect_ok "plot: ellipse $f.csv to PNG" plot "$tmp/$f.csv" -o "$tmp/$f.png"
  [ "$(head -c 8 "$tmp/$f.png" | od -An -c | tr -d ' ')" = '211PNG\r\n032\n' ] &&
    pass "plot: ellipse $f.png is a PNG" || fail "plot: ellipse $f.png is not a PNG"
  expect_ok "plot: ellipse $f.csv to SVG" plot "$tmp/$f.csv" -o "$tmp/$f.svg"
  gnuplot -e "file='$tmp/$f.csv'; out='$tmp/g.svg'" "$gp" >"$tmp/gp.out" 2>&1
  [ ! -s "$tmp/gp.out" ] && [ -s "$tmp/g.svg" ] && pass "plots/plot.gp: ellipse $f.csv without a warning" ||
    fail "plots/plot.gp: ellipse $f.csv: $(head -3 "$tmp/gp.out")"
done
has() { grep -qF ">$2<" "$tmp/$1.svg" && pass "plot: $1.svg shows '$2'" || fail "plot: $1.svg lacks '$2'"; }
has e 'how far from a circle: the mode-2 shape of the hand-swung chain of 2 links, a = 0.05 L'
has e 'rate omega [sqrt(g/L)]'
has e 'torus: two pairs meet on the unit circle'
has si 'rate omega [rad/s]'

# bad input: one line naming the option, nothing written
expect_error "ellipse no eps" "whirl periodic: --chart ellipse needs --eps" periodic --chart ellipse --omega-min 3 --omega-max 4 -o "$tmp/out.csv"
expect_error "ellipse e-max" "whirl periodic: --e-max must be" periodic --chart ellipse --eps 0.05 --omega-min 3 --omega-max 4 --e-max 2 -o "$tmp/out.csv"
expect_error "ellipse with amplitudes" "whirl periodic: --amp-min, --amp-max, --amp-rows and --edge-tol are for --chart hanging or inverted" periodic --chart ellipse --eps 0.05 --omega-min 3 --omega-max 4 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "ellipse side" "whirl periodic: --side must be 1 or -1" periodic --chart ellipse --eps 0.05 --omega-min 3 --omega-max 4 --side 0 -o "$tmp/out.csv"
expect_error "hanging with eps" "whirl periodic: --eps, --e-max, --mode, --side and --arc-step are for --chart ellipse" periodic --chart hanging --eps 0.05 --omega-min 3 --omega-max 4 --amp-max 0.1 -o "$tmp/out.csv"
expect_error "mode without steady" "whirl periodic: --mode and --side need --start steady" periodic --pivot circle:0.05 --omega 3 --mode 2 -o "$tmp/out.csv"
expect_error "eps without chart" "whirl periodic: --eps needs --chart" periodic --pivot circle:0.05 --omega 3 --eps 0.05 -o "$tmp/out.csv"
finish
