# Plots any file whirl writes, whatever its name, by its header line:
#   s,r,z,tension               a steady shape (whirl shape, minimize): true to scale, with the axis
#   s,x,y,z,tension             a hand-swung shape (whirl driven --omega)       -> driven.gp
#   omega,mode,tip_r,...        branches (whirl sweep): tip radius and top tension against omega
#   omega,mode,links,eig_growth stability (whirl stability, a map)             -> stability_map.gp
#   mode,from,to,...            the stability atlas (whirl windows --atlas)    -> atlas.gp
#   mode,links,from,to,...      windows (whirl windows, with or without
#                               dissipation)                                      -> atlas.gp
#   omega,tip_x,tip_y,...       a hand-swung branch (whirl driven --omega-min)  -> driven.gp
#   index,omega,eps,state,...   a regime map (whirl regime)                     -> regime.gp
#   leg,omega,state,...         a hysteresis sweep (whirl regime --sweep)       -> regime.gp
#   curve,edge,omega,amplitude  a stability chart (whirl periodic --chart)      -> chart.gp
#   curve,event,omega,ellipticity  the ellipticity chart (--chart ellipse)      -> chart_ellipse.gp
#   t,...                       a run (whirl simulate)                          -> simulate.gp
#   x y z t blocks              a trace (whirl simulate, regime --trace)        -> animate.gp
# usage: gnuplot -e "file='my.csv'; out='my.png'" plots/plot.gp   (out: default FILE.png, .gif
#        for a trace; .svg or .pdf for vector output)
#        gnuplot -e "files='s2.csv s4.csv s6.csv'; out='shapes.png'" plots/plot.gp   (one figure)
if (!exists("file") && !exists("files")) { print "usage: gnuplot -e \"file='my.csv'; out='my.png'\" plots/plot.gp"; exit status 1 }
# files='a.csv b.csv': several files of one kind on one figure (shapes, branches); file: the first
if (!exists("files")) { files = file }
if (!exists("file")) { file = word(files, 1) }
here = system("dirname '".ARG0."'")
load here."/style.gp"
header = system(sprintf("grep -m 1 -v '^#' '%s' | grep -v '^$' | head -1", file))
kind = strstrt(header, ",") == 0 ? "trace" : \
       header eq "s,r,z,tension" ? "shape" : \
       header eq "s,x,y,z,tension" ? "driven_shape" : \
       strstrt(header, "omega,mode,links,eig_growth") == 1 ? "stability" : \
       strstrt(header, "omega,mode,tip_r") == 1 ? "branches" : \
       strstrt(header, "omega,tip_x,tip_y") == 1 ? "driven_branch" : \
       strstrt(header, "mode,from,to,") == 1 ? "windows" : \
       strstrt(header, "mode,links,from,to,") == 1 ? "windows" : \
       strstrt(header, "index,omega,eps,state") == 1 ? "regime_map" : \
       strstrt(header, "leg,omega,state") == 1 ? "regime_sweep" : \
       strstrt(header, "curve,edge,omega,amplitude") == 1 ? "chart" : \
       strstrt(header, "curve,event,omega,ellipticity") == 1 ? "chart_ellipse" : \
       strstrt(header, "t,") == 1 ? "run" : "unknown"
if (kind eq "unknown") { print "plot.gp: ".file.": unknown header '".header."'"; exit status 1 }
if (!exists("out")) { out = file . (kind eq "trace" ? ".gif" : ".png") }

