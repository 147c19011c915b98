#!/bin/sh
# pixcheck.sh: render a fixed set of raycast and mip pictures (colour as a
# float IMAG stream, depth and normals as PFM) and save them, or compare them bit for bit with a
# saved set.  For optimizations that must not change a single bit:
#
#   sh examples/bench/pixcheck.sh save DIR     before the change (bin/ built)
#   sh examples/bench/pixcheck.sh check DIR    after: prints each differing file,
#                                              exits 1 if any differs
#
# Run from the repository root after `make`.  Data: synthetic fields, the
# Debian MRI head (/usr/share/mricron/templates/ch2.nii.gz) and, when present,
# the Visible Human head CT of ../shared/data (VHF=path to override).  The
# cases cover both sample types of the real data and f32, bricked and linear
# layouts, flat and hierarchical walks, 1 and 2 threads, the three root
# solvers, shadows, transparent layers, several macrocell sizes, perspective,
# orthographic and named views.  PIXCHECK_QUICK=1 leaves the CT out.
set -eu
mode=${1:-}
dir=${2:-}
case $mode in save|check) ;; *) echo "usage: pixcheck.sh save|check DIR" >&2; exit 64;; esac
[ -n "$dir" ] || { echo "pixcheck.sh: no DIR" >&2; exit 64; }
B=${VX_BIN:-bin}
CH2=/usr/share/mricron/templates/ch2.nii.gz
VHF=${VHF:-/work/shared/data/vhf_head_ct_512x512x234_int16le.raw.gz}
[ -r "$VHF" ] && [ -z "${PIXCHECK_QUICK:-}" ] || VHF=
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$dir"
out=$work/out
mkdir -p "$out"

# streams
"$B/vread" "$CH2" > "$work/ch2-l.vx"
"$B/brick" < "$work/ch2-l.vx" | "$B/macrocell" > "$work/ch2-b.vx"
"$B/macrocell" < "$work/ch2-l.vx" > "$work/ch2-lm.vx"
"$B/brick" < "$work/ch2-l.vx" | "$B/macrocell" --sizes 8x8x8,8x8x8 > "$work/ch2-b8.vx"
"$B/brick" < "$work/ch2-l.vx" | "$B/macrocell" --sizes 4x4x4,4x4x4,4x4x4 > "$work/ch2-b444.vx"
"$B/vread" --synth ml --size 41 | "$B/brick" | "$B/macrocell" > "$work/ml.vx"
"$B/vread" --synth torus --size 33,29,37 | "$B/macrocell" > "$work/torus.vx"
if [ -n "$VHF" ]; then
	"$B/vread" --raw 512,512,234 --type i16 "$VHF" | "$B/brick" | "$B/macrocell" > "$work/vhf-b.vx"
fi

S=examples/scenes
HL=$S/iso-headlight.scn
. "$(dirname "$0")/cameras.sh"
CAM=$CAM_CH2
VCAM=$CAM_VHF
n=0
rc() {   # rc NAME STREAM ARGS...: raycast colour, depth, normals
	name=$1 stream=$2
	shift 2
	"$B/raycast" --hdr --depth "$out/$name.depth.pfm" \
	    --normals "$out/$name.normals.pfm" -o "$out/$name.vx" "$@" "$stream"
	n=$((n + 1))
}
mp() {   # mp NAME STREAM ARGS...: mip value and depth
	name=$1 stream=$2
	shift 2
	"$B/mip" --hdr --depth "$out/$name.depth.pfm" -o "$out/$name.vx" "$@" "$stream"
	n=$((n + 1))
}

for j in 1 2; do
	rc ch2-127-j$j "$work/ch2-b.vx" --scene $HL --set "$CAM" --iso 127.5 --size 256x256 -j $j
done
rc ch2-40-lin "$work/ch2-lm.vx" --scene $HL --set "$CAM" --iso 40.5 --size 256x256
rc ch2-40-flat "$work/ch2-b.vx" --scene $HL --set "$CAM" --iso 40.5 --size 160x160 --flat
rc ch2-127-s8 "$work/ch2-b8.vx" --scene $HL --set "$CAM" --iso 127.5 --size 256x256
rc ch2-127-s444 "$work/ch2-b444.vx" --scene $HL --set "$CAM" --iso 127.5 --size 256x256
rc ch2-int "$work/ch2-b.vx" --scene $HL --set "$CAM" --iso 127 --size 256x256
for sv in neubauer linear; do
	rc ch2-$sv "$work/ch2-b.vx" --scene $HL --set "$CAM" --iso 90.5 --size 200x200 --solver $sv
done
rc head "$work/ch2-b.vx" --scene $S/head.scn --size 320x240 -j 2
rc layers "$work/ch2-b.vx" --scene $S/head-layers.scn --size 320x240
rc layers-lin "$work/ch2-lm.vx" --scene $S/head-layers.scn --size 200x150 --view left
rc ortho "$work/ch2-b.vx" --scene $S/head.scn --size 200x200 --ortho --view top
rc multi "$work/ch2-b.vx" --scene $HL --iso 40.5,90.5,127.5 --size 200x200 --view 30,20
rc ml "$work/ml.vx" --iso 0.5 --size 200x200 --view 20,30
rc ml-flat "$work/ml.vx" --iso 0.5 --size 120x120 --view 20,30 --flat
rc torus "$work/torus.vx" --iso 0.25,0.4 --size 200x200 --view 40,60 --effects shadows
mp mip-front "$work/ch2-b.vx" --size 200x200 --view front
mp mip-obl "$work/ch2-b.vx" --size 200x200 --view 33,21 -j 2
mp mip-ml "$work/ml.vx" --size 160x160 --view 20,30
if [ -n "$VHF" ]; then
	rc vhf-600 "$work/vhf-b.vx" --scene $HL --set "$VCAM" --iso 600.5 --size 256x256
	rc vhf-1224 "$work/vhf-b.vx" --scene $HL --set "$VCAM" --iso 1224.5 --size 256x256 -j 2
	mp vhf-mip "$work/vhf-b.vx" --size 200x200 --view front
fi

bad=0
for f in "$out"/*; do
	b=$(basename "$f")
	if [ "$mode" = save ]; then
		cp "$f" "$dir/$b"
		continue
	fi
	case $b in
	*.vx) same=$(python3 tests/cli/vximg.py same "$f" "$dir/$b" 2>&1 || true)
	      [ "$same" = same ] ;;   # the IMAG chunks (the history differs)
	*) cmp -s "$f" "$dir/$b" ;;
	esac || { echo "pixcheck: $b differs"; bad=1; }
done
nf=$(ls "$out" | wc -l)
if [ "$mode" = save ]; then
	echo "pixcheck: saved $nf images of $n renders in $dir"
elif [ $bad = 0 ]; then
	echo "pixcheck: all $nf images of $n renders bit-identical"
fi
exit $bad
