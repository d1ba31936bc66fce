#!/bin/sh
# Runs every benchmark program (tests/bench_*.c); each writes its CSV under out/bench/ and
# prints its figures, then the figures out/bench/workprecision_*.png and scaling.png are drawn.
# Timings are medians of repeats, reported as measured on this machine.
build=${1:-build}
mkdir -p out/bench
echo "machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
status=0
for b in "$build"/tests/bench_*; do
  [ -x "$b" ] || continue
  echo "== $b"
  WHIRL="$build/whirl" "$b" out/bench || status=1
done
for s in tests/bench_*.sh; do
  [ -f "$s" ] || continue
  echo "== $s"
  WHIRL="$build/whirl" sh "$s" out/bench || status=1
done
# figures from the CSVs (plots/*.gp), when gnuplot is installed
if command -v gnuplot >/dev/null 2>&1; then
  for g in workprecision scaling; do
    echo "== plots/$g.gp"
    gnuplot -e "dir='out/bench'" "plots/$g.gp" || status=1
  done
else
  echo "gnuplot not found: figures not drawn"
fi
exit $status
