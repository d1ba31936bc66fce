#!/bin/sh
# whirl stability: bad input, the CSV, the agreement of the perturbed runs with the linear
# analysis (growth within 5%; a neutral shape stays within 100 times the perturbation; with
# damping mode 1 converges and mode 2 grows), the map form, and the hand-swung chain (driven
# pivot, air drag: an unstable trailing shape grows as predicted, a stable one converges).
# The runs stopped by Ctrl-C and their --resume: tests/cli/test_stability_stops.sh.
. "$(dirname "$0")/lib.sh"

expect_error "mode absent at omega" "mode 3.*(exist|omega)" stability --omega 2 --mode 3 -o "$tmp/out.csv"
expect_error "one link" "links" stability --omega 2 --mode 1 --links 1 -o "$tmp/out.csv"
expect_error "zero periods" "periods" stability --omega 2 --mode 1 --periods 0 -o "$tmp/out.csv"
expect_error "negative periods" "periods" stability --omega 2 --mode 1 --periods -3 -o "$tmp/out.csv"
expect_error "zero perturbation" "perturb" stability --omega 2 --mode 1 --perturb 0 -o "$tmp/out.csv"
expect_error "perturbation 1" "perturb" stability --omega 2 --mode 1 --perturb 1 -o "$tmp/out.csv"
expect_error "negative damping" "damping" stability --omega 2 --mode 1 --damping -0.1 -o "$tmp/out.csv"
expect_error "unknown method" "method" stability --omega 2 --mode 1 --method euler -o "$tmp/out.csv"
expect_error "no rate" "omega" stability --mode 1 -o "$tmp/out.csv"
expect_error "rate and map" "cannot be given with" stability --omega 2 --omega-min 1 --omega-max 3 --omega-count 5 -o "$tmp/out.csv"
expect_error "map without count" "--omega-min needs --omega-max --omega-count|needs --omega-count" stability --omega-min 1 --omega-max 3 -o "$tmp/out.csv"
expect_error "non-number" "omega" stability --omega fast --mode 1 -o "$tmp/out.csv"
expect_error "bad side" "side" stability --omega 3 --mode 1 --eps 0.05 --side 2 -o "$tmp/out.csv"
expect_error "eps too large" "eps" stability --omega 3 --mode 1 --eps 1 -o "$tmp/out.csv"
expect_error "negative drag" "drag" stability --omega 3 --mode 1 --eps 0.05 --drag -0.1 -o "$tmp/out.csv"
expect_error "negative quadratic drag" "drag-quadratic" stability --omega 3 --mode 1 --eps 0.05 --drag-quadratic -1 -o "$tmp/out.csv"
expect_error "drag without eps" "eps" stability --omega 3 --mode 1 --drag 0.1 -o "$tmp/out.csv"
expect_error "driven mode absent" "mode 3|exist|omega" stability --omega 2 --mode 3 --eps 0.05 --drag 0.1 -o "$tmp/out.csv"
expect_ok "help" stability --help

# csv_field FILE COLUMN: the value of COLUMN in the first data row
csv_field() { grep -v '^#' "$1" | awk -F, -v c="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) k = i } NR == 2 { print $k }'; }

# An unstable shape: the run's growth agrees with the eigenvalue within 5%.
if "$WHIRL" stability --omega 6.3 --mode 2 --links 12 -o "$tmp/u.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/u.csv" | head -1)" = "omega,mode,links,eig_growth,sim_growth,max_deviation,verdict,index" ] \
   && [ "$(csv_field "$tmp/u.csv" verdict)" = unstable ] \
   && awk -v e="$(csv_field "$tmp/u.csv" eig_growth)" -v s="$(csv_field "$tmp/u.csv" sim_growth)" \
        'BEGIN { exit !(e > 0.01 && s > 0 && (s - e) / e < 0.05 && (e - s) / e < 0.05) }'; then
  pass "unstable mode 2 (N = 12, omega 6.3): sim_growth within 5% of eig_growth"
else fail "unstable mode 2: $(cat "$tmp/err" "$tmp/u.csv" 2>/dev/null | tail -2)"; fi

# A gyroscopically stabilised shape (mode 2 has two negative directions of K): eig_growth 0 and
# the deviation stays below 100 times the perturbation.
if "$WHIRL" stability --omega 4.5 --mode 2 --links 12 --periods 60 -o "$tmp/s.csv" 2>"$tmp/err" \
   && [ "$(csv_field "$tmp/s.csv" eig_growth)" = 0 ] \
   && [ "$(csv_field "$tmp/s.csv" verdict)" = "neutral (gyroscopic)" ] \
   && [ "$(csv_field "$tmp/s.csv" index)" = 2 ] \
   && [ "$(csv_field "$tmp/s.csv" sim_growth)" = 0 ] \
   && awk -v d="$(csv_field "$tmp/s.csv" max_deviation)" 'BEGIN { exit !(d >= 1 && d < 100) }'; then
  pass "stabilised mode 2 (N = 12, omega 4.5): bounded deviation, neutral (gyroscopic), index 2"
else fail "stabilised mode 2: $(cat "$tmp/err" "$tmp/s.csv" 2>/dev/null | tail -2)"; fi

