#!/bin/sh
# run_voxlux.sh: voxlux's own side of a benchmark picture, timed like the peers: run
# `mip` or `raycast` on a stream (volume + macrocells) with a scene RUNS times, report the
# median of the program's own render time (its --stats line) and of its CPU time, and
# write the last float image as a gray PFM (mip: the maximum; raycast: the red channel of
# the colour, a white surface).
#
# usage: run_voxlux.sh [-n RUNS] [-j THREADS] [-b BINDIR] mip|raycast STREAM SCENE OUT.pfm
set -eu
runs=5 threads=$(nproc) bin=../../bin
while getopts n:j:b: o; do
	case $o in
	n) runs=$OPTARG ;;
	j) threads=$OPTARG ;;
	b) bin=$OPTARG ;;
	*) echo "usage: run_voxlux.sh [-n RUNS] [-j THREADS] [-b BINDIR] mip|raycast STREAM SCENE OUT.pfm" >&2; exit 64 ;;
	esac
done
shift $((OPTIND - 1))
[ $# -eq 4 ] || { echo "run_voxlux.sh: need mip|raycast STREAM SCENE OUT.pfm" >&2; exit 64; }
prog=$1 stream=$2 scene=$3 out=$4
case $prog in
mip) name=mip ;;
raycast) name=color ;;
*) echo "run_voxlux.sh: mip or raycast, not $prog" >&2; exit 64 ;;
esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
cpu_of() {
	awk 'NR == 2 { split($1, u, "m"); split($2, s, "m"); sub("s", "", u[2]); sub("s", "", s[2]);
		printf "%.6f\n", u[1] * 60 + u[2] + s[1] * 60 + s[2] }' "$1"
}
i=0
while [ $i -lt "$runs" ]; do
	times >"$tmp/times0"
	if ! "$bin/$prog" --scene "$scene" --hdr --stats -j "$threads" -o "$tmp/img.vxs" \
	    "$stream" 2>"$tmp/log"; then
		cat "$tmp/log" >&2
		exit 70
	fi
	times >"$tmp/times1"
	# "mip: 512x512, 2 threads, 0.560 s" / "raycast: 512x512, 2 threads, 0.583 s (...)"
	sed -n "s/^$prog: [0-9]*x[0-9]*, [0-9]* threads\{0,1\}, \([0-9.e+-]*\) s.*/\1/p" "$tmp/log" >>"$tmp/render"
	echo "$(cpu_of "$tmp/times0") $(cpu_of "$tmp/times1")" | awk '{ printf "%.6f\n", $2 - $1 }' >>"$tmp/cpu"
	i=$((i + 1))
done
[ -s "$tmp/render" ] || { echo "run_voxlux.sh: no time in $prog --stats output" >&2; cat "$tmp/log" >&2; exit 70; }
"$bin/tonemap" --pfm --name "$name" -o "$out" "$tmp/img.vxs"
median() { sort -g "$1" | awk '{ v[NR] = $1 } END { printf "%.3f", 1e3 * (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
grep -v "^$prog: [0-9]*x[0-9]*, " "$tmp/log" | sed "s/^/stats: /"
echo "render_ms $(median "$tmp/render") ($prog's own time, median of $runs, threads $threads)"
echo "render_cpu_ms $(median "$tmp/cpu") (whole $prog process, user + system, median of $runs)"
