#!/bin/sh
# Units never misread, and the friction a first user meets: a value with a physical unit where the
# command works in dimensionless units is an error naming the option that gives the scale; "4 Hz"
# and "4HZ" read as 4Hz; SI units without --mass say that M = 1 kg was assumed; a sweep over
# rates where a mode does not exist says so; "did you mean"; whirl help CMD.
. "$(dirname "$0")/lib.sh"

# a unit without the scale it needs
expect_error "shape --omega 4Hz without --length" \
  "^whirl shape: --omega 4Hz needs the chain's length: give --length \(SI units\), or W as a number in units of sqrt\(g/L\)$" \
  shape --omega 4Hz --mode 2 -o "$tmp/out.csv"
expect_error "shape --omega 240rpm without --length" "needs the chain's length: give --length" \
  shape --omega 240rpm --mode 2 -o "$tmp/out.csv"
expect_error "shape --omega 25rad/s without --length" "needs the chain's length" \
  shape --omega 25rad/s --mode 2 -o "$tmp/out.csv"
expect_error "shape --omega 2Hz,4Hz without --length" "--omega 2Hz,4Hz needs the chain's length" \
  shape --omega 2Hz,4Hz --mode 2 --plot "$tmp/out.png"
expect_error "driven --eps 5cm without --length" "--eps 5cm needs the chain's length: give --length" \
  driven --omega 1.5 --eps 5cm -o "$tmp/out.csv"
expect_error "shape --tip-mass 10g without --mass" "--tip-mass 10g needs the chain's mass: give --mass" \
  shape --omega 3 --mode 1 --tip-mass 10g -o "$tmp/out.csv"
expect_error "regime --omega 4Hz without --length" "needs the chain's length" \
  regime --omega 4Hz --eps 0.03 -o "$tmp/out.csv"
expect_error "sweep --omega-min 1Hz without --length" "--omega-min 1Hz needs the chain's length" \
  sweep --modes 1 --omega-min 1Hz --omega-max 2Hz --omega-count 3 -o "$tmp/out.csv"
# with the scale given, the unit is right (4 Hz = 8 pi rad/s)
"$WHIRL" shape --omega 4Hz --mode 2 --length 60cm --mass 50g -o "$tmp/a.csv"
"$WHIRL" shape --omega 25.132741228718345 --mode 2 --length 0.6 --mass 0.05 -o "$tmp/b.csv"
cmp -s "$tmp/a.csv" "$tmp/b.csv" 2>/dev/null ||
  diff "$(grep -v '^# rate' "$tmp/a.csv" >"$tmp/a2"; echo "$tmp/a2")" \
       "$(grep -v '^# rate' "$tmp/b.csv" >"$tmp/b2"; echo "$tmp/b2")" >/dev/null &&
  pass "4Hz is 8 pi rad/s" || fail "4Hz is 8 pi rad/s"
for form in "4 Hz" "4HZ" "4hz" "4 hZ"; do
  "$WHIRL" shape --omega "$form" --mode 2 --length 60cm --mass 50g -o "$tmp/c.csv" 2>"$tmp/stderr" &&
    cmp -s "$tmp/a.csv" "$tmp/c.csv" && pass "'$form' reads as 4Hz" || fail "'$form': $(cat "$tmp/stderr")"
done
expect_error "a unit of another kind" "needs a finite number \(optionally with rad/s, Hz or rpm\)" \
  shape --omega 4cm --mode 2 --length 1 -o "$tmp/out.csv"
# --length without --mass: the assumed mass is stated; with --mass it is not
"$WHIRL" shape --omega 4Hz --mode 2 --length 60cm -o "$tmp/d.csv"
grep -q '^# mass: M=1 kg assumed (no --mass given)' "$tmp/d.csv" && pass "M = 1 kg assumed, said" ||
  fail "M = 1 kg assumed, said"
grep -q '^# mass:' "$tmp/a.csv" && fail "no mass line with --mass" || pass "no mass line with --mass"
# the rate in Hz in the shape's comment lines
grep -q '^# rate: 4 Hz (omega=25.13 rad/s)$' "$tmp/a.csv" && pass "shape: the rate in Hz" ||
  fail "shape: the rate in Hz"

# where the modes are born, in Hz: omega_k = (j_0,k / 2) sqrt(g/L) for the continuum (the zeros of
# the Bessel function J0), divided by 2 pi
want=$(awk 'BEGIN { split("2.404825557695773 5.520078110286311 8.653727912911013", j, " ");
  r = sqrt(9.80665 / 0.6); pi = 4 * atan2(1, 1); s = "# in Hz:"
  for (k = 1; k <= 3; k++) s = s sprintf("%s mode %d from %.4g Hz", k > 1 ? "," : "", k, j[k] / 2 * r / (2 * pi))
  print s }')
"$WHIRL" critical --modes 3 --length 60cm --mass 50g -o "$tmp/c.csv"
grep -qxF "$want" "$tmp/c.csv" && pass "critical: the births in Hz ($want)" || fail "critical: $(grep 'in Hz' "$tmp/c.csv") vs $want"

# a sweep where a mode does not exist
expect_error "sweep: no mode on the grid" \
  "no mode exists on the grid 1 rad/s \(0.1592 Hz\) to 3 rad/s \(0.4775 Hz\): mode 3 exists only above 17.49 rad/s \(2.784 Hz\)" \
  sweep --modes 3 --omega-min 1 --omega-max 3 --omega-count 5 --length 60cm --mass 50g -o "$tmp/out.csv"
expect_error "sweep: no mode on the grid, N links" "mode 3 exists only above 4.241 sqrt\(g/L\)" \
  sweep --modes 3 --omega-min 1 --omega-max 3 --omega-count 5 --links 5 -o "$tmp/out.csv"
"$WHIRL" sweep --modes 1,3 --omega-min 1Hz --omega-max 2Hz --omega-count 3 --length 60cm --mass 50g \
  -o "$tmp/s.csv" 2>"$tmp/stderr"
rc=$?
[ $rc -eq 0 ] && grep -q 'note: mode 3 exists only above 17.49 rad/s (2.784 Hz)' "$tmp/stderr" &&
  grep -q '^# no rows: mode 3 exists only above' "$tmp/s.csv" &&
  [ "$(grep -v '^#' "$tmp/s.csv" | tail -n +2 | cut -d, -f2 | sort -u)" = 1 ] &&
  pass "sweep: one mode absent, said, the other's rows written" || fail "sweep: one mode absent (rc=$rc)"

# did you mean, whirl help CMD
expect_error "a mistyped option" "unknown option '--omgea' \(did you mean --omega\? see --help\)" \
  shape --omgea 3 --mode 1
expect_error "a mistyped command" "unknown command 'shpae' \(did you mean shape\?" shpae --omega 3
expect_error "an option far from any" "unknown option '--colour' \(see --help\)" shape --colour red
"$WHIRL" help shape >"$tmp/h1" && "$WHIRL" shape --help >"$tmp/h2" && cmp -s "$tmp/h1" "$tmp/h2" &&
  grep -q '^usage: whirl shape ' "$tmp/h1" && pass "whirl help shape = whirl shape --help" ||
  fail "whirl help shape"
expect_error "whirl help nosuch" "unknown command 'nosuch'" help nosuch
finish
