#!/bin/sh
# test_pixsum.sh: picture checksums.  A fixed set of renders (volumes and
# tet meshes, linear and bricked, flat and hierarchical walks, every root
# solver, shadows, transparent layers, textures, several macrocell sizes,
# perspective and orthographic cameras, 1 and 2 threads, MIP, depth and
# normals, direct volume rendering) is written as PFM and its SHA-256 compared with
# tests/cli/pixsums.txt.  Any change of a single bit in any picture fails
# here: a change meant to alter pictures rewrites the list with
#     VX_PIXSUM_WRITE=1 sh tests/cli/test_pixsum.sh
# (and says why in its commit).  The oracle is the committed list: the
# pictures it was made from were checked against the analytic tests of
# test_raycast.sh, test_tet.sh and the mip tests.
. "$(dirname "$0")/lib.sh"
SUMS=$(cd "$(dirname "$0")" && pwd)/pixsums.txt
CH2=/usr/share/mricron/templates/ch2.nii.gz
S=examples/scenes
HL=$S/iso-headlight.scn
. examples/bench/cameras.sh
out=$T/out; mkdir -p "$out"

if ! command -v sha256sum >/dev/null 2>&1; then
	skip "picture checksums" "no sha256sum"; done_testing; exit
fi
# streams: synthetic fields always, the Debian MRI head when installed
vread --synth ml --size 41 | brick | macrocell > "$T/ml.vx"
vread --synth torus --size 33,29,37 | macrocell > "$T/torus.vx"
vread --synth sphere --size 24 > "$T/sph.vx"
vread --synth linear --size 24 --name tex --add "$T/sph.vx" | macrocell > "$T/tex.vx"
vread --synth sphere --size 16 --split 5 | macrocell > "$T/s5.vx"
vread --synth torus --size 17 --split 6 > "$T/t6.vx"
vread --synth linear --size 16 --name tex --add "$T/s5.vx" > "$T/s5tex.vx"
have_ch2=
if [ -r "$CH2" ]; then
	have_ch2=1
	vread "$CH2" > "$T/ch2-l.vx"
	brick < "$T/ch2-l.vx" | macrocell > "$T/ch2-b.vx"
	macrocell < "$T/ch2-l.vx" > "$T/ch2-lm.vx"
	brick < "$T/ch2-l.vx" | macrocell --sizes 4x4x4,4x4x4,4x4x4 > "$T/ch2-b444.vx"
fi

names=""
rc() {   # rc NAME STREAM ARGS...: colour, depth, normals as PFM
	name=$1 stream=$2; shift 2
	raycast --hdr --depth "$out/$name.depth.pfm" --normals "$out/$name.normals.pfm" \
	    "$@" "$stream" | tonemap --pfm -o "$out/$name.pfm" - || echo "$name: failed" >&2
	names="$names $name.pfm $name.depth.pfm $name.normals.pfm"
}
mp() {   # mp NAME STREAM ARGS...: value and depth as PFM
	name=$1 stream=$2; shift 2
	mip --hdr --depth "$out/$name.depth.pfm" "$@" "$stream" \
	    | tonemap --pfm -o "$out/$name.pfm" - || echo "$name: failed" >&2
	names="$names $name.pfm $name.depth.pfm"
}
dv() {   # dv NAME STREAM ARGS...: dvr's colour over the background as PFM
	name=$1 stream=$2; shift 2
	dvr --pfm "$out/$name.pfm" -o /dev/null "$@" "$stream" || echo "$name: failed" >&2
	names="$names $name.pfm"
}
rc ml "$T/ml.vx" --iso 0.5 --size 96x96 --view 20,30
rc ml-flat "$T/ml.vx" --iso 0.5 --size 64x64 --view 20,30 --flat
rc ml-neubauer "$T/ml.vx" --iso 0.5 --size 64x64 --view 20,30 --solver neubauer
rc ml-linear "$T/ml.vx" --iso 0.5 --size 64x64 --view 20,30 --solver linear
rc torus "$T/torus.vx" --iso 0.25,0.4 --size 96x96 --view 40,60 --effects shadows -j 2
rc torus-ortho "$T/torus.vx" --iso 0.3 --size 64x64 --view top --ortho --aa 2
rc tex "$T/tex.vx" --iso 0.5 --size 64x64 --set "surface iso 0.5 ks 0 texture tex window -1.5 0.5"
rc mesh5 "$T/s5.vx" --iso 0.6 --size 64x64 --view 30,20 \
    --light "directional direction 1 1 -1 shadows on"
