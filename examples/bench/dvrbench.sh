#!/bin/sh
# dvrbench.sh: dvr's frame time, lit against unshaded (Kniss et al. 2003
# claim lighting costs at most 60% over unshaded rendering).  The MRI head
# (ch2 from mricron-data, or $DATA's copy), 512x512, the transfer function
# of examples/scenes/head-dvr.scn without its surface list (so unshaded is
# the emission-absorption picture, with no gradient), three variants:
#   unshaded       effects none: no light buffer
#   shadows        effects volumetric-shadows: the light buffer
#   shadows+scat   effects volumetric-shadows scattering: the blur too
# each RUNS times, interleaved round by round; the median of the rendering
# time dvr --stats reports (reading the stream and building macrocells
# excluded).  A markdown table on standard output.
#
#   sh dvrbench.sh BIN_DIR RUNS THREADS
set -eu
BIN=${1:-../../bin}
RUNS=${2:-5}
NT=${3:-$(nproc)}
DATA=${DATA:-/work/shared/data}
CH2=/usr/share/mricron/templates/ch2.nii.gz
[ -r "$CH2" ] || CH2=$DATA/ch2_mri_181x217x181_uint8.nii.gz
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
"$BIN/vread" "$CH2" | "$BIN/macrocell" > "$W/ch2.vx"
S=$(dirname "$0")/../scenes/head-dvr.scn
grep -v '^transfer surface' "$S" > "$W/head.scn"
run() {   # run NAME EFFECTS: one render, its seconds appended to W/NAME
	"$BIN/dvr" --scene "$W/head.scn" --size 512x512 -j "$NT" --stats \
	    --effects "$2" -o /dev/null "$W/ch2.vx" 2>&1 |
	    sed -n 's/^dvr: [0-9]* slices, .*, \([0-9.]*\) s$/\1/p' >> "$W/$1"
}
i=0
while [ "$i" -lt "$RUNS" ]; do
	run unshaded none
	run shadows volumetric-shadows
	run scat "volumetric-shadows scattering"
	i=$((i + 1))
done
med() { sort -n "$W/$1" | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
u=$(med unshaded); s=$(med shadows); c=$(med scat)
echo "| dvr, ch2 MRI head 512x512, $NT threads, median of $RUNS | seconds | over unshaded |"
echo "| --- | --- | --- |"
echo "| unshaded (effects none) | $u | |"
awk -v u="$u" -v s="$s" 'BEGIN { printf "| volumetric shadows | %s | %+.0f%% |\n", s, 100 * (s / u - 1) }'
awk -v u="$u" -v s="$c" 'BEGIN { printf "| volumetric shadows + scattering | %s | %+.0f%% |\n", s, 100 * (s / u - 1) }'
