# aa.gp: antialiasing's color error against its frame time, from
# results/aa.tsv (aa.sh).  Run by aa.sh for PNG and SVG; to try a change:
# gnuplot -e "size='384x384'" aa.gp  (a terminal and an output may be set
# with -e too).  The reference is 6x6 samples per pixel.
if (!exists("size")) size = "?"
set datafile separator "\t"
set title sprintf("Samples per pixel: color error against time (ch2 head, %s; 6x6 is the reference)", size)
set xlabel "frame time (s, median of the runs)"
set ylabel "color RMSE against 6x6"
set yrange [0:*]
set grid
set key off
set offsets graph 0.05, graph 0.15, graph 0.15, 0
plot "results/aa.tsv" using 2:3 with linespoints pt 7 ps 1.5, \
     "" using 2:3:(sprintf("%dx%d", $1, $1)) with labels offset char 1, char 1 left