rc mesh6 "$T/t6.vx" --iso 0.3 --size 64x64 --view 10,50 -j 2
rc mesh-tex "$T/s5tex.vx" --iso 0.6 --name density --size 64x64 \
    --set "surface iso 0.6 ks 0 texture tex window -1.5 0.5"
mp mip-ml "$T/ml.vx" --size 64x64 --view 20,30
mp mip-ml-front "$T/ml.vx" --size 64x64 --view front -j 2
dv dvr-torus "$T/torus.vx" --size 64x64 --view 40,60 --light-size 64 -j 2 \
    --set "transfer opacity 0 0.3 0.3 0.1 0.45 0" \
    --set "transfer transport 0 0.9 0.7 0.5 0.45 1 1 1" \
    --set "medium phase henyey-greenstein g 0.4" \
    --light "directional direction 1 0.5 -1" --effects "volumetric-shadows scattering"
dv dvr-ml-ortho "$T/ml.vx" --size 64x64 --view 20,30 --ortho --light-size 48 \
    --set "transfer opacity 0 0 0.45 0 0.55 0.4 1 0.4" --set "transfer surface 0 1" \
    --set "transfer color 0 0.2 0.5 1 1 1 0.6 0.3" --set "light point position 2 -3 2" \
    --effects "volumetric-shadows specular"
# the cloud of examples/cloud, small: dvr's perturbation (coordinates and
# density) with volumetric shadows and scattering
vread --synth sphere --size 32,32,20 --spacing 0.1,0.1,0.1 --origin -1.55,-1.55,-0.95 \
    | macrocell --levels 1 --sizes 2x2x2 > "$T/blob.vx"
dv dvr-cloud "$T/blob.vx" --scene examples/cloud/cloud.scn --size 64x44 --slices 48 \
    --light-size 48 -j 2
if [ -n "$have_ch2" ]; then
	rc ch2-127-j1 "$T/ch2-b.vx" --scene $HL --set "$CAM_CH2" --iso 127.5 --size 128x128 -j 1
	rc ch2-127-j2 "$T/ch2-b.vx" --scene $HL --set "$CAM_CH2" --iso 127.5 --size 128x128 -j 2
	rc ch2-40-lin "$T/ch2-lm.vx" --scene $HL --set "$CAM_CH2" --iso 40.5 --size 128x128
	rc ch2-40-flat "$T/ch2-b.vx" --scene $HL --set "$CAM_CH2" --iso 40.5 --size 96x96 --flat
	rc ch2-444 "$T/ch2-b444.vx" --scene $HL --set "$CAM_CH2" --iso 127.5 --size 128x128
	rc ch2-neubauer "$T/ch2-b.vx" --scene $HL --set "$CAM_CH2" --iso 90.5 --size 96x96 --solver neubauer
	rc head "$T/ch2-b.vx" --scene $S/head.scn --size 160x120 -j 2
	rc layers "$T/ch2-b.vx" --scene $S/head-layers.scn --size 160x120
	rc ortho "$T/ch2-b.vx" --scene $S/head.scn --size 96x96 --ortho --view top
	mp mip-ch2 "$T/ch2-b.vx" --size 96x96 --view 33,21 -j 2
	dv dvr-head "$T/ch2-b.vx" --scene $S/head-dvr.scn --size 96x96 --light-size 96 -j 2
fi

if [ -n "${VX_PIXSUM_WRITE:-}" ]; then
	(cd "$out" && sha256sum $names) > "$SUMS"
	echo "# wrote $(wc -l < "$SUMS") checksums to $SUMS"
	ok "checksums written"
	done_testing; exit
fi
for f in $names; do
	want=$(awk -v f="$f" '$2 == f { print $1 }' "$SUMS")
	if [ -z "$want" ]; then
		not_ok "checksum of $f" "not in $SUMS"
		continue
	fi
	got=$(sha256sum < "$out/$f" | cut -d' ' -f1)
	check_eq "picture checksum $f" "$got" "$want"
done
if [ -z "$have_ch2" ]; then
	skip "the MRI head's pictures" "mricron-data not installed"
fi
done_testing
