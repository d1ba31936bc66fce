#!/bin/sh
# Command-line tests of whirl driven: one shape, a branch with its fold, bad input.
. "$(dirname "$0")/lib.sh"

# one shape of the continuum: three comment lines (parameters, units, summary), the header, P rows from the pivot to the free end
expect_ok "driven shape" driven --omega 1.6 --eps 0.05 --drag 0.05 --drag-quadratic 0.02 --points 41 -o "$tmp/shape.csv"
if [ "$(grep -c '^#' "$tmp/shape.csv")" -eq 3 ] \
   && grep -Eq '^# omega=1.6 mode=1 node_count=1 tip_x=[0-9.e-]+ tip_y=-[0-9.e-]+ tip_z=-[0-9.e-]+ tip_r=[0-9.e-]+ top_tension=[0-9.e-]+ residual=[0-9.e-]+$' "$tmp/shape.csv" \
   && [ "$(grep -v '^#' "$tmp/shape.csv" | head -1)" = "s,x,y,z,tension" ] \
   && [ "$(grep -vc '^#' "$tmp/shape.csv")" -eq 42 ]; then
  pass "driven shape: comments, header, 41 rows"; else fail "driven shape: comments, header, 41 rows"; fi
# first row: the pivot at (eps, 0, 0); last row: the free end (s = 1, no tension) trailing (y < 0)
if grep -v '^#' "$tmp/shape.csv" | sed -n 2p | awk -F, '{exit !($1 == 0 && ($2 - 0.05) ^ 2 < 1e-24 && $3 ^ 2 < 1e-24 && $4 == 0)}' \
   && tail -1 "$tmp/shape.csv" | awk -F, '{exit !($1 == 1 && $3 < 0 && $4 < 0 && $5 == 0)}'; then
  pass "driven shape: pivot first, trailing free end last"; else fail "driven shape: pivot first, trailing free end last"; fi

# N-link chain with a tip mass: N + 1 rows
expect_ok "driven --links" driven --omega 3.5 --mode 2 --side -1 --eps 0.02 --drag 0.01 --links 30 --tip-mass 0.1 -o "$tmp/nl.csv"
if [ "$(grep -vc '^#' "$tmp/nl.csv")" -eq 32 ] && grep -q ' node_count=2 ' "$tmp/nl.csv"; then
  pass "driven --links: N+1 rows, 2 nodes"; else fail "driven --links: N+1 rows, 2 nodes"; fi

# branch: the anti-phase mode-1 branch folds once above omega_1 = 1.2024
expect_ok "driven branch" driven --omega-min 0.8 --omega-max 2 --eps 0.02 --side -1 --arc-step 0.05 -o "$tmp/br.csv"
fold=$(sed -n 's/^# fold omega=//p' "$tmp/br.csv")
if [ "$(grep -c '^# fold omega=' "$tmp/br.csv")" -eq 1 ] \
   && awk -v f="$fold" 'BEGIN {exit !(f > 1.2024 && f < 1.4)}' \
   && [ "$(grep -v '^#' "$tmp/br.csv" | head -1)" = "omega,tip_x,tip_y,tip_r,top_tension,nodes,fold" ] \
   && awk -F, -v f="$fold" '/^#/ || /^omega/ {next} $7 == 1 {n++; ok = ($1 == f)} END {exit !(n == 1 && ok)}' "$tmp/br.csv"; then
  pass "driven branch: one fold, commented and flagged"; else fail "driven branch: one fold, commented and flagged"; fi
# every rate of the branch stays at or above the fold
if awk -F, -v f="$fold" '/^#/ || /^omega/ {next} $1 < f - 1e-12 {bad = 1} END {exit bad}' "$tmp/br.csv"; then
  pass "driven branch: no shape below the fold"; else fail "driven branch: no shape below the fold"; fi
