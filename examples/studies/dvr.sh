#!/bin/sh
# dvr.sh: what half-angle slicing (dvr) costs in accuracy.  The MRI head
# through examples/scenes/head-dvr.scn with volumetric shadows only (no
# scattering term: the model the ray march computes exactly), at DVR_SIZE
# (default 128x128: the exact-shadow reference is O(n^2) a pixel).
# References: dvr --reference raymarch (exact shadow rays, the reference
# step) and dvr --reference pathtrace (single scattering, DVR_SPP paths a
# pixel).  Swept: the slice count at light buffer 256, the light buffer's
# edge at 320 slices (about one voxel apart: the default is 319).  Error:
# relative RMSE of the premultiplied colour over the pixels either picture
# covers (tests/cli/vximg.py relrmse-all).  Time: dvr --stats, median of
# RUNS.  Writes results/dvr.tsv (the sweep: block 0 slices, block 1 light
# buffer), results/dvr-refs.tsv (the references against each other and the
# scattering slicer against multiple scattering), results/dvr.png and .svg,
# and the pictures results/dvr-*.png.
. ./common.sh
: "${DVR_SIZE:=128x128}" "${DVR_SPP:=1024}" "${DVR_SPP_MS:=256}"
scene=../scenes/head-dvr.scn
rel() { python3 ../../tests/cli/vximg.py relrmse-all "$1" "$2"; }
D() { dvr --scene "$scene" --size "$DVR_SIZE" --effects "volumetric-shadows specular" "$@"; }
# run OUT CMD...: CMD (a dvr) RUNS times, its picture into OUT (--hdr);
# prints the median of the seconds its --stats line reports
run() {
	out=$1
	shift
	i=0
	: > results/.times
	while [ "$i" -lt "$RUNS" ]; do
		"$@" --stats --hdr results/head.vx 2>&1 > "$out" | sed -n 's/^dvr: .*threads*, \([0-9.]*\) s$/\1/p' >> results/.times
		i=$((i + 1))
	done
	sort -n results/.times | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
png() { tonemap -o "results/$2.png" "$1" >/dev/null; }

# the references, each with its own error: the ray march against itself
# at half the step, the path tracer against another seed (the noise of
# one picture is that RMSE / sqrt 2)
t_rm=$(run results/dvr-rm.vx D --reference raymarch)
# (the slowest picture, not timed: kept in results/ from run to run as
# head.vx is; make clean removes it)
[ -s results/dvr-rm2.vx ] ||
    D --reference raymarch --march-step 0.5 --hdr results/head.vx > results/dvr-rm2.vx
t_pt=$(run results/dvr-pt.vx D --reference pathtrace --spp "$DVR_SPP")
D --reference pathtrace --spp "$DVR_SPP" --seed 2 --hdr results/head.vx > results/dvr-pt2.vx
png results/dvr-rm.vx dvr-raymarch
png results/dvr-pt.vx dvr-pathtrace

printf 'slices\tlight_size\tseconds\trelrmse_raymarch\trelrmse_pathtrace\n' > results/dvr.tsv
sweep() {
	t=$(run results/dvr-s.vx D --slices "$1" --light-size "$2")
	printf '%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$t" \
	    "$(rel results/dvr-rm.vx results/dvr-s.vx)" \
	    "$(rel results/dvr-pt.vx results/dvr-s.vx)" >> results/dvr.tsv
	[ "$1" != 320 ] || [ "$2" != 256 ] || { png results/dvr-s.vx dvr-slicing; cp results/dvr-s.vx results/dvr-s320.vx; }
}
for n in 80 160 320 640; do sweep $n 256; done
printf '\n\n' >> results/dvr.tsv
for l in 64 128 256 512; do sweep 320 $l; done

{
	printf 'picture\tagainst\tseconds\trelrmse\n'
	printf 'raymarch step 1\traymarch step 0.5\t%s\t%s\n' "$t_rm" "$(rel results/dvr-rm2.vx results/dvr-rm.vx)"
	printf 'pathtrace %s spp\tpathtrace seed 2 (the noise of one: this / sqrt 2)\t%s\t%s\n' "$DVR_SPP" "$t_pt" "$(rel results/dvr-pt2.vx results/dvr-pt.vx)"
	printf 'pathtrace %s spp\traymarch step 0.5\t%s\t%s\n' "$DVR_SPP" "$t_pt" "$(rel results/dvr-rm2.vx results/dvr-pt.vx)"
} > results/dvr-refs.tsv

# multiple scattering, at the scene's medium albedo 1 and at 0.5: the
# slicer with its scattering term and without, and single scattering,
# against the path tracer with up to 16 vertices a path
for a in 1 0.5; do
	S() { dvr --scene "$scene" --size "$DVR_SIZE" --set "medium albedo $a $a $a" "$@"; }
	t_sc=$(run results/dvr-sc-$a.vx S)
	t_ptm=$(run results/dvr-ptm-$a.vx S --reference pathtrace --spp "$DVR_SPP_MS" --bounces 16)
	m="pathtrace 16 bounces, $DVR_SPP_MS spp, albedo $a"
	{
		printf 'dvr scattering\t%s\t%s\t%s\n' "$m" "$t_sc" "$(rel results/dvr-ptm-$a.vx results/dvr-sc-$a.vx)"
		printf 'dvr shadows only (320, 256)\t%s\t-\t%s\n' "$m" "$(rel results/dvr-ptm-$a.vx results/dvr-s320.vx)"
		printf 'pathtrace 1 bounce\t%s\t%s\t%s\n' "$m" "$t_ptm" "$(rel results/dvr-ptm-$a.vx results/dvr-pt.vx)"
	} >> results/dvr-refs.tsv
done
png results/dvr-sc-1.vx dvr-slicing-scatter
png results/dvr-ptm-1.vx dvr-pathtrace-multiple
SIZE=$DVR_SIZE plot dvr
cat results/dvr.tsv results/dvr-refs.tsv
