#!/bin/sh
# Command-line tests of whirl critical, shape and sweep: contract and bad input.
. "$(dirname "$0")/lib.sh"

# critical: the continuum's j0k/2 to 12 digits and more
expect_ok "critical runs" critical --modes 4 -o "$tmp/crit.csv"
if awk -F, '/^#/ {next} !h {h = $0; next} {n++; w[$1] = $2}
     END {exit !(h == "mode,omega" && n == 4 && w[1] == "1.2024127788478853" &&
                 (w[2] - 2.7600390551431524) ^ 2 < 1e-26)}' "$tmp/crit.csv"; then
  pass "critical: header and j0k/2"; else fail "critical: header and j0k/2"; fi
expect_ok "critical --links" critical --links 50 --modes 3
expect_ok "critical --tip-mass" critical --tip-mass 0.5 --modes 3
# physical units: rates scale with sqrt(g/L)
"$WHIRL" critical --modes 1 --length 2 --gravity 9.81 --mass 3 >"$tmp/phys.csv"
if awk -F, '/^#/ || /mode/ {next} {exit !(($2 / (1.2024127788478853 * sqrt(9.81 / 2)) - 1) ^ 2 < 1e-28)}' \
     "$tmp/phys.csv"; then pass "critical: physical units"; else fail "critical: physical units"; fi

# shape: comment line, header, rows from the pivot to the free end
expect_ok "shape runs" shape --omega 6.5 --mode 3 --points 51 -o "$tmp/shape.csv"
if head -1 "$tmp/shape.csv" | grep -Eq '^# omega=6.5 mode=3 node_count=3 tip_r=[0-9.e-]+ max_r=[0-9.e-]+ top_tension=[0-9.e-]+ depth=[0-9.e-]+ crossing_s=[0-9.e-]+;[0-9.e-]+$' \
   && [ "$(grep -v '^#' "$tmp/shape.csv" | head -1)" = "s,r,z,tension" ] \
   && [ "$(grep -vc '^#' "$tmp/shape.csv")" -eq 52 ]; then
  pass "shape: comment, header, 51 rows"; else fail "shape: comment, header, 51 rows"; fi
# the tip row: s = 1, r = tip_r, z = -depth
tip=$(head -1 "$tmp/shape.csv" | sed 's/.*tip_r=\([^ ]*\).*/\1/')
if tail -1 "$tmp/shape.csv" | awk -F, -v tip="$tip" '{exit !($1 == 1 && $2 == tip && $3 < 0)}'; then
  pass "shape: the last row is the free end"; else fail "shape: the last row is the free end"; fi
expect_ok "shape --links" shape --omega 6.5 --mode 3 --links 40 -o "$tmp/nl.csv"
if [ "$(grep -vc '^#' "$tmp/nl.csv")" -eq 42 ]; then pass "shape --links: N+1 rows"
else fail "shape --links: N+1 rows"; fi
expect_ok "shape tip mass" shape --omega 30 --mode 6 --tip-mass 0.3
expect_ok "shape near critical" shape --omega 4.3268683833 --mode 3
expect_ok "shape physical units" shape --omega 20 --mode 2 --length 0.5 --gravity 9.81 --mass 0.2

# sweep
expect_ok "sweep runs" sweep --modes 1,2,3 --omega-min 1 --omega-max 10 --omega-count 91 -o "$tmp/sw.csv"
if awk -F, '/^#/ {next} !h {h = $0; next} {n[$2]++}
     END {exit !(h == "omega,mode,tip_r,max_r,top_tension,depth,nodes" && n[1] == 88 && n[2] == 73 && n[3] == 57)}' \
     "$tmp/sw.csv"; then pass "sweep: a row wherever the mode exists"
else fail "sweep: a row wherever the mode exists"; fi
expect_ok "sweep --links --tip-mass" sweep --modes 2 --omega-min 3 --omega-max 5 --omega-count 11 --links 30 --tip-mass 0.2
# the 7-link chain's mode-4 branch is S-shaped: two folds, rates 6.9 and 7.0 crossed three times
expect_ok "sweep through folds" sweep --modes 4 --links 7 --omega-min 5 --omega-max 8 --omega-count 31 \
  --events "$tmp/ev.csv" -o "$tmp/s7.csv"
