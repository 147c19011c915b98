#!/bin/sh
# examples/sh-turn.sh: relightable global illumination (Wyman et al. 2006,
# §4.1.2): the MRI head's skin baked once into an SH transfer volume
# (bake-sh: visibility and one bounce, order 5, half precision), then an
# environment turned about the vertical axis in steps, each frame one
# `sh-rotate | raycast` away without baking again.  Prints the bake's and
# every frame's time.
#
#   sh examples/sh-turn.sh [ENVIRONMENT] [FRAMES]
#
# ENVIRONMENT: a lat-long map (.hdr, .pfm, .exr); default Grace Cathedral
# where the shared data is, else Blender's CC0 courtyard (make deps).
# Knobs (environment): VX_SAMPLES (paths a texel, 64), VX_ORDER (5),
# VX_SIZE (frame size, 512x512), VX_BIN, VX_DEMO_OUT.
set -eu
bin=${VX_BIN:-bin}
head=/usr/share/mricron/templates/ch2.nii.gz
out=${VX_DEMO_OUT:-examples/out}
env=${1:-}
frames=${2:-12}
samples=${VX_SAMPLES:-64}
order=${VX_ORDER:-5}
size=${VX_SIZE:-512x512}
if [ -z "$env" ]; then
	for f in ../shared/data/grace_latlong_256x128.hdr \
	    /usr/share/blender/datafiles/studiolights/world/courtyard.exr; do
		[ -r "$f" ] && { env=$f; break; }
	done
fi
[ -r "$head" ] || { echo "sh-turn: $head: missing (run: make deps)" >&2; exit 66; }
[ -n "$env" ] && [ -r "$env" ] || { echo "sh-turn: no environment map (give one)" >&2; exit 66; }
mkdir -p "$out"
PATH="$bin:$PATH"
now() { date +%s.%N; }
t0=$(now)
vread "$head" | brick | macrocell |
    bake-sh --iso 40 --set "surface iso 40 color 0.93 0.78 0.68 kd 0.9" \
        --bounces 1 --order "$order" --samples "$samples" --half --stats \
        -o "$out/ch2-sh.vx"
t1=$(now)
echo "sh-turn: bake $(awk "BEGIN { print $t1 - $t0 }") s (order $order, $samples samples a texel)"
k=0
while [ "$k" -lt "$frames" ]; do
	deg=$((k * 360 / frames))
	f=$(printf '%s/head-sh-%03d.png' "$out" "$deg")
	a=$(now)
	sh-rotate --env "$env" --order "$order" --axis 0,0,1,"$deg" "$out/ch2-sh.vx" |
	    raycast --iso 40 --set "surface iso 40 color 0.93 0.78 0.68 kd 0.9" \
	        --set "illumination sh" --size "$size" -o "$f"
	b=$(now)
	echo "sh-turn: frame $deg degrees: $(awk "BEGIN { print $b - $a }") s -> $f"
	k=$((k + 1))
done
