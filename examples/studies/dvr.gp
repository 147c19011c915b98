# dvr.gp: half-angle slicing's relative RMSE against the exact-shadow ray
# march, against its frame time, from results/dvr.tsv (dvr.sh, which runs
# it for PNG and SVG; to try a change: gnuplot -e "size='128x128'" dvr.gp,
# with a terminal and an output set by -e too).  Block 0 sweeps the slice
# count (light buffer 256), block 1 the light buffer's edge (320 slices);
# the labels are the swept values.  The dashed lines: the same pictures
# against the single-scattering path tracer; the dotted one the ray
# march's own error (step 1 against 0.5, from results/dvr-refs.tsv).
if (!exists("size")) size = "?"
rmerr = real(system("awk -F'\t' 'NR == 2 { print $4 }' results/dvr-refs.tsv"))
set datafile separator "\t"
set title sprintf("Half-angle slicing against the exact-shadow ray march (ch2 head, volumetric shadows, %s)", size)
set xlabel "dvr frame time (s, median of the runs)"
set ylabel "relative RMSE"
set logscale xy
set grid
set key top right
set format y "%.1f%%"
set offsets graph 0.05, graph 0.1, 0, 0
if (rmerr > 0) set arrow from graph 0, first 100 * rmerr to graph 1, first 100 * rmerr nohead dt 3
if (rmerr > 0) set label "the ray march's own error (step 1 vs 0.5)" at graph 0.01, first 100 * rmerr offset 0, char -0.8
plot "results/dvr.tsv" index 0 using 3:(100 * $4) with linespoints pt 7 ps 1.2 \
       title "slices (light buffer 256) vs ray march", \
     "" index 0 using 3:(100 * $4):(sprintf("%d", $1)) with labels offset char 0.8, char 0.8 left notitle, \
     "" index 1 using 3:(100 * $4) with linespoints pt 5 ps 1.2 \
       title "light buffer edge (320 slices) vs ray march", \
     "" index 1 using 3:(100 * $4):(sprintf("%d", $2)) with labels offset char 0.8, char -0.9 left notitle, \
     "" index 0 using 3:(100 * $5) with linespoints pt 6 dt 2 lc 1 \
       title "slices vs path tracer (single scattering)", \
     "" index 1 using 3:(100 * $5) with linespoints pt 4 dt 2 lc 2 \
       title "light buffer vs path tracer (single scattering)"