# Kelvin-Tait-Chetaev: with damping, mode 1 converges and mode 2 (stable without) grows.
if "$WHIRL" stability --omega 4.5 --mode 1 --links 12 --damping 0.01 --periods 300 -o "$tmp/d1.csv" 2>"$tmp/err" \
   && [ "$(csv_field "$tmp/d1.csv" verdict)" = converging ] \
   && awk -v e="$(csv_field "$tmp/d1.csv" eig_growth)" 'BEGIN { exit !(e < 0) }' \
   && "$WHIRL" stability --omega 4.5 --mode 2 --links 12 --damping 0.01 -o "$tmp/d2.csv" 2>"$tmp/err" \
   && [ "$(csv_field "$tmp/d2.csv" verdict)" = unstable ] \
   && awk -v e="$(csv_field "$tmp/d2.csv" eig_growth)" -v s="$(csv_field "$tmp/d2.csv" sim_growth)" \
        'BEGIN { exit !(e > 0.01 && (s - e) / e < 0.05 && (e - s) / e < 0.05) }'; then
  pass "damping: mode 1 converges, mode 2 grows as predicted"
else fail "damping: $(cat "$tmp/err" "$tmp/d1.csv" "$tmp/d2.csv" 2>/dev/null | tail -3)"; fi

# The map: one row per rate where the mode exists (mode 2 starts at its critical rate ~2.7).
if "$WHIRL" stability --omega-min 2 --omega-max 5 --omega-count 7 --modes 1,2 --links 10 --linear \
     -o "$tmp/map.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/map.csv" | awk -F, '$2 == 1' | wc -l)" -eq 7 ] \
   && [ "$(grep -v '^#' "$tmp/map.csv" | awk -F, '$2 == 2' | wc -l)" -eq 5 ] \
   && [ "$(grep -v '^#' "$tmp/map.csv" | awk -F, 'NR > 1 && ($5 != "" || $6 != "")' | wc -l)" -eq 0 ] \
   && ! grep -qi nan "$tmp/map.csv"; then
  pass "map form: rows where the modes exist"
else fail "map form: $(cat "$tmp/err" "$tmp/map.csv" 2>/dev/null | tail -3)"; fi

# A map at high rates (N = 15, mode 7 up to omega 150, where the tip radius no longer fixes the
# shape): the shapes come from the branch's link angles, the row at 150 is the single point's.
if "$WHIRL" stability --omega-min 140 --omega-max 150 --omega-count 2 --modes 7 --links 15 --linear \
     -o "$tmp/hmap.csv" 2>"$tmp/err" \
   && "$WHIRL" stability --omega 150 --mode 7 --links 15 --linear -o "$tmp/h1.csv" 2>>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/hmap.csv" | awk -F, '$1 == 150 {print $4}')" = "$(csv_field "$tmp/h1.csv" eig_growth)" ] \
   && awk -v e="$(csv_field "$tmp/h1.csv" eig_growth)" 'BEGIN { exit !(e > 39.9 && e < 40.1) }'; then
  pass "map at high rates: the branch's shapes, as the single point"
else fail "map at high rates: $(cat "$tmp/err" "$tmp/hmap.csv" 2>/dev/null | tail -3)"; fi

# A long chain at a high mode (N = 100, mode 50, omega 250): the unstable mode turns a few links
# about 1e3 times faster than it moves the masses; the fit stays where the run is linear and
# agrees with the eigenvalue (72.33) within 2% for two seeds (it gave 68.74 when it ran on to
# link turns of 0.04 rad).
ok=1
for seed in 1 2; do
  "$WHIRL" stability --omega 250 --mode 50 --links 100 --periods 10 --seed $seed \
     -o "$tmp/n100.csv" 2>"$tmp/err" \
   && [ "$(csv_field "$tmp/n100.csv" verdict)" = unstable ] \
   && awk -v e="$(csv_field "$tmp/n100.csv" eig_growth)" -v s="$(csv_field "$tmp/n100.csv" sim_growth)" \
        'BEGIN { exit !(e > 72.33 && e < 72.34 && (s - e) / e < 0.02 && (e - s) / e < 0.02) }' \
   || { ok=0; echo "# seed $seed: $(cat "$tmp/err" "$tmp/n100.csv" 2>/dev/null | tail -1)"; }
done
if [ $ok = 1 ]; then pass "N = 100 mode 50 at omega 250: sim_growth within 2% of eig_growth, seeds 1 and 2"
else fail "N = 100 mode 50 at omega 250: sim_growth within 2% of eig_growth"; fi

# Hand-swung chain: mode 1 on the far side of the axis from the pivot trails and is unstable; the
# run's growth agrees with the eigenvalue within 5% (linear and quadratic drag).
driven_header="omega,mode,links,eig_growth,sim_growth,max_deviation,verdict,index,tip_x,tip_y,nodes"
if "$WHIRL" stability --omega 3 --mode 1 --side -1 --links 12 --eps 0.05 --drag 0.1 \
     --drag-quadratic 0.05 -o "$tmp/du.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/du.csv" | head -1)" = "$driven_header" ] \
   && [ "$(csv_field "$tmp/du.csv" verdict)" = unstable ] \
   && [ "$(csv_field "$tmp/du.csv" nodes)" = 1 ] \
   && awk -v y="$(csv_field "$tmp/du.csv" tip_y)" 'BEGIN { exit !(y < -0.1) }' \
   && awk -v e="$(csv_field "$tmp/du.csv" eig_growth)" -v s="$(csv_field "$tmp/du.csv" sim_growth)" \
        'BEGIN { exit !(e > 0.01 && s > 0 && (s - e) / e < 0.05 && (e - s) / e < 0.05) }'; then
  pass "driven mode 1, far side: trails, sim_growth within 5% of eig_growth"
else fail "driven mode 1, far side: $(cat "$tmp/err" "$tmp/du.csv" 2>/dev/null | tail -2)"; fi

