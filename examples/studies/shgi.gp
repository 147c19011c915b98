# shgi.gp: Wyman et al. 2006's Fig. 7: relative RMSE against the
# path-traced reference of SH shading, irradiance shading and path tracing
# against the samples (a texel's for the baked volumes, a pixel's for path
# tracing), from results/shgi.tsv (shgi.sh, which runs it for PNG and SVG;
# to try a change: gnuplot -e "spp=4096; noise=0.003; envname='grace';
# shsize='128x128'; order=5" shgi.gp, with a terminal and an output set by
# -e too).  The dashed line is the reference's own noise.
if (!exists("shsize")) shsize = "?"
if (!exists("envname")) envname = "?"
if (!exists("spp")) spp = 0
if (!exists("noise")) noise = 0
if (!exists("order")) order = 5
set datafile separator "\t"
set title sprintf("Convergence (Wyman et al. Fig. 7): ch2 skin under %s, %s; reference %d paths a pixel, its noise %.2f%%", envname, shsize, spp, 100 * noise)
set xlabel "samples (a texel's for SH and irradiance, a pixel's for path tracing)"
set ylabel "relative RMSE against the reference"
set logscale xy
set grid
set key top right
set format y "%g%%"
set offsets graph 0.05, graph 0.1, 0, 0
if (noise > 0) set arrow from graph 0, first 100 * noise to graph 1, first 100 * noise nohead dt 2
if (noise > 0) set label "the reference's noise" at graph 0.01, first 100 * noise offset 0, char 0.6
plot "results/shgi.tsv" index 0 using 2:(100 * $5) with linespoints pt 7 ps 1.2 title sprintf("SH order %d (bake-sh)", order), \
     "" index 1 using 2:(100 * $5) with linespoints pt 5 ps 1.2 title "irradiance (bake-irr)", \
     "" index 2 using 2:(100 * $5) with linespoints pt 9 ps 1.2 title "path tracing (--spp)"
