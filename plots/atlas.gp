# Windows over the rotation rate, one row per mode, as horizontal bars, from any of the window
# files of whirl stability (told apart by their header line):
#   mode,from,to,...,sig_from,sig_to,max_growth,at,...        the atlas (whirl windows --atlas):
#       the continuous chain, dimensionless; each mode's birth omega_k (where it branches from the
#       hanging chain: j_{0,k} / 2, Kolodner 1955) as a black diamond
#   mode,links,from,to,...,max_growth,at[,err_from,err_to]    windows of instability (whirl
#       windows: the N-link chain with --links, else the continuum)
#   mode,links,from,to,...,growth,at,verdict                  intervals with dissipation (whirl
#       windows with --damping, or --eps with --drag): unstable and converging
# Windows of instability are coloured by the largest growth rate in the window (log scale); the
# intervals with dissipation by their verdict, unstable or converging. Each mode's examined range
# ("# mode K: examined A..B"; the atlas: from the birth to the end of the last chunk done) is a
# thin grey line, so that a mode without windows keeps its row; a file without windows gives the
# rows and says so. Bars narrower than 0.3% of the axis are drawn that wide to be seen. Rates in
# rad/s with a Hz axis on top for a file in SI units ("# units: length=m ..."), else sqrt(g/L).
# usage: gnuplot -e "csv='atlas.csv'; out='atlas.png'" plots/atlas.gp   (out: .png, .svg or .pdf)
# optional: note='TEXT' (e.g. where the windows come from), printed under the plot
if (!exists("csv")) { print "usage: gnuplot -e \"csv='atlas.csv'; out='atlas.png'\" plots/atlas.gp"; exit status 1 }
if (!exists("out")) { out = "atlas.png" }
load system("dirname '".ARG0."'")."/style.gp"
# the column named name in the header line (0: none)
col(name) = int(system(sprintf("awk -F, '!/^#/ { for (i = 1; i <= NF; i++) if ($i == \"%s\") { print i; exit } print 0; exit }' '%s'", name, csv)))
c_from = col("from"); c_to = col("to"); c_verdict = col("verdict")
c_growth = c_verdict ? col("growth") : col("max_growth")
if (col("mode") != 1 || !c_from || !c_to || !c_growth) { print "atlas.gp: ".csv.": not a file of windows (columns mode,...,from,to,...,max_growth; or growth and verdict)"; exit status 1 }
is_atlas = col("links") == 0
dissipative = c_verdict > 0
# the birth omega_k = j_{0,k} / 2 from the zeros of J0 (asymptotic form, exact to 1e-3 for k >= 2)
birth = 'function birth(k, p) { p = atan2(0, -1); return ((k - 0.25) * p + 1 / (8 * (k - 0.25) * p)) / 2 }'
# the examined ranges as rows k,from,to: "# mode K: examined A..B, ..." (whirl stability
# --windows); "# done mode K omega LO HI" (the atlas: chunks, from the birth)
examined = "< awk '".birth.' /^# mode [0-9]+: examined / { s = $0; sub(/.*examined /, "", s); sub(/,.*/, "", s); split(s, r, /\.\./); print $3 + 0 "," r[1] "," r[2] } /^# done mode / { k = $4; if (!(k in lo) || $6 < lo[k]) lo[k] = $6; if (!(k in hi) || $7 > hi[k]) hi[k] = $7 } END { for (k in lo) print k "," (lo[k] > birth(k) ? lo[k] : birth(k)) "," hi[k] }'."' '".csv."'"
# the modes interrupted before they were done ("# mode K: interrupted, not done") as rows k
notdone = "< awk '/^# mode [0-9]+: interrupted/ { print $3 + 0 }' '".csv."'"
# the extent of everything: words kmin kmax xmin xmax gmin gmax rows examined notdone
extent = system(sprintf("(awk -F, '!/^#/ && n++ { print $1 \",\" $%d \",\" $%d \",\" $%d \",r\" }' '%s'; %s | sed 's/$/,0,e/'; %s | sed 's/$/,,,0,n/') | awk -F, 'BEGIN { kmin = 1e9; kmax = -1e9; xmin = 1e300; xmax = -1e300; gmin = 1e300; gmax = 0 } { k = $1 + 0; if (k < kmin) kmin = k; if (k > kmax) kmax = k; c[$5]++; if ($5 == \"n\") next; if ($2 + 0 < xmin) xmin = $2 + 0; if ($3 + 0 > xmax) xmax = $3 + 0; g = ($4 < 0 ? -$4 : $4) + 0; if ($5 == \"r\" && g > 0 && g < gmin) gmin = g; if ($5 == \"r\" && g > gmax) gmax = g } END { if (xmin > xmax) { xmin = 0; xmax = 1 } if (gmin > gmax) { gmin = gmax = 1 } printf \"%%d %%d %%.16e %%.16e %%.16e %%.16e %%d %%d %%d\\n\", kmin, kmax, xmin, xmax, gmin, gmax, c[\"r\"], c[\"e\"], c[\"n\"] }'", c_from, c_to, c_growth, csv, examined[3:], notdone[3:]))
kmin = int(word(extent, 1)); kmax = int(word(extent, 2))
xmin = real(word(extent, 3)); xmax = real(word(extent, 4))
gmin = real(word(extent, 5)); gmax = real(word(extent, 6))
nrows = int(word(extent, 7)); nexamined = int(word(extent, 8)); nnotdone = int(word(extent, 9))
if (nrows + nexamined + nnotdone == 0) { print "atlas.gp: ".csv.": no windows and no mode examined"; exit status 1 }
if (is_atlas) { xmin = 0 }
if (xmax <= xmin) { xmax = xmin + 1 }
hw = 0.0015 * (xmax - xmin)
nmodes = kmax - kmin + 1
note_h = exists("note") ? 22 : 0
H = 170 + 48 * nmodes + note_h; H = H < 380 + note_h ? 380 + note_h : H
set terminal @term size (1000) * px, (H) * px
set output out
set xrange [xmin:xmax]
set yrange [kmin - 0.7:kmax + 0.7]
set ytics 1
set ylabel "mode k"
set xlabel "rotation rate omega [".u_rate(csv)."]"
if (physical(csv)) {
    set link x2 via x / (2 * pi) inverse x * (2 * pi)
    set x2tics nice((xmax - xmin) / (2 * pi) / 7)
    set x2label "rotation frequency omega / 2 pi [Hz]"
    set xtics nomirror
}
chain = system(sprintf("sed -n '1s/^# whirl stability --windows: \\([^,]*\\),.*/\\1/p' '%s'", csv))
chain = chain eq "continuous chain" ? "continuum" : chain
set title (is_atlas ? "Windows of instability of the whirling chain (continuum), births marked" : \
           dissipative ? sprintf("Where each mode is unstable or converging with dissipation (%s)", chain) : \
           sprintf("Windows of instability of the whirling chain (%s)", chain)) noenhanced