# Mode 2 with its upper lobe on the pivot's side is stable under drag: eig_growth < 0 (-c/2 for
# the uniform chain with linear drag) and the run converges; also with quadratic drag.
if "$WHIRL" stability --omega 3.5 --mode 2 --side -1 --links 12 --eps 0.05 --drag 0.2 \
     -o "$tmp/ds.csv" 2>"$tmp/err" \
   && [ "$(csv_field "$tmp/ds.csv" verdict)" = converging ] \
   && [ "$(csv_field "$tmp/ds.csv" nodes)" = 2 ] \
   && awk -v e="$(csv_field "$tmp/ds.csv" eig_growth)" 'BEGIN { exit !(e > -0.1 - 1e-9 && e < -0.1 + 1e-9) }' \
   && "$WHIRL" stability --omega 3.5 --mode 2 --side -1 --links 12 --eps 0.05 --drag 0.1 \
        --drag-quadratic 0.1 -o "$tmp/ds2.csv" 2>"$tmp/err" \
   && [ "$(csv_field "$tmp/ds2.csv" verdict)" = converging ] \
   && awk -v e="$(csv_field "$tmp/ds2.csv" eig_growth)" 'BEGIN { exit !(e < -0.01) }'; then
  pass "driven mode 2, upper lobe on the pivot's side: converging"
else fail "driven mode 2: $(cat "$tmp/err" "$tmp/ds.csv" "$tmp/ds2.csv" 2>/dev/null | tail -3)"; fi

# The three shapes of the forced chain at one rate past the fold (omega 1.5, eps 0.05, 20 links),
# each checked by a perturbed run of 30 periods: mode 0 (the near-axis shape, far side) neutral,
# index 2; mode 1 on the pivot's side a minimum; mode 1 on the far side unstable, the run growing
# at the eigenvalue's rate within 1%. With linear drag c the near-axis shape converges at -c/2 (the
# uniform chain's drag damps every motion alike) and so does the run.
T="--omega 1.5 --links 20 --eps 0.05 --periods 30"
if "$WHIRL" stability $T --mode 0 -o "$tmp/n0.csv" 2>"$tmp/err" \
   && "$WHIRL" stability $T --mode 1 -o "$tmp/n1.csv" 2>>"$tmp/err" \
   && "$WHIRL" stability $T --mode 1 --side -1 -o "$tmp/n2.csv" 2>>"$tmp/err" \
   && "$WHIRL" stability $T --mode 0 --drag 0.05 -o "$tmp/n3.csv" 2>>"$tmp/err" \
   && [ "$(csv_field "$tmp/n0.csv" verdict),$(csv_field "$tmp/n0.csv" index)" = "neutral (gyroscopic),2" ] \
   && [ "$(csv_field "$tmp/n1.csv" verdict),$(csv_field "$tmp/n1.csv" index)" = "stable (minimum),0" ] \
   && [ "$(csv_field "$tmp/n2.csv" verdict),$(csv_field "$tmp/n2.csv" index)" = "unstable,1" ] \
   && [ "$(csv_field "$tmp/n3.csv" verdict)" = converging ] \
   && awk -v a="$(csv_field "$tmp/n0.csv" tip_x)" -v b="$(csv_field "$tmp/n2.csv" tip_x)" -v c="$(csv_field "$tmp/n1.csv" tip_x)" \
        'BEGIN { exit !(b < a && a < 0 && a > -0.25 && c > 0.5) }' \
   && awk -v d0="$(csv_field "$tmp/n0.csv" max_deviation)" -v d1="$(csv_field "$tmp/n1.csv" max_deviation)" \
        'BEGIN { exit !(d0 < 10 && d1 < 10) }' \
   && awk -v e="$(csv_field "$tmp/n2.csv" eig_growth)" -v s="$(csv_field "$tmp/n2.csv" sim_growth)" \
        'BEGIN { exit !(e > 0.1 && (s - e) / e < 0.01 && (e - s) / e < 0.01) }' \
   && awk -v e="$(csv_field "$tmp/n3.csv" eig_growth)" 'BEGIN { exit !(e > -0.025 - 1e-9 && e < -0.025 + 1e-9) }'; then
  pass "driven, one rate: near-axis neutral, pivot side a minimum, far side unstable (runs agree); drag: -c/2"
else fail "driven, one rate, three shapes: $(cat "$tmp/err" "$tmp/n0.csv" "$tmp/n1.csv" "$tmp/n2.csv" "$tmp/n3.csv" 2>/dev/null | grep -v '^#' | tail -5)"; fi
# The near-axis shape of a tiny drive is the hanging chain seen from the rotating frame: its
# eigenvalues are i (nu_k +- omega), nu_k the hanging chain's pendulum frequencies, which are the
# rates where the free whirling modes are born (whirl critical).
if "$WHIRL" stability --omega 1.5 --mode 0 --links 20 --eps 1e-6 --eigenvalues --linear \
     -o "$tmp/ev.csv" 2>"$tmp/err" && "$WHIRL" critical --links 20 -o "$tmp/crit.csv" 2>>"$tmp/err"; then
  bad=$(grep -v '^[#m]' "$tmp/crit.csv" | head -3 | while IFS=, read -r k nu; do
    for f in $(awk -v n="$nu" 'BEGIN { printf "%.15g %.15g\n", n + 1.5, (n > 1.5 ? n - 1.5 : 1.5 - n) }'); do
      grep -v '^[#r]' "$tmp/ev.csv" | awk -F, -v f="$f" '{ d = $2 - f; if (d < 0) d = -d; if (d < 1e-6 && ($1 < 0 ? -$1 : $1) < 1e-9) hit = 1 }
        END { if (!hit) print f }'
    done; done)
  if [ -z "$bad" ] && [ "$(grep -vc '^[#r]' "$tmp/ev.csv")" -eq 80 ]; then
    pass "near-axis eigenvalues: i (nu_k +- omega) for k = 1..3"
  else fail "near-axis eigenvalues: missing $bad"; fi
