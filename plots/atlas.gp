# The stability atlas of the continuous chain (whirl stability --atlas -o atlas.csv): for each
# mode (vertical axis) the windows of instability as horizontal bars over the rotation rate,
# coloured by the largest growth rate in the window (log scale), the mode's birth omega_k (where
# it branches from the hanging chain: j_{0,k} / 2, Kolodner 1955) as a black diamond; windows
# narrower than 0.12 are drawn 0.12 wide to be seen.
# atlas.csv: mode,from,to,open_from,open_to,freq_from,freq_to,sig_from,sig_to,max_growth,at,...
# usage: gnuplot -e "csv='atlas.csv'; out='atlas.png'" plots/atlas.gp
# optional: note='TEXT' (e.g. where the windows come from), printed under the plot
if (!exists("csv")) { print "usage: gnuplot -e \"csv='atlas.csv'; out='atlas.png'\" plots/atlas.gp"; exit status 1 }
if (!exists("out")) out = "atlas.png"
load system("dirname '".ARG0."'")."/style.gp"
set terminal @term size 1000, 560
set output out
set datafile separator ","
set xlabel "rotation rate omega [sqrt(g/L)]"
set ylabel "mode k"
set ytics 1
wmax = real(system(sprintf("awk -F, '/^[0-9]/ { if ($3 > m) m = $3 } END { print m + 0 }' '%s'", csv)))
kmin = int(system(sprintf("awk -F, '/^[0-9]/ { if (m == \"\" || $1 < m) m = $1 } END { print m + 0 }' '%s'", csv)))
kmax = int(system(sprintf("awk -F, '/^[0-9]/ { if ($1 > m) m = $1 } END { print m + 0 }' '%s'", csv)))
set xrange [0:wmax]
set yrange [kmin - 0.7:kmax + 0.7]
set logscale cb
set cblabel "largest growth rate in the window [sqrt(g/L)]"
set palette defined (0 "#fde725", 0.35 "#35b779", 0.7 "#31688e", 1 "#440154")
set title "Windows of instability of the whirling chain (continuum), births marked"
if (exists("note")) { set label 1 note at screen 0.01, screen 0.02 left font ",9"; set bmargin 5 }
# the births: omega_k = j_{0,k} / 2 from the zeros of J0 (asymptotic form, exact to 1e-3 for k >= 2)
j0(k) = (k - 0.25) * pi + 1 / (8 * (k - 0.25) * pi)
set samples kmax - kmin + 1
plot csv using (($2 + $3) / 2):1:(($3 - $2) / 2 > 0.06 ? ($3 - $2) / 2 : 0.06):(0.28):10 every ::1 \
         with boxxyerror fs solid 1.0 noborder lc palette notitle, \
     [kmin:kmax] '+' using (j0($1) / 2):1 with points pt 13 ps 1.6 lc rgb "black" title "birth omega_k"
set output
