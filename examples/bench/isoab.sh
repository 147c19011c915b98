#!/bin/sh
# isoab.sh A B [ROUNDS]: two isobench binaries (two builds of voxlux) timed
# alternately on the four cases of table (a), the fastest of 9 frames per
# round (the cell mask kept, as in table (a)), so that both see the same
# minutes of a noisy machine.  Prints per case the fastest frame of each and
# the median over rounds of the per-round ratio B / A.  J=2 for 2 threads.
# Run from examples/bench after `make -C examples/bench iso` has made out/:
#
#   gcc -std=c11 -O2 -fopenmp $(make -s -C ../.. print-core-inc | sed 's|-I|-I../../|g') -o /tmp/ib_old isobench.c \
#       ../../build/libvoxlux.a -lpng -lz -lm      # in the old checkout
#   ...the same for /tmp/ib_new in the new one...
#   sh isoab.sh /tmp/ib_old /tmp/ib_new 5
set -eu
A=$1
B=$2
R=${3:-5}
S=../scenes/iso-headlight.scn
. "$(dirname "$0")/cameras.sh"
run() {
	case $2 in
	ch2:*) cam=$CAM_CH2; f=out/ch2-b.vx ;;
	*) cam=$CAM_VHF; f=out/vhf-b.vx ;;
	esac
	"$1" --scene $S --set "$cam" --iso "${2#*:}" -j "${J:-1}" -n 9 --warm 1 \
	    "$f" | awk '$1 == "frame_ms_min" { print $2 }'
}
for c in ch2:127.5 ch2:40.5 vhf:600.5 vhf:1224.5; do
	rs= ma=1e9 mb=1e9
	for i in $(seq "$R"); do
		a=$(run "$A" $c)
		b=$(run "$B" $c)
		rs="$rs $(echo "$b $a" | awk '{ printf "%.4f", $1 / $2 }')"
		ma=$(echo "$a $ma" | awk '{ print ($1 < $2) ? $1 : $2 }')
		mb=$(echo "$b $mb" | awk '{ print ($1 < $2) ? $1 : $2 }')
	done
	med=$(echo $rs | tr ' ' '\n' | sort -n |
	    awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')
	echo "$c fastest A $ma B $mb; median of B/A per round $med"
done
