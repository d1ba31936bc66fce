# Stability map: eig_growth (largest real part of the linearisation about the steady shape, in
# sqrt(g/L)) against omega, one panel per mode, one line per chain (CSVs of
# `whirl stability --omega-min A --omega-max B --omega-count N --linear`).
# usage: gnuplot -e "files='map_N25.csv map_N50.csv map_N100.csv'; out='map.png'" plots/stability_map.gp
if (!exists("files")) { print "usage: gnuplot -e \"files='a.csv b.csv'; out='map.png'\" plots/stability_map.gp"; exit status 1 }
if (!exists("out")) out = "stability_map.png"
set datafile separator ","
set terminal png size 900, 760
set output out
set multiplot layout 3, 1 margins 0.1, 0.97, 0.07, 0.97 spacing 0, 0.03
set key top left
set grid
do for [k = 1:3] {
    set ylabel sprintf("mode %d: eig growth", k)
    if (k == 3) { set xlabel "omega [sqrt(g/L)]"; set format x "%g" } else { unset xlabel; set format x "" }
    plot for [f in files] f skip 0 using 1:(($2 == k) ? $4 : NaN) with lines lw 1.5 \
         title sprintf("N = %s", system(sprintf("grep -m 1 -o '[0-9]* links' '%s' | cut -d' ' -f1", f)))
}
unset multiplot
set output
