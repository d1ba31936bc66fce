# Stability map: eig_growth (largest real part of the linearisation about the steady shape)
# against omega, one panel per mode, one line per chain (CSVs of
# `whirl stability --omega-min A --omega-max B --omega-count N --linear`). A mode whose growth is
# zero over the whole range (stable everywhere, like mode 1 of the free chain) gets a panel
# saying so, on a fixed small range around 0, instead of an empty one.
# usage: gnuplot -e "files='map_N25.csv map_N50.csv map_N100.csv'; out='map.png'" plots/stability_map.gp
# optional: modes=3 (panels for modes 1..modes)
if (!exists("files")) { print "usage: gnuplot -e \"files='a.csv b.csv'; out='map.png'\" plots/stability_map.gp"; exit status 1 }
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("out")) { out = "stability_map.png" }
if (!exists("modes")) { modes = 3 }
f1 = word(files, 1)
set terminal @term size (900) * px, (260 * modes + 60) * px
set output out
set multiplot layout modes, 1 margins 0.12, 0.97, 0.08, 0.93 spacing 0, 0.03 \
    title "Stability of the steady shapes: largest growth rate of a perturbation (> 0: unstable)"
set key top left
links(f) = system(sprintf("grep -m 1 -o '[0-9]* links' '%s' | cut -d' ' -f1", f))
do for [k = 1:modes] {
    # the panel's range: that of the mode's rows in every file
    lo = 0; hi = 0
    do for [f in files] {
        stats [*:*][*:*] f skip skip_of(f) using 1:(($2 == k) ? $4 : NaN) nooutput
        if (STATS_records > 0) { lo = (STATS_min_y < lo ? STATS_min_y : lo); hi = (STATS_max_y > hi ? STATS_max_y : hi) }
    }
    unset label 1
    if (hi - lo == 0) {
        set yrange [-1:1]
        set label 1 sprintf("mode %d: growth 0 everywhere (stable)", k) at graph 0.5, graph 0.7 center
    } else {
        set yrange [lo - 0.05 * (hi - lo) : hi + 0.05 * (hi - lo)]
    }
    set ylabel sprintf("mode %d [1/%s]", k, u_time(f1))
    if (k == modes) { set xlabel "omega [".u_rate(f1)."]"; set format x "%g" } else { unset xlabel; set format x "" }
    plot for [f in files] f skip skip_of(f) using 1:(($2 == k) ? $4 : NaN) with lines \
         title sprintf("N = %s links", links(f))
}
unset multiplot
set output
