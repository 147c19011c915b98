#!/bin/sh
# test_dvrref.sh: dvr --reference (the ray-marched and path-traced
# references): Beer-Lambert through a homogeneous slab (the ray march
# exactly at any step, the path tracer within 4 standard deviations of the
# binomial fraction of paths that meet the slab), the shadow of one slab on
# another by formula, the same bits at any thread count and from run to
# run, a new seed another picture, more paths less noise, --explain and
# --stats, and one line on every misuse of the options.
. "$(dirname "$0")/lib.sh"
MK="python3 tests/cli/mkstream.py"
px() { python3 tests/cli/vximg.py "$@"; }

# 1. a homogeneous slab 39 deep seen straight on, emission 1, no light
$MK volume "$T/slab.vx" --type f32 --dims 8 8 40 --formula 1
slab_scene "$T/slab.scn"
want=$(awk 'BEGIN { printf "%.9f", 1 - exp(39 * log(0.95)) }')
for h in 1 0.3 7; do
	dvr --scene "$T/slab.scn" --reference raymarch --march-step $h --hdr "$T/slab.vx" > "$T/rm.out"
	check_close "raymarch, step $h: coverage 1 - exp(-sigma d)" \
	    "$(px img "$T/rm.out" color 2 5 3)" "$want" 2e-6
done
# one pixel, 4096 paths: sd = sqrt(p (1 - p) / 4096) < 0.0054
dvr --scene "$T/slab.scn" --set "image width 1 height 1" --reference pathtrace \
    --spp 4096 --hdr "$T/slab.vx" > "$T/pt.out"
check_close "pathtrace: coverage within 4 sd" \
    "$(px img "$T/pt.out" color 0 0 3)" "$want" 0.0216
check_close "pathtrace: colour = coverage (emission 1)" \
    "$(px img "$T/pt.out" color 0 0 0)" "$(px img "$T/pt.out" color 0 0 3)" 0

# 2. the shadow of a slab (z 24..29) on a slab (z 6..13), light along the
# view, opacity 0.2 from value 0.25: the receiver's 9 samples lose q^7
# through the occluder's 7 eye samples and q^6 through its 6 shadow
# segments: both = occluder + q^13 receiver
for f in "z >= 6 and z <= 13" "z >= 24 and z <= 29" \
    "(z >= 6 and z <= 13) or (z >= 24 and z <= 29)"; do
	$MK volume "$T/v.vx" --type f32 --dims 8 8 40 --formula "1 if $f else 0" 2>/dev/null ||
	    { echo "Bail out! mkstream --formula"; exit 1; }
	dvr --set "camera orthographic eye 3.5 3.5 100 look 3.5 3.5 0 up 0 1 0 width 7" \
	    --set "image width 8 height 8" --light "directional direction 0 0 -1" \
	    --effects volumetric-shadows --set "ambient intensity 0" \
	    --set "transfer opacity 0 0 0.25 0 0.25 0.2" --reference raymarch \
	    --hdr "$T/v.vx" > "$T/v.out"
	echo "$(px img "$T/v.out" color 4 3 1)"
done > "$T/sh.txt"
rec=$(sed -n 1p "$T/sh.txt"); occ=$(sed -n 2p "$T/sh.txt"); both=$(sed -n 3p "$T/sh.txt")
check_close "receiver alone: 0.2 (1 - 0.8^18) / (1 - 0.8^2)" "$rec" \
    "$(awk 'BEGIN { printf "%.9f", 0.2 * (1 - 0.8 ^ 18) / (1 - 0.64) }')" 1e-6
check_close "the shadow: both = occluder + 0.8^13 receiver" "$both" \
    "$(awk -v r="$rec" -v o="$occ" 'BEGIN { printf "%.9f", o + 0.8 ^ 13 * r }')" 1e-6

