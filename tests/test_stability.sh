#!/bin/sh
# whirl stability: bad input, the CSV, the agreement of the perturbed runs with the linear
# analysis (growth within 5%; a neutral shape stays within 100 times the perturbation; with
# damping mode 1 converges and mode 2 grows), and the map form.
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
expect_error "rate and map" "either" stability --omega 2 --omega-min 1 --omega-max 3 --steps 5 -o "$tmp/out.csv"
expect_error "map without steps" "steps" stability --omega-min 1 --omega-max 3 -o "$tmp/out.csv"
expect_error "non-number" "omega" stability --omega fast --mode 1 -o "$tmp/out.csv"
expect_ok "help" stability --help

# csv_field FILE COLUMN: the value of COLUMN in the first data row
csv_field() { grep -v '^#' "$1" | awk -F, -v c="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) k = i } NR == 2 { print $k }'; }

# An unstable shape: the run's growth agrees with the eigenvalue within 5%.
if "$WHIRL" stability --omega 6.3 --mode 2 --links 12 -o "$tmp/u.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/u.csv" | head -1)" = "omega,mode,links,eig_growth,sim_growth,max_deviation,verdict" ] \
   && [ "$(csv_field "$tmp/u.csv" verdict)" = unstable ] \
   && awk -v e="$(csv_field "$tmp/u.csv" eig_growth)" -v s="$(csv_field "$tmp/u.csv" sim_growth)" \
        'BEGIN { exit !(e > 0.01 && s > 0 && (s - e) / e < 0.05 && (e - s) / e < 0.05) }'; then
  pass "unstable mode 2 (N = 12, omega 6.3): sim_growth within 5% of eig_growth"
else fail "unstable mode 2: $(cat "$tmp/err" "$tmp/u.csv" 2>/dev/null | tail -2)"; fi

# A gyroscopically stabilised shape (mode 2 has two negative directions of K): eig_growth 0 and
# the deviation stays below 100 times the perturbation.
if "$WHIRL" stability --omega 4.5 --mode 2 --links 12 --periods 60 -o "$tmp/s.csv" 2>"$tmp/err" \
   && [ "$(csv_field "$tmp/s.csv" eig_growth)" = 0 ] \
   && [ "$(csv_field "$tmp/s.csv" verdict)" = stable ] \
   && [ "$(csv_field "$tmp/s.csv" sim_growth)" = 0 ] \
   && awk -v d="$(csv_field "$tmp/s.csv" max_deviation)" 'BEGIN { exit !(d >= 1 && d < 100) }'; then
  pass "stabilised mode 2 (N = 12, omega 4.5): bounded deviation"
else fail "stabilised mode 2: $(cat "$tmp/err" "$tmp/s.csv" 2>/dev/null | tail -2)"; fi

# Kelvin-Tait-Chetaev: with damping, mode 1 converges and mode 2 (stable without) grows.
if "$WHIRL" stability --omega 4.5 --mode 1 --links 12 --damping 0.01 -o "$tmp/d1.csv" 2>"$tmp/err" \
   && [ "$(csv_field "$tmp/d1.csv" verdict)" = converging ] \
   && awk -v e="$(csv_field "$tmp/d1.csv" eig_growth)" 'BEGIN { exit !(e < 0) }' \
   && "$WHIRL" stability --omega 4.5 --mode 2 --links 12 --damping 0.01 -o "$tmp/d2.csv" 2>"$tmp/err" \
   && [ "$(csv_field "$tmp/d2.csv" verdict)" = unstable ] \
   && awk -v e="$(csv_field "$tmp/d2.csv" eig_growth)" -v s="$(csv_field "$tmp/d2.csv" sim_growth)" \
        'BEGIN { exit !(e > 0.01 && (s - e) / e < 0.05 && (e - s) / e < 0.05) }'; then
  pass "damping: mode 1 converges, mode 2 grows as predicted"
else fail "damping: $(cat "$tmp/err" "$tmp/d1.csv" "$tmp/d2.csv" 2>/dev/null | tail -3)"; fi

# The map: one row per rate where the mode exists (mode 2 starts at its critical rate ~2.7).
if "$WHIRL" stability --omega-min 2 --omega-max 5 --steps 7 --modes 1,2 --links 10 --linear \
     -o "$tmp/map.csv" 2>"$tmp/err" \
   && [ "$(grep -v '^#' "$tmp/map.csv" | awk -F, '$2 == 1' | wc -l)" -eq 7 ] \
   && [ "$(grep -v '^#' "$tmp/map.csv" | awk -F, '$2 == 2' | wc -l)" -eq 5 ] \
   && [ "$(grep -v '^#' "$tmp/map.csv" | awk -F, 'NR > 1 && ($5 != "" || $6 != "")' | wc -l)" -eq 0 ] \
   && ! grep -qi nan "$tmp/map.csv"; then
  pass "map form: rows where the modes exist"
else fail "map form: $(cat "$tmp/err" "$tmp/map.csv" 2>/dev/null | tail -3)"; fi

finish
