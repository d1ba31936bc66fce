# Steady shapes of modes 1-3 side by side (whirl shape): each mode at three rates (continuum)
# and the 12-link chain at the middle rate (points). Reads the rate from each file's comment
# line. Usage: gnuplot -e "dir='out/demo'" plots/shapes.gp
if (!exists("dir")) { dir = 'out/demo' }
set terminal pngcairo size 1500,680 font ",12"
set output dir.'/shapes.png'
set datafile separator ','
set datafile commentschars '#'
# the rate of a shape file: "# omega=W mode=..." on its first line
rate(f) = sprintf('%.4g', real(system(sprintf("head -1 '%s' | sed 's/^# omega=\\([^ ]*\\) .*/\\1/'", f))))
colors = '#1b9e77 #d95f02 #7570b3'
set multiplot layout 1,3 title "Steady shapes of a chain whirling about the vertical axis (L = M = g = 1; lines: continuum, points: 12 links)" font ",14"
set yrange [-1.02:0.04]
set size ratio -1
set grid lc rgb '#dddddd'
set xlabel 'r / L (signed distance from the axis)'
set ylabel 'z / L'
set key below box samplen 2 maxrows 2 width 1
do for [k = 1:3] {
  if (k == 1) { set xrange [-0.03:1.03] } else { set xrange [-0.53:0.53] }
  set title sprintf('mode %d: %d axis crossing%s below the pivot', k, k - 1, k == 2 ? '' : 's')
  f(i) = dir.sprintf('/shape_k%d_%d.csv', k, i)
  plot 0 with lines lc rgb '#999999' dt 3 notitle, \
       for [i = 1:3] f(i) using 2:3 every ::1 with lines lw 2.5 lc rgb word(colors, i) \
         title sprintf('{/Symbol w} = %s', rate(f(i))), \
       dir.sprintf('/shape_k%d_n12.csv', k) using 2:3 every ::1 with points pt 7 ps 0.9 \
         lc rgb 'black' title sprintf('12 links, {/Symbol w} = %s', rate(f(2)))
}
unset multiplot
