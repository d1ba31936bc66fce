#!/bin/sh
# Runs the benchmarks and prints their headline ratios as one table (out/bench/headline.csv).
# Usage: scripts/bench.sh [BUILD [quick]].
#  - full (default): every benchmark program (tests/bench_*.c, *.sh, *.py); each writes its CSV
#    under out/bench/ and prints its figures; then the figures out/bench/workprecision_*.png and
#    scaling.png are drawn;
#  - quick: the peers (tests/bench_peers.c quick: MuJoCo, SUNDIALS, GSL, the seed formulation,
#    ns per link) and the continuum shapes against scipy (tests/bench_scipy.py quick): every
#    headline ratio of the README in under 10 minutes.
# Timings are medians of repeats, reported as measured on this machine.
build=${1:-build}
mode=${2:-full}
out=out/bench
mkdir -p "$out"
echo "machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
rm -f "$out/headline.csv"
status=0
start=$(date +%s)
if [ "$mode" = quick ]; then
  echo "== $build/tests/bench_peers quick"
  "$build/tests/bench_peers" "$out" quick || status=1
  echo "== tests/bench_scipy.py quick"
  /usr/bin/python3 tests/bench_scipy.py "$out" "$build/whirl" quick || status=1
else
  for b in "$build"/tests/bench_*; do
    [ -x "$b" ] || continue
    echo "== $b"
    WHIRL="$build/whirl" "$b" "$out" || status=1
  done
  for s in tests/bench_*.sh; do
    [ -f "$s" ] || continue
    echo "== $s"
    WHIRL="$build/whirl" sh "$s" "$out" || status=1
  done
  echo "== tests/bench_scipy.py"
  /usr/bin/python3 tests/bench_scipy.py "$out" "$build/whirl" || status=1
  # figures from the CSVs (plots/*.gp), when gnuplot is installed
  if command -v gnuplot >/dev/null 2>&1; then
    for g in workprecision scaling; do
      echo "== plots/$g.gp"
      gnuplot -e "dir='$out'" "plots/$g.gp" || status=1
    done
  else
    echo "gnuplot not found: figures not drawn"
  fi
fi
echo
echo "Headline figures ($mode run, $(( $(date +%s) - start )) s; ratios are the peer's time over whirl's, within this run):"
if [ -f "$out/headline.csv" ]; then
  awk -F, '{ printf "  %-82s %10s  %-7s %s\n", $2, ($3 == "" ? "-" : $3), $4, $5 }' "$out/headline.csv"
else
  echo "  (none recorded)"
  status=1
fi
exit $status
