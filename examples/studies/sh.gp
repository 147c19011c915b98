# sh.gp: irradiance error of order-n SH lighting against exact quadrature,
# one line per environment map, from results/sh.tsv (sh.sh).
set datafile separator "\t"
set title "SH lighting: irradiance error against exact quadrature (256 normals)"
set xlabel "SH order n (bands 0 .. n-1)"
set ylabel "relative RMS irradiance error"
set logscale y
set grid
set key outside right
set xrange [0.5:10.5]
if (!exists("names")) names = ""
plot for [i=1:words(names)] "results/sh.tsv" index i-1 using 2:3 \
     with linespoints title word(names, i)
