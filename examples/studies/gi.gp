# gi.gp: irradiance shading's relative RMSE against the path-traced
# reference, against the bake time of the texels the view reads, one line a
# lattice scale, from results/gi.tsv (gi.sh, which runs it for PNG and SVG;
# to try a change: gnuplot -e "spp=1024; noise=0.003; gisize='256x256';
# scales='0.5 1 2'" gi.gp, with a terminal and an output set by -e too).
# The dotted line is the issue's 5% goal, the dashed one the reference's
# own noise (off the scale when it is far below the errors).
if (!exists("gisize")) gisize = "?"
if (!exists("spp")) spp = 0
if (!exists("noise")) noise = 0
if (!exists("scales")) scales = "0.5 1 2"
set datafile separator "\t"
set title sprintf("Irradiance volume: error against bake time (ch2 skin, %s; reference %d paths a pixel, its noise %.2f%%)", gisize, spp, 100 * noise)
set xlabel "bake time of the texels the view reads (s, raycast --lazy)"
set ylabel "relative RMSE against the path-traced reference"
set logscale xy
set grid
set key top right
set format y "%.0f%%"
set offsets graph 0.05, graph 0.1, 0, 0
set arrow from graph 0, first 5 to graph 1, first 5 nohead dt 3
set label "goal: 5%" at graph 0.01, first 5 offset 0, char 0.6
if (noise > 0) set arrow from graph 0, first 100 * noise to graph 1, first 100 * noise nohead dt 2
if (noise > 0) set label "the reference's noise" at graph 0.01, first 100 * noise offset 0, char 0.6
# one data block a scale; the points' labels are the samples per texel
plot for [i = 1:words(scales)] "results/gi.tsv" index i - 1 using 5:(100 * $6) \
       with linespoints pt 7 ps 1.2 title sprintf("lattice scale %s", word(scales, i)), \
     for [i = 1:words(scales)] "" index i - 1 using 5:(100 * $6):(sprintf("%d", $2)) \
       with labels offset char 0.8, char (i == words(scales) ? -0.9 : 0.8) left notitle
