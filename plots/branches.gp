# Branches of the steady shapes against the rotation rate (whirl sweep): tip radius and top
# tension of modes 1-3, the continuum's critical rates omega_k = j0k/2 marked, the 10-link chain as points.
# Each continuum branch starts where it bifurcates from the hanging chain, at (omega_k, tip
# radius 0, top tension M g): the linear theory's exact point, prepended to the sweep's rows.
# Usage: gnuplot -e "dir='out/demo'" plots/branches.gp   (fmt='svg' or 'pdf': branches.svg, .pdf)
if (!exists("dir")) { dir = 'out/demo' }
load system("dirname '".ARG0."'")."/style.gp"
set terminal @term size (1400) * px, (560) * px
set output dir.'/branches.'.fmt
set datafile commentschars '#'
crit = dir.'/critical.csv'
stats crit using ($1 == 1 ? $2 : 1/0) every ::1 nooutput
w1 = STATS_max
stats crit using ($1 == 2 ? $2 : 1/0) every ::1 nooutput
w2 = STATS_max
stats crit using ($1 == 3 ? $2 : 1/0) every ::1 nooutput
w3 = STATS_max
# the branches, each from its bifurcation point: $b1, $b2, $b3 (columns as the sweep's)
do for [k = 1:3] {
  w = k == 1 ? w1 : k == 2 ? w2 : w3
  eval sprintf("set print $b%d", k)
  print sprintf("%.17g,%d,0,0,1,1", w, k)
  print system(sprintf("grep -v '^#' '%s' | awk -F, '$2 == %d'", dir.'/branches.csv', k))
  set print
}
colors = '#1b9e77 #d95f02 #7570b3'
set multiplot layout 1,2 title "Branches of steady shapes (continuum lines, 10-link chain points)" font ",14"
set grid lc rgb '#dddddd'
set tmargin 5
set xlabel '{/Symbol w} ['.u_rate(dir.'/branches.csv').']'
set xrange [1:10]
set key right center box opaque
do for [i = 1:3] {
  w = i == 1 ? w1 : i == 2 ? w2 : w3
  set arrow i from w, graph 0 to w, graph 1 nohead dt 2 lc rgb word(colors, i)
  set label i sprintf('{/Symbol w}_%d', i) at w, graph 1 offset -0.9,0.7 tc rgb word(colors, i)
}
set title 'tip radius' offset 0,1.2
set ylabel 'r_{tip} / L'
set yrange [0:1.05]
plot for [k = 1:3] sprintf("$b%d", k) using 1:3 with lines lw 2.5 \
       lc rgb word(colors, k) title sprintf('mode %d', k), \
     for [k = 1:3] dir.'/branches_n10.csv' using 1:($2 == k ? $3 : 1/0) every ::1 with points \
       pt 6 ps 0.7 lc rgb word(colors, k) notitle
set title 'tension at the pivot' offset 0,1.2
set key right bottom
set ylabel 'T_{top} / (M g)'
set logscale y
set yrange [0.8:60]
plot for [k = 1:3] sprintf("$b%d", k) using 1:5 with lines lw 2.5 \
       lc rgb word(colors, k) title sprintf('mode %d', k), \
     for [k = 1:3] dir.'/branches_n10.csv' using 1:($2 == k ? $5 : 1/0) every ::1 with points \
       pt 6 ps 0.7 lc rgb word(colors, k) notitle
unset multiplot
