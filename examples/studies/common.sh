# common.sh: helpers for the studies (sourced).
set -eu
: "${BIN:=../../bin}" "${RUNS:=5}" "${SIZE:=384x384}"
: "${HEAD:=/usr/share/mricron/templates/ch2.nii.gz}"
PATH="$BIN:$PATH"
mkdir -p results
[ -r "$HEAD" ] || { echo "studies: $HEAD: missing (make deps)" >&2; exit 66; }
command -v gnuplot >/dev/null || { echo "studies: gnuplot: missing (make deps)" >&2; exit 69; }
[ -s results/head.vx ] || vread "$HEAD" | brick | macrocell > results/head.vx

# median_time CMD...: run CMD (a raycast with --stats) RUNS times, print the
# median of the seconds its --stats line reports.
median_time() {
	i=0
	: > results/.times
	while [ "$i" -lt "$RUNS" ]; do
		"$@" 2>&1 >/dev/null | sed -n 's/^raycast: [0-9]*x[0-9]*, [0-9]* threads*, \([0-9.]*\) s.*/\1/p' >> results/.times
		i=$((i + 1))
	done
	sort -n results/.times | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

# plot NAME: results/NAME.png and results/NAME.svg from the gnuplot script
# NAME.gp, which reads results/NAME.tsv.
plot() {
	gnuplot -e "size='$SIZE'; set terminal pngcairo size 800,500 font ',10'; set output 'results/$1.png'" "$1.gp"
	gnuplot -e "size='$SIZE'; set terminal svg size 800,500 font ',10' background '#ffffff'; set output 'results/$1.svg'" "$1.gp"
}

# metric REF IMG NAME KEY: one value of tonemap --compare.
metric() {
	tonemap --name "$3" --compare "$1" "$2" | sed -n "s/^$4 //p"
}
