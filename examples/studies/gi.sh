#!/bin/sh
# gi.sh: irradiance shading (Wyman et al. 2006) against its bake time: the
# relative RMSE of the irradiance-shaded MRI head (examples/scenes/
# head-gi-sky.scn: sky, key light with shadows, one bounce) against the
# path-traced reference (raycast --set "illumination pathtrace" --spp
# GI_SPP), over the pixels both cover, for samples per texel GI_SAMPLES and
# lattice scales GI_SCALES.  Each irradiance volume is baked lazily (raycast
# --lazy: the texels this view reads, which equal the full bake's bit for
# bit); its bake time is the one raycast --stats reports for them (wall
# seconds, one run: the bake of the whole skin band costs about 11 times as
# much at scale 1).  The reference's own noise is measured from a second
# reference of a quarter of the paths.  The reference is kept in results/
# for the next run of the same GI_SIZE and GI_SPP (make clean drops it).
. ./common.sh
scene=../scenes/head-gi-sky.scn
: "${GI_SIZE:=256x256}" "${GI_SPP:=1024}" "${GI_SAMPLES:=4 16 64 256}"
: "${GI_SCALES:=0.5 1 2}"
R() { raycast --scene "$scene" --size "$GI_SIZE" --hdr "$@"; }
relrmse() { python3 ../../tests/cli/vximg.py relrmse "$1" "$2"; }
[ -s "results/gi-ref-$GI_SIZE-$GI_SPP.vx" ] ||
	R --set "illumination pathtrace" --spp "$GI_SPP" results/head.vx \
	    > "results/gi-ref-$GI_SIZE-$GI_SPP.vx" 2>/dev/null
ref=results/gi-ref-$GI_SIZE-$GI_SPP.vx
R --set "illumination pathtrace" --spp $((GI_SPP / 4)) results/head.vx \
    > results/gi-ref4.vx 2>/dev/null
# ref4 - ref holds the noise of both: sigma4^2 (1 + 1/4); ref's is sigma4 / 2
noise=$(relrmse "$ref" results/gi-ref4.vx | awk '{ printf "%.5f", $1 / sqrt(1.25) / 2 }')
printf '# scale\tsamples\ttexels\tpaths\tbake_seconds\trelrmse\n' > results/gi.tsv
for sc in $GI_SCALES; do
	for n in $GI_SAMPLES; do
		bake-irr --scene "$scene" --scale "$sc" --samples "$n" --lazy \
		    results/head.vx > results/gi-lazy.vx 2>/dev/null
		R --lazy --stats results/gi-lazy.vx > results/gi-irr.vx 2> results/gi.err
		# "lazy: the view reads T texels: B baked now (P paths, S s)"
		sed -n 's/.*lazy: the view reads \([0-9]*\) texels: [0-9]* baked now (\([0-9]*\) paths, \([0-9.]*\) s).*/\1\t\2\t\3/p' \
		    results/gi.err > results/.lazy
		[ -s results/.lazy ] || { echo "gi.sh: no lazy line from raycast" >&2; exit 70; }
		printf '%s\t%s\t%s\t%s\n' "$sc" "$n" "$(cat results/.lazy)" \
		    "$(relrmse "$ref" results/gi-irr.vx)" >> results/gi.tsv
	done
	printf '\n\n' >> results/gi.tsv      # one gnuplot data block a scale
done
rm -f results/gi-lazy.vx results/gi-ref4.vx results/gi.err results/.lazy
printf '%s\n' "$noise" > results/gi-noise.txt
gnuplot -e "spp=$GI_SPP; noise=$noise; gisize='$GI_SIZE'; scales='$GI_SCALES'" -e "size='$SIZE'; set terminal pngcairo size 800,500 font ',10'; set output 'results/gi.png'" gi.gp
gnuplot -e "spp=$GI_SPP; noise=$noise; gisize='$GI_SIZE'; scales='$GI_SCALES'" -e "size='$SIZE'; set terminal svg size 800,500 font ',10' background '#ffffff'; set output 'results/gi.svg'" gi.gp
cat results/gi.tsv
echo "gi.sh: the reference's own relative noise: $noise"