if (kind eq "trace") { trace = file; load here."/animate.gp" }
if (kind eq "driven_shape") { shape = file; load here."/driven.gp" }
if (kind eq "driven_branch") { branch = file; load here."/driven.gp" }
if (kind eq "stability") { files = file; load here."/stability_map.gp" }
if (kind eq "windows") { csv = file; load here."/atlas.gp" }
if (kind eq "regime_map") { map = file; load here."/regime.gp" }
if (kind eq "regime_sweep") { sweep = file; load here."/regime.gp" }
if (kind eq "run") { csv = file; load here."/simulate.gp" }
if (kind eq "chart") { csv = file; load here."/chart.gp" }
if (kind eq "chart_ellipse") { csv = file; load here."/chart_ellipse.gp" }
if (kind eq "shape") {
    # every file of files (or file alone) on one pair of equal axes, true to scale: the canvas
    # takes the shapes' aspect ratio (plot box at most 720 x 720 px, at least 260 px across),
    # the pivot a black dot, the rotation axis dashed, each curve "mode K, RATE" as its writer
    # gave the rate
    ul = u_len(file)
    rmin = 0; rmax = 0; zmin = 0
    do for [f in files] {
        stats [*:*][*:*] f skip skip_of(f) using 2:3 nooutput
        rmin = STATS_min_x < rmin ? STATS_min_x : rmin
        rmax = STATS_max_x > rmax ? STATS_max_x : rmax
        zmin = STATS_min_y < zmin ? STATS_min_y : zmin
    }
    span = (rmax - rmin) > -zmin ? (rmax - rmin) : -zmin
    pad = 0.04 * span
    x0 = rmin - pad; x1 = rmax + pad; y0 = zmin - pad; y1 = pad
    # a narrow figure widened about the axis to 0.35 of its height (room for the key and ticks)
    if ((x1 - x0) < 0.35 * (y1 - y0)) { w = 0.35 * (y1 - y0); c = 0.5 * (x0 + x1); x0 = c - w / 2; x1 = c + w / 2 }
    scale = 720.0 / ((x1 - x0) > (y1 - y0) ? (x1 - x0) : (y1 - y0))
    # the margins, the key and the labels in pixels of text: fs times larger to present
    # (style.gp), the box as it is
    pw = (x1 - x0) * scale; ph = (y1 - y0) * scale
    if (ph < 260) { ph = 260.0; c = 0.5 * (y0 + y1); y0 = c - 130 / scale; y1 = c + 130 / scale }
    # the key to the right of the box: as wide as its longest title (7 px a character at 11 pt)
    keylen = 0
    do for [f in files] { t = strlen(sprintf("mode %s, %s", meta(f, "mode"), rate_label(f))); keylen = t > keylen ? t : keylen }
    # the key inside the box where no curve runs (a corner or the middle of a side, checked on
    # every point of every file, 8.5 px a character and 18 px a line, 10 px from the frame),
    # else to the right of the box, or below it when the box is narrow (a tall figure)
    nfiles = words(files)
    kw = fs * (80 + 8.5 * keylen) / scale; kh = fs * (10 + 18 * nfiles) / scale; gap = 10 / scale
    inside = 0
    do for [c = 1:5] {
        if (!inside) {
            # candidate c: right middle, bottom right, top right, bottom left, top left
            kx = c <= 3 ? x1 - gap - kw : x0 + gap
            ky = c == 1 ? 0.5 * (y0 + y1) - kh / 2 : (c == 2 || c == 4) ? y0 + gap : y1 - gap - kh
            hits = 0
            do for [f in files] {
                stats [*:*][*:*] f skip skip_of(f) using (($2 > kx - gap && $2 < kx + kw + gap && $3 > ky - gap && $3 < ky + kh + gap) ? 1 : 0) nooutput
                hits = hits + STATS_sum
            }
            # the pivot and the axis label are drawn too
            if (kx - gap < 0 && kx + kw + gap > 0) { hits = hits + 1 }
            if (hits == 0 && kw + 2 * gap < x1 - x0) { inside = c }
        }
    }
    below = !inside && pw < 420
    # (the top margin holds the title and, above the axis, the label of the pivot and the axis)
    lm = 80 * fs; rm = fs * (inside || below ? 40 : 110 + 8.5 * keylen); tm = 70 * fs; bm = fs * (below ? 88 + 18 * nfiles : 60)
    cw = pw + lm + rm; ch = ph + tm + bm; @canvas
    set output out
    set lmargin at screen lm / (pw + lm + rm); set rmargin at screen (lm + pw) / (pw + lm + rm)
    set bmargin at screen bm / (ph + tm + bm); set tmargin at screen (bm + ph) / (ph + tm + bm)
    set xrange [x0:x1]; set yrange [y0:y1]
    # a labelled tick every 90 px across and 60 px down at most, on round values
    set xtics nice((x1 - x0) * 90 / pw); set ytics nice((y1 - y0) * 60 / ph)
    set size ratio -1
    L = meta(file, "L"); M = meta(file, "M")
    set title (physical(file) ? sprintf("Steady shapes of a chain, L = %s m, M = %s kg", L, M) : \
               "Steady shapes of a chain (L = M = g = 1)") noenhanced offset 0, 1.3
    set xlabel "r, distance from the rotation axis [".ul."]"
    set ylabel "z, height (pivot at 0) [".ul."]"
    if (inside) { set key at first kx, first ky + kh left top Left reverse box opaque samplen 2 spacing 1.2 noenhanced } \
    else { if (below) { set key at screen 10.0 / (pw + lm + rm), (bm - 62 * fs) / (ph + tm + bm) left top Left reverse box samplen 2 spacing 1.2 noenhanced } \
    else { set key at screen (lm + pw + 12 * fs) / (pw + lm + rm), (bm + ph) / (ph + tm + bm) left top Left reverse box samplen 2 spacing 1.2 noenhanced } }
    set arrow 1 from 0, y0 to 0, y1 nohead dt 2 lc rgb "#666666"
    # the label above the box, clear of every curve
    # (centred on the axis, or from it inwards when half of it, 7 px a character, would pass the
    # box's edge)
    axis_text = "pivot (dot) on the rotation axis (dashed)"
    half = 3.5 * fs * strlen(axis_text)
    just = -x0 * scale < half ? "left" : x1 * scale < half ? "right" : "center"
    set label 1 axis_text at 0, y1 center offset 0, 0.8 textcolor rgb "#444444"
    if (just eq "left") { set label 1 left offset -0.5, 0.8 }
    if (just eq "right") { set label 1 right offset 0.5, 0.8 }
    plot for [f in files] f skip skip_of(f) using 2:3 with lines lw 2.5 \
           title sprintf("mode %s, %s", meta(f, "mode"), rate_label(f)), \
         '+' using (0):(0) every ::0::0 with points pt 7 ps 1.4 lc rgb "black" notitle
    set output
}
if (kind eq "branches") {
    # tip radius and pivot tension against the rate, a curve per mode in the file: the modes
    # read once (one pass of the file per mode drawn); the title names the file (name: the
    # user's file, as whirl plot gives it)
    skip = skip_of(file)
    modes = system(sprintf("awk -F, 'NR > %d && !seen[$2]++ { print $2 }' '%s' | sort -n | tr '\\n' ' '", skip, file))
    if (!exists("name")) { name = system(sprintf("basename '%s'", file)) }
    cw = 1200; ch = 540; @canvas
    set output out
    set multiplot layout 1, 2 title "Branches of steady shapes: ".name noenhanced
    # the key above the two panels, in one row (clear of the curves)
    set tmargin 4.5
    set key horizontal center bottom at screen 0.5, graph 1.04 reverse Left samplen 2 width 2 noenhanced
    set xlabel "omega [".u_rate(file)."]"
    set ylabel "tip radius [".u_len(file)."]"
    plot for [m in modes] file skip skip using 1:(int($2) == int(m) ? $3 : NaN) with lines lt int(m) title "mode ".m
    unset key
    set ylabel "tension at the pivot [".u_force(file)."]"
    plot for [m in modes] file skip skip using 1:(int($2) == int(m) ? $5 : NaN) with lines lt int(m) notitle
    unset multiplot
    set output
}
