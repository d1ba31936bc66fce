#!/bin/sh
# How the number of planar equilibria of the N-link chain departs from Kolodner's count (the
# number of modes born below the rate, the continuum's exact count) as the rate grows: for each
# N and rate, `whirl equilibria --no-stability`, printed as a Markdown table of
# "count (isolated)" cells, with the wall time of each run. A run that fails (scan not settled,
# budget) shows its reason; one over LIMIT seconds (default 300) is stopped.
# Usage: [LIMIT=S] scripts/equilibria_counts.sh [BUILD] [N...]
build=${1:-build}
shift 2>/dev/null
links=${*:-5 10 25 100}
rates="5 7.5 10 12.5 15 20 25 30 40 50"
whirl=$build/whirl
limit=${LIMIT:-300} # seconds per run
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '| N |'
for w in $rates; do printf ' %s |' "$w"; done
printf '\n|---|'
for w in $rates; do printf -- '---|'; done
printf '\n'
for n in $links; do
  printf '| %s |' "$n"
  for w in $rates; do
    start=$(date +%s.%N)
    if timeout "$limit" "$whirl" equilibria --omega "$w" --links "$n" --no-stability -o "$tmp/e.csv" 2>"$tmp/err"; then
      t=$(echo "$(date +%s.%N) - $start" | bc)
      born=$(sed -n 's/.* \([0-9]*\) modes born below omega$/\1/p' "$tmp/e.csv")
      count=$(grep -v '^#' "$tmp/e.csv" | tail -n +2 | wc -l)
      iso=$(grep -v '^#' "$tmp/e.csv" | tail -n +2 | grep -c ',isolated,')
      unid=$(grep -v '^#' "$tmp/e.csv" | tail -n +2 | grep -c ',unidentified,')
      cell="$count / $born"
      [ "$iso" -gt 0 ] && cell="$cell, $iso iso"
      [ "$unid" -gt 0 ] && cell="$cell, $unid unid"
      printf ' %s (%.1fs) |' "$cell" "$t"
    elif [ $? -eq 124 ]; then
      printf ' (over %s s) |' "$limit"
    else
      printf ' (%s) |' "$(sed 's/^whirl equilibria: //' "$tmp/err" | cut -c1-40)"
    fi
  done
  printf '\n'
done
