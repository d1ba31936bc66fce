# Animates a trace (`whirl simulate` [output] trace, `whirl regime --trace`): one frame per block
# (the pivot, then every mass; columns x y z t, inertial frame). The view is true to scale: the
# same scale on all three axes (a planar trace, y = 0 throughout, is drawn in the x-z plane with
# equal axes). The rotation axis is drawn dashed, the pivot's circle (radius eps, from the
# trace's "# trace:" line) in orange, and every frame names the time, the rate, eps, the drag and
# the number of links with their units (from the "# units:" line).
# usage: gnuplot -e "trace='run.dat'; out='run.gif'" plots/animate.gp
# optional: step=K (every K-th block), delay=D (hundredths of a second per frame), width=W
#           (pixels), view='70,30' (gnuplot's set view), mp4='run.mp4' (also an MP4 movie, made
#           with ffmpeg from PNG frames; Debian's ffmpeg).
if (!exists("trace")) { print "usage: gnuplot -e \"trace='run.dat'; out='run.gif'\" plots/animate.gp"; exit status 1 }
load system("dirname '".ARG0."'")."/style.gp"
set datafile separator whitespace
if (!exists("out")) { out = trace . ".gif" }
if (!exists("step")) { step = 1 }
if (!exists("delay")) { delay = 4 }
if (!exists("width")) { width = 640 }
if (!exists("view")) { view = "70,30" }

max(a, b) = a > b ? a : b
omega = meta(trace, "omega"); eps_s = meta(trace, "eps"); links = meta(trace, "links")
drag = meta(trace, "drag"); drag2 = meta(trace, "drag_quadratic")
eps = eps_s eq "" ? 0 : real(eps_s)
ul = u_len(trace); ut = u_time(trace); ur = u_rate(trace)
info = sprintf("N = %s   omega = %s %s   eps = %s %s   drag C = %s, C2 = %s", links, omega, ur, eps_s, ul, drag, drag2)

# extent of the whole run, so that the axes stay fixed
stats trace using 1 nooutput
nblocks = STATS_blocks
xmin = STATS_min; xmax = STATS_max
stats trace using 2 nooutput
ymin = STATS_min; ymax = STATS_max
stats trace using 3 nooutput
zmin = STATS_min; zmax = STATS_max
R = 1.08 * max(max(max(abs(xmin), abs(xmax)), max(abs(ymin), abs(ymax))), eps)
R = R > 0 ? R : 0.1
ztop = max(zmax, 0) + 0.06 * (max(zmax, 0) - zmin)
zbot = zmin - 0.06 * (max(zmax, 0) - zmin)
planar = (ymin == 0 && ymax == 0)

unset key
set tmargin 4
set style line 11 lc rgb "#999999" dt 2 lw 1
set style line 12 lc rgb "#e67e22" lw 1.5
set samples 100
set xlabel "x [".ul."]"
if (planar) {
    set size ratio -1
    set xrange [-R:R]
    set yrange [zbot:ztop]
    set ylabel "z [".ul."]"
    set arrow 1 from 0, zbot to 0, ztop nohead ls 11
    if (eps > 0) { set arrow 2 from -eps, 0 to eps, 0 nohead ls 12 }
} else {
    set view @view, 0.72
    set view equal xyz
    set xrange [-R:R]
    set yrange [-R:R]
    set zrange [zbot:ztop]
    set xyplane at zbot
    set ylabel "y [".ul."]"
    set zlabel "z [".ul."]" rotate parallel
    set arrow 1 from 0, 0, zbot to 0, 0, ztop nohead ls 11
    # the pivot's circle, as data
    set print $circle
    do for [k = 0:64] { print sprintf("%.6g %.6g 0", eps * cos(2 * pi * k / 64), eps * sin(2 * pi * k / 64)) }
    set print
    set xtics R / 2 format "%.2g"
    set ytics R / 2 format "%.2g"
}
# one frame: block i, titled with the parameters and its time
if (planar) {
    draw = "stats [*:*][*:*] trace index i using 4 nooutput; set title sprintf('%s   t = %.2f %s', info, STATS_min, ut) font ',10'; plot trace index i using 1:3 with linespoints lt 1 pt 7 ps 0.5"
} else {
    draw = "stats [*:*][*:*] trace index i using 4 nooutput; set title sprintf('%s   t = %.2f %s', info, STATS_min, ut) font ',10'; splot trace index i using 1:2:3 with linespoints lt 1 pt 7 ps 0.4, $circle using 1:2:3 with lines ls 12"
}

height = planar ? width : int(1.15 * width)
set terminal gif animate delay delay size width, height font "DejaVu Sans,10"
set output out
do for [i = 0:nblocks - 1:step] { @draw }
set output
if (exists("mp4")) {
    dir = system("mktemp -d")
    set terminal @term size width, height
    k = 0
    do for [i = 0:nblocks - 1:step] {
        set output sprintf("%s/f%05d.png", dir, k)
        @draw
        k = k + 1
    }
    set output
    rc = system(sprintf("ffmpeg -loglevel error -y -framerate %g -i '%s/f%%05d.png' -pix_fmt yuv420p -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' '%s' && echo ok", 100.0 / delay, dir, mp4))
    system(sprintf("rm -r '%s'", dir))
    if (rc ne "ok") { print "animate.gp: ffmpeg failed for ".mp4; exit status 1 }
}
