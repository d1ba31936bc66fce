#!/bin/sh
# Command-line tests of whirl minimize and whirl fit: agreement with whirl shape, fit as the
# inverse of shape (points shuffled, mirrored, scaled, extra columns), the example data, bad input.
. "$(dirname "$0")/lib.sh"
example="$(dirname "$0")/../../data/fit_example.csv"

# field FILE NAME: the value of NAME=... on the summary line of a shape-like output
field() { head -1 "$1" | sed "s/.* $2=\([^ ]*\).*/\1/"; }
# close A B TOL: |A - B| <= TOL * max(1, |B|)
close() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN {d = a - b; if (d < 0) d = -d; s = b < 0 ? -b : b;
                                                  exit !(d <= t * (s > 1 ? s : 1))}'; }
# csv_close A B TOL: the data rows of two CSV files agree column by column within TOL
csv_close() {
  grep -v '^#' "$1" >"$tmp/a.rows"; grep -v '^#' "$2" >"$tmp/b.rows"
  [ "$(wc -l <"$tmp/a.rows")" -eq "$(wc -l <"$tmp/b.rows")" ] &&
    paste -d, "$tmp/a.rows" "$tmp/b.rows" | awk -F, -v t="$3" -v h="$(head -1 "$tmp/a.rows")" '
      NR == 1 {ok = ($0 == h "," h); next}
      {n = NF / 2; for (i = 1; i <= n; i++) {d = $i - $(i + n); if (d < 0) d = -d; if (d > t) ok = 0}}
      END {exit !ok}'
}
# fit_value FILE COLUMN: a column of the result row of a fit
fit_value() { grep -v '^#' "$1" | awk -F, -v c="$2" 'NR == 2 {print $c}'; }

# ---- minimize ----
expect_ok "minimize runs" minimize --omega 2.385 --links 100 -o "$tmp/min.csv"
"$WHIRL" shape --omega 2.385 --links 100 --mode 1 -o "$tmp/shp.csv"
if close "$(field "$tmp/min.csv" tip_r)" "$(field "$tmp/shp.csv" tip_r)" 1e-9 &&
   [ "$(field "$tmp/min.csv" mode)" = 1 ] && head -1 "$tmp/min.csv" | grep -q ' crossing_s=$'; then
  pass "minimize: tip_r of shape --mode 1 at N = 100 to 1e-9"
else fail "minimize: tip_r of shape --mode 1 at N = 100 to 1e-9"; fi
if csv_close "$tmp/min.csv" "$tmp/shp.csv" 1e-9 &&
   [ "$(sed -n 2p "$tmp/min.csv")" = "$(sed -n 2p "$tmp/shp.csv")" ] &&
   sed -n 3p "$tmp/min.csv" | grep -Eq '^# minimum of V: algorithm=LD_LBFGS evaluations=[0-9]+ .*seconds='; then
  pass "minimize: the rows and comments of shape --links 100"
else fail "minimize: the rows and comments of shape --links 100"; fi
# with a tip mass and physical units, and a derivative-free algorithm
"$WHIRL" minimize --omega 20 --links 30 --tip-mass 0.1 --length 0.5 --gravity 9.81 --mass 0.2 \
  --algorithm LN_BOBYQA -o "$tmp/min2.csv"
"$WHIRL" shape --omega 20 --links 30 --tip-mass 0.1 --length 0.5 --gravity 9.81 --mass 0.2 \
  --mode 1 -o "$tmp/shp2.csv"
if csv_close "$tmp/min2.csv" "$tmp/shp2.csv" 1e-9; then pass "minimize: tip mass, units, LN_BOBYQA"
else fail "minimize: tip mass, units, LN_BOBYQA"; fi
# without the Newton polish LD_LBFGS alone is close, not exact
"$WHIRL" minimize --omega 2.385 --links 100 --no-polish -o "$tmp/min3.csv"
if close "$(field "$tmp/min3.csv" tip_r)" "$(field "$tmp/shp.csv" tip_r)" 1e-6 &&
   sed -n 3p "$tmp/min3.csv" | grep -q 'newton_steps=0'; then pass "minimize --no-polish"
else fail "minimize --no-polish"; fi
expect_ok "minimize --help" minimize --help

expect_error "minimize: unknown algorithm" "^whirl minimize: unknown NLopt algorithm 'LD_NOPE'" \
  minimize --omega 2 --links 10 --algorithm LD_NOPE -o "$tmp/out.csv"
expect_error "minimize: algorithm needing a subsidiary" "^whirl minimize: NLopt algorithm AUGLAG" \
  minimize --omega 2 --links 10 --algorithm AUGLAG -o "$tmp/out.csv"