else fail "near-axis eigenvalues: $(tail -1 "$tmp/err")"; fi
expect_error "near-axis without a drive" "mode 0 .*needs --eps" stability --omega 1.5 --mode 0 --links 20 -o "$tmp/out.csv"
expect_error "near-axis with a side" "--side picks the seed" stability --omega 1.5 --mode 0 --links 20 --eps 0.05 --side -1 -o "$tmp/out.csv"
expect_error "near-axis between birth and fold" "could not be followed" stability --omega 1.3 --mode 0 --links 20 --eps 0.05 -o "$tmp/out.csv"

# The driven map: rows where the shapes exist, with the tip columns.
if "$WHIRL" stability --omega-min 2 --omega-max 5 --omega-count 4 --modes 1,2 --links 10 --eps 0.03 \
     --drag 0.1 --linear -o "$tmp/dmap.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/dmap.csv" | head -1)" = "$driven_header" ] \
   && [ "$(grep -v '^#' "$tmp/dmap.csv" | awk -F, '$2 == 1' | wc -l)" -ge 3 ] \
   && [ "$(grep -v '^#' "$tmp/dmap.csv" | awk -F, '$2 == 2' | wc -l)" -ge 1 ] \
   && [ "$(grep -v '^#' "$tmp/dmap.csv" | awk -F, 'NR > 1 && NF != 11' | wc -l)" -eq 0 ] \
   && ! grep -qi nan "$tmp/dmap.csv"; then
  pass "driven map form"
else fail "driven map form: $(cat "$tmp/err" "$tmp/dmap.csv" 2>/dev/null | tail -3)"; fi

# --windows: bad input, the CSV, and each edge against the linear map just outside and inside.
R="--omega-min 1 --omega-max 10"
expect_error "windows with --omega" "omega" stability --windows --omega 3 -o "$tmp/out.csv"
expect_error "windows without a range" "omega-min" stability --windows -o "$tmp/out.csv"
expect_error "windows with --mode" "mode" stability --windows $R --mode 2 -o "$tmp/out.csv"
expect_error "windows with damping, no links" "damping.*links" stability --windows $R --damping 0.1 -o "$tmp/out.csv"
expect_error "windows with a run option" "periods" stability --windows $R --periods 5 -o "$tmp/out.csv"
expect_error "windows with a count" "omega-count" stability --windows $R --omega-count 5 -o "$tmp/out.csv"
expect_error "windows tolerance 0" "tol" stability --windows $R --tol 0 -o "$tmp/out.csv"
expect_error "windows tolerance above the step" "tol" stability --windows $R --tol 0.5 -o "$tmp/out.csv"
expect_error "windows scan step" "scan-step" stability --windows $R --scan-step -1 -o "$tmp/out.csv"
expect_error "scan step without windows: an option of whirl windows" "unknown option '--scan-step'" stability --omega 3 --mode 2 --scan-step 0.1 -o "$tmp/out.csv"
expect_error "windows mode above N" "modes" stability --windows $R --links 10 --modes 11 -o "$tmp/out.csv"
expect_error "windows below birth" "mode 3.*omega_3" stability --windows --links 10 --modes 3 --omega-min 1 --omega-max 4 -o "$tmp/out.csv"
expect_error "windows reversed range" "omega-max" stability --windows --omega-min 5 --omega-max 4 -o "$tmp/out.csv"
if "$WHIRL" stability --windows --links 10 --modes 2 --omega-min 3 --omega-max 5 -o "$tmp/w.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/w.csv" | head -1)" = "mode,links,from,to,open_from,open_to,freq_from,freq_to,max_growth,at" ] \
   && [ "$(grep -v '^#' "$tmp/w.csv" | wc -l)" -eq 2 ] \
   && grep -q '^# mode 2: .*eigen-solves' "$tmp/w.csv"; then
  from=$(csv_field "$tmp/w.csv" from); to=$(csv_field "$tmp/w.csv" to)
  ok=1
  for w in "$from -1e-6 0" "$from 1e-6 1" "$to -1e-6 1" "$to 1e-6 0"; do
    set -- $w
    at=$(awk -v a="$1" -v d="$2" 'BEGIN { printf "%.12f", a + d }')
    g=$("$WHIRL" stability --omega "$at" --mode 2 --links 10 --linear | grep -v '^[#o]' | cut -d, -f4)
    awk -v g="$g" -v u="$3" 'BEGIN { exit !((g > 0) == u) }' || ok=0
  done
  if [ $ok -eq 1 ] && awk -v a="$from" -v b="$to" 'BEGIN { exit !(a > 4.2 && b < 4.5 && a < b) }'; then
    pass "windows: mode 2 (N = 10) edges [$from, $to] change the linear verdict within 1e-6"
  else fail "windows: the edges [$from, $to] disagree with the linear map"; fi
else fail "windows CSV: $(cat "$tmp/err" "$tmp/w.csv" 2>/dev/null | tail -3)"; fi

