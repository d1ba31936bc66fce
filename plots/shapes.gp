# Steady shapes of modes 1-3 side by side (whirl shape): each mode at three rates (continuum)
# and the 12-link chain at the middle rate (points). Reads the rate from each file's comment
# line. Usage: gnuplot -e "dir='out/demo'" plots/shapes.gp   (fmt='svg' or 'pdf': shapes.svg, .pdf)
if (!exists("dir")) { dir = 'out/demo' }
load system("dirname '".ARG0."'")."/style.gp"
set terminal @term size (1500) * px, (560) * px
set output dir.'/shapes.'.fmt
set datafile separator ','
set datafile commentschars '#'
# the rate of a shape file: "# omega=W mode=..." on its first line
rate(f) = sprintf('%.4g %s', real(system(sprintf("head -1 '%s' | sed 's/^# omega=\\([^ ]*\\) .*/\\1/'", f))), u_rate(f))
colors = '#1b9e77 #d95f02 #7570b3'
set multiplot layout 1,3 margins 0.05, 0.99, 0.1, 0.88 spacing 0.05, 0 title "Steady shapes of a chain whirling about the vertical axis (L = M = g = 1; lines: continuum, points: 12 links)" font ",14"
set key noenhanced
set yrange [-1.02:0.04]
set size ratio -1
set grid lc rgb '#dddddd'
set xlabel 'r / L (signed distance from the axis)'
set ylabel 'z / L'
set key box opaque samplen 2 spacing 1.1 title 'rate omega' noenhanced
# the rotation axis, dashed, through the pivot
set arrow 1 from 0, -1.02 to 0, 0.04 nohead dt 2 lc rgb '#999999' back
do for [k = 1:3] {
  # each key where no curve runs: mode 1 right of the steep low-rate shape, the others bottom left
  if (k == 1) { set xrange [-0.03:1.03]; set key at graph 0.98, graph 0.62 right top } else { set xrange [-0.53:0.53]; set key at graph 0.02, graph 0.02 left bottom }
  set title sprintf('mode %d: %d axis crossing%s below the pivot', k, k - 1, k == 2 ? '' : 's')
  f(i) = dir.sprintf('/shape_k%d_%d.csv', k, i)
  plot for [i = 1:3] f(i) using 2:3 every ::1 with lines lw 2.5 lc rgb word(colors, i) \
         title rate(f(i)), \
       dir.sprintf('/shape_k%d_n12.csv', k) using 2:3 every ::1 with points pt 7 ps 0.9 \
         lc rgb 'black' title '12 links'
}
unset multiplot
