# Plots any file whirl writes, whatever its name, by its header line:
#   s,r,z,tension               a steady shape (whirl shape, minimize): true to scale, with the axis
#   s,x,y,z,tension             a hand-swung shape (whirl driven --omega)       -> driven.gp
#   omega,mode,tip_r,...        branches (whirl sweep): tip radius and top tension against omega
#   omega,mode,links,eig_growth stability (whirl stability, a map)             -> stability_map.gp
#   omega,tip_x,tip_y,...       a hand-swung branch (whirl driven --omega-min)  -> driven.gp
#   index,omega,eps,state,...   a regime map (whirl regime)                     -> regime.gp
#   leg,omega,state,...         a hysteresis sweep (whirl regime --sweep)       -> regime.gp
#   t,...                       a run (whirl simulate)                          -> simulate.gp
#   x y z t blocks              a trace (whirl simulate, regime --trace)        -> animate.gp
# usage: gnuplot -e "file='my.csv'; out='my.png'" plots/plot.gp   (out: default FILE.png, .gif
#        for a trace)
if (!exists("file")) { print "usage: gnuplot -e \"file='my.csv'; out='my.png'\" plots/plot.gp"; exit status 1 }
here = system("dirname '".ARG0."'")
load here."/style.gp"
header = system(sprintf("grep -m 1 -v '^#' '%s' | grep -v '^$' | head -1", file))
kind = strstrt(header, ",") == 0 ? "trace" : \
       header eq "s,r,z,tension" ? "shape" : \
       header eq "s,x,y,z,tension" ? "driven_shape" : \
       strstrt(header, "omega,mode,links,eig_growth") == 1 ? "stability" : \
       strstrt(header, "omega,mode,tip_r") == 1 ? "branches" : \
       strstrt(header, "omega,tip_x,tip_y") == 1 ? "driven_branch" : \
       strstrt(header, "index,omega,eps,state") == 1 ? "regime_map" : \
       strstrt(header, "leg,omega,state") == 1 ? "regime_sweep" : \
       strstrt(header, "t,") == 1 ? "run" : "unknown"
if (kind eq "unknown") { print "plot.gp: ".file.": unknown header '".header."'"; exit status 1 }
if (!exists("out")) { out = file . (kind eq "trace" ? ".gif" : ".png") }

if (kind eq "trace") { trace = file; load here."/animate.gp" }
if (kind eq "driven_shape") { shape = file; load here."/driven.gp" }
if (kind eq "driven_branch") { branch = file; load here."/driven.gp" }
if (kind eq "stability") { files = file; load here."/stability_map.gp" }
if (kind eq "regime_map") { map = file; load here."/regime.gp" }
if (kind eq "regime_sweep") { sweep = file; load here."/regime.gp" }
if (kind eq "run") { csv = file; load here."/simulate.gp" }
if (kind eq "shape") {
    ul = u_len(file)
    set terminal @term size 640, 760
    set output out
    set title sprintf("%s: omega = %s %s, mode %s", system(sprintf("basename '%s'", file)), \
                      meta(file, "omega"), u_rate(file), meta(file, "mode")) noenhanced
    set size ratio -1
    set xlabel "r, distance from the axis [".ul."]"
    set ylabel "z [".ul."]"
    unset key
    stats [*:*][*:*] file skip skip_of(file) using 2:3 nooutput
    set arrow 1 from 0, STATS_min_y to 0, 0 nohead dt 2 lc rgb "#999999"
    plot file skip skip_of(file) using 2:3 with lines lt 1, \
         '' skip skip_of(file) every ::0::0 using 2:3 with points pt 7 ps 1.2 lc rgb "black"
    set output
}
if (kind eq "branches") {
    set terminal @term size 1200, 500
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