# --windows with dissipation: the intervals where the growth has one sign, edges its roots.
expect_error "windows of the hand-swung chain without dissipation" "dissipation" stability --windows $R --links 10 --eps 0.02 -o "$tmp/out.csv"
expect_error "windows with damping and --full" "full" stability --windows $R --links 10 --damping 1e-3 --full -o "$tmp/out.csv"
expect_error "windows with too little damping" "round-off" stability --windows $R --links 10 --modes 2 --damping 1e-14 -o "$tmp/out.csv"
# Kelvin-Tait-Chetaev: with internal damping the minimum (mode 1) converges, the saddle (mode 2)
# grows, over the whole range
if "$WHIRL" stability --windows --links 10 --modes 1,2 --omega-min 2 --omega-max 6 --damping 1e-3 \
     -o "$tmp/dw.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/dw.csv" | head -1)" = "mode,links,from,to,open_from,open_to,freq_from,freq_to,growth,at,verdict" ] \
   && grep -q '^# whirl stability --windows: 10 links, tip mass 0, damping 0.001' "$tmp/dw.csv" \
   && [ "$(grep -v '^#' "$tmp/dw.csv" | sed 1d | cut -d, -f1,3-6,11 | tr '\n' ' ')" = \
        "1,2,6,1,1,converging 2,$(grep '^# mode 2' "$tmp/dw.csv" | sed 's/.*examined \([^.]*\.[0-9]*\)\.\..*/\1/'),6,1,1,unstable " ]; then
  pass "windows with damping: mode 1 converging and mode 2 unstable over the whole range"
else fail "windows with damping: $(cat "$tmp/err" "$tmp/dw.csv" 2>/dev/null | tail -4)"; fi
# the hand-swung chain with linear drag, far side: an unstable interval between two converging
# ones; each edge against the linear growth 1e-6 either side
D="--links 10 --eps 0.02 --drag 0.01 --side -1"
if "$WHIRL" stability --windows $D --modes 2 --omega-min 2 --omega-max 6 -o "$tmp/dd.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/dd.csv" | sed 1d | cut -d, -f11 | tr '\n' ' ')" = "converging unstable converging " ]; then
  from=$(grep -v '^#' "$tmp/dd.csv" | sed -n 3p | cut -d, -f3); to=$(grep -v '^#' "$tmp/dd.csv" | sed -n 3p | cut -d, -f4)
  ok=1
  for w in "$from -1e-6 0" "$from 1e-6 1" "$to -1e-6 1" "$to 1e-6 0"; do
    set -- $w
    at=$(awk -v a="$1" -v d="$2" 'BEGIN { printf "%.12f", a + d }')
    g=$("$WHIRL" stability --omega "$at" --mode 2 $D --linear | grep -v '^[#o]' | cut -d, -f4)
    awk -v g="$g" -v u="$3" 'BEGIN { exit !((g > 0) == u) }' || ok=0
  done
  if [ $ok -eq 1 ]; then
    pass "windows with drag: mode 2 (N = 10, far side) unstable on [$from, $to], the linear growth changes sign within 1e-6"
  else fail "windows with drag: the edges [$from, $to] disagree with the linear growth"; fi
else fail "windows with drag: $(cat "$tmp/err" "$tmp/dd.csv" 2>/dev/null | tail -4)"; fi

# --memory: the collocation's bound. Mode 8 at 20.5 needs 731 points, more than the 720 of
# 16 MB: that mode fails naming the option (exit 1), mode 2 is written whole, mode 8 marked with
# the failure; 32 MB hold it.
mwin="stability --windows --omega-min 20 --omega-max 21"
# shellcheck disable=SC2086
"$WHIRL" $mwin --modes 2,8 --memory 16 -o "$tmp/mem.csv" 2>"$tmp/mem.err"
rc=$?
# shellcheck disable=SC2086
if [ $rc -eq 1 ] && [ "$(wc -l <"$tmp/mem.err")" -eq 1 ] &&
   grep -q "mode 8 at omega = 20.5 needs 731 collocation points.*more than the 720 that 16 MB hold: lower the rate or raise the memory bound (--memory MB); 1 of 2 modes written to '$tmp/mem.csv'" "$tmp/mem.err" &&
   grep -q '^# mode 8: not done: mode 8 at omega = 20.5 needs 731' "$tmp/mem.csv" &&
   "$WHIRL" $mwin --modes 2 -o "$tmp/mem2.csv" &&
   [ "$(grep -v '^#' "$tmp/mem.csv")" = "$(grep -v '^#' "$tmp/mem2.csv")" ] &&
   "$WHIRL" $mwin --modes 8 --memory 32 -o "$tmp/mem8.csv" && grep -q '^# mode 8: examined' "$tmp/mem8.csv"; then
  pass "--memory 16: mode 8 beyond the bound names --memory, mode 2 kept whole; --memory 32 holds mode 8"
else fail "--memory (rc=$rc, $(cat "$tmp/mem.err"; grep '^# mode' "$tmp/mem.csv"))"; fi
expect_error "--memory with --links" "--memory applies to the continuum" stability --windows $R --links 10 --memory 100 -o "$tmp/out.csv"
expect_error "--memory without windows: an option of whirl windows" "unknown option '--memory'" stability --omega 3 --mode 1 --memory 100 -o "$tmp/out.csv"
expect_error "--memory below 16 MB" "memory" stability --windows $R --memory 8 -o "$tmp/out.csv"
# the atlas takes the bound too: mode 20 at its birth (31.0243) needs 765 points, more than the
# 720 of 16 MB (the default 1024 MB hold them)
expect_error "--atlas --memory 16: the shape at the birth of mode 20 is beyond it" \
  "mode 20, omega 30\.\.31\.5: mode 20 at omega = 31\.0243 needs 765 collocation points.*720 that 16 MB hold.*\(--memory MB\)" \
  stability --atlas --modes 20 --omega-max 31.5 --memory 16 -o "$tmp/out.csv"
