# Work-precision diagrams of tests/bench/bench_workprecision.c: wall time against the final position
# error, log-log, one curve per method (whirl's solid, GSL's dashed, the seed formulation's
# dotted), one PNG per scene found in dir (workprecision_SCENE.csv -> workprecision_SCENE.png).
# usage: gnuplot -e "dir='out/bench'" plots/workprecision.gp
if (!exists("dir")) { dir = "out/bench" }
set datafile separator ","
set terminal png size 900, 620
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [*:*] reverse
set xlabel "final position error max_i |x_i - x_{ref,i}| [L]"
set ylabel "wall time [s]"
set key outside right top noenhanced
set grid
methods = "gauss2 gauss3 rk4 rk8 gsl-rk8pd gsl-rkf45 gsl-rk4 gsl-msadams gsl-msbdf gsl-rk4imp seed-gauss2 seed-gsl-rk8pd"
dashes = "1 1 1 1 2 2 2 2 2 2 3 3"
colors = "#1f77b4 #d62728 #2ca02c #000080 #ff7f0e #9467bd #8c564b #bcbd22 #e377c2 #7f7f7f #000000 #17becf"
do for [scene in "double_pendulum chain10 chain100 chain1000"] {
    csv = dir . "/workprecision_" . scene . ".csv"
    if (system(sprintf("test -f '%s' && echo 1 || echo 0", csv)) eq "1") {
        set output dir . "/workprecision_" . scene . ".png"
        info = system(sprintf("grep -m 1 '^#' '%s' | cut -c3-", csv))
        set title info noenhanced font ",10"
        plot for [k = 1:words(methods)] csv skip 4 \
            using (strcol(1) eq word(methods, k) && $4 > 0 ? $4 : NaN):5 \
            with linespoints lw 2 pt k dt int(word(dashes, k)) lc rgb word(colors, k) \
            title word(methods, k)
        set output
    }
}
