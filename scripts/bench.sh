#!/bin/sh
# Runs the benchmarks and prints their headline ratios as one table (out/bench/headline.csv).
# Usage: scripts/bench.sh [BUILD [quick]].
#  - full (default, under an hour here): every benchmark program (tests/bench/bench_*.c, *.sh, *.py),
#    some with shorter settings than their own defaults (listed in args_of below; the README's
#    Performance section says what each cut leaves out); each writes its CSV under out/bench/ and
#    prints its figures; then the figures out/bench/workprecision_*.png and scaling.png are drawn;
#  - quick: the peers (tests/bench/bench_peers.c quick: MuJoCo, SUNDIALS, GSL, the seed formulation,
#    ns per link) and the continuum shapes against scipy (tests/bench/bench_scipy.py quick): every
#    headline ratio of the README in under 10 minutes.
# Every step's wall time and the load average at its start go to out/bench/bench_times.csv and
# are printed at the end. Timings are medians of repeats, reported as measured on this machine.
build=${1:-build}
mode=${2:-full}
out=out/bench
mkdir -p "$out"
echo "machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
rm -f "$out/headline.csv"
echo "step,seconds,load_average_at_start,status" >"$out/bench_times.csv"
status=0
start=$(date +%s)

# step NAME COMMAND...: runs the command, records its wall time
step() {
  name=$1
  shift
  echo "== $name"
  t0=$(date +%s)
  l0=$(cut -d' ' -f1 /proc/loadavg)
  "$@"
  rc=$?
  [ $rc -eq 0 ] || status=1
  echo "$name,$(( $(date +%s) - t0 )),$l0,$rc" >>"$out/bench_times.csv"
  echo "-- $name: $(( $(date +%s) - t0 )) s (load average at start $l0)"
}

# The full run's arguments per program (after the output directory): shorter than the programs'
# own defaults, which are the longer studies (run by hand; the README says what each cut leaves
# out).
args_of() {
  case $1 in
    # chain1000 over 2 rotation periods instead of 20 (its gauss3 reference alone takes 11 min
    # over 20, the whole scene 100 min); the other scenes over 20
    bench_workprecision) echo "all 20,2" ;;
    # the long energy runs: 8 x 2.5e6 steps per step size instead of 8 x 1e7 (22 min)
    bench_stress) echo "all 2500000" ;;
    # windows and costs up to N = 200; N = 400 (the edges followed there, a dgeev of 1600 rows
    # at 200 s) left out
    bench_windows) echo "200" ;;
    *) echo "" ;;
  esac
}

export WHIRL="$build/whirl"
if [ "$mode" = quick ]; then
  step bench_peers_quick "$build/tests/bench_peers" "$out" quick
  step bench_scipy_quick /usr/bin/python3 tests/bench/bench_scipy.py "$out" "$build/whirl" quick
else
  for b in "$build"/tests/bench_*; do
    [ -x "$b" ] || continue
    name=$(basename "$b")
    if [ "$name" = bench_peers ]; then
      # the peers as in the quick run (the full sweeps, about 15 min more, by hand:
      # bench_peers out/bench full), MuJoCo's step at N = 1000, and ARKODE with projection
      # against whirl rk8 over 15 interleaved rounds (the ratio's spread)
      step bench_peers_quick "$b" "$out" quick
      step bench_peers_steps1000 "$b" "$out" steps1000
      step bench_peers_arkode "$b" "$out" arkode 15
      continue
    fi
    # shellcheck disable=SC2046 # the arguments are words
    step "$name" "$b" "$out" $(args_of "$name")
  done
  for s in tests/bench/bench_*.sh; do
    [ -f "$s" ] || continue
    step "$(basename "$s")" sh "$s" "$out"
  done
  step bench_scipy /usr/bin/python3 tests/bench/bench_scipy.py "$out" "$build/whirl"
  # figures from the CSVs (plots/*.gp), when gnuplot is installed
  if command -v gnuplot >/dev/null 2>&1; then
    for g in workprecision scaling; do
      step "plots/$g.gp" gnuplot -e "dir='$out'" "plots/$g.gp"
    done
  else
    echo "gnuplot not found: figures not drawn"
  fi
fi
echo
echo "Wall time per step ($out/bench_times.csv):"
awk -F, 'NR > 1 { printf "  %-28s %6d s  (load average at start %s)%s\n", $1, $2, $3, ($4 == 0 ? "" : "  FAILED") }' "$out/bench_times.csv"
echo
echo "Headline figures ($mode run, $(( $(date +%s) - start )) s; ratios are the peer's time over whirl's, within this run):"
if [ -f "$out/headline.csv" ]; then
  awk -F, '{ printf "  %-82s %10s  %-7s %s\n", $2, ($3 == "" ? "-" : $3), $4, $5 }' "$out/headline.csv"
else
  echo "  (none recorded)"
  status=1
fi
exit $status
