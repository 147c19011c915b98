#!/bin/sh
# sh.sh: spherical-harmonic lighting (sh-rotate) against exact quadrature.
# For each light probe under ../../../shared/data (when present) and each
# blender-data environment: the relative RMS error of the irradiance of the
# order-n SH lighting against the exact quadrature of the map's pixels at
# 256 normals (sh-rotate --irradiance-error), n = 1..10, and the time of the
# projection and of a rotation at each order (sh-rotate --stats, median of
# RUNS).  Then Grace Cathedral's nine coefficients beside Ramamoorthi and
# Hanrahan's published ones, and Grace rebuilt at orders 3 and 10 as PNGs.
set -eu
: "${BIN:=../../bin}" "${RUNS:=5}" "${SIZE:=384x384}"
: "${DATA:=../../../shared/data}"   # the repository's ../shared/data
PATH="$BIN:$PATH"
mkdir -p results
command -v gnuplot >/dev/null || { echo "studies: gnuplot: missing (make deps)" >&2; exit 69; }
W=${WORLD:-/usr/share/blender/datafiles/studiolights/world}   # WORLD=: another folder of .exr maps

maps=""
for p in grace uffizi ennis pisa wells; do
	f="$DATA/${p}_latlong_256x128.hdr"
	[ -r "$f" ] && maps="$maps $p=$f"
done
if [ -r "$DATA/forest_latlong_1024x512.pfm.gz" ]; then
	gzip -dc "$DATA/forest_latlong_1024x512.pfm.gz" > results/forest-probe.pfm
	maps="$maps forest-probe=results/forest-probe.pfm"
fi
for f in "$W"/*.exr; do
	[ -r "$f" ] && maps="$maps blender-$(basename "$f" .exr)=$f"
done
[ -n "$maps" ] || { echo "studies: no environment maps (blender-data)" >&2; exit 66; }

# med FILE: the median of the numbers in FILE
med() { sort -g "$1" | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

names=""
for m in $maps; do names="$names ${m%%=*}"; done
printf 'map\torder\tirr_rms\tirr_max\tproject_s\trotate_s\n' > results/sh.tsv
for m in $maps; do
	name=${m%%=*}; f=${m#*=}
	for n in 1 2 3 4 5 6 7 8 9 10; do
		e=$(sh-rotate --env "$f" --order $n --irradiance-error)
		: > results/.tp; : > results/.tr; i=0
		while [ $i -lt "$RUNS" ]; do
			sh-rotate --env "$f" --order $n --euler 30,40,50 --stats \
			    -o /dev/null 2>&1 | sed -n 's/.*projection \([0-9.]*\) s.*rotation \([0-9.]*\) s/\1 \2/p' > results/.t
			cut -d' ' -f1 results/.t >> results/.tp
			cut -d' ' -f2 results/.t >> results/.tr
			i=$((i + 1))
		done
		printf '%s\t%d\t%s\t%s\t%s\t%s\n' "$name" $n \
		    "$(echo "$e" | awk '{ print $4 }')" "$(echo "$e" | awk '{ print $6 }')" \
		    "$(med results/.tp)" "$(med results/.tr)" >> results/sh.tsv
	done
	printf '\n\n' >> results/sh.tsv      # gnuplot: one block per map
done
gnuplot -e "names='$names'; set terminal pngcairo size 900,500 font ',10'; set output 'results/sh.png'" sh.gp
gnuplot -e "names='$names'; set terminal svg size 900,500 font ',10' background '#ffffff'; set output 'results/sh.svg'" sh.gp

# Grace Cathedral: our nine L_lm beside the published ones
g="$DATA/grace_latlong_256x128.hdr"
csv="$DATA/ramamoorthi_hanrahan_sh9_irradiance.csv"
if [ -r "$g" ] && [ -r "$csv" ]; then
	sh-rotate --env "$g" --order 3 --irradiance | grep '^L' > results/.ours
	grep '^grace_cathedral,' "$csv" | cut -d, -f2- | tr , ' ' > results/.pub
	{ printf 'coef\tours_r\tours_g\tours_b\tpub_r\tpub_g\tpub_b\n'
	  paste -d' ' results/.ours results/.pub | awk '{ printf "%s\t%.4f\t%.4f\t%.4f\t%s\t%s\t%s\n", $1, $2, $3, $4, $6, $7, $8 }'
	} > results/sh-grace.tsv
	# reconstructions at orders 3 and 10 beside the map itself
	tonemap -o results/sh-grace-orig.png "$g"
	for n in 3 10; do
		sh-rotate --env "$g" --order $n --reconstruct results/sh-grace-$n.pfm --width 256 --height 128
		tonemap -o results/sh-grace-$n.png results/sh-grace-$n.pfm
	done
	cat results/sh-grace.tsv
fi
awk -F'\t' 'NR == 1 || $2 == 2 || $2 == 3 || $2 == 5 || $2 == 10' results/sh.tsv
