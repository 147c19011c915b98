#!/bin/sh
# solver.sh: the root solver's accuracy against its cost.  The exact solver
# (full precision) is the reference; Neubauer's repeated linear
# interpolation and one secant step are cheaper approximations.  Error:
# RMSE and maximum of the depth image (in world units, mm for the head)
# and of the color image.  Time: raycast --stats, median of RUNS.
. ./common.sh
scene=../scenes/head.scn
raycast --scene "$scene" --size "$SIZE" --hdr results/head.vx > results/solver-exact.vx 2>/dev/null
printf 'solver\tseconds\tdepth_rmse\tdepth_max\tcolor_rmse\tcolor_max\n' > results/solver.tsv
for s in exact neubauer linear; do
	raycast --scene "$scene" --size "$SIZE" --solver $s --hdr results/head.vx > results/solver-$s.vx 2>/dev/null
	t=$(median_time raycast --scene "$scene" --size "$SIZE" --solver $s --stats results/head.vx)
	printf '%s\t%s\t%s\t%s\t%s\t%s\n' $s "$t" \
	    "$(metric results/solver-exact.vx results/solver-$s.vx depth rmse)" \
	    "$(metric results/solver-exact.vx results/solver-$s.vx depth max_abs)" \
	    "$(metric results/solver-exact.vx results/solver-$s.vx color rmse)" \
	    "$(metric results/solver-exact.vx results/solver-$s.vx color max_abs)" >> results/solver.tsv
done
plot solver
cat results/solver.tsv
