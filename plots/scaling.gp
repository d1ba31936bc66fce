# Scaling figures of tests/bench/bench_scaling.c, from dir/scaling.csv and dir/scaling_tension.csv:
# left, ns per right-hand side and per step against N (log-log, with a line of slope 1);
# right, the relative round-off of the tensions against N (whirl against plain double Thomas
# elimination), written to dir/scaling.png.
# usage: gnuplot -e "dir='out/bench'" plots/scaling.gp
if (!exists("dir")) { dir = "out/bench" }
set datafile separator ","
set terminal png size 1200, 520
set output dir . "/scaling.png"
set multiplot layout 1, 2
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set grid
set key left top noenhanced
set xlabel "N (links, 3D)"
set ylabel "ns"
set title "cost per right-hand side and per step"
csv = dir . "/scaling.csv"
plot csv skip 2 using 1:2 with linespoints lw 2 title "rhs", \
     csv skip 2 using 1:3 with linespoints lw 2 title "rhs, all forces", \
     csv skip 2 using 1:4 with linespoints lw 2 title "rhs, seed formulation", \
     csv skip 2 using 1:5 with linespoints lw 2 title "rk4 step", \
     csv skip 2 using 1:6 with linespoints lw 2 title "gauss2 step", \
     [10:1e5] 50 * x with lines dt 2 lc "black" title "50 ns x N"
set title "tension round-off"
set ylabel "max_i |T_i / T_{ref,i} - 1|"
set key left top noenhanced font ",9"
ten = dir . "/scaling_tension.csv"
# columns: n, then whirl and plain double for the hanging, smooth and mode-2 states (0 = exact,
# drawn at 1e-17)
states = "hanging smooth mode2"
fl(v) = v > 0 ? v : (v == 0 ? 1e-17 : NaN)
plot for [k = 1:3] ten skip 2 using 1:(fl(column(2 * k))) \
         with linespoints lw 2 pt k lc k title "whirl, " . word(states, k), \
     for [k = 1:3] ten skip 2 using 1:(fl(column(2 * k + 1))) \
         with linespoints lw 1 dt 2 pt k lc k title "plain double Thomas, " . word(states, k), \
     1e-12 with lines lc "black" dt 3 title "1e-12 (target at 10^5)"
unset multiplot
set output
