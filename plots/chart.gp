# The stability chart of the vertically shaken chain (whirl periodic --chart hanging|inverted):
# its edges as curves of the amplitude A against the rate omega, one line per curve (the CSV's
# blocks, a blank line between curves), coloured by the edge: a multiplier pair through -1
# (period doubling: the odd tongues, Mathieu's a_1, b_1, ...) or through +1 (the even tongues;
# the inverted chain's lower edge, Kapitza's). With --drag the title names the linear air drag.
# Rates in rad/s and amplitudes in m for a file in SI units ("# units: length=m ..."), else
# sqrt(g/L) and L.
# usage: gnuplot -e "csv='chart.csv'; out='chart.png'" plots/chart.gp   (out: .png, .svg or .pdf)
if (!exists("csv")) { print "usage: gnuplot -e \"csv='chart.csv'; out='chart.png'\" plots/chart.gp"; exit status 1 }
if (!exists("out")) { out = "chart.png" }
load system("dirname '".ARG0."'")."/style.gp"
header = system(sprintf("grep -m 1 -v '^#' '%s'", csv))
if (strstrt(header, "curve,edge,omega,amplitude") != 1) { print "chart.gp: ".csv.": not a chart (header curve,edge,omega,amplitude,err)"; exit status 1 }
rows = int(system(sprintf("grep -v '^#' '%s' | grep -c ','", csv))) - 1
which = system(sprintf("sed -n '/^# chart: the /{s/^# chart: the //;s/ chain.*//;p;q}' '%s'", csv))
links = meta(csv, "links")
# the damped chart (--drag C): the drag with its unit, from the first line's " drag=C UNIT;"
drag = system(sprintf("grep -m 1 -o ' drag=[^;]*' '%s' | cut -d= -f2", csv))
cw = 900; ch = 620; @canvas
set output out
set title sprintf("the %s chain of %s link%s shaken vertically, A cos(omega t)%s", which, links, links eq "1" ? "" : "s", strlen(drag) > 0 ? ", linear air drag ".drag : "") noenhanced
set xlabel "shaking rate omega [".u_rate(csv)."]"
set ylabel "amplitude A [".u_len(csv)."]"
set key outside below horizontal noenhanced
if (rows <= 0) {
    set label 1 "no edge in the range" at graph 0.5, 0.5 center
    set xrange [0:1]; set yrange [0:1]
    plot NaN notitle
} else {
    plot csv skip skip_of(csv) using 3:($2 < 0 ? $4 : NaN) with lines lt 2 title "edge -1: a multiplier pair through -1 (period doubling)", \
         csv skip skip_of(csv) using 3:($2 > 0 ? $4 : NaN) with lines lt 1 title "edge +1: a pair through +1"
}
