#!/bin/sh
# shgi.sh: the convergence of Wyman et al. 2006's Fig. 7: the relative RMSE
# against a converged path-traced reference, as the samples grow, of
#   SH shading      bake-sh --order SHGI_ORDER, N samples a texel, lit by
#                   the environment projected (raycast --set "illumination sh")
#   irradiance      bake-irr, N samples a texel, the same environment
#   path tracing    raycast --set "illumination pathtrace" --spp N
# on the MRI head's skin (iso 40, albedo 0.93 0.78 0.68 x kd 0.9, one
# bounce) lit by Grace Cathedral alone (../shared/data's lat-long map when
# present, else blender-data's courtyard), SHGI_SIZE pixels, seen from the
# side (the ear's occlusion).  The volumes are baked lazily (the texels the
# view reads, equal to the full bake's bit for bit), bake-sh's piped into
# raycast (its lazy stream holds the band's accumulators: gigabytes).
# Columns: the method, N, the paths traced (texels or covered pixels x N),
# the seconds raycast --stats reports for them (wall, one run: the lazy
# bake's, or the path-traced frame's), the relative RMSE over the pixels
# both cover (tests/cli/vximg.py relrmse) and the mean colour over the
# reference's (relmean: below 1 is darker).  The reference's own noise is
# measured from a second one of a quarter of its paths; the reference is
# kept in results/ for the next run of the same settings (make clean drops
# it).  Pictures: results/shgi-METHOD-N.png and results/shgi-ref.png.
. ./common.sh
: "${SHGI_SIZE:=128x128}" "${SHGI_SPP:=4096}" "${SHGI_SAMPLES:=16 64 256}"
: "${SHGI_ORDER:=5}" "${SHGI_INTENSITY:=1.5}"
: "${DATA:=../../../shared/data}"
env=""
for f in "$DATA/grace_latlong_256x128.hdr" \
    /usr/share/blender/datafiles/studiolights/world/courtyard.exr; do
	[ -r "$f" ] && { env=$(cd "$(dirname "$f")" && pwd)/$(basename "$f"); break; }
done
[ -n "$env" ] || { echo "shgi.sh: no environment map (make deps)" >&2; exit 66; }
envname=$(basename "$env" | sed 's/_.*//; s/\..*//')
scene=results/shgi.scn
cat > "$scene" <<SCN
voxlux-scene 1
camera auto view left distance 1.1 fov 30
image width ${SHGI_SIZE%x*} height ${SHGI_SIZE#*x}
background color 0.02 0.02 0.03
light environment file $env intensity $SHGI_INTENSITY
surface iso 40 color 0.93 0.78 0.68 kd 0.9
interreflection bounces 1 samples 32
effects shadows interreflection
illumination irradiance
SCN
vximg() { python3 ../../tests/cli/vximg.py "$@"; }
R() { raycast --scene "$scene" --hdr "$@"; }
pt() { R --set "illumination pathtrace" --spp "$1" --stats results/head.vx; }
# secs FILE: the frame's seconds from raycast --stats
secs() { sed -n 's/^raycast: [0-9]*x[0-9]*, [0-9]* threads*, \([0-9.]*\) s.*/\1/p' "$1"; }
ref=results/shgi-ref-$envname-$SHGI_SIZE-$SHGI_SPP.vx
[ -s "$ref" ] || { pt "$SHGI_SPP" > "$ref.tmp" 2>/dev/null && mv "$ref.tmp" "$ref"; }
pt $((SHGI_SPP / 4)) > results/shgi-ref4.vx 2>/dev/null
# ref4 - ref holds the noise of both: sigma4^2 (1 + 1/4); ref's is sigma4 / 2
noise=$(vximg relrmse "$ref" results/shgi-ref4.vx | awk '{ printf "%.5f", $1 / sqrt(1.25) / 2 }')
tonemap -o results/shgi-ref.png "$ref"
printf '# method\tsamples\tpaths\tseconds\trelrmse\trelmean\n' > results/shgi.tsv
row() {         # row METHOD N IMAGE PATHS SECONDS
	tonemap -o "results/shgi-$1-$2.png" "$3"
	printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$4" "$5" \
	    "$(vximg relrmse "$ref" "$3")" "$(vximg relmean "$ref" "$3")" \
	    >> results/shgi.tsv
}
# lazy: "lazy: the view reads T texels: B baked now (P paths, S s)"
lazy() { sed -n 's/.*lazy: the view reads [0-9]* texels: [0-9]* baked now (\([0-9]*\) paths, \([0-9.]*\) s).*/\1 \2/p' "$1"; }
for n in $SHGI_SAMPLES; do
	bake-sh --scene "$scene" --order "$SHGI_ORDER" --samples "$n" --lazy \
	    results/head.vx | R --set "illumination sh" --lazy --stats - \
	    2> results/shgi.err | python3 dropchunks.py SHTV > results/shgi-img.vx
	set -- $(lazy results/shgi.err)
	row sh "$n" results/shgi-img.vx "$1" "$2"
done
printf '\n\n' >> results/shgi.tsv
for n in $SHGI_SAMPLES; do
	bake-irr --scene "$scene" --samples "$n" --lazy results/head.vx |
	    R --lazy --stats - 2> results/shgi.err |
	    python3 dropchunks.py IRRV > results/shgi-img.vx
	set -- $(lazy results/shgi.err)
	row irr "$n" results/shgi-img.vx "$1" "$2"
done
printf '\n\n' >> results/shgi.tsv
for n in $SHGI_SAMPLES; do
	pt "$n" > results/shgi-img.vx 2> results/shgi.err
	p=$(sed -n 's/.*pathtrace: \([0-9]*\) paths.*/\1/p' results/shgi.err)
	row pathtrace "$n" results/shgi-img.vx "$p" "$(secs results/shgi.err)"
done
rm -f results/shgi-img.vx results/shgi-ref4.vx results/shgi.err
printf '%s\n' "$noise" > results/shgi-noise.txt
for t in "pngcairo size 800,500 font ',10'; set output 'results/shgi.png'" \
    "svg size 800,500 font ',10' background '#ffffff'; set output 'results/shgi.svg'"; do
	gnuplot -e "spp=$SHGI_SPP; noise=$noise; envname='$envname'; shsize='$SHGI_SIZE'; order=$SHGI_ORDER" \
	    -e "set terminal $t" shgi.gp
done
cat results/shgi.tsv
echo "shgi.sh: the reference's own relative noise: $noise"
