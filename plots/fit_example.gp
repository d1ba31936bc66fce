# The example measurement data/fit_example.csv (a 120 cm chain, 40 points with 1.2 mm noise) and
# the continuum shape whirl fit finds for it, drawn by whirl shape. From the repository root:
# usage: gnuplot -e "whirl='build/whirl'; out='fit_example.png'" plots/fit_example.gp
if (!exists("whirl")) { whirl = 'build/whirl' }
if (!exists("out")) { out = 'fit_example.png' }
units = '--length 120 --gravity 981'
fit = system(whirl.' fit --shape data/fit_example.csv '.units.' | grep -v "^#" | tail -1 | tr , " "')
omega = real(word(fit, 1))
mode = int(word(fit, 3))
set datafile separator ','
set terminal pngcairo size 640,720 font ',11'
set output out
set title noenhanced sprintf("fit: omega = %.4f rad/s (3.2 sqrt(g/L) = 9.1494), mode %d", omega, mode)
set xlabel 'r [cm]'
set ylabel 'z [cm]'
set size ratio -1
set key bottom right
set grid
plot '< '.whirl.sprintf(' shape --omega %.17g --mode %d --points 401 %s', omega, mode, units) \
       every ::1 using (-$2):3 with lines lw 2 title 'fitted shape (mirrored)', \
     'data/fit_example.csv' skip 6 using 2:3 with points pt 7 ps 0.8 title 'measured points'
