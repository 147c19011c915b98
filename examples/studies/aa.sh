#!/bin/sh
# aa.sh: samples per pixel against image error.  Reference: 6x6 samples per
# pixel; error: color RMSE and maximum against it.  Time: raycast --stats,
# median of RUNS.
. ./common.sh
scene=../scenes/head.scn
raycast --scene "$scene" --size "$SIZE" --aa 6 --hdr results/head.vx > results/aa-ref.vx 2>/dev/null
printf 'aa\tseconds\tcolor_rmse\tcolor_max\n' > results/aa.tsv
for n in 1 2 3 4; do
	raycast --scene "$scene" --size "$SIZE" --aa $n --hdr results/head.vx > results/aa-$n.vx 2>/dev/null
	t=$(median_time raycast --scene "$scene" --size "$SIZE" --aa $n --stats results/head.vx)
	printf '%s\t%s\t%s\t%s\n' $n "$t" \
	    "$(metric results/aa-ref.vx results/aa-$n.vx color rmse)" \
	    "$(metric results/aa-ref.vx results/aa-$n.vx color max_abs)" >> results/aa.tsv
done
plot aa
cat results/aa.tsv