expect_ok "driven branch in phase, up, N-link" driven --omega-min 0.5 --omega-max 2 --omega 1.5 --up --eps 0.02 --drag 0.01 --links 20
if ! grep -q '^# fold' "$tmp/stdout" && grep -q 'left the interval' "$tmp/stdout"; then
  pass "driven branch in phase: no fold"; else fail "driven branch in phase: no fold"; fi
expect_ok "driven --help" driven --help

# bad input
expect_error "no rate" "whirl driven: --omega .* is required" driven --eps 0.1 -o "$tmp/out.csv"
expect_error "half a range" "whirl driven: --omega-min needs --omega-max" driven --omega-min 1 -o "$tmp/out.csv"
expect_error "inverted range" "whirl driven: need --omega-min < --omega-max" driven --omega-min 2 --omega-max 1 -o "$tmp/out.csv"
expect_error "drag without drive" "whirl driven: air drag needs --eps > 0" driven --omega 2 --drag 0.1 -o "$tmp/out.csv"
expect_error "negative eps" "whirl driven: --eps must be in" driven --omega 2 --eps -0.1 -o "$tmp/out.csv"
expect_error "negative drag" "whirl driven: --drag must be >= 0" driven --omega 2 --eps 0.1 --drag -1 -o "$tmp/out.csv"
expect_error "bad mode" "whirl driven: --mode must be between" driven --omega 2 --mode -1 -o "$tmp/out.csv"
expect_error "side of the near-axis shape" "whirl driven: --side picks the seed" driven --omega 2 --mode 0 --side -1 --eps 0.05 -o "$tmp/out.csv"
expect_error "bad side" "whirl driven: --side must be 1 or -1" driven --omega 2 --side 0 -o "$tmp/out.csv"
expect_error "points with links" "whirl driven: --points cannot be given with --links" driven --omega 2 --links 5 --points 9 -o "$tmp/out.csv"
expect_error "step without branch" "whirl driven: --arc-step needs --omega-min" driven --omega 2 --arc-step 0.1 -o "$tmp/out.csv"
expect_error "mode below its rate" "whirl driven: .*does not exist" driven --omega 2 --mode 2 --eps 0.01 -o "$tmp/out.csv"
expect_error "start outside range" "whirl driven: --omega \(the branch's start\) is outside" driven --omega 3 --omega-min 1 --omega-max 2 -o "$tmp/out.csv"
expect_error "not a number" "whirl driven: option --eps needs a finite number" driven --omega 2 --eps abc -o "$tmp/out.csv"
expect_error "unknown option" "whirl driven: unknown option '--bogus'" driven --omega 2 --bogus 1 -o "$tmp/out.csv"
# --stability: the verdict of every shape of a branch. Mode 1 with the pivot's circle eps = 0.05
# (20 links): the branch seeded on the pivot's side runs down below resonance to the small
# near-axis shape and is a minimum all along; the far-side branch is unstable (index 1) up to its
# fold, then neutral; a point's growth equals that of whirl stability's own shape at that rate.
if "$WHIRL" driven --omega-min 0.6 --omega-max 1.6 --omega 1.6 --mode 1 --eps 0.05 --links 20 \
     --stability -o "$tmp/bs.csv" 2>"$tmp/err" \
   && "$WHIRL" driven --omega-min 0.6 --omega-max 1.6 --omega 1.6 --mode 1 --eps 0.05 --links 20 \
     --side -1 --stability -o "$tmp/bm.csv" 2>>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/bs.csv" | head -1)" = "omega,tip_x,tip_y,tip_r,top_tension,nodes,fold,eig_growth,index,verdict" ] \
   && grep -v '^[#o]' "$tmp/bs.csv" | awk -F, '{ n++; if ($10 != "stable (minimum)") bad++; if ($1 < m || m == "") m = $1; if (m == $1) r = $4 }
        END { exit !(n > 20 && !bad && m < 0.65 && r < 0.1) }' \
   && grep -v '^[#o]' "$tmp/bm.csv" | head -1 | awk -F, '{ exit !($10 == "unstable" && $9 == 1) }' \
   && grep -v '^[#o]' "$tmp/bm.csv" | tail -1 | awk -F, '{ exit !($10 == "neutral (gyroscopic)") }'; then
  w=$(grep -v '^[#o]' "$tmp/bm.csv" | head -1 | cut -d, -f1); g=$(grep -v '^[#o]' "$tmp/bm.csv" | head -1 | cut -d, -f8)
  g2=$("$WHIRL" stability --omega "$w" --mode 1 --links 20 --eps 0.05 --side -1 --linear | grep -v '^[#o]' | cut -d, -f4)
  if awk -v a="$g" -v b="$g2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a > 0.1 && d < 1e-8 * a) }'; then
    pass "driven --stability: near-axis branch a minimum down to omega 0.6, far side unstable then neutral; growth $g as whirl stability's"
  else fail "driven --stability: growth $g against whirl stability's $g2 at omega $w"; fi
else fail "driven --stability: $(cat "$tmp/err" | tail -2)"; fi
expect_error "stability without links" "--stability needs --links" driven --omega-min 1 --omega-max 2 --eps 0.05 --stability
expect_error "stability of one shape without links" "--stability needs --links" driven --omega 1.5 --eps 0.05 --stability

# One rate, every shape: --mode 0 is the near-axis shape. At omega 1.5 (20 links, eps 0.05, past
# the fold near 1.38) the forced chain has three shapes: mode 1 on the pivot's side a minimum,
# mode 1 on the far side unstable (index 1), the near-axis one on the far side neutral (index 2);
# the near-axis one has the growth and tip of the far-side branch's small end at the same rate.
# Below resonance (omega 0.8) the near-axis shape is the only one: the pivot-side branch
# continued down, a minimum.
one() { "$WHIRL" driven --omega "$1" --eps 0.05 --links 20 --stability $2 2>>"$tmp/err" | grep '^# '"$3"; }
verdicts=$(for a in "--mode 0" "--mode 1" "--mode 1 --side -1"; do one 1.5 "$a" eig_growth; done | tr '\n' ';')
if [ "$verdicts" = "# eig_growth=0 index=2 verdict=neutral (gyroscopic);# eig_growth=0 index=0 verdict=stable (minimum);$(one 1.5 "--mode 1 --side -1" eig_growth | grep 'index=1 verdict=unstable$');" ] \
   && one 1.5 "--mode 1 --side -1" eig_growth | awk '{ split($2, a, "="); exit !(a[2] > 0.1) }'; then
  pass "driven --omega --stability: the three shapes at omega 1.5, neutral / minimum / unstable"
else fail "driven --omega --stability: the three shapes at omega 1.5: $verdicts $(tail -1 "$tmp/err")"; fi
row=$(grep -v '^[#o]' "$tmp/bm.csv" | tail -1)
w=$(echo "$row" | cut -d, -f1)
x=$(one "$w" "--mode 0" omega= | sed 's/.* tip_x=\([^ ]*\) .*/\1/')
if [ -n "$x" ] && awk -v a="$x" -v b="$(echo "$row" | cut -d, -f2)" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a < 0 && d < 1e-9) }' \
   && [ "$(one "$w" "--mode 0" eig_growth)" = "# eig_growth=0 index=$(echo "$row" | cut -d, -f9) verdict=$(echo "$row" | cut -d, -f10)" ]; then
  pass "driven --mode 0 at omega $w: the far-side branch's small end (tip $x, its verdict)"
else fail "driven --mode 0 at omega $w: tip $x against the branch's $row"; fi
if [ "$(one 0.8 "--mode 0" eig_growth)" = "# eig_growth=0 index=0 verdict=stable (minimum)" ] \
   && one 0.8 "--mode 0" omega= | grep -q 'tip_x=0\.1'; then
  pass "driven --mode 0 below resonance: in phase with the pivot, a minimum"
else fail "driven --mode 0 below resonance: $(one 0.8 "--mode 0" omega=) $(tail -1 "$tmp/err")"; fi

finish
