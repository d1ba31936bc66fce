#!/bin/sh
# How the number of planar equilibria of the N-link chain departs from Kolodner's count (the
# number of modes born below the rate, the continuum's exact count) as the rate grows: for each
# N and rate, `whirl equilibria --no-branches --no-stability` (the two scans only), one Markdown
# row: the rate, its ratio to omega_N (the highest critical rate), Kolodner's count, the number
# found, whether the tip scan and the pivot scan found the same equilibria, the count by node
# number (nodes:count) and the wall time. A run that fails (budget) shows its reason; one over
# LIMIT seconds (default 300) is stopped; SHOT_BUDGET=E passes --shot-budget E (the scans' bound,
# 2e7 residual evaluations by default: N = 25 at 50 and N = 100 at 80 need more).
# Usage: [LIMIT=S] [SHOT_BUDGET=E] [RATES_5="..."] [RATES_10=...] scripts/equilibria_counts.sh
#        [BUILD] [N...]
build=${1:-build}
shift 2>/dev/null
links=${*:-5 10 25 100}
whirl=$build/whirl
limit=${LIMIT:-300} # seconds per run
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '| N | W | W / omega_N | Kolodner | found | scans agree | by node number | time |\n'
printf '|---|---|---|---|---|---|---|---|\n'
for n in $links; do
  case $n in
    5) rates=${RATES_5:-5 7.5 10 12.5 16 20 30 50} ;;
    10) rates=${RATES_10:-5 10 15 20 25 30 35 40 50 60} ;;
    25) rates=${RATES_25:-10 15 20 25 30 35 40 50 70} ;;
    100) rates=${RATES_100:-10 20 30 40 50 60 80 100 200 300} ;;
    *) rates=${RATES:-5 10 20 40} ;;
  esac
  "$whirl" critical --links "$n" --modes "$n" > "$tmp/crit.csv"
  wn=$(tail -n 1 "$tmp/crit.csv" | cut -d, -f2)
  for w in $rates; do
    ratio=$(awk -v w="$w" -v c="$wn" 'BEGIN { printf "%.2f", w / c }')
    start=$(date +%s.%N)
    if timeout "$limit" "$whirl" equilibria --omega "$w" --links "$n" --no-branches --no-stability ${SHOT_BUDGET:+--shot-budget "$SHOT_BUDGET"} -o "$tmp/e.csv" 2>"$tmp/err"; then
      t=$(echo "$(date +%s.%N) - $start" | bc)
      born=$(sed -n 's/.* \([0-9]*\) modes born below omega$/\1/p' "$tmp/e.csv")
      count=$(grep -v '^#' "$tmp/e.csv" | tail -n +2 | wc -l)
      agree=$(sed -n 's/.*tip scan: \([0-9]*\) roots.*pivot scan: \([0-9]*\) roots.*both: \([0-9]*\); not polished: \([0-9]*\)$/\1 \2 \3 \4/p' "$tmp/e.csv")
      # and no two roots of one scan on one equilibrium
      distinct=$(grep -c '; 0 roots on the equilibrium of another root' "$tmp/e.csv")
      if [ "$agree" = "$count $count $count 0" ] && [ "$distinct" -eq 1 ]; then agree=yes
      else agree="no (tip, pivot, both, not polished: $agree)"; fi
      nodes=$(grep -v '^#' "$tmp/e.csv" | tail -n +2 | cut -d, -f1 | sort -n | uniq -c | awk '{ printf "%s%s:%s", sep, $2, $1; sep = " " }')
      printf '| %s | %s | %s | %s | %s | %s | %s | %.1f s |\n' "$n" "$w" "$ratio" "$born" "$count" "$agree" "$nodes" "$t"
    elif [ $? -eq 124 ]; then
      printf '| %s | %s | %s | | | | over %s s | |\n' "$n" "$w" "$ratio" "$limit"
    else
      printf '| %s | %s | %s | | | | %s | |\n' "$n" "$w" "$ratio" "$(sed 's/^whirl equilibria: //' "$tmp/err" | head -n 1 | cut -c1-60)"
    fi
  done
done
