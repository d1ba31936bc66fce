#!/bin/sh
# Checks of the exact stability windows (run by scripts/bench.sh with the output directory as $1,
# after bench_windows, whose windows_N*.csv it reads):
#  1. perturbed runs just inside and just outside every closed window edge of modes 2 and 3 at
#     N = 25 and 50 (1% of the window's width away): inside the run grows (verdict unstable,
#     sim_growth within 5% of eig_growth), outside it stays within 100 times the perturbation
#     (windows_runs_N*.csv);
#  2. the stability maps of bench_stability.sh (step 0.01, the first-order form's eigenvalues),
#     when present: every map point of modes 2 and 3 is unstable exactly when it lies inside a
#     window (window edges from bench_windows);
#  3. the continuous chain's own windows (whirl windows without --links: the string
#     equations linearised and solved by collocation, no N-link chain) against every extrapolated
#     edge of windows_continuum.csv: each within its error estimate (windows_collocation.csv; an
#     edge without an estimate fails);
#  4. the figure windows_continuum.png: the edges against 1/N with their extrapolation and the
#     collocation's values.
out=${1:-out/bench}
WHIRL=${WHIRL:-build/whirl}
jobs=${BENCH_JOBS:-2} # perturbed runs at once (BENCH_JOBS=1 on a shared machine)
status=0

for n in 25 50; do
  csv="$out/windows_N$n.csv"
  [ -f "$csv" ] || { echo "no $csv (run bench_windows first)"; status=1; continue; }
  runs="$out/windows_runs_N$n.csv"
  echo "edge,side,omega,mode,links,eig_growth,sim_growth,max_deviation,verdict" >"$runs"
  start=$(date +%s)
  # "edge side omega mode": 1% of the width inside and outside each closed edge
  grep -v '^#' "$csv" | awk -F, 'NR > 1 {
      d = 0.01 * ($4 - $3); OFMT = "%.12g"
      if (!$5) { print $3, "outside", $3 - d, $1; print $3, "inside", $3 + d, $1 }
      if (!$6) { print $4, "inside", $4 - d, $1; print $4, "outside", $4 + d, $1 } }' |
  while read -r e side w k; do
    g=$("$WHIRL" stability --omega "$w" --mode "$k" --links $n --linear | grep -v '^[#o]' | cut -d, -f4)
    p=$(awk -v g="$g" -v w="$w" 'BEGIN { p = 150; if (g > 0) { q = 1.3 * (log(1e4) + 6) / g * w / (2 * 3.141592653589793) + 20; if (q > p) p = int(q) } print p }')
    echo "$e $side $w $k $p"
  done | xargs -P "$jobs" -L 1 sh -c \
    'echo "$0,$1,$("'"$WHIRL"'" stability --omega "$2" --mode "$3" --links '$n' --periods "$4" | grep -v "^[#o]")"' >>"$runs"
  echo "runs N = $n: $(( $(date +%s) - start )) s wall for $(($(wc -l <"$runs") - 1)) runs"
  awk -F, -v n=$n 'NR > 1 {
      if ($2 == "inside") { i++; e = $7 / $6 - 1; if (e < 0) e = -e; if (e > worst) worst = e
                            if (!($6 > 0 && $9 == "unstable" && e < 0.05)) { bad++; print "  inside " $3 " mode " $4 ": " $0 } }
      else { o++; if ($8 > dmax) dmax = $8
             if (!($6 == 0 && ($9 == "neutral (gyroscopic)" || $9 == "stable (minimum)") && $8 < 100)) { bad++; print "  outside " $3 " mode " $4 ": " $0 } } }
    END { printf "  N = %d: %d runs inside (unstable, worst |sim/eig - 1| = %.3g), %d outside (stable, largest deviation %.3g times the start), %d disagree\n", n, i, worst, o, dmax, bad
          exit (bad > 0) }' "$runs" || status=1
done

for n in 25 50 100; do
  map="$out/stability_map_N$n.csv"; csv="$out/windows_N$n.csv"
  [ -f "$map" ] && [ -f "$csv" ] || { echo "map N = $n: $map or $csv missing, not compared"; continue; }
  grep -v '^#' "$csv" | awk -F, 'NR > 1 { print $1, $3, $4 }' >"$out/windows_list_N$n.txt"
  grep -v '^#' "$map" | awk -F, -v n=$n -v list="$out/windows_list_N$n.txt" '
    BEGIN { while ((getline l < list) > 0) { split(l, f, " "); k++; m[k] = f[1]; a[k] = f[2]; b[k] = f[3] } }
    NR > 1 && ($2 == 2 || $2 == 3) {
      inside = 0; for (i = 1; i <= k; i++) if (m[i] == $2 && $1 >= a[i] && $1 <= b[i]) inside = 1
      total++; if (($4 > 0) != inside) { bad++; print "  map N = " n " omega " $1 " mode " $2 ": eig_growth " $4 ", inside " inside } }
    END { printf "  map N = %d: %d points of modes 2-3, %d disagree with the windows\n", n, total, bad; exit (bad > 0) }' || status=1
done

coll="$out/windows_collocation.csv"
if [ -f "$out/windows_continuum.csv" ]; then
  start=$(date +%s)
  if "$WHIRL" windows --omega-min 1 --omega-max 10 --modes 2,3 -o "$coll"; then
    echo "continuum windows by collocation, modes 2-3 over 1..10: $(( $(date +%s) - start )) s wall"
    # every extrapolated edge against the collocation's edge of the same mode and side nearest it
    grep -v '^#' "$coll" | awk -F, 'NR > 1 { print $1, "from", $3, $5; print $1, "to", $4, $6 }' \
      >"$out/windows_collocation_edges.txt"
    awk -F, -v list="$out/windows_collocation_edges.txt" '
      BEGIN { while ((getline l < list) > 0) { split(l, f, " "); if (f[4] == 0) { k++; m[k] = f[1]; side[k] = f[2]; e[k] = f[3] } } }
      NR > 1 && $10 != "" {
        best = -1; for (i = 1; i <= k; i++) if (m[i] == $1 && side[i] == $3) { d = e[i] - $10; if (d < 0) d = -d; if (best < 0 || d < best) { best = d; v = e[i] } }
        # an edge without an error estimate is a failure, not a pass
        ok = $11 != "" && best >= 0 && best <= $11 + 1e-8
        printf "  mode %d window %d %s: extrapolated %.9g +- %s (%s), collocation %.10g, difference %.2g%s\n", $1, $2, $3, $10, $11 == "" ? "?" : $11, $12, v, best, ok ? "" : ($11 == "" ? " (no error estimate)" : " (outside the error)")
        if (!ok) bad++ }
      END { exit (bad > 0) }' "$out/windows_continuum.csv" || status=1
  else
    status=1
  fi
fi

if command -v gnuplot >/dev/null 2>&1 && [ -f "$out/windows_continuum.csv" ]; then
  gnuplot -e "csv='$out/windows_continuum.csv'; coll='$coll'; out='$out/windows_continuum.png'" plots/windows.gp \
    && echo "figure: $out/windows_continuum.png" || status=1
fi
exit $status
