# solver.gp: the root solvers' depth error against their frame time, from
# results/solver.tsv (solver.sh).  solver.sh runs it for PNG and SVG; to
# try a change:  gnuplot -e "size='384x384'" solver.gp  (set a terminal and
# an output with -e too).  The exact solver is the reference: its error, 0,
# has no place on the log scale, so its time is the dashed line.
if (!exists("size")) size = "?"
set datafile separator "\t"
set title sprintf("Root solver: depth error against time (ch2 head, %s)", size)
set xlabel "frame time (s, median of the runs)"
set ylabel "depth error against exact (world units, mm)"
set logscale y
set format y "%.0e"
set grid
set key bottom left
set offsets graph 0.15, graph 0.25, 0, 0
stats "results/solver.tsv" using (strcol(1) eq "exact" ? $2 : 1/0) nooutput
set arrow from STATS_min, graph 0 to STATS_min, graph 1 nohead dt 2
set label "exact (the reference)" at STATS_min, graph 0.93 offset char 0.5, 0
pos(y) = y > 0 ? y : 1/0
plot "results/solver.tsv" using 2:(pos($3)) with points pt 7 ps 1.5 title "RMSE", \
     "" using 2:(pos($4)) with points pt 9 ps 1.5 title "maximum", \
     "" using 2:(pos($3)):1 with labels offset char 1.5, char 0 left notitle
