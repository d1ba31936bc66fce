# Window edges of modes 2 and 3 against 1/N, with their continuum values (1/N -> 0, Richardson
# extrapolation) as open circles with error bars (windows_continuum.csv of tests/bench/bench_windows.c:
# mode,window,edge,N25,N50,N100,N200,N400,order,continuum,error), and with coll='FILE' the
# continuous chain's windows by collocation (whirl windows without --links) as crosses.
# usage: gnuplot -e "csv='windows_continuum.csv'; coll='windows_collocation.csv'; out='windows_continuum.png'" plots/windows.gp
if (!exists("csv")) { print "usage: gnuplot -e \"csv='windows_continuum.csv'; out='w.png'\" plots/windows.gp"; exit status 1 }
if (!exists("out")) out = "windows_continuum.png"
set datafile separator ","
set terminal png size 900, 700
set output out
set multiplot layout 1, 2 margins 0.09, 0.98, 0.1, 0.93 spacing 0.08, 0
set grid
set xlabel "1 / N"
set xrange [-0.002:0.042]
# one line per edge: (1/N, edge) for N = 25, 50, 100, 200, 400
lines(k) = sprintf("< awk -F, -v k=%d 'NR > 1 && $1 == k { split(\"25 50 100 200 400\", n, \" \"); for (i = 4; i <= 8; i++) if ($i != \"\") print 1 / n[i - 3] \",\" $i; print \"\"; print \"\" }' '%s'", k, csv)
have_coll = exists("coll")
do for [k = 2:3] {
    set title sprintf("mode %d: window edges", k)
    set ylabel "omega [sqrt(g/L)]"
    if (have_coll) {
        plot lines(k) using 1:2 with linespoints pt 7 ps 0.8 lc rgb "#1f77b4" title "N-link chain", \
             csv every ::1 using (0):(($1 == k) ? $10 : NaN):11 with yerrorbars pt 6 ps 1.5 lc rgb "#d62728" title "continuum (extrapolated)", \
             coll every ::1 using (0):(($1 == k) ? $3 : NaN) with points pt 2 ps 2 lc rgb "#2ca02c" title "continuum (collocation)", \
             coll every ::1 using (0):(($1 == k && $6 == 0) ? $4 : NaN) with points pt 2 ps 2 lc rgb "#2ca02c" notitle
    } else {
        plot lines(k) using 1:2 with linespoints pt 7 ps 0.8 lc rgb "#1f77b4" title "N-link chain", \
             csv every ::1 using (0):(($1 == k) ? $10 : NaN):11 with yerrorbars pt 6 ps 1.5 lc rgb "#d62728" title "continuum (extrapolated)"
    }
}
unset multiplot
set output
