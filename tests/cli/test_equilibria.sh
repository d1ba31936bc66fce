# whirl equilibria from the command line: the CSV (columns, one row per equilibrium, node counts
# of N = 5 at omega = 11.62, Kolodner's count for the continuum), physical units, bad input
# (one-line error, non-zero exit, no file) and Ctrl-C (exit 130, no file).
. "$(dirname "$0")/lib.sh"
out=$tmp/out.csv

expect_ok "equilibria of 5 links at 11.62" equilibria --omega 11.62 --links 5 -o "$out"
header=$(grep -v '^#' "$out" | head -n 1)
if [ "$header" = "nodes,branch,born_at,tip_r,max_r,depth,top_tension,eig_growth,verdict,index" ]; then
  pass "columns"; else fail "columns: $header"; fi
counts=$(grep -v '^#' "$out" | tail -n +2 | cut -d, -f1 | sort | uniq -c | awk '{ printf "%s:%s ", $2, $1 }')
if [ "$counts" = "1:1 2:1 3:3 4:5 5:7 " ]; then pass "1, 1, 3, 5, 7 equilibria with 1..5 nodes"
else fail "node counts: $counts"; fi
branches=$(grep -v '^#' "$out" | tail -n +2 | cut -d, -f2 | sort | uniq -c | awk '{ printf "%s:%s ", $2, $1 }')
if [ "$branches" = "1:1 2:1 3:1 4:1 5:1 isolated:12 " ]; then pass "one per branch, 12 isolated"
else fail "branches: $branches"; fi
if grep -q '^# units: dimensionless' "$out" && grep -q '0 missed by the scans' "$out"; then
  pass "units line, nothing missed"; else fail "comment lines: $(grep '^#' "$out")"; fi
verdicts=$(grep -v '^#' "$out" | tail -n +2 | awk -F, '$9 != "stable (minimum)" && $9 != "neutral (gyroscopic)" && $9 != "unstable"' | wc -l)
if [ "$verdicts" -eq 0 ]; then pass "a verdict on every row"; else fail "$verdicts rows without a verdict"; fi

# the continuum: Kolodner's count, one row per mode born
expect_ok "continuum at 5" equilibria --omega 5 -o "$out"
rows=$(grep -v '^#' "$out" | tail -n +2 | cut -d, -f1,2 | tr '\n' ' ')
if [ "$rows" = "3,3 2,2 1,1 " ]; then pass "continuum at omega 5: modes 3, 2, 1"; else fail "continuum rows: $rows"; fi

# a high rate, the scans only: both scans find every root, the branch column left empty
expect_ok "10 links at 30, --no-branches" equilibria --omega 30 --links 10 --no-branches --no-stability -o "$out"
rows=$(grep -v '^#' "$out" | tail -n +2 | wc -l)
scans=$(sed -n 's/.*tip scan: \([0-9]*\) roots.*pivot scan: \([0-9]*\) roots.*both: \([0-9]*\); not polished: \([0-9]*\)$/\1 \2 \3 \4/p' "$out")
labelled=$(grep -v '^#' "$out" | tail -n +2 | awk -F, '$2 != "" || $3 != ""' | wc -l)
if [ "$scans" = "$rows $rows $rows 0" ] && [ "$rows" -ge 1084 ] && [ "$labelled" -eq 0 ] \
   && grep -q '0 cells unresolved' "$out" && grep -q 'continuation: not run' "$out" \
   && grep -q '^# polish: 0 roots from a shot in quadruple precision' "$out" \
   && grep -q '; 0 roots on the equilibrium of another root of the same scan' "$out"; then
  pass "10 links at 30: $rows equilibria, both scans agree"
else fail "10 links at 30: $rows rows, scans $scans, $labelled labelled"; fi

# physical units: the same equilibria, rates in rad/s and lengths in m
rate=$(awk 'BEGIN { printf "%.10f", 11.62 * sqrt(9.81 / 0.5) }')
expect_ok "physical units" equilibria --omega "$rate" --links 5 --length 0.5 --gravity 9.81 -o "$tmp/si.csv"
rows_si=$(grep -v "^#" "$tmp/si.csv" | tail -n +2 | wc -l)
tip=$(grep -v '^#' "$tmp/si.csv" | tail -n 1 | cut -d, -f4)
if [ "$rows_si" -eq 17 ] && grep -q '^# units: length=m' "$tmp/si.csv" \
   && awk -v t="$tip" 'BEGIN { exit !(t > 0.4999 && t < 0.5) }'; then
  pass "SI units: 17 equilibria, mode 1's tip radius in m"
else fail "SI units: $rows_si rows, tip $tip"; fi

expect_error "omega zero" "must be > 0|range" equilibria --omega 0 --links 5 -o "$out"
expect_error "omega above the range" "omega=1001 is out of range for the N-link chain: it must be > 0 and at most omega=1000$" equilibria --omega 1001 --links 5 -o "$out"
expect_error "continuum omega above its range" "omega=51 is out of range for the continuum: it must be > 0 and at most omega=50$" equilibria --omega 51 -o "$out"
expect_error "too many links" "a chain of 1..200 links" equilibria --omega 5 --links 201 -o "$out"
crit=$("$WHIRL" critical --links 5 --modes 3 | tail -n 1 | cut -d, -f2)
expect_error "omega at a critical rate" "critical rate of mode 3" equilibria --omega "$crit" --links 5 -o "$out"
expect_error "--no-stability without --links" "needs|--links" equilibria --omega 5 --no-stability -o "$out"
expect_error "--no-branches without --links" "needs|--links" equilibria --omega 5 --no-branches -o "$out"
# the scans' budget: over it, a one-line error that names the flag; within it, the same count
expect_error "a scan over its budget" "the scan needs more than 1000 residual evaluations; --shot-budget raises the bound$" equilibria --omega 50 --links 25 --no-branches --no-stability --shot-budget 1000 -o "$out"
expect_error "--shot-budget below 1000" "--shot-budget must be >= 1000" equilibria --omega 5 --links 5 --shot-budget 999 -o "$out"
expect_error "--shot-budget without --links" "needs|--links" equilibria --omega 5 --shot-budget 5000 -o "$out"
expect_ok "5 links at 11.62, --shot-budget 100000" equilibria --omega 11.62 --links 5 --shot-budget 100000 --no-branches -o "$out"
rows=$(grep -v '^#' "$out" | tail -n +2 | wc -l)
if [ "$rows" -eq 17 ]; then pass "--shot-budget 100000: 17 equilibria"; else fail "--shot-budget: $rows rows"; fi

# Ctrl-C: exit 130 within a short time, no file left
rm -rf "$tmp/int"; mkdir "$tmp/int"
"$WHIRL" equilibria --omega 40 --links 100 -o "$tmp/int/out.csv" >/dev/null 2>"$tmp/int.err" &
pid=$!
sleep 1
kill -INT $pid
start=$(date +%s%N)
wait $pid
rc=$?
ms=$(( ($(date +%s%N) - start) / 1000000 ))
if [ $rc -eq 130 ] && [ -z "$(ls -A "$tmp/int")" ]; then pass "Ctrl-C: exit 130, no file ($ms ms)"
else fail "Ctrl-C: rc=$rc, left: $(ls -A "$tmp/int"), $(head -c 200 "$tmp/int.err")"; fi
finish
