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
load system("dirname '".ARG0."'")."/style.gp"
# a branch's legend: its eps and side, from its "# driven:" line
branch_title(f) = sprintf("eps = %s %s, %s", meta(f, "eps"), u_len(f), \
    meta(f, "side") eq "1" ? "tip on the pivot's side" : "tip opposite the pivot")

if (exists("branch")) {
    if (!exists("out")) { out = word(branch, 1) . ".png" }
    f1 = word(branch, 1)
    set terminal @term size (900) * px, (760) * px
    set output out
    set multiplot layout 2, 1 margins 0.1, 0.97, 0.08, 0.92 spacing 0, 0.04 \
        title sprintf("Hand-swung chain, mode-%s branches (drag C = %s): folds as black dots", \
                      meta(f1, "mode"), meta(f1, "drag"))
    set key top left
    set grid
    unset xlabel
    set format x ""
    set ylabel "tip distance from the axis [".u_len(f1)."]"
    plot for [f in branch] f skip skip_of(f) using 1:4 with lines lw 2 title branch_title(f), \
         for [f in branch] f skip skip_of(f) using 1:($7 == 1 ? $4 : 1/0) with points pt 7 ps 1.2 lc rgb "black" notitle
    set xlabel "omega [".u_rate(f1)."]"
    set format x "%g"
    set ylabel "tip x (pivot at +eps) [".u_len(f1)."]"
    unset key
    plot for [f in branch] f skip skip_of(f) using 1:2 with lines lw 2, \
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
    ul = u_len(shape)
    eps = real(meta(shape, "eps"))
    set print $circle
    do for [k = 0:64] { print sprintf("%.6g,%.6g,0", eps * cos(2 * pi * k / 64), eps * sin(2 * pi * k / 64)) }
    set print
    set terminal @term size (1100) * px, (560) * px
    set output out
    set multiplot layout 1, 2 title sprintf("Hand-swung chain: mode %s, omega = %s %s, eps = %s %s, drag C = %s, C2 = %s (co-rotating frame)", \
        meta(shape, "mode"), meta(shape, "omega"), u_rate(shape), meta(shape, "eps"), ul, \
        meta(shape, "drag"), meta(shape, "drag_quadratic"))
    unset key
    set xlabel "x [".ul."]"; set ylabel "y [".ul."]"; set zlabel "z [".ul."]" rotate parallel
    set xrange [-rmax:rmax]; set yrange [-rmax:rmax]
    # round tick steps from the extent: two or three labels per axis, none colliding at the corners
    stats shape skip skip using 4 nooutput
    depth = -STATS_min > 0 ? -STATS_min : 1
    set xtics nice(rmax / 1.5); set ytics nice(rmax / 1.5); set ztics nice(depth / 2)
    set view 65, 30, 1.15
    set view equal xyz
    set ticslevel 0
    set title "true to scale; dashed: the rotation axis; orange: the pivot's circle"
    splot shape skip skip using 2:3:4 with lines lt 1, \
          shape skip skip using (0):(0):4 with lines dt 2 lc rgb "gray", \
          $circle using 1:2:3 with lines lc rgb "#e67e22"
    set title "from above (rotation counter-clockwise)"
    set size ratio -1
    set view map
    set xtics nice(rmax / 2.5); set ytics nice(rmax / 2.5)
    plot shape skip skip using 2:3 with lines lt 1, \
         shape skip skip every ::0::0 using 2:3 with points pt 7 ps 1.5 lc rgb "black", \
         $circle using 1:2 with lines lc rgb "#e67e22", \
         "+" using (0):(0) with points pt 2 ps 2 lc rgb "gray"
    unset multiplot
    set output
}
