# A perturbed run about a steady shape: deviation / initial deviation against t on a log scale
# (the --trace CSV of `whirl stability --omega W --mode K`), with the slope the linearisation
# predicts, exp(eig_growth t), through the envelope (the largest deviation) at the end of the run
# or of the window where the run's growth was fitted (its "fitted from t = A" line), the part
# where the slowest mode dominates; flat through 1 for a neutral shape (eig_growth = 0).
# usage: gnuplot -e "csv='trace.csv'; out='deviation.png'" plots/deviation.gp
if (!exists("csv")) { print "usage: gnuplot -e \"csv='trace.csv'; out='deviation.png'\" plots/deviation.gp"; exit status 1 }
if (!exists("out")) { out = csv . ".png" }
load system("dirname '".ARG0."'")."/style.gp"
eig = real(system(sprintf("grep -m 1 -o 'eig_growth [^ ,]*' '%s' | cut -d' ' -f2", csv)))
sim = real(system(sprintf("grep -m 1 -o 'sim_growth [^ ,]*' '%s' | cut -d' ' -f2", csv)))
verdict = system(sprintf("grep -m 1 -o 'verdict [a-z]*' '%s' | cut -d' ' -f2", csv))
title = system(sprintf("grep -m 1 '^# omega' '%s' | cut -c3- | cut -d, -f1-4", csv))
from = system(sprintf("grep -m 1 -o 'fitted from t = [^ ]*' '%s' | cut -d' ' -f5", csv))
t0 = (from eq "" || eig == 0) ? 0 : real(from)
stats [*:*][*:*] csv skip skip_of(csv) using 1:2 nooutput
t_end = STATS_max_x
# the anchor: a neutral shape's line runs flat through 1; otherwise the line goes through the
# envelope of the deviation (its largest value) over the last tenth of the run, or of the fit
# window when the run reports one, so that an oscillating deviation is compared by its peaks
t_from = (t0 > 0 ? t0 : 0.9 * t_end)
stats [*:*][*:*] csv skip skip_of(csv) using ($1 >= t_from ? $1 : NaN):2 nooutput
t_a = (eig != 0 ? STATS_pos_max_y : 0)
d_a = (eig != 0 ? STATS_max_y : 1)
set terminal @term size (900) * px, (500) * px
set output out
set logscale y
set format y "10^{%L}"
set xlabel "t [".u_time(csv)."]"
set ylabel "deviation / initial"
set title sprintf("%s: %s", title, verdict) noenhanced
set key below
set offsets 0, 0, graph 0.05, graph 0.05
set grid
fitted = (sim != 0 ? sprintf(", the run's fit %.4g", sim) : "")
if (t0 > 0) { set arrow 1 from t0, graph 0 to t0, graph 1 nohead dt 3 lc rgb "#999999"; \
              set label 1 " fit window" at t0, graph 0.95 left tc rgb "#777777" }
plot csv skip skip_of(csv) using 1:2 with lines lt 1 title "run", \
     d_a * exp(eig * (x - t_a)) with lines lt 2 dt 2 \
     title sprintf("linearisation: growth %.4g per %s%s", eig, u_time(csv), fitted)
set output