if awk -F, '/^#/ {next} !h {h = $0; next} {n[$1]++} END {exit !(n["6.9"] == 3 && n["7"] == 3)}' "$tmp/s7.csv" \
   && [ "$(grep -c '^# fold: mode=4 omega=' "$tmp/s7.csv")" -eq 2 ] \
   && awk -F, '/^#/ {next} !h {h = $0; next} {n++; ok += ($1 == 4 && $2 == "fold")}
        END {exit !(h == "mode,kind,omega,tip_r,arclength,nodes" && n == 2 && ok == 2)}' "$tmp/ev.csv"; then
  pass "sweep: through the folds, each listed"; else fail "sweep: through the folds, each listed"; fi
# mode N of N near omega_N (omega_15 = 26.8401): found, with its node count
expect_ok "shape mode N" shape --links 15 --mode 15 --omega 26.85 -o "$tmp/m15.csv"
if head -1 "$tmp/m15.csv" | grep -q ' mode=15 node_count=15 '; then pass "shape mode N: 15 nodes"
else fail "shape mode N: 15 nodes"; fi
# every mode of a long chain, beyond 64: mode 150 of 200 at 1.02 omega_150 (252.93), all its
# 149 crossings listed; 200 critical rates, increasing
expect_ok "shape mode 150 of 200" shape --links 200 --mode 150 --omega 258 -o "$tmp/m150.csv"
if head -1 "$tmp/m150.csv" | grep -q ' mode=150 node_count=150 ' \
   && [ "$(head -1 "$tmp/m150.csv" | sed 's/.*crossing_s=//' | tr ';' '\n' | grep -c .)" -eq 149 ] \
   && [ "$(grep -vc '^#' "$tmp/m150.csv")" -eq 202 ]; then
  pass "shape mode 150 of 200: 150 nodes, 149 crossings listed"
else fail "shape mode 150 of 200: 150 nodes, 149 crossings listed"; fi
expect_ok "critical 200 modes" critical --links 200 --modes 200 -o "$tmp/c200.csv"
if awk -F, '/^#/ {next} !h {h = $0; next} {n++; ok += ($1 == n && $2 > last); last = $2}
     END {exit !(n == 200 && ok == 200 && last > 391.87 && last < 391.88)}' "$tmp/c200.csv"; then
  pass "critical: 200 modes of 200 links"; else fail "critical: 200 modes of 200 links"; fi
# all 3183 continuum modes with a tip mass in one sweep; the last equals the Bessel determinant's
# 3183rd root by mpmath (40 digits): 9655.9238544007285973
expect_ok "critical 3183 modes, tip mass" critical --tip-mass 0.5 --modes 3183 -o "$tmp/c3183.csv"
if awk -F, '/^#/ {next} !h {h = $0; next} {n++; ok += ($1 == n && $2 > last); last = $2}
     END {exit !(n == 3183 && ok == 3183 && last > 9655.923854400 && last < 9655.923854401)}' \
     "$tmp/c3183.csv"; then
  pass "critical: 3183 modes with tip mass 0.5"; else fail "critical: 3183 modes with tip mass 0.5"; fi
expect_ok "sweep mode 100 of 200" sweep --links 200 --modes 100 --omega-min 150 --omega-max 165 --omega-count 2 -o "$tmp/s200.csv"
if awk -F, '/^#/ {next} !h {h = $0; next} {n++; ok += ($2 == 100 && $7 == 100)} END {exit !(n == 1 && ok == 1)}' \
     "$tmp/s200.csv"; then pass "sweep: mode 100 of 200 above its birth (160.93) only"
