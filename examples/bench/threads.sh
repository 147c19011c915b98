#!/bin/sh
# threads.sh: thread scaling of dvr (ch2 512x512: unshaded, volumetric
# shadows + scattering, and examples/scenes/head-dvr.scn) and of bake-irr
# (the ch2 band under head-gi-sky.scn, 4 samples) at 1, 2, 4, ... THREADS.
# dvr: each time as --stats reports it (the frame, reading excluded),
# RUNS times; bake-irr: its --stats lines (the bake phase and paths per
# core-second).  Meant for a machine with many cores.
#
#   sh threads.sh BIN_DIR [THREADS [RUNS]]
#
# RUN, if set, prefixes every command (for binaries carried with their
# own loader: RUN="lib/ld-linux-x86-64.so.2 --library-path lib").
set -eu
BIN=${1:-../../bin}
MAXT=${2:-$(nproc)}
RUNS=${3:-3}
RUN=${RUN:-}
DATA=${DATA:-/work/shared/data}
CH2=/usr/share/mricron/templates/ch2.nii.gz
[ -r "$CH2" ] || CH2=$DATA/ch2_mri_181x217x181_uint8.nii.gz
S=$(cd "$(dirname "$0")/../scenes" && pwd)
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
if [ -n "${CH2VX:-}" ]; then cp "$CH2VX" "$W/ch2.vx"; else
	$RUN "$BIN/vread" "$CH2" | $RUN "$BIN/macrocell" > "$W/ch2.vx"; fi
grep -v '^transfer surface' "$S/head-dvr.scn" > "$W/head.scn"
ts() { j=1; while [ "$j" -le "$MAXT" ]; do echo "$j"; j=$((j * 2)); done; }
frame() { sed -n 's/^dvr: [0-9]* slices, .*, \([0-9.]*\) s$/\1/p'; }
for what in unshaded lit scene; do
	for j in $(ts); do
		r=0
		while [ "$r" -lt "$RUNS" ]; do
			case $what in
			unshaded) $RUN "$BIN/dvr" --scene "$W/head.scn" -j "$j" \
			    --stats --effects none -o /dev/null "$W/ch2.vx" ;;
			lit) $RUN "$BIN/dvr" --scene "$W/head.scn" -j "$j" \
			    --stats --effects "volumetric-shadows scattering" \
			    -o /dev/null "$W/ch2.vx" ;;
			scene) $RUN "$BIN/dvr" --scene "$S/head-dvr.scn" -j "$j" \
			    --stats -o /dev/null "$W/ch2.vx" ;;
			esac 2>&1 | frame | sed "s/^/dvr $what j$j /"
			r=$((r + 1))
		done
	done
done
for j in $(ts); do
	$RUN "$BIN/bake-irr" --scene "$S/head-gi-sky.scn" --samples 4 -j "$j" \
	    --stats -o /dev/null "$W/ch2.vx" 2>&1 |
	    grep -E 'paths/s|time:' | sed "s/^/bake-irr j$j: /"
done
