#!/bin/sh
# Stability study (long; run by scripts/bench.sh with the output directory as $1):
#  1. the stability map: eig_growth against omega (1..10, step 0.01) for modes 1-3 at N = 25
#     and 50 (stability_map_N*.csv, stability_map.png) and the instability windows found (N = 100
#     too in make study);
#  2. the perturbed runs against the linear analysis at N = 25 and 50 on a coarse grid of rates
#     plus the rate of largest growth in every window (stability_runs_N*.csv): where
#     eig_growth > 0.01, |sim_growth / eig_growth - 1| < 5%; where eig_growth = 0, max_deviation
#     < 100. Unstable points run long enough for the fit: P = (ln 1e4 + 6) / eig_growth periods
#     at least (the run stops early once settled); the others 100 periods;
#  3. one traced run (N = 25, omega 9, mode 2): stability_trace.csv, stability_deviation.png.
out=${1:-out/bench}
WHIRL=${WHIRL:-build/whirl}
jobs=${BENCH_JOBS:-2} # perturbed runs at once (BENCH_JOBS=1 on a shared machine)
mkdir -p "$out"
status=0

# the maps at N = 25 and 50 (the one at N = 100, half an hour, is in make study)
STABILITY_LINKS="25 50" WHIRL="$WHIRL" sh scripts/study.sh stability "$out" || exit 1

# one run traced: deviation against t with the predicted growth (plots/deviation.gp)
"$WHIRL" stability --omega 9 --mode 2 --links 25 --periods 1000 --trace "$out/stability_trace.csv" \
  -o "$out/stability_trace_row.csv" && grep -v '^[#o]' "$out/stability_trace_row.csv"
if command -v gnuplot >/dev/null; then
  gnuplot -e "csv='$out/stability_trace.csv'; out='$out/stability_deviation.png'" plots/deviation.gp \
    2>/dev/null && echo "figure: $out/stability_deviation.png"
fi

for n in 25 50; do
  step=$([ $n -eq 25 ] && echo 0.5 || echo 1)
  # points: "omega mode eig_growth" on the coarse grid and at the maxima of the windows (> 0.01)
  grep -v '^#' "$out/stability_map_N$n.csv" | awk -F, -v step=$step '
    NR == 1 { next }
    { k = ($1 - 1) / step; if (k - int(k + 0.5) < 1e-9 && int(k + 0.5) - k < 1e-9 && $1 >= 1.5) print $1, $2, $4 }
    $2 != mode { if (gmax > 0.01) print at, mode, gmax; mode = $2; gmax = 0 }
    $4 > gmax { gmax = $4; at = $1 }
    $4 == 0 && gmax > 0 { if (gmax > 0.01) print at, mode, gmax; gmax = 0 }
    END { if (gmax > 0.01) print at, mode, gmax }' | sort -u -k2,2n -k1,1g >"$out/stability_points_N$n.txt"
  csv="$out/stability_runs_N$n.csv"
  echo "omega,mode,links,eig_growth,sim_growth,max_deviation,verdict,index" >"$csv"
  start=$(date +%s)
  while read -r w k g; do
    p=$(awk -v g="$g" -v w="$w" 'BEGIN { p = 100; if (g > 0) { q = (log(1e4) + 6) / g * w / (2 * 3.141592653589793) + 20; if (q > p) p = int(q) } print p }')
    echo "$w $k $p"
  done <"$out/stability_points_N$n.txt" | xargs -P "$jobs" -L 1 sh -c \
    '"$0" stability --omega "$1" --mode "$2" --links '$n' --periods "$3" | grep -v "^[#o]"' "$WHIRL" >>"$csv" || status=1
  echo "runs N = $n: $(( $(date +%s) - start )) s wall for $(($(wc -l <"$csv") - 1)) runs"
  awk -F, -v n=$n 'NR > 1 {
      if ($4 > 0.01) { u++; e = $5 / $4 - 1; if (e < 0) e = -e; if (e > worst) { worst = e; wat = $1 " mode " $2 } if (e >= 0.05) bad_u++ }
      else if ($4 == 0) { s++; if ($6 > dmax) { dmax = $6; dat = $1 " mode " $2 } if ($6 >= 100) bad_s++ }
      else other++ }
    END { printf "  N = %d: %d unstable points (eig > 0.01): worst |sim/eig - 1| = %.3g (omega %s), %d beyond 5%%\n", n, u, worst, wat, bad_u
          printf "  N = %d: %d neutral points (eig = 0): largest max_deviation = %.3g (omega %s), %d at or beyond 100\n", n, s, dmax, dat, bad_s
          if (other) printf "  N = %d: %d points with 0 < eig_growth <= 0.01 (not checked)\n", n, other
          exit (bad_u + bad_s > 0) }' "$csv" || status=1
done
exit $status
