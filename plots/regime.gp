# Heat map of `whirl regime` (a map): the state each point of the (omega, eps) grid settles into
# from rest, one cell per point: the node count if settled (open circle: still converging at
# t_max, counted with the node count of its last shape), otherwise periodic, quasi-periodic,
# chaotic or failed. Dashed lines: the critical rates of the free chain (from the map's header);
# points: the folds of the steady driven branches (the --folds file), coloured by the branch's
# mode.
#   usage: gnuplot -e "map='map.csv'; out='map.png'" plots/regime.gp
#          gnuplot -e "map='map.csv'; folds='folds.csv'; out='map.png'" plots/regime.gp
#   optional: title_text='...'
# A sweep CSV (leg,omega,...): the class against omega, up and down (hysteresis):
#   usage: gnuplot -e "sweep='sweep.csv'; out='sweep.png'" plots/regime.gp
if (!exists("map") && !exists("sweep")) {
    print "usage: gnuplot -e \"map='map.csv'; [folds='folds.csv';] out='map.png'\" plots/regime.gp"
    print "   or: gnuplot -e \"sweep='sweep.csv'; out='sweep.png'\" plots/regime.gp"
    exit status 1
}
load system("dirname '".ARG0."'")."/style.gp"
# the class column: node count (1, 2, 3, ...), 0 periodic, -1 quasi-periodic, -2 chaotic, -3 failed
set palette defined (-3 "black", -2 "#d7301f", -1 "#fc8d59", 0 "#fee08b", \
                     1 "#91bfdb", 2 "#4575b4", 3 "#1a9850", 4 "#762a83", 5 "#999999")
set cbrange [-3.5:5.5]
set cbtics ("failed" -3, "chaotic" -2, "quasi-per." -1, "periodic" 0, \
            "1 node" 1, "2 nodes" 2, "3 nodes" 3, "4 nodes" 4, "5" 5)
set grid front
if (!exists("title_text")) { title_text = "" }

if (exists("map")) {
    if (!exists("out")) { out = map . ".png" }
    skip = skip_of(map)
    stats map skip skip using 2 nooutput
    n_omega = 0 + system(sprintf("grep -v '^#' '%s' | tail -n +2 | cut -d, -f2 | sort -u | wc -l", map))
    wmin = STATS_min; wmax = STATS_max
    stats map skip skip using 3 nooutput
    n_eps = 0 + system(sprintf("grep -v '^#' '%s' | tail -n +2 | cut -d, -f3 | sort -u | wc -l", map))
    emin = STATS_min; emax = STATS_max
    dw = n_omega > 1 ? (wmax - wmin) / (n_omega - 1) : 0.1
    de = n_eps > 1 ? (emax - emin) / (n_eps - 1) : 0.01
    crit = system(sprintf("sed -n 's/^# critical rates of the free chain (modes 1..[0-9]*)://p' '%s'", map))
    set terminal @term size (1000) * px, (600) * px
    set output out
    set tmargin 4
    set title title_text noenhanced offset 0, 1
    set xlabel "omega [".u_rate(map)."]"
    set ylabel "eps [".u_len(map)."]"
    set xrange [wmin - dw / 2 : wmax + dw / 2]
    set yrange [emin - de / 2 : emax + de / 2]
    set key outside right top noenhanced
    do for [k = 1 : words(crit)] {
        w = 0 + word(crit, k)
        if (w > wmin - dw / 2 && w < wmax + dw / 2) {
            set arrow from w, graph 0 to w, graph 1 nohead dt 2 lw 2 lc rgb "black" front
            set label sprintf("omega_%d", k) at w, graph 1.03 center noenhanced
        }
    }
    set colorbox user origin 0.8, 0.12 size 0.025, 0.5
    plot map skip skip using 2:3:(dw / 2):(de / 2):5 with boxxyerror fs solid 1.0 noborder \
             lc palette notitle, \
         map skip skip using 2:(strcol(4) eq "converging" ? $3 : 1/0) with points pt 6 ps 1.6 \
             lw 2 lc rgb "black" title "still converging at t_max", \
         for [m = 1 : 3] (exists("folds") ? folds : map) skip (exists("folds") ? skip_of(folds) : skip) \
             using (exists("folds") && $2 == m ? $5 : 1/0):1 with points pt (2 * m + 3) \
             ps (2.4 - 0.5 * m) lw 2 lc rgb word("black magenta #00ffff", m) \
             title sprintf("fold, steady mode %d", m)
}

if (exists("sweep")) {
    if (!exists("out")) { out = sweep . ".png" }
    skip = skip_of(sweep)
    set terminal @term size (900) * px, (420) * px
    set output out
    set title title_text noenhanced
    set xlabel "omega [".u_rate(sweep)."]"
    set ylabel "settled state"
    set yrange [-3.5:4.5]
    set ytics ("failed" -3, "chaotic" -2, "quasi-per." -1, "periodic" 0, "1 node" 1, "2 nodes" 2, \
               "3 nodes" 3, "4 nodes" 4)
    unset colorbox
    set key top left
    plot sweep skip skip using 2:(strcol(1) eq "up" ? $4 + 0.06 : 1/0) with linespoints pt 9 ps 1.4 \
             lc rgb "#d7301f" title "omega up", \
         sweep skip skip using 2:(strcol(1) eq "down" ? $4 - 0.06 : 1/0) with linespoints pt 11 ps 1.4 \
             lc rgb "#4575b4" title "omega down"
}
