# Time series of a `whirl simulate` CSV: every column against t, one panel each (energy, jacobi
# and lz as their change from the first row; constraint and deviation on a logarithmic scale).
# usage: gnuplot -e "csv='run.csv'; out='run.png'" plots/simulate.gp
if (!exists("csv")) { print "usage: gnuplot -e \"csv='run.csv'; out='run.png'\" plots/simulate.gp"; exit status 1 }
if (!exists("out")) out = csv . ".png"
set datafile separator ","
header = system(sprintf("grep -m 1 -v '^#' '%s'", csv))
skip = int(system(sprintf("grep -n -m 1 -v '^#' '%s' | cut -d: -f1", csv)))
stats csv skip skip nooutput
ncol = STATS_columns
set terminal png size 800, 180 * (ncol - 1) + 40
set output out
set multiplot layout ncol - 1, 1 margins 0.14, 0.97, 0.06, 0.98 spacing 0, 0.02
unset key
do for [c = 2:ncol] {
    name = system(sprintf("echo '%s' | cut -d, -f%d", header, c))
    if (c == ncol) { set xlabel "t"; set format x "%g" } else { unset xlabel; set format x "" }
    if (name eq "energy" || name eq "jacobi" || name eq "lz") {
        # a conserved quantity: its change from the first row, which is what measures the run
        stats csv skip skip using c every ::0::0 nooutput
        first = STATS_min
        unset logscale y
        set format y "%.1e"
        set ylabel sprintf("%s - %s(0)", name, name) noenhanced
        plot csv skip skip using 1:(column(c) - first) with lines lw 1.5
    } else {
        if (name eq "constraint" || name eq "deviation") { set logscale y } else { unset logscale y }
        set format y "%g"
        set ylabel name noenhanced
        plot csv skip skip using 1:c with lines lw 1.5
    }
}
unset multiplot
set output
