# A perturbed run about a steady shape: deviation / initial deviation against t on a log scale
# (the --trace CSV of `whirl stability --omega W --mode K`), with the slope the linearisation
# predicts, exp(eig_growth t), drawn through the end of the run: rising for an unstable shape,
# falling for a converging one (damping > 0); flat through the start for a neutral one
# (eig_growth = 0).
# usage: gnuplot -e "csv='trace.csv'; out='deviation.png'" plots/deviation.gp
if (!exists("csv")) { print "usage: gnuplot -e \"csv='trace.csv'; out='deviation.png'\" plots/deviation.gp"; exit status 1 }
if (!exists("out")) out = csv . ".png"
set datafile separator ","
eig = real(system(sprintf("grep -m 1 -o 'eig_growth [^ ,]*' '%s' | cut -d' ' -f2", csv)))
sim = real(system(sprintf("grep -m 1 -o 'sim_growth [^ ,]*' '%s' | cut -d' ' -f2", csv)))
verdict = system(sprintf("grep -m 1 -o 'verdict [a-z]*' '%s' | cut -d' ' -f2", csv))
title = system(sprintf("grep -m 1 '^# omega' '%s' | cut -c3- | cut -d, -f1-4", csv))
stats csv skip 2 using 1:2 nooutput
t_end = STATS_max_x
# the predicted line passes through the last sample (the end of the run), or, when it is flat
# (neutral), through the start
stats csv skip 2 using ($1 == t_end ? $2 : NaN) nooutput
d_end = (eig != 0 ? STATS_max : 1)
set terminal png size 800, 480
set output out
set logscale y
set format y "10^{%L}"
set xlabel "t [sqrt(L/g)]"
set ylabel "deviation / initial"
set title sprintf("%s: %s", title, verdict) noenhanced
set key below
set offsets 0, 0, graph 0.05, graph 0.05
set grid
fitted = (sim != 0 ? sprintf(", fitted %.4g", sim) : "")
plot csv skip 2 using 1:2 with lines lw 1.5 title "run", \
     d_end * exp(eig * (x - t_end)) with lines dt 2 lw 2 \
     title sprintf("predicted exp(eig growth t): eig growth %.4g%s", eig, fitted)
set output