physical=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 }' /proc/meminfo)
if [ "$physical" -gt 0 ] && [ "$physical" -lt 1000000 ]; then
  expect_error "--memory beyond the machine's memory ($physical MB)" \
    "--memory 1e\+06 MB is more than the machine's [0-9]+ MB" stability --windows $R --memory 1e6 -o "$tmp/out.csv"
fi

# --windows without --links: the continuous chain (collocation of the string equations)
expect_error "continuum windows: degree" "degree" stability --windows $R --degree 5 -o "$tmp/out.csv"
expect_error "continuum windows: degree with --links" "degree.*links|links.*degree" stability --windows $R --links 10 --degree 12 -o "$tmp/out.csv"
expect_error "tip mass without windows: an option of whirl windows" "unknown option '--tip-mass'" stability --omega 3 --mode 2 --tip-mass 0.1 -o "$tmp/out.csv"
expect_error "continuum windows: negative tip mass" "tip-mass" stability --windows $R --tip-mass -1 -o "$tmp/out.csv"
expect_error "continuum windows below birth" "mode 3.*omega_3" stability --windows --modes 3 --omega-min 1 --omega-max 4 -o "$tmp/out.csv"
if "$WHIRL" stability --windows --modes 2 --omega-min 4.38 --omega-max 4.42 --scan-step 0.05 --tol 1e-7 \
     -o "$tmp/cw.csv" 2>"$tmp/err" \
   && grep -q '^# whirl stability --windows: continuous chain' "$tmp/cw.csv" \
   && [ "$(grep -v '^#' "$tmp/cw.csv" | wc -l)" -eq 2 ] \
   && [ "$(csv_field "$tmp/cw.csv" links)" = inf ] && [ "$(csv_field "$tmp/cw.csv" open_to)" = 1 ]; then
  from=$(csv_field "$tmp/cw.csv" from)
  if awk -v a="$from" 'BEGIN { exit !(a > 4.4032203 && a < 4.4032209) }'; then
    pass "continuum windows: mode 2 opens at $from (N-link chain extrapolated: 4.403221 +- 2e-6)"
  else fail "continuum windows: mode 2 opens at $from"; fi
else fail "continuum windows CSV: $(cat "$tmp/err" "$tmp/cw.csv" 2>/dev/null | tail -3)"; fi

# With a tip mass (0.5): the continuum's mode-2 window against the N-link chain's (the same
# tip mass on the last node) at N = 25, 50, 100, extrapolated with errors a/N + b/N^2, i.e.
# (8 x_100 - 6 x_50 + x_25) / 3 (observed: within 1.1e-6 and 2.5e-6 of the continuum's edges,
# while the N = 100 edges are 2.2e-3 away).
tm="--tip-mass 0.5 --modes 2 --omega-min 4.2 --omega-max 4.5"
if "$WHIRL" stability --windows $tm -o "$tmp/tc.csv" 2>"$tmp/err" &&
   "$WHIRL" stability --windows $tm --links 25 -o "$tmp/t25.csv" 2>>"$tmp/err" &&
   "$WHIRL" stability --windows $tm --links 50 -o "$tmp/t50.csv" 2>>"$tmp/err" &&
   "$WHIRL" stability --windows $tm --links 100 -o "$tmp/t100.csv" 2>>"$tmp/err" &&
   grep -q '^# whirl stability --windows: 100 links, tip mass 0.5' "$tmp/t100.csv"; then
  bad=""
  for edge in from to; do
    c=$(csv_field "$tmp/tc.csv" $edge); a=$(csv_field "$tmp/t25.csv" $edge)
    b=$(csv_field "$tmp/t50.csv" $edge); d=$(csv_field "$tmp/t100.csv" $edge)
    awk -v c="$c" -v a="$a" -v b="$b" -v d="$d" 'BEGIN { x = (8 * d - 6 * b + a) / 3;
      exit !(x - c < 1e-5 && c - x < 1e-5 && (d - c > 1e-3 || c - d > 1e-3)) }' || bad="$bad $edge"
  done
  if [ -z "$bad" ]; then
    pass "continuum windows with a tip mass: mode 2 edges equal the N-link chain's extrapolated to 1e-5"
  else fail "continuum windows with a tip mass: edges$bad disagree with the N-link extrapolation"; fi
else fail "windows with a tip mass: $(cat "$tmp/err" | tail -3)"; fi

# ---- --eigenvalues: every eigenvalue of the linearisation; the growth in the comment is the
# largest real part, the spectrum is Hamiltonian (symmetric about both axes) without damping ----
if "$WHIRL" stability --omega 4.5 --mode 2 --links 6 --eigenvalues -o "$tmp/ev.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/ev.csv" | head -1)" = "re,im" ] \
   && [ "$(grep -vc '^#' "$tmp/ev.csv")" -eq 23 ] \
   && grep -q "index 2, verdict unstable" "$tmp/ev.csv" \
   && g=$(sed -n 's/.*growth \([^,]*\), index.*/\1/p' "$tmp/ev.csv") \
   && grep -v '^[#r]' "$tmp/ev.csv" | awk -F, -v g="$g" '
        { if ($1 > hi) hi = $1; if ($1 < lo) lo = $1; sr += $1; si += $2 }
        END { exit !(g > 0.1 && hi - g < 1e-12 && hi + lo < 1e-12 && sr < 1e-9 && si < 1e-9 && si > -1e-9) }'; then
  pass "--eigenvalues: 22 eigenvalues (4N - 2), the largest real part is the growth, Hamiltonian"
