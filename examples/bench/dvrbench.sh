#!/bin/sh
# dvrbench.sh: dvr's frame time, lit against unshaded (Kniss et al. 2003
# claim lighting costs at most 60% over unshaded rendering).  The MRI head
# (ch2 from mricron-data, or $DATA's copy), 512x512, the transfer function
# of examples/scenes/head-dvr.scn without its surface list (so unshaded is
# the emission-absorption picture, with no gradient), three variants:
#   unshaded       effects none: no light buffer
#   shadows        effects volumetric-shadows: the light buffer
#   shadows+scat   effects volumetric-shadows scattering: the blur too
# each RUNS times, interleaved round by round; the median and the minimum
# of the rendering time dvr --stats reports (reading the stream and
# building macrocells excluded; on a shared machine the minimum is the
# closer to the unloaded time).  A markdown table on standard output.
#
#   sh dvrbench.sh BIN_DIR RUNS THREADS
set -eu
BIN=${1:-../../bin}
RUNS=${2:-5}
NT=${3:-$(nproc)}
SIZE=${SIZE:-512x512}
DATA=${DATA:-/work/shared/data}
CH2=/usr/share/mricron/templates/ch2.nii.gz
[ -r "$CH2" ] || CH2=$DATA/ch2_mri_181x217x181_uint8.nii.gz
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
"$BIN/vread" "$CH2" | "$BIN/macrocell" > "$W/ch2.vx"
S=$(dirname "$0")/../scenes/head-dvr.scn
grep -v '^transfer surface' "$S" > "$W/head.scn"
run() {   # run NAME EFFECTS: one render, its seconds appended to W/NAME
	"$BIN/dvr" --scene "$W/head.scn" --size "$SIZE" -j "$NT" --stats \
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
low() { sort -n "$W/$1" | head -1; }
echo "| dvr, ch2 MRI head $SIZE, $NT threads, $RUNS runs | median s | over unshaded | minimum s | over unshaded |"
echo "| --- | --- | --- | --- | --- |"
for v in unshaded shadows scat; do
	case $v in
	unshaded) what="unshaded (effects none)" ;;
	shadows) what="volumetric shadows" ;;
	scat) what="volumetric shadows + scattering" ;;
	esac
	awk -v w="$what" -v m="$(med $v)" -v mu="$(med unshaded)" \
	    -v l="$(low $v)" -v lu="$(low unshaded)" 'BEGIN {
		if (m == mu) printf "| %s | %s | | %s | |\n", w, m, l
		else printf "| %s | %s | %+.0f%% | %s | %+.0f%% |\n", w, m,
		    100 * (m / mu - 1), l, 100 * (l / lu - 1) }'
done
