# A perturbed run about a steady shape: deviation / initial deviation against t on a log scale
# (the --trace CSV of `whirl stability --omega W --mode K`), with the growth the linearisation
# predicts, exp(eig_growth t), drawn through the end of the run.
# usage: gnuplot -e "csv='trace.csv'; out='deviation.png'" plots/deviation.gp
if (!exists("csv")) { print "usage: gnuplot -e \"csv='trace.csv'; out='deviation.png'\" plots/deviation.gp"; exit status 1 }
if (!exists("out")) out = csv . ".png"
set datafile separator ","
eig = real(system(sprintf("grep -m 1 -o 'eig_growth [^ ,]*' '%s' | cut -d' ' -f2", csv)))
sim = system(sprintf("grep -m 1 -o 'sim_growth [^ ,]*' '%s' | cut -d' ' -f2", csv))
title = system(sprintf("grep -m 1 '^# omega' '%s' | cut -c3-", csv))
stats csv skip 2 using 1:2 nooutput
t_end = STATS_max_x
d_end = STATS_max_y
set terminal png size 800, 480
set output out
set logscale y
set format y "10^{%L}"
set xlabel "t [sqrt(L/g)]"
set ylabel "deviation / initial"
set title title noenhanced
set key top left
set grid
plot csv skip 2 using 1:2 with lines lw 1.5 title "run", \
     (eig > 0 ? d_end * exp(eig * (x - t_end)) : NaN) with lines dt 2 lw 1.5 \
     title sprintf("exp(eig growth t): eig growth %.4g, fitted %.4g", eig, real(sim))
set output
