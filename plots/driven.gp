# Figures of `whirl driven` (pivot driven on a circle of radius eps, air drag).
# A branch CSV (omega,tip_x,tip_y,tip_r,top_tension,nodes,fold): the tip's distance from the axis
# and its signed position along the pivot's direction against omega, folds marked.
#   usage: gnuplot -e "branch='br.csv'; out='br.png'" plots/driven.gp
#   several branches: branch='a.csv b.csv' (space-separated), drawn in one figure.
# A shape CSV (s,x,y,z,tension): a 3D view and the view from above (co-rotating frame; the
# rotation is counter-clockwise seen from above, so a trailing chain lies at y < 0).
#   usage: gnuplot -e "shape='shape.csv'; out='shape.png'" plots/driven.gp
if (!exists("branch") && !exists("shape")) {
    print "usage: gnuplot -e \"branch='br.csv'; out='br.png'\" plots/driven.gp"
    print "   or: gnuplot -e \"shape='shape.csv'; out='shape.png'\" plots/driven.gp"
    exit status 1
}
set datafile separator ","
# lines of comments and header before the data of a CSV
skip_of(f) = int(system(sprintf("grep -n -m 1 -v '^#' '%s' | cut -d: -f1", f)))

if (exists("branch")) {
    if (!exists("out")) { out = word(branch, 1) . ".png" }
    set terminal png size 900, 700
    set output out
    set multiplot layout 2, 1 margins 0.1, 0.97, 0.08, 0.97 spacing 0, 0.04
    set key top left noenhanced
    set grid
    unset xlabel
    set format x ""
    set ylabel "tip distance from the axis [L]"
    plot for [f in branch] f skip skip_of(f) using 1:4 with lines lw 1.5 title f, \
         for [f in branch] f skip skip_of(f) using 1:($7 == 1 ? $4 : 1/0) with points pt 7 ps 1.2 lc rgb "black" notitle
    set xlabel "omega [sqrt(g/L)]"
    set format x "%g"
    set ylabel "tip x (pivot at +eps) [L]"
    unset key
    plot for [f in branch] f skip skip_of(f) using 1:2 with lines lw 1.5, \
         for [f in branch] f skip skip_of(f) using 1:($7 == 1 ? $2 : 1/0) with points pt 7 ps 1.2 lc rgb "black"
    unset multiplot
    set output
}

if (exists("shape")) {
    if (!exists("out") || exists("branch")) { out = shape . ".png" }
    skip = skip_of(shape)
    stats shape skip skip using 2 nooutput
    rmax = 1.05 * (abs(STATS_min) > abs(STATS_max) ? abs(STATS_min) : abs(STATS_max))
    stats shape skip skip using 3 nooutput
    rmax = 1.05 * abs(STATS_min) > rmax ? 1.05 * abs(STATS_min) : rmax
    rmax = 1.05 * abs(STATS_max) > rmax ? 1.05 * abs(STATS_max) : rmax
    set terminal png size 1100, 520
    set output out
    set multiplot layout 1, 2
    unset key
    set xlabel "x"; set ylabel "y"; set zlabel "z"
    set xrange [-rmax:rmax]; set yrange [-rmax:rmax]
    set view 65, 30
    set ticslevel 0
    splot shape skip skip using 2:3:4 with lines lw 2, \
          shape skip skip using (0):(0):4 with lines dt 2 lc rgb "gray"
    set title "from above (rotation counter-clockwise)"
    set size ratio -1
    set grid
    plot shape skip skip using 2:3 with lines lw 2, \
         shape skip skip every ::0::0 using 2:3 with points pt 7 ps 1.5 lc rgb "black", \
         "+" using (0):(0) with points pt 2 ps 2 lc rgb "gray"
    unset multiplot
    set output
}