# 3. a lit sphere: threads, determinism, seeds, noise
vread --synth sphere --size 24 > "$T/s.vx"
cat > "$T/s.scn" <<'SCN'
image width 32 height 32
light directional direction 1 -1 -1
light point position 0 3 0 intensity 0.3
transfer opacity 0 0.1 0.6 0.1 0.7 0.02 0.8 0
transfer color 0 1 0.8 0.6 0.7 0.9 0.9 1
transfer surface 0 0 0.5 1
medium phase henyey-greenstein g 0.3 albedo 0.9 0.9 0.9
effects volumetric-shadows specular
SCN
R() { dvr --scene "$T/s.scn" "$@" "$T/s.vx"; }
R --reference raymarch -j 1 --hdr > "$T/r1.out"
R --reference raymarch -j 2 --hdr > "$T/r2.out"
check_eq "raymarch: -j 1 = -j 2, bit for bit" "$(px same "$T/r1.out" "$T/r2.out")" same
R --reference pathtrace --spp 4 --bounces 4 -j 1 --hdr > "$T/p1.out"
R --reference pathtrace --spp 4 --bounces 4 -j 2 --hdr > "$T/p2.out"
R --reference pathtrace --spp 4 --bounces 4 -j 2 --hdr > "$T/p3.out"
R --reference pathtrace --spp 4 --bounces 4 -j 2 --seed 7 --hdr > "$T/p4.out"
check_eq "pathtrace: -j 1 = -j 2, bit for bit" "$(px same "$T/p1.out" "$T/p2.out")" same
check_eq "pathtrace: the same bits run to run" "$(px same "$T/p2.out" "$T/p3.out")" same
check_eq "pathtrace: another seed, another picture" "$(px same "$T/p2.out" "$T/p4.out")" differ
R --reference pathtrace --spp 4 --hdr > "$T/p4b1.out"
R --reference pathtrace --spp 64 --hdr > "$T/p64.out"
R --reference pathtrace --spp 1024 --hdr > "$T/pref.out"
e4=$(px relrmse-all "$T/pref.out" "$T/p4b1.out")
e64=$(px relrmse-all "$T/pref.out" "$T/p64.out")
# noise falls as 1 / sqrt(spp): 4x less from 4 to 64 paths
check "pathtrace: 16x the paths, about 4x less noise ($e4 -> $e64)" \
    awk -v a="$e4" -v b="$e64" 'BEGIN { exit !(b < a / 3 && b > a / 6) }'
e=$(px relrmse-all "$T/r1.out" "$T/pref.out")
check "single scattering (1024 paths) agrees with the ray march ($e)" close "$e" 0 0.05
R --reference raymarch --stats -o /dev/null 2>"$T/st.err"
check "--stats: raymarch samples and shadow steps" \
    grep -q "^dvr: eye samples [0-9]*, shadow steps [1-9][0-9]*" "$T/st.err"
R --reference pathtrace --spp 2 --stats -o /dev/null 2>"$T/st2.err"
check "--stats: paths" grep -q "^dvr: paths 2048, vertices [1-9]" "$T/st2.err"

# 4. --explain
R --reference raymarch -n 2>"$T/ex.err" >/dev/null
check "--explain: the ray march and its cost" grep -q "O(n^2) per pixel" "$T/ex.err"
check "--explain: the second light unshadowed" grep -q "light 2 point .*unshadowed" "$T/ex.err"
R --reference pathtrace --bounces 8 -n 2>"$T/ex2.err" >/dev/null
check "--explain: multiple scattering" grep -q "multiple: up to 8 vertices" "$T/ex2.err"
check "--explain: noisy as 1/sqrt(spp)" grep -q "noisy as 1/sqrt(spp)" "$T/ex2.err"

# 5. misuse
expect_fail "--reference foo" 64 "raymarch or pathtrace" R --reference foo
expect_fail "--spp without --reference pathtrace" 64 "only with --reference pathtrace" \
    R --spp 4
expect_fail "--march-step with the path tracer" 64 "only with --reference raymarch" \
    R --reference pathtrace --march-step 0.5
expect_fail "--spp 0" 64 "--spp" R --reference pathtrace --spp 0
expect_fail "--bounces 0" 64 "--bounces" R --reference pathtrace --bounces 0
done_testing
