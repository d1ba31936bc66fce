# The ellipticity chart of the hand-swung chain (whirl periodic --chart ellipse): per rate omega,
# the ellipticity e_crit at which the circle drive's steady shape (as a periodic motion, the
# pivot on the ellipse of semi-axes a and a (1 - e)) is lost, one line per curve (the CSV's
# blocks, a blank line between curves), each point marked by how it is lost: a torus (two pairs
# of multipliers meet on the unit circle), a period doubling (-1), a fold or branch point (+1);
# "none": the shape survives up to e_max (a triangle at e_max). The points on e = 0 end the
# curves where the circle's shape itself changes stability. Rates in rad/s for a file in SI units.
# usage: gnuplot -e "csv='ellipse.csv'; out='ellipse.png'" plots/chart_ellipse.gp   (out: .png, .svg or .pdf)
if (!exists("csv")) { print "usage: gnuplot -e \"csv='ellipse.csv'; out='ellipse.png'\" plots/chart_ellipse.gp"; exit status 1 }
if (!exists("out")) { out = "ellipse.png" }
load system("dirname '".ARG0."'")."/style.gp"
header = system(sprintf("grep -m 1 -v '^#' '%s'", csv))
if (strstrt(header, "curve,event,omega,ellipticity") != 1) { print "chart_ellipse.gp: ".csv.": not an ellipticity chart (header curve,event,omega,ellipticity,err)"; exit status 1 }
rows = int(system(sprintf("grep -v '^#' '%s' | grep -c ','", csv))) - 1
links = meta(csv, "links")
radius = meta(csv, "a")
mode = system(sprintf("sed -n '/^# chart: /{s/.*of mode \\([0-9]*\\).*/\\1/;p;q}' '%s'", csv))
cw = 900; ch = 620; @canvas
set output out
set title sprintf("how far from a circle: the mode-%s shape of the hand-swung chain of %s link%s, a = %s %s", mode, links, links eq "1" ? "" : "s", radius, u_len(csv)) noenhanced
set xlabel "rate omega [".u_rate(csv)."]"
set ylabel "ellipticity e = 1 - b/a where the shape is lost"
set key outside below horizontal noenhanced
set datafile separator ","
set yrange [0:*]
kind(k) = strcol(2) eq k ? $4 : NaN
if (rows <= 0) {
    set label 1 "no rate where the shape is stable on the circle" at graph 0.5, 0.5 center
    set xrange [0:1]; set yrange [0:1]
    plot NaN notitle
} else {
    plot csv skip skip_of(csv) using 3:4 with lines lc rgb "#555555" lw 1.5 title "e_crit(omega)", \
         csv skip skip_of(csv) using 3:(kind("torus")) with points lt 1 pt 7 ps 0.8 title "torus: two pairs meet on the unit circle", \
         csv skip skip_of(csv) using 3:(kind("period-doubling")) with points lt 2 pt 5 ps 0.8 title "period doubling (-1)", \
         csv skip skip_of(csv) using 3:(strcol(2) eq "fold" || strcol(2) eq "branch" ? $4 : NaN) with points lt 3 pt 9 ps 0.9 title "fold or branch (+1)", \
         csv skip skip_of(csv) using 3:(kind("none")) with points lt 5 pt 8 ps 0.9 title "none up to e_max"
}