else fail "sweep: mode 100 of 200 above its birth (160.93) only"; fi
# the continuum's modes beyond 64: mode 200 at 1.001 omega_200 (316.59), its 199 crossings
# counted, the first 64 listed and said so
expect_ok "continuum mode 200" shape --mode 200 --omega 316.9 --points 11 -o "$tmp/c200s.csv"
if head -1 "$tmp/c200s.csv" | grep -q ' mode=200 node_count=200 ' \
   && [ "$(head -1 "$tmp/c200s.csv" | sed 's/.*crossing_s=//' | tr ';' '\n' | grep -c .)" -eq 64 ] \
   && grep -q '^# crossing_s: the first 64 of the 199 axis crossings below the pivot$' "$tmp/c200s.csv"; then
  pass "continuum mode 200: 200 nodes, the first 64 listed"
else fail "continuum mode 200: 200 nodes, the first 64 listed"; fi

# mode 500 of 500 at 1.2 times its birth (988.80): its radii decay below the smallest normal
# double towards the tip (to 1e-540 of the largest), so they are 0 or subnormal in the CSV; the
# node count takes their signs from the force balance linearised about the hanging chain and is
# 500 (a 60-digit tip shot has 499 sign changes; the count stopped at 376 before), all 499
# crossings listed, increasing, those below the last normal radius included
expect_ok "mode 500 of 500 links" shape --links 500 --mode 500 --omega 1186.557 -o "$tmp/m500.csv"
# the last mass whose radius is a normal double (row 1 is the pivot)
last=$(grep -v '^#' "$tmp/m500.csv" | tail -n +2 \
       | awk -F, '$2 + 0 >= 2.2250738585072014e-308 || -$2 >= 2.2250738585072014e-308 {k = NR - 1}
                  END {print k}')
tail_said="the smallest normal double (0 or subnormal here): their signs and nodes are those of \
the force balance linearised about the hanging chain at this rate, from the tip up"
if [ -n "$last" ] && [ "$last" -gt 300 ] && [ "$last" -lt 450 ] \
   && head -1 "$tmp/m500.csv" | grep -q ' mode=500 node_count=500 ' \
   && head -1 "$tmp/m500.csv" | sed 's/.*crossing_s=//' | tr ';' '\n' \
      | awk -v s="$last" '{n++; ok += ($1 > p && $1 < 1); p = $1; tail += ($1 > s / 500)}
                          END {exit !(n == 499 && ok == 499 && tail > 100)}' \
   && grep -q "^# the radii of masses $((last + 1))\.\.500 are below $tail_said\$" "$tmp/m500.csv" \
   && ! grep -q 'can change its node count' "$tmp/m500.csv"; then
  pass "mode 500 of 500: 500 nodes, those of the tail below mass $last from the linearised balance"
else fail "mode 500 of 500: 500 nodes (last normal radius at mass $last)"; fi

# help
expect_ok "critical --help" critical --help
expect_ok "shape --help" shape --help
expect_ok "sweep --help" sweep --help

# bad input
expect_error "unknown flag" "whirl shape: unknown option '--bogus'" shape --omega 3 --mode 1 --bogus 1 -o "$tmp/out.csv"
expect_error "missing value" "whirl shape: option --omega needs a value" shape --mode 1 -o "$tmp/out.csv" --omega
expect_error "non-numeric" "whirl shape: option --omega needs a finite number" shape --omega abc --mode 1 -o "$tmp/out.csv"
expect_error "NaN" "whirl shape: option --omega needs a finite number" shape --omega nan --mode 1 -o "$tmp/out.csv"
expect_error "infinite" "whirl shape: option --omega needs a finite number" shape --omega inf --mode 1 -o "$tmp/out.csv"
expect_error "omega missing" "whirl shape: --omega is required" shape --mode 1 -o "$tmp/out.csv"
expect_error "omega zero" "whirl shape: --omega must be > 0" shape --omega 0 --mode 1 -o "$tmp/out.csv"
expect_error "omega negative" "whirl shape: --omega must be > 0" shape --omega -2 --mode 1 -o "$tmp/out.csv"
expect_error "mode zero" "whirl shape: --mode must be >= 1, got 0" shape --omega 3 --mode 0 -o "$tmp/out.csv"
expect_error "links zero" "whirl shape: --links must be >= 1" shape --omega 3 --mode 1 --links 0 -o "$tmp/out.csv"
expect_error "negative tip mass" "whirl shape: --tip-mass must be >= 0" shape --omega 3 --mode 1 --tip-mass -1 -o "$tmp/out.csv"
expect_error "points" "whirl shape: --points must be between 2 and" shape --omega 3 --mode 1 --points 1 -o "$tmp/out.csv"
expect_error "mode does not exist" "whirl shape: mode 3 does not exist at omega=4: it exists only above omega_3=4.3268" shape --omega 4 --mode 3 -o "$tmp/out.csv"
expect_error "mode above N" "whirl shape: .*modes 1..3" shape --omega 30 --mode 4 --links 3 -o "$tmp/out.csv"
expect_error "bad units" "whirl shape: --length must be > 0" shape --omega 3 --mode 1 --length -1 -o "$tmp/out.csv"
expect_error "critical modes" "whirl critical: --modes must be >= 1, got 0" critical --modes 0 -o "$tmp/out.csv"
expect_error "critical modes above N" "whirl critical: .*exceeds" critical --modes 5 --links 4 -o "$tmp/out.csv"
expect_error "critical tip mass" "whirl critical: --tip-mass must be >= 0" critical --tip-mass -0.5 -o "$tmp/out.csv"
expect_error "sweep count" "whirl sweep: --omega-count must be between 1 and" sweep --modes 1 --omega-min 1 --omega-max 2 --omega-count 0 -o "$tmp/out.csv"
expect_error "sweep order" "whirl sweep: need --omega-min < --omega-max" sweep --modes 1 --omega-min 3 --omega-max 2 --omega-count 5 -o "$tmp/out.csv"
expect_error "sweep old --steps" "whirl sweep: unknown option '--steps'" sweep --modes 1 --omega-min 1 --omega-max 2 --steps 5 -o "$tmp/out.csv"
expect_error "sweep omega-min" "whirl sweep: --omega-min must be > 0" sweep --modes 1 --omega-min 0 --omega-max 2 --omega-count 5 -o "$tmp/out.csv"
expect_error "sweep modes list" "whirl sweep: option --modes needs a comma-separated list" sweep --modes 1,x --omega-min 1 --omega-max 2 --omega-count 5 -o "$tmp/out.csv"
expect_error "sweep mode zero" "whirl sweep: --modes: each entry must be >= 1, got 0" sweep --modes 1,0 --omega-min 1 --omega-max 2 --omega-count 5 -o "$tmp/out.csv"
expect_error "sweep missing count" "whirl sweep: --omega-count is required" sweep --modes 1 --omega-min 1 --omega-max 2 -o "$tmp/out.csv"
expect_error "unwritable output" "whirl shape: .*cannot write" shape --omega 3 --mode 1 -o "$tmp/no/such/dir/out.csv"
expect_error "mode above N" "whirl shape: mode 6 does not exist: a chain of 5 links has modes 1..5" shape --omega 30 --mode 6 --links 5 -o "$tmp/out.csv"
expect_error "below the birth" "whirl shape: mode 15 does not exist at omega=26.8: it exists only above omega_15=26.84" shape --links 15 --mode 15 --omega 26.8 -o "$tmp/out.csv"
expect_error "sweep mode above N" "whirl sweep: mode 6 does not exist: a chain of 5 links has modes 1..5" sweep --modes 2,6 --links 5 --omega-min 1 --omega-max 9 --omega-count 9 -o "$tmp/out.csv"
expect_error "mode above N (long chain)" "whirl shape: mode 201 does not exist: a chain of 200 links has modes 1..200" shape --links 200 --mode 201 --omega 300 -o "$tmp/out.csv"
expect_error "continuum mode above 3183" "whirl shape: mode 3184 is out of range: the continuous chain's solvers take modes 1..3183, those born below omega=5000" shape --mode 3184 --omega 4000 -o "$tmp/out.csv"
expect_error "critical continuum above 3183" "whirl critical: mode 3184 is out of range" critical --modes 3184 -o "$tmp/out.csv"
expect_error "below the birth (long chain)" "whirl shape: mode 150 does not exist at omega=250: it exists only above omega_150=252.93" shape --links 200 --mode 150 --omega 250 -o "$tmp/out.csv"
# sweep: a rate between the birth and the first point of the path (mode 100 of 100 at 1 + 1e-12
# of its birth) has its row, as shape has it (the same tip radius)
w100=$("$WHIRL" critical --links 100 --modes 100 | grep -v '^#' | tail -n 1 | cut -d, -f2)
lo=$(awk -v w="$w100" 'BEGIN { printf "%.17g", w * (1 + 1e-12) }')
hi=$(awk -v w="$w100" 'BEGIN { printf "%.17g", w * (1 + 1e-6) }')
"$WHIRL" sweep --links 100 --modes 100 --omega-min "$lo" --omega-max "$hi" --omega-count 3 \
  -o "$tmp/gap.csv" && "$WHIRL" shape --links 100 --mode 100 --omega "$lo" -o "$tmp/gap1.csv" &&
tip=$(grep -m1 '^# .*tip_r=' "$tmp/gap1.csv" | sed 's/.*tip_r=\([^ ,]*\).*/\1/')
if [ "$(grep -vc '^#' "$tmp/gap.csv")" -eq 4 ] &&
   grep -v '^#' "$tmp/gap.csv" | awk -F, -v tip="$tip" 'NR == 2 { exit !($3 == tip && $7 == 100) }'; then
  pass "sweep: a rate just above the birth (1 + 1e-12)"
else fail "sweep: a rate just above the birth (1 + 1e-12) (tip $tip: $(grep -v '^#' "$tmp/gap.csv" | head -2 | tr '\n' ' '))"; fi
expect_error "events without links" "whirl sweep: --events needs --links" sweep --modes 2 --omega-min 1 --omega-max 9 --omega-count 9 --events "$tmp/ev2.csv" -o "$tmp/out.csv"
if [ -e "$tmp/ev2.csv" ]; then fail "no events file after an error"; else pass "no events file after an error"; fi
# the heaviest tip mass (1e12 chain masses): mode 16 of 30 links, which stopped near omega 4.4e7
# (its branch turns sharply where the symmetric branch of the string pinned by the tip splits),
# reaches 2.2e8; sweep lists modes 15 and 16 at every rate, with an events file
expect_ok "shape: heavy tip at 5 times the birth" \
  shape --links 30 --tip-mass 1e12 --mode 16 --omega 2.2e8 -o "$tmp/heavy.csv"
if head -1 "$tmp/heavy.csv" | grep -q '^# omega=220000000 mode=16 node_count=16 ' \
   && [ "$(grep -vc '^#' "$tmp/heavy.csv")" -eq 32 ]; then pass "shape: heavy tip, 31 nodes"
else fail "shape: heavy tip, 31 nodes"; fi
expect_ok "sweep: heavy tip" \
  sweep --links 30 --tip-mass 1e12 --modes 15,16 --omega-min 4.3e7 --omega-max 2.2e8 --omega-count 5 \
  --events "$tmp/ev3.csv" -o "$tmp/out.csv"
if awk -F, '/^#/ {next} !h {h = 1; next} {n[$2]++} END {exit !(n[15] == 5 && n[16] == 5)}' "$tmp/out.csv" \
   && [ -s "$tmp/ev3.csv" ]; then pass "sweep: heavy tip, both modes at every rate"
else fail "sweep: heavy tip, both modes at every rate"; fi
expect_error "unwritable output (sweep)" "whirl sweep: .*cannot write" sweep --modes 1 --omega-min 1 --omega-max 2 --omega-count 2 -o "$tmp/no/such/dir/out.csv"
finish