set key below center horizontal reverse Left noenhanced samplen 2 width 2 height 1
if (exists("note")) { set label 1 note at screen 0.01, screen 0.015 left font ",9" noenhanced; set bmargin 6 }
if (nrows == 0) { set label 2 (dissipative ? "no interval found in the examined ranges" : "no window found in the examined ranges") at graph 0.5, graph 0.5 center font ",13" }
if (!dissipative && nrows > 0) {
    # a log scale when the growth rates span more than a factor 20
    if (gmax <= gmin) { gmin = gmin / 2; gmax = gmax * 2 }
    if (gmax > 20 * gmin) { set logscale cb } else { set cbtics nice((gmax - gmin) / 5) }
    set cbrange [gmin:gmax]
    set cblabel "largest growth rate [".(physical(csv) ? "1/s" : "sqrt(g/L)")."]"
    set palette defined (0 "#fde725", 0.35 "#35b779", 0.7 "#31688e", 1 "#440154")
} else { unset colorbox }
# the pieces of the plot present in the file (an empty piece would draw nothing but a warning)
bar_x(a, b) = (a + b) / 2
bar_w(a, b) = (b - a) / 2 > hw ? (b - a) / 2 : hw
verdict_rgb(v) = v eq "unstable" ? 0xc0392b : v eq "converging" ? 0x1f78b4 : 0x888888
p = ""
if (nexamined > 0) { p = p."examined using 2:1:($3 - $2):(0) with vectors nohead lw 1.5 lc rgb '#999999' title 'examined range', " }
if (nrows > 0 && !dissipative) { p = p."csv skip skip_of(csv) using (bar_x(column(c_from), column(c_to))):1:(bar_w(column(c_from), column(c_to))):(0.28):(column(c_growth)) with boxxyerror fs solid 1.0 noborder lc palette notitle, " }
if (nrows > 0 && dissipative) { p = p."csv skip skip_of(csv) using (bar_x(column(c_from), column(c_to))):1:(bar_w(column(c_from), column(c_to))):(0.28):(verdict_rgb(strcol(c_verdict))) with boxxyerror fs solid 1.0 noborder lc rgb variable notitle, " }
if (dissipative) { p = p."keyentry with boxes fs solid 1.0 noborder lc rgb '#c0392b' title 'unstable (growth > 0)', keyentry with boxes fs solid 1.0 noborder lc rgb '#1f78b4' title 'converging (growth < 0)', " }
if (nnotdone > 0) { p = p."notdone using (xmin):1:('  not done (interrupted)') with labels left notitle, " }
if (is_atlas) { p = p.sprintf("'< awk \"%s BEGIN { for (k = %d; k <= %d; k++) print birth(k) \\\",\\\" k }\"' with points pt 13 ps 1.6 lc rgb 'black' title 'birth omega_k', ", birth, kmin, kmax) }
plot @p
set output
