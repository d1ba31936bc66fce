# Animates the trace file of `whirl simulate` ([output] trace) to a GIF: one frame per block
# (the pivot, then every mass; columns x y z t; blocks separated by two blank lines).
# usage: gnuplot -e "trace='run.dat'; out='run.gif'" plots/animate.gp
# optional: step=K (every K-th block), delay=D (hundredths of a second per frame),
#           width=W (pixels). A planar trace (y = 0 throughout) is drawn in the x-z plane.
# Needs gnuplot's gif terminal (libgd), present in Debian's gnuplot-nox.
if (!exists("trace")) { print "usage: gnuplot -e \"trace='run.dat'; out='run.gif'\" plots/animate.gp"; exit status 1 }
if (!exists("out")) out = trace . ".gif"
if (!exists("step")) step = 1
if (!exists("delay")) delay = 4
if (!exists("width")) width = 640

max(a, b) = a > b ? a : b

# extent of the whole run, so that the axes stay fixed
stats trace using 1 nooutput
nblocks = STATS_blocks
xmin = STATS_min; xmax = STATS_max
stats trace using 2 nooutput
ymin = STATS_min; ymax = STATS_max
stats trace using 3 nooutput
zmin = STATS_min; zmax = STATS_max
rmax = 1.05 * max(max(abs(xmin), abs(xmax)), max(abs(ymin), abs(ymax)))
rmax = rmax > 0 ? rmax : 1
ztop = zmax > 0 ? 1.05 * zmax : 0.05 * (zmax - zmin) + 0.05
zbot = zmin - 0.05 * (ztop - zmin)
planar = (ymin == 0 && ymax == 0)

set terminal gif animate delay delay size width, width
set output out
unset key
set xrange [-rmax:rmax]
set xlabel "x"
if (planar) {
    set yrange [zbot:ztop]
    set ylabel "z"
    set size ratio -1
    do for [i = 0:nblocks - 1:step] {
        plot trace index i using 1:3 with linespoints lw 2 pt 7 ps 0.6, \
             '' index i every ::0::0 using (-0.95 * rmax):(ztop - 0.05 * (ztop - zbot)):(sprintf("t = %.2f", $4)) with labels left
    }
} else {
    set yrange [-rmax:rmax]
    set zrange [zbot:ztop]
    set ylabel "y"
    set zlabel "z"
    set view 70, 30
    set xyplane at zbot
    do for [i = 0:nblocks - 1:step] {
        splot trace index i using 1:2:3 with linespoints lw 2 pt 7 ps 0.4, \
              '' index i every ::0::0 using (-rmax):(-rmax):(ztop):(sprintf("t = %.2f", $4)) with labels left
    }
}
set output