else fail "--eigenvalues: $(cat "$tmp/err" "$tmp/ev.csv" 2>/dev/null | head -3)"; fi
# the hand-swung chain's eigenvalues: the header records its eps, drag and side
if "$WHIRL" stability --omega 3 --mode 1 --links 12 --eps 0.05 --drag 0.1 --side -1 --eigenvalues \
     -o "$tmp/evd.csv" 2>"$tmp/err" \
   && grep -q '^# whirl stability --eigenvalues: omega 3, mode 1, 12 links, damping 0, hand-swung: eps 0.05, drag 0.1, drag_quadratic 0, side -1;' "$tmp/evd.csv"; then
  pass "--eigenvalues of the hand-swung chain: eps, drag, drag_quadratic and side in the header"
else fail "--eigenvalues of the hand-swung chain's header: $(cat "$tmp/err"; head -1 "$tmp/evd.csv")"; fi
expect_error "eigenvalues without --omega" "--eigenvalues needs --omega" stability --omega-min 1 --omega-max 2 --omega-count 2 --eigenvalues

# ---- --eigenvectors: one row per (mode, node); its eigenvalues are --eigenvalues' (same rows in
# the same order); the pivot does not move; the largest node displacement is 1 (in metres with
# SI units, the angles scaled alike); a link's angles give its nodes' displacement difference ----
if "$WHIRL" stability --omega 4.5 --mode 2 --links 6 --eigenvectors -o "$tmp/evec.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/evec.csv" | head -1)" = "eig,re,im,krein,node,s,dx,dy,dz,dx_im,dy_im,dz_im,a,b,a_im,b_im" ] \
   && [ "$(grep -vc '^#' "$tmp/evec.csv")" -eq $((22 * 7 + 1)) ] \
   && grep -q '^# units:' "$tmp/evec.csv" \
   && grep -v '^[#e]' "$tmp/evec.csv" | awk -F, '$5 == 0' | cut -d, -f2,3 >"$tmp/evec_ev" \
   && grep -v '^[#r]' "$tmp/ev.csv" >"$tmp/ev_ev" \
   && paste -d, "$tmp/evec_ev" "$tmp/ev_ev" | awk -F, 'NF != 4 { bad = 1 }
        { d = $1 - $3; if (d < 0) d = -d; e = $2 - $4; if (e < 0) e = -e
          if (d > 1e-12 || e > 1e-12) bad = 1; n++ }
        END { exit bad || n != 22 }' \
   && grep -v '^[#e]' "$tmp/evec.csv" | awk -F, '
        $5 == 0 && ($7 != 0 || $8 != 0 || $9 != 0 || $10 != 0 || $11 != 0 || $12 != 0) { bad = 1 }
        { m = $7^2 + $8^2 + $9^2 + $10^2 + $11^2 + $12^2; if (m > big[$1]) big[$1] = m }
        END { for (k in big) if (big[k] - 1 > 1e-12 || 1 - big[k] > 1e-12) bad = 1; exit bad }'; then
  pass "--eigenvectors: 22 modes x 7 nodes, eigenvalues equal to --eigenvalues', pivot fixed, largest displacement 1"
else fail "--eigenvectors: $(cat "$tmp/err"; head -5 "$tmp/evec.csv" 2>/dev/null)"; fi
# SI units (the same rate, 4.5 sqrt(g/L)): s in metres; the displacements still at most 1 (m)
# and the angles scaled by 1 / 0.6 (to round-off: the rate goes through rad/s and back)
w_si=$(awk 'BEGIN { printf "%.17g", 4.5 * sqrt(9.80665 / 0.6) }')
if "$WHIRL" stability --omega "$w_si" --mode 2 --links 6 --eigenvectors --length 0.6 --mass 0.05 \
     -o "$tmp/evec_si.csv" 2>"$tmp/err" \
   && grep -q '^# units: length=m .* L=0.6 ' "$tmp/evec_si.csv" \
   && paste -d, "$tmp/evec.csv" "$tmp/evec_si.csv" | grep -v '^[#e]' | awk -F, '
        { if ($6 != 0 && ($22 / $6 - 0.6 > 1e-12 || 0.6 - $22 / $6 > 1e-12)) bad = 1
          d = $7 - $23; if (d > 1e-9 || d < -1e-9) bad = 1
          if ($13 != "" && $13 != 0 && ($29 * 0.6 / $13 - 1 > 1e-12 || 1 - $29 * 0.6 / $13 > 1e-12)) bad = 1
          if ($4 != $20) bad = 1 }
        END { exit bad }'; then
  pass "--eigenvectors with SI units: s in metres, displacements kept, angles / 0.6"
else fail "--eigenvectors with SI units: $(cat "$tmp/err"; grep '^#' "$tmp/evec_si.csv" 2>/dev/null)"; fi
# a minimum of the amended potential (mode 1): every mode neutral with positive energy
if "$WHIRL" stability --omega 2 --mode 1 --links 6 --eigenvectors -o "$tmp/evec1.csv" 2>"$tmp/err" \
   && grep -v '^[#e]' "$tmp/evec1.csv" | awk -F, '$4 != 1 { bad = 1 } END { exit bad }'; then
  pass "--eigenvectors: every mode of mode 1 (a minimum) neutral with Krein signature +1"
else fail "--eigenvectors Krein signatures of mode 1: $(cat "$tmp/err")"; fi
expect_error "eigenvectors without --links" "--eigenvectors needs --links" stability --omega 4.5 --mode 2 --eigenvectors
expect_error "eigenvectors without --omega" "--eigenvectors needs --omega" stability --omega-min 1 --omega-max 2 --omega-count 2 --links 6 --eigenvectors
expect_error "eigenvectors and eigenvalues" "cannot be given with|excludes" stability --omega 4.5 --mode 2 --links 6 --eigenvectors --eigenvalues
expect_error "eigenvectors of an absent mode" "mode 7|exist|links" stability --omega 4.5 --mode 7 --links 6 --eigenvectors -o "$tmp/evbad.csv"
[ ! -e "$tmp/evbad.csv" ] && pass "--eigenvectors: no file on failure" || fail "--eigenvectors left a file on failure"

# ---- --atlas: the windows of --windows, a Krein signature at each edge, resumable ----
if "$WHIRL" stability --atlas --modes 2 --omega-max 6 -o "$tmp/atlas.csv" 2>"$tmp/err" \
   && "$WHIRL" stability --windows --modes 2 --omega-min 1 --omega-max 6 -o "$tmp/aw.csv" \
   && [ "$(grep -v '^#' "$tmp/atlas.csv" | head -1)" = "mode,from,to,open_from,open_to,freq_from,freq_to,sig_from,sig_to,max_growth,at,err_from,err_to" ] \
   && [ "$(grep -v '^#' "$tmp/atlas.csv" | tail -n +2 | cut -d, -f2,3)" = "$(grep -v '^#' "$tmp/aw.csv" | tail -n +2 | cut -d, -f3,4)" ] \
   && [ "$(grep -v '^#' "$tmp/atlas.csv" | tail -n +2 | cut -d, -f8,9)" = "-1,1" ]; then
  pass "atlas: mode 2 to omega 6 has the window of --windows, signatures -1 / 1 at its edges"
else fail "atlas: $(cat "$tmp/err" "$tmp/atlas.csv" 2>/dev/null | tail -3)"; fi
# a file with the second chunk undone: --resume computes it, and the file is the same again
grep -v "^# done mode 2 omega 5 6" "$tmp/atlas.csv" >"$tmp/apart.csv"
if "$WHIRL" stability --atlas --modes 2 --omega-max 6 -o "$tmp/apart.csv" --resume \
   && cmp -s "$tmp/apart.csv" "$tmp/atlas.csv"; then
  pass "atlas --resume completes the chunks not done"
else fail "atlas --resume completes the chunks not done"; fi
if "$WHIRL" stability --atlas --modes 2-3,5 --omega-max 1 -o "$tmp/a1.csv" \
   && [ "$(grep -c '^# done mode' "$tmp/a1.csv")" -eq 3 ] && [ "$(grep -vc '^#' "$tmp/a1.csv")" -eq 1 ]; then
  pass "atlas below every birth: the chunks done, no window"
else fail "atlas below every birth"; fi
expect_error "atlas to stdout" "--atlas needs --output" stability --atlas --modes 2
expect_error "atlas mode 0" "--modes: each entry must be >= 1" stability --atlas --modes 0,65 -o "$tmp/a0.csv"
expect_error "atlas with --links" "--atlas cannot be given with --links" stability --atlas --links 10 -o "$tmp/a0.csv"

# ---- whirl windows: the command that --windows and --atlas are aliases of (for one release) ----
# the same files (the comment line of each mode apart: its time)
if "$WHIRL" windows --links 10 --modes 2 --omega-min 3 --omega-max 5 -o "$tmp/ww.csv" \
   && [ "$(grep -v '^# mode' "$tmp/ww.csv")" = "$(grep -v '^# mode' "$tmp/w.csv")" ] \
   && "$WHIRL" windows --atlas --modes 2 --omega-max 6 -o "$tmp/watlas.csv" \
   && cmp -s "$tmp/watlas.csv" "$tmp/atlas.csv" \
   && "$WHIRL" windows --links 10 --modes 1,2 --omega-min 2 --omega-max 6 --damping 1e-3 -o "$tmp/wdw.csv" \
   && [ "$(grep -v '^# mode' "$tmp/wdw.csv")" = "$(grep -v '^# mode' "$tmp/dw.csv")" ]; then
  pass "whirl windows: the files of stability --windows (N-link, damped) and --atlas"
else fail "whirl windows: not the files of its aliases"; fi
if "$WHIRL" stability --help | grep -q -- "--windows *alias of whirl windows, kept for one release" \
   && "$WHIRL" stability --help | grep -q -- "--atlas *alias of whirl windows --atlas, kept for one release" \
   && "$WHIRL" --help | grep -q "^  windows "; then
  pass "stability --help names --windows and --atlas as aliases of whirl windows"
else fail "stability --help: the aliases"; fi
expect_error "windows without a range or --atlas" "--omega-min or --atlas is required" windows -o "$tmp/out.csv"
expect_error "windows --resume without --atlas" "--resume needs --atlas" windows $R --resume -o "$tmp/out.csv"
expect_error "windows: a point's option" "unknown option '--omega'" windows --omega 3 -o "$tmp/out.csv"
expect_error "windows --atlas with --omega-min" "--omega-min cannot be given with --atlas|--atlas cannot be given with --omega-min" windows --atlas --omega-min 2 -o "$tmp/out.csv"
finish
