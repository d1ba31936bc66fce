# Time series of a `whirl simulate` CSV: every column against t, one panel each (energy, jacobi
# and lz as their change from the first row; constraint and deviation on a logarithmic scale).
# usage: gnuplot -e "csv='run.csv'; out='run.png'" plots/simulate.gp
if (!exists("csv")) { print "usage: gnuplot -e \"csv='run.csv'; out='run.png'\" plots/simulate.gp"; exit status 1 }
if (!exists("out")) { out = csv . ".png" }
load system("dirname '".ARG0."'")."/style.gp"
header = system(sprintf("grep -m 1 -v '^#' '%s'", csv))
skip = int(system(sprintf("grep -n -m 1 -v '^#' '%s' | cut -d: -f1", csv)))
stats csv skip skip nooutput
ncol = STATS_columns
ul = u_len(csv); ut = u_time(csv); uf = u_force(csv)
# each column's meaning and unit
label(n) = n eq "tip_x" ? "tip x [".ul."]" : n eq "tip_y" ? "tip y [".ul."]" : \
    n eq "tip_z" ? "tip z [".ul."]" : n eq "energy" ? "energy E - E(0) [".uf." ".ul."]" : \
    n eq "jacobi" ? "Jacobi integral - at t=0 [".uf." ".ul."]" : \
    n eq "lz" ? "angular momentum L_z - L_z(0)" : n eq "constraint" ? "link length error [".ul."]" : \
    n eq "deviation" ? "deviation from the start shape [".ul."]" : n
set terminal @term size (900) * px, (170 * (ncol - 1) + 80) * px
set output out
set multiplot layout ncol - 1, 1 margins 0.16, 0.97, 0.07, 0.94 spacing 0, 0.04 \
    title system(sprintf("sed -n '2s/^# //p' '%s' | cut -c1-95", csv)) noenhanced
unset key
do for [c = 2:ncol] {
    name = system(sprintf("echo '%s' | cut -d, -f%d", header, c))
    # a constant column (say a constraint kept to round-off) gets a range around its value
    # (on the logarithmic scale, of the positive values)
    logscale = name eq "constraint" || name eq "deviation"
    range = system(sprintf("grep -v '^#' '%s' | tail -n +2 | cut -d, -f%d | awk '!%d || $1 > 0' | sort -g | sed -n '1p;$p' | tr '\\n' ' '", csv, c, logscale))
    flat = word(range, 1) eq word(range, 2)
    v = real(word(range, 1))
    if (c == ncol) { set xlabel "t [".ut."]"; set format x "%g" } else { unset xlabel; set format x "" }
    if (name eq "energy" || name eq "jacobi" || name eq "lz") {
        # a conserved quantity: its change from the first row, which is what measures the run
        first = real(system(sprintf("grep -v '^#' '%s' | sed -n 2p | cut -d, -f%d", csv, c)))
        unset logscale y
        set format y "%g"
        set ylabel label(name) noenhanced
        # four or five ticks from the data's span (short labels that cannot overlap)
        lo = real(word(range, 1)) - first; hi = real(word(range, 2)) - first
        if (flat) { set yrange [-1e-15:1e-15]; set ytics autofreq } else { set yrange [*:*]; set ytics nice((hi - lo) / 4) }
        plot csv skip skip using 1:(column(c) - first) with lines lt 1
    } else {
        if (name eq "constraint" || name eq "deviation") { set logscale y } else { unset logscale y }
        set format y "%g"
        set ylabel label(name) noenhanced
        if (flat) { if (v > 0) { set yrange [v / 10 : v * 10] } else { set yrange [v - 1 : v + 1] } } else { set yrange [*:*] }
        hi = real(word(range, 2)); lo = real(word(range, 1))
        if (logscale || flat) { set ytics autofreq } else { set ytics nice((hi - lo) / 4) }
        plot csv skip skip using 1:c with lines lt 1
    }
}
unset multiplot
set output