expect_error "minimize: below omega_1" "^whirl minimize: no mode-1 shape at omega=1.1[0-9]*: up to omega_1=1.199" \
  minimize --omega 1.1 --links 100 -o "$tmp/out.csv"
expect_error "minimize: links missing" "^whirl minimize: --links is required" minimize --omega 2 -o "$tmp/out.csv"
expect_error "minimize: links zero" "^whirl minimize: --links must be >= 1" minimize --omega 2 --links 0 -o "$tmp/out.csv"
expect_error "minimize: omega negative" "^whirl minimize: --omega must be > 0" minimize --omega -2 --links 5 -o "$tmp/out.csv"
expect_error "minimize: omega NaN" "^whirl minimize: option --omega needs a finite number" minimize --omega nan --links 5 -o "$tmp/out.csv"

# ---- fit: the inverse of shape ----
"$WHIRL" shape --omega 3.71 --mode 2 --links 30 -o "$tmp/nl.csv"
expect_ok "fit --links runs" fit --shape "$tmp/nl.csv" --links 30 -o "$tmp/fit1.csv"
if [ "$(grep -v '^#' "$tmp/fit1.csv" | head -1)" = "omega,omega_err,mode,rms_residual" ] &&
   [ "$(grep -vc '^#' "$tmp/fit1.csv")" -eq 2 ] && close "$(fit_value "$tmp/fit1.csv" 1)" 3.71 1e-9 &&
   [ "$(fit_value "$tmp/fit1.csv" 3)" = 2 ]; then pass "fit --links: omega to 1e-9, mode 2"
else fail "fit --links: omega to 1e-9, mode 2"; fi

# continuum, shuffled, on the side r < 0, with an extra column first, read from stdin
"$WHIRL" shape --omega 4.1 --mode 2 --points 37 |
  awk -F, '/^#/ {print; next} !h {h = 1; print "id,z,r"; next} {print NR "," $3 "," (-$2)}' |
  awk '/^#/ || $0 == "id,z,r" {print; next} {print (NR * 7919) % 101 "\t" $0}' | sort -n | cut -f2- >"$tmp/c2.csv"
if "$WHIRL" fit --shape - <"$tmp/c2.csv" >"$tmp/fit2.csv" && close "$(fit_value "$tmp/fit2.csv" 1)" 4.1 1e-6 &&
   [ "$(fit_value "$tmp/fit2.csv" 3)" = 2 ] && grep -q 'side=r<0' "$tmp/fit2.csv"; then
  pass "fit: continuum mode 2, shuffled, mirrored, stdin: omega to 1e-6"
else fail "fit: continuum mode 2, shuffled, mirrored, stdin: omega to 1e-6 ($(cat "$tmp/fit2.csv"))"; fi
# mode 3 given; physical units: the rate in rad/s comes back
"$WHIRL" shape --omega 21 --mode 3 --points 45 --length 1.2 --gravity 9.81 -o "$tmp/c3.csv"
if "$WHIRL" fit --shape "$tmp/c3.csv" --mode 3 --length 1.2 --gravity 9.81 -o "$tmp/fit3.csv" &&
   close "$(fit_value "$tmp/fit3.csv" 1)" 21 1e-6 && [ "$(fit_value "$tmp/fit3.csv" 3)" = 3 ]; then
  pass "fit --mode 3 in physical units: omega to 1e-6"
else fail "fit --mode 3 in physical units: omega to 1e-6"; fi

# the example: noise 1e-3 L; the truth 3.2 sqrt(981/120) = 9.14940 rad/s within 1% and 3 omega_err
if "$WHIRL" fit --shape "$example" --length 120 --gravity 981 -o "$tmp/ex.csv" &&
   awk -F, '/^#/ {next} !h {h = 1; next} {t = 3.2 * sqrt(981 / 120); d = $1 - t; if (d < 0) d = -d;
              exit !($3 == 2 && d < 0.01 * t && d < 3 * $2 && $2 < 0.01 * t && $4 > 0.06 && $4 < 0.24)}' "$tmp/ex.csv"; then
  pass "fit: data/fit_example.csv"
else fail "fit: data/fit_example.csv ($(cat "$tmp/ex.csv"))"; fi
# the same points read in cm by --shape-unit with the chain's length 120cm and standard gravity
# (9.80665 m/s^2): the rate 3.2 sqrt(9.80665 / 1.2) rad/s, the residual 1e-3 L in m
if "$WHIRL" fit --shape "$example" --shape-unit cm --length 120cm -o "$tmp/excm.csv" &&
   grep -q '^# units: length=m .*L=1.2 ' "$tmp/excm.csv" &&
   awk -F, '/^#/ {next} !h {h = 1; next} {t = 3.2 * sqrt(9.80665 / 1.2); d = $1 - t; if (d < 0) d = -d;
              exit !($3 == 2 && d < 0.01 * t && d < 3 * $2 && $4 > 0.0006 && $4 < 0.0024)}' "$tmp/excm.csv"; then
  pass "fit --shape-unit cm --length 120cm: data/fit_example.csv in SI"
