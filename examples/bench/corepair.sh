#!/bin/sh
# corepair.sh [ROUNDS]: does running side by side slow a program down, and
# which?  Per round, each of four programs alone and then two copies of it
# side by side (one per vCPU), one after the other so that all four see the
# same minutes:
#   alu      coreprobe alu: integer additions, no memory (busy units)
#   div      coreprobe div: dependent divisions, no memory (idle units)
#   voxlux   isobench -j 1, ch2 127.5 (the fastest of 9 frames)
#   embree   embree_render -j 1 on the extracted mesh (median of 9 frames)
# and prints pair / alone per program (the slower copy of the pair; 1.00:
# no slowdown), then the medians over rounds.  If alu slows with voxlux
# and div does not, what the pair shares is the core's execution units.
# Run from examples/bench after `make -C examples/bench iso`:
#
#   sh corepair.sh 9
set -eu
R=${1:-5}
S=../scenes/iso-headlight.scn
MESH=out/iso/ch2-iso-127.5-fe.mesh
. "$(dirname "$0")/cameras.sh"
PROBE=out/coreprobe
[ -x $PROBE ] && [ $PROBE -nt coreprobe.c ] ||
	${CC:-cc} -std=c11 -O2 -o $PROBE coreprobe.c
for f in out/isobench out/embree_render $MESH; do
	[ -e $f ] || { echo "corepair.sh: $f: missing (make -C examples/bench iso)" >&2; exit 1; }
done
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

one() {
	case $1 in
	alu) $PROBE alu 1000000000 ;;
	div) $PROBE div 100000000 ;;
	voxlux) out/isobench --scene $S --set "$CAM_CH2" --iso 127.5 -j 1 \
	    -n 9 --warm 1 out/ch2-b.vx | awk '$1 == "frame_ms_min" { print $2 }' ;;
	embree) out/embree_render -m $MESH -o "$T/e$2.pfm" -j 1 -n 9 -b 1 \
	    $(embree_flags "$CAM_CH2") --size 512 512 |
	    awk '$1 == "render_ms" { print $2 }' ;;
	esac
}

echo "round alu div voxlux embree   (pair / alone; alone: alu s, voxlux ms, embree ms)"
for i in $(seq "$R"); do
	line="$i"
	alone=
	for p in alu div voxlux embree; do
		a=$(one $p 0)
		one $p 1 > "$T/p1" &
		one $p 2 > "$T/p2"
		wait
		r=$(cat "$T/p1" "$T/p2" | awk -v a="$a" '$1 > m { m = $1 }
		    END { printf "%.2f", m / a }')
		line="$line $r"
		alone="$alone $a"
		echo "$r" >> "$T/$p"
	done
	echo "$line  ($alone )"
done
med() {
	sort -n "$T/$1" | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
echo "median $(med alu) $(med div) $(med voxlux) $(med embree)"
