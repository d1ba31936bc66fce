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
    pw = (x1 - x0) * scale; ph = (y1 - y0) * scale
    if (ph < 260) { ph = 260; c = 0.5 * (y0 + y1); y0 = c - 130 / scale; y1 = c + 130 / scale }
    # the key to the right of the box: as wide as its longest title (7 px a character at 11 pt)
    keylen = 0
    do for [f in files] { t = strlen(sprintf("mode %s, %s", meta(f, "mode"), rate_label(f))); keylen = t > keylen ? t : keylen }
    # the key inside the box where no curve runs (a corner or the middle of a side, checked on
    # every point of every file, 8 px a character and 18 px a line, 10 px from the frame),
    # else to the right of the box, or below it when the box is narrow (a tall figure)
    nfiles = words(files)
    kw = (60 + 8 * keylen) / scale; kh = (10 + 18 * nfiles) / scale; gap = 10 / scale
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
    lm = 80; rm = inside || below ? 40 : 100 + 8 * keylen; tm = 50; bm = below ? 88 + 18 * nfiles : 60
    set terminal @term size (pw + lm + rm) * px, (ph + tm + bm) * px
    set output out
    set lmargin at screen lm / (pw + lm + rm); set rmargin at screen (lm + pw) / (pw + lm + rm)
    set bmargin at screen bm / (ph + tm + bm); set tmargin at screen (bm + ph) / (ph + tm + bm)
    set xrange [x0:x1]; set yrange [y0:y1]
    # a labelled tick every 90 px across and 60 px down at most, on round values
    set xtics nice((x1 - x0) * 90 / pw); set ytics nice((y1 - y0) * 60 / ph)
    set size ratio -1
    L = meta(file, "L"); M = meta(file, "M")
    set title (physical(file) ? sprintf("Steady shapes of a chain, L = %s m, M = %s kg", L, M) : \
               "Steady shapes of a chain (L = M = g = 1)") noenhanced
    set xlabel "r, distance from the rotation axis [".ul."]"
    set ylabel "z, height (pivot at 0) [".ul."]"
    if (inside) { set key at first kx, first ky + kh left top Left reverse box opaque samplen 2 spacing 1.2 noenhanced } \
    else { if (below) { set key at screen 10.0 / (pw + lm + rm), (bm - 62) / (ph + tm + bm) left top Left reverse box samplen 2 spacing 1.2 noenhanced } \
    else { set key at screen (lm + pw + 12) / (pw + lm + rm), (bm + ph) / (ph + tm + bm) left top Left reverse box samplen 2 spacing 1.2 noenhanced } }
    set arrow 1 from 0, y0 to 0, y1 nohead dt 2 lc rgb "#666666"
    set label 1 "rotation axis" at 0, y0 rotate by 90 offset -1, 0.6 left textcolor rgb "#666666"
    set label 2 "pivot" at 0, 0 offset 0.8, -0.8 left
    plot for [f in files] f skip skip_of(f) using 2:3 with lines lw 2.5 \
           title sprintf("mode %s, %s", meta(f, "mode"), rate_label(f)), \
         '+' using (0):(0) every ::0::0 with points pt 7 ps 1.4 lc rgb "black" notitle
    set output
}
if (kind eq "branches") {
    set terminal @term size (1200) * px, (500) * px
    set output out
    set multiplot layout 1, 2 title system(sprintf("basename '%s'", file))
    set xlabel "omega [".u_rate(file)."]"
    set key top left
    set ylabel "tip radius [".u_len(file)."]"
    plot for [k = 1:64] file skip skip_of(file) using 1:($2 == k ? $3 : NaN) with lines \
         title (system(sprintf("grep -v '^#' '%s' | cut -d, -f2 | grep -qx %d && echo y", file, k)) eq "y" ? sprintf("mode %d", k) : "")
    set ylabel "tension at the pivot [".u_force(file)."]"
    plot for [k = 1:64] file skip skip_of(file) using 1:($2 == k ? $5 : NaN) with lines notitle
    unset multiplot
    set output
}