else fail "fit --shape-unit cm --length 120cm ($(cat "$tmp/excm.csv"))"; fi
expect_error "fit: --shape-unit without --length" "^whirl fit: --shape-unit cm needs --length" \
  fit --shape "$example" --shape-unit cm -o "$tmp/out.csv"
expect_error "fit: bad --shape-unit" "^whirl fit: --shape-unit must be m, cm or mm, got 'kg'" \
  fit --shape "$example" --shape-unit kg --length 1 -o "$tmp/out.csv"
expect_ok "fit --help" fit --help

# ---- fit: bad input ----
printf 'r,z\n0.1,-0.5\n0.2,-0.5\n0.3,-0.5\n0.4,-0.5\n-0.2,-0.5\n-0.4,-0.5\n' >"$tmp/flat.csv"
expect_error "fit: a shape no mode explains" "^whirl fit: no mode explains the shape: the best fit \(mode [0-9]+, omega=[0-9.]+\) leaves an rms residual of 0.[0-9]+ L" \
  fit --shape "$tmp/flat.csv" -o "$tmp/out.csv"
expect_error "fit: the wrong mode" "^whirl fit: mode 1 explains the shape" \
  fit --shape "$tmp/c3.csv" --length 1.2 --gravity 9.81 --mode 1 -o "$tmp/out.csv"
printf '# no header\n0.1,-0.3\n0.2,-0.6\n0.25,-0.9\n' >"$tmp/nohead.csv"
expect_error "fit: no header" "^whirl fit: .*nohead.csv:2: the header has no column 'r'" fit --shape "$tmp/nohead.csv" -o "$tmp/out.csv"
printf 'r,x\n0.1,-0.3\n' >"$tmp/noz.csv"
expect_error "fit: missing column" "^whirl fit: .*noz.csv:1: the header has no column 'z'" fit --shape "$tmp/noz.csv" -o "$tmp/out.csv"
printf 'r,z\n0.1,-0.3\n0.2,abc\n' >"$tmp/text.csv"
expect_error "fit: non-numeric value" "^whirl fit: .*text.csv:3: z = 'abc' is not a number" fit --shape "$tmp/text.csv" -o "$tmp/out.csv"
printf 'r,z\n0.1,-0.3\nnan,-0.5\n' >"$tmp/nan.csv"
expect_error "fit: NaN" "^whirl fit: .*nan.csv:3: r = 'nan' is not finite" fit --shape "$tmp/nan.csv" -o "$tmp/out.csv"
printf 'r,z\n0.1,-0.3\n0.2\n' >"$tmp/short.csv"
expect_error "fit: missing value" "^whirl fit: .*short.csv:3: no value in column 'z'" fit --shape "$tmp/short.csv" -o "$tmp/out.csv"
printf 'r,z\n0.1,-0.3\n0.2,-0.6\n' >"$tmp/two.csv"
expect_error "fit: too few points" "^whirl fit: .*two.csv has 2 points; a fit needs at least 3" fit --shape "$tmp/two.csv" -o "$tmp/out.csv"
: >"$tmp/empty.csv"
expect_error "fit: empty file" "^whirl fit: .*empty.csv: no header line" fit --shape "$tmp/empty.csv" -o "$tmp/out.csv"
expect_error "fit: no such file" "^whirl fit: .*nosuch.csv: cannot read" fit --shape "$tmp/nosuch.csv" -o "$tmp/out.csv"
expect_error "fit: --shape missing" "^whirl fit: --shape is required" fit -o "$tmp/out.csv"
expect_error "fit: mode zero" "^whirl fit: --mode must be between 1 and" fit --shape "$example" --mode 0 -o "$tmp/out.csv"
expect_error "fit: links zero" "^whirl fit: --links must be >= 1" fit --shape "$example" --links 0 -o "$tmp/out.csv"
expect_error "fit: bad length" "^whirl fit: --length must be > 0" fit --shape "$example" --length -1 -o "$tmp/out.csv"
expect_error "fit: bad max residual" "^whirl fit: --max-residual must be > 0" fit --shape "$example" --max-residual 0 -o "$tmp/out.csv"
expect_error "fit: unknown option" "^whirl fit: unknown option '--bogus'" fit --shape "$example" --bogus 1 -o "$tmp/out.csv"
expect_error "fit: mode above omega-max" "^whirl fit: mode 9 starts at omega_9" fit --shape "$example" --mode 9 --omega-max 10 -o "$tmp/out.csv"

finish
