# Work-precision before and after the right-hand side in double (data/workprecision/
# rhs_before_after.csv: tests/bench/bench_workprecision.c's chain100 scene run with the library built
# before and after, one method at a time, rk8 and rk4): left, processor time against the final
# position error, one colour per method, before dashed, after solid; right, the right-hand sides against the error
# (the same curves before and after: the methods and their steps did not change, only the cost of
# an evaluation).
# usage: gnuplot -e "csv='data/workprecision/rhs_before_after.csv'; out='rhs.png'" plots/workprecision_rhs.gp
# optional: ylabel='...' (default "processor time [s]")
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("csv")) { csv = "data/workprecision/rhs_before_after.csv" }
if (!exists("out")) { out = "workprecision_rhs.png" }
if (!exists("ylabel")) { ylabel = "processor time [s]" }
set terminal @term size (1200) * px, (520) * px
set output out
skip = skip_of(csv)
methods = "rk8 rk4"
set multiplot layout 1, 2 title "N = 100, 3D, 20 rotation periods: before (long double recursions, dashed) and after (double, solid)"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [*:*] reverse
set xlabel "final position error max_i |x_i - x_{ref,i}| [L]"
set ylabel ylabel
set key left top
pick(who, m, col) = (strcol(1) eq who && strcol(2) eq m) ? column(col) : NaN
plot for [k = 1:words(methods)] csv skip skip using (pick("after", word(methods, k), 5)):(pick("after", word(methods, k), 6)) \
         with linespoints lt k title word(methods, k) . ", after", \
     for [k = 1:words(methods)] csv skip skip using (pick("before", word(methods, k), 5)):(pick("before", word(methods, k), 6)) \
         with linespoints lt k dt 2 pt 6 title word(methods, k) . ", before"
set ylabel "right-hand sides"
set key left top
plot for [k = 1:words(methods)] csv skip skip using (pick("after", word(methods, k), 5)):(pick("after", word(methods, k), 9)) \
         with linespoints lt k title word(methods, k) . ", after", \
     for [k = 1:words(methods)] csv skip skip using (pick("before", word(methods, k), 5)):(pick("before", word(methods, k), 9)) \
         with linespoints lt k dt 2 pt 6 title word(methods, k) . ", before"
unset multiplot
set output
