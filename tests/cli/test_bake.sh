#!/bin/sh
# test_bake.sh: bake-irr in pipelines, and raycast's `illumination
# irradiance`: radiance against the white-furnace oracle, the same bits at
# any thread count, resumed = one run, merged = one run, final stores, the
# plan and the statistics, and one line on every error.
. "$(dirname "$0")/lib.sh"
MK="python3 tests/cli/mkstream.py"
CH2=/usr/share/mricron/templates/ch2.nii.gz
irrv() { $MK payload "$1" IRRV | cksum; }
px() { python3 tests/cli/vximg.py "$@"; }

vread --synth sphere --size 32 | macrocell > "$T/s.vx"

# 1. white furnace: the sphere field is a distance (higher outside), so the
# lit side is the high one; a convex surface under a sky of radiance 1 has
# E = pi everywhere, and raycast draws albedo * E / pi = 0.8 (the default
# surface colour, kd 1) at the centre pixel (oracle: formats/irradiance.md)
bake-irr --light sky --iso 0.5 --side high --samples 8 --bounces 2 -j 2 \
    "$T/s.vx" > "$T/b8.vx" 2>"$T/b.err"
check_eq "bake: silent when stderr is not a terminal" "$(cat "$T/b.err")" ""
raycast --iso 0.5 --set "illumination irradiance" --size 33x33 --hdr \
    "$T/b8.vx" > "$T/r.vx"
check_close "white furnace: radiance 0.8 at the centre" \
    "$(px img "$T/r.vx" color 16 16 0)" 0.8 1e-5
check_close "white furnace: radiance 0.8 off centre" \
    "$(px img "$T/r.vx" color 13 19 2)" 0.8 1e-5
for m in nearest nearest-iso tricubic; do
	raycast --iso 0.5 --set "illumination irradiance interpolation $m" \
	    --size 33x33 --hdr "$T/b8.vx" > "$T/rm.vx"
	check_close "white furnace, interpolation $m" \
	    "$(px img "$T/rm.vx" color 12 18 1)" 0.8 1e-5
done

# 2. the same bits at any thread count
bake-irr --light sky --iso 0.5 --side high --samples 8 --bounces 2 -j 1 \
    "$T/s.vx" > "$T/b8j1.vx"
check_eq "-j 1 = -j 2, bit for bit" "$(irrv "$T/b8j1.vx")" "$(irrv "$T/b8.vx")"

# 3. resumed = one run; merged = one run (a scene with a shadowing point
# light, bounces and a sky: every part of the estimator)
L() { bake-irr --light sky --light "point position 0 0 3 intensity 2" \
    --iso 0.5 --side high --bounces 1 "$@"; }
L --samples 12 "$T/s.vx" > "$T/one.vx"
L --samples 5 "$T/s.vx" | L --samples 7 > "$T/res.vx"
check_eq "resumed (5 + 7 samples) = one run of 12" "$(irrv "$T/res.vx")" "$(irrv "$T/one.vx")"
L --samples 5 "$T/s.vx" > "$T/a.vx"
L --first-sample 5 --samples 7 "$T/s.vx" > "$T/b.vx"
L --merge "$T/b.vx" "$T/a.vx" > "$T/m.vx"
check_eq "merged ([0,5) + [5,12)) = one run of 12" "$(irrv "$T/m.vx")" "$(irrv "$T/one.vx")"
# texel ranges: two bands baked apart and merged = the union band baked
# at once (a texel both bands want holds the same samples: kept once)
L --samples 4 --iso-range 0.3,0.5 --fresh "$T/s.vx" > "$T/t1.vx"
L --samples 4 --iso-range 0.5,0.7 --fresh "$T/s.vx" > "$T/t2.vx"
L --samples 4 --iso-range 0.3,0.7 --fresh "$T/s.vx" > "$T/t12.vx"
L --merge "$T/t2.vx" "$T/t1.vx" > "$T/tm.vx"
check_eq "merged texel bands = the union band in one run" "$(irrv "$T/tm.vx")" "$(irrv "$T/t12.vx")"
expect_fail "merge: ranges that do not join" 65 "do not join" \
    L --merge "$T/b.vx" "$T/one.vx"
expect_fail "resume: other settings" 65 "other settings" \
    bake-irr --light sky --iso 0.5 --side high --bounces 3 "$T/one.vx"
expect_fail "--side: a word of its table" 64 \
    "--side: unknown side 'mid' (one of: low, high)" bake-irr --side mid
expect_fail "no light to bake (only the default headlight)" 64 "no light to bake" \
    bake-irr --iso 0.5 "$T/s.vx"

# 3b. lazy illumination: bake-irr --lazy records the settings and bakes
# nothing; raycast --lazy bakes the texels its view reads: the picture equals
# the one drawn from the full bake, and the lazy texels merge onto the full
# bake as the very same samples (a texel that differed would not join)
L --samples 8 --lazy "$T/s.vx" > "$T/empty.vx"
L --samples 8 "$T/s.vx" > "$T/full.vx"
R() { raycast --light sky --light "point position 0 0 3 intensity 2" \
    --set "interreflection bounces 1" --effects +interreflection --iso 0.5 \
    --set "illumination irradiance" --size 48x48 --hdr "$@"; }
R "$T/full.vx" > "$T/rfull.vx"
R --lazy --lazy-save "$T/lazy.vx" --stats "$T/empty.vx" > "$T/rlazy.vx" 2>"$T/lst"
check_eq "lazy: the picture of the full bake" "$(px same "$T/rfull.vx" "$T/rlazy.vx")" same
check "lazy: says what it baked" grep -q "lazy: the view reads [1-9][0-9]* texels: [1-9][0-9]* baked now" "$T/lst"
L --merge "$T/lazy.vx" "$T/full.vx" > "$T/lm.vx"
check_eq "lazy texels = the full bake's, bit for bit" "$(irrv "$T/lm.vx")" "$(irrv "$T/full.vx")"
R --lazy --stats "$T/lazy.vx" 2>"$T/lst2" >/dev/null
check "lazy: the saved texels are reused" grep -q "texels: 0 baked now" "$T/lst2"
expect_fail "lazy: a scene whose lights differ from the bake's" 65 "other settings" \
    raycast --light sky --iso 0.5 --set "illumination irradiance" --lazy "$T/empty.vx"

# 3c. the path-traced reference (illumination pathtrace): the white furnace
# exactly, the same bits at any thread count, and irradiance shading within
# its interpolation error of it on a convex sphere under a directional light
# and a sky.  The bound: E = pi I max(0, cos) is smooth but for the kink at
# the terminator, where linear interpolation errs by at most the slope's
# jump (pi I / r per unit length) times h / 4: h / (4 r) of E's scale with
# texel spacing h = 2/31 and radius r = 0.5, 3.2%; the RMSE is below it.
P() { raycast --iso 0.5 --set "illumination pathtrace" --size 33x33 --hdr "$@"; }
P --light sky --spp 4 "$T/s.vx" > "$T/pt.vx"
check_close "pathtrace: white furnace 0.8" "$(px img "$T/pt.vx" color 16 16 0)" 0.8 1e-6
D="directional direction 1 1 -1 intensity 1.5"
P --light sky --light "$D" --set "interreflection bounces 1" \
    --effects +interreflection --spp 3 -j 1 "$T/s.vx" > "$T/p1.vx"
P --light sky --light "$D" --set "interreflection bounces 1" \
    --effects +interreflection --spp 3 -j 2 "$T/s.vx" > "$T/p2.vx"
check_eq "pathtrace: -j 1 = -j 2" "$(px same "$T/p1.vx" "$T/p2.vx")" same
# the bounce and shadow rays decide cells by the frame's cell mask: the same
# bits as without one (--no-cellmask), on the Marschner-Lobb field's wavy
# surface, where bounce rays hit (under the sky alone every ray is a bounce
# ray: more rays than paths)
vread --synth ml --size 41 | brick | macrocell > "$T/ml.vx"
for m in "" --no-cellmask; do
	P --light sky --light "$D" --set "interreflection bounces 1" \
	    --effects +interreflection --spp 3 --size 65x65 -j 2 $m \
	    "$T/ml.vx" > "$T/pm$m.vx"
done
check_eq "pathtrace: the GI rays' cell mask changes no bit" \
    "$(px same "$T/pm.vx" "$T/pm--no-cellmask.vx")" same
P --light sky --set "interreflection bounces 1" --effects +interreflection \
    --spp 3 --size 65x65 --stats "$T/ml.vx" 2>"$T/pm.err" >/dev/null
check "pathtrace on ml: bounce rays hit" awk '/pathtrace:/ { p = $3; r = $5 }
    END { exit !(r > 1.1 * p) }' "$T/pm.err"
bake-irr --light sky --light "$D" --iso 0.5 --side high --samples 4 \
    "$T/s.vx" > "$T/d.vx"
raycast --iso 0.5 --set "illumination irradiance" --size 96x96 --hdr \
    "$T/d.vx" > "$T/ri.vx"
raycast --iso 0.5 --light sky --light "$D" --set "illumination pathtrace" \
    --spp 2 --size 96x96 --hdr "$T/s.vx" > "$T/rp.vx"
e=$(px relrmse "$T/rp.vx" "$T/ri.vx")
check "irradiance vs the path-traced reference: relative RMSE $e <= h/4r" \
    awk -v e="$e" 'BEGIN { exit !(e <= 0.0323) }'

# 3d. an environment map: a constant map of radiance 0.5 (a PFM made here)
# on the convex sphere gives E = pi 0.5 (oracle: the furnace), by
# importance sampling with MIS: unbiased, not exact per sample, so within
# 2% after 32 samples; raycast's reference agrees; the map's hash joins the
# bake's settings
python3 -c "
import struct, sys
w, h = 16, 8
sys.stdout.buffer.write(b'PF\\n%d %d\\n-1.0\\n' % (w, h) + struct.pack('<%df' % (w * h * 3), *([0.5] * (w * h * 3))))
" > "$T/env.pfm"
bake-irr --light "environment file $T/env.pfm" --iso 0.5 --side high \
    --samples 32 --bounces 1 --stats "$T/s.vx" > "$T/eb.vx" 2>"$T/est"
raycast --iso 0.5 --set "illumination irradiance" --size 33x33 --hdr \
    "$T/eb.vx" > "$T/er.vx"
check_close "environment: furnace radiance 0.8 * 0.5 (2%)" \
    "$(px img "$T/er.vx" color 16 16 0)" 0.4 0.008
P --light "environment file $T/env.pfm" --spp 32 "$T/s.vx" > "$T/ep.vx"
check_close "environment: the path-traced reference (2%)" \
    "$(px img "$T/ep.vx" color 16 16 1)" 0.4 0.008
check "environment: shadow rays to the map (MIS)" grep -q "[1-9][0-9]* shadow rays" "$T/est"
check "environment: its hash in the bake's settings" sh -c "vinfo '$T/eb.vx' | grep -q 'environment [0-9a-f]\\{16\\}'"

# 4. texel bands: --iso-range bakes fewer texels than --all; a render at an
# isovalue outside the band finds no texel and says so
bake-irr --light sky --iso-range 0.45,0.55 --side high --samples 2 --stats \
    "$T/s.vx" 2>"$T/st1" >/dev/null
bake-irr --light sky --all --side high --samples 2 --stats "$T/s.vx" \
    2>"$T/st2" >/dev/null
w1=$(sed -n 's/.* texels), \([0-9]*\) wanted.*/\1/p' "$T/st1")
w2=$(sed -n 's/.* texels), \([0-9]*\) wanted.*/\1/p' "$T/st2")
check "band: fewer texels wanted ($w1 of $w2)" test "$w1" -gt 0 -a "$w1" -lt "$w2"
check_eq "--all wants every texel" "$w2" 32768
check "--stats: paths per core-second" grep -q "paths per core-second" "$T/st1"
raycast --iso 0.9 --set "illumination irradiance" --size 33x33 --stats \
    "$T/b8.vx" 2>"$T/rst" >/dev/null
check "raycast counts points outside the band" grep -q "found no baked texel" "$T/rst"

# 5. final stores: half precision within binary16's rounding of f32
bake-irr --light sky --iso 0.5 --side high --samples 8 --bounces 2 --half \
    --stats "$T/s.vx" > "$T/h.vx" 2>"$T/hst"
check "--half: 8 bytes a texel" grep -q "f16 RGB irradiance, 8 bytes per texel in the stream" "$T/hst"
raycast --iso 0.5 --set "illumination irradiance" --size 33x33 --hdr \
    "$T/h.vx" > "$T/rh.vx"
check_close "--half: radiance within 2^-11 of 0.8" \
    "$(px img "$T/rh.vx" color 16 16 0)" 0.8 4e-4
# a final store draws only baked texels: the texels of a stored brick that
# nobody asked for are not read as E = 0 (tricubic reads 4^3 around)
raycast --iso 0.5 --set "illumination irradiance interpolation tricubic" \
    --size 33x33 --hdr "$T/h.vx" > "$T/rht.vx"
check_close "--half, tricubic: radiance within 2^-11 of 0.8" \
    "$(px img "$T/rht.vx" color 12 18 1)" 0.8 4e-4
expect_fail "a final bake cannot be resumed" 65 "final" \
    bake-irr --light sky --iso 0.5 --side high --bounces 2 "$T/h.vx"

# 6. the plan
bake-irr --light sky --light "directional direction 0 0 -1" --iso 0.5 -n \
    "$T/s.vx" 2>"$T/ex" >"$T/ex.out"
check "--explain: wanted texels" grep -q "wanted (cells whose values meet" "$T/ex"
check "--explain: lights and bounces" grep -q "1 delta light (shadow rays on), a sky" "$T/ex"
check "--explain: predicted paths" grep -q "paths, .* rays" "$T/ex"
check_eq "-n writes nothing" "$(wc -c < "$T/ex.out" | tr -d ' ')" 0
raycast --iso 0.5 --set "illumination irradiance" -n "$T/b8.vx" 2>"$T/rex" >/dev/null
check "raycast --explain: irradiance lookup" grep -q "on  *illumination  *irradiance" "$T/rex"
expect_fail "raycast: irradiance without a bake" 65 "no irradiance volume" \
    raycast --iso 0.5 --set "illumination irradiance" "$T/s.vx"

# 7. the MRI head: a bake of the skin band, drawn with every pixel read
if [ -r "$CH2" ]; then
	vread "$CH2" | brick | macrocell > "$T/ch2.vx"
	bake-irr --light sky --iso 40.5 --samples 2 --scale 0.5 "$T/ch2.vx" \
	    > "$T/ch2b.vx"
	raycast --iso 40.5 --set "illumination irradiance" --size 64x64 \
	    --stats --hdr "$T/ch2b.vx" 2>"$T/hst" > "$T/hr.vx"
	check "head: every shaded point reads the bake" sh -c "! grep -q 'found no baked texel' '$T/hst'"
	v=$(px img "$T/hr.vx" color 32 32 0)
	check "head: lit skin at the centre ($v)" awk -v v="$v" 'BEGIN { exit !(v > 0.05 && v < 1) }'
else
	skip "the MRI head" "mricron-data not installed"
fi
# 8. ambient occlusion and vicinity shading by name (the scene's occlusion
# directive): a white sky of radiance 1 in place of the lights, no bounces;
# a convex sphere is open everywhere (radiance = albedo 0.8, the lights
# given play no part), in the bake, lazily and path traced; the plan says so
O="occlusion distance 0.5"
bake-irr --light "point position 0 0 3 intensity 9" --set "$O" --iso 0.5 \
    --side high --samples 4 "$T/s.vx" > "$T/ao.vx"
raycast --iso 0.5 --set "$O" --set "illumination irradiance" --size 33x33 \
    --hdr "$T/ao.vx" > "$T/rao.vx"
check_close "occlusion: a convex sphere is open: radiance 0.8" \
    "$(px img "$T/rao.vx" color 13 19 0)" 0.8 1e-5
bake-irr --light "point position 0 0 3 intensity 9" --set "$O" --iso 0.5 \
    --side high --samples 4 --lazy "$T/s.vx" |
    raycast --iso 0.5 --set "$O" --set "illumination irradiance" \
    --size 33x33 --hdr --lazy > "$T/raol.vx"
check_eq "occlusion, lazy: the bake's picture" "$(px same "$T/rao.vx" "$T/raol.vx")" same
raycast --iso 0.5 --set "$O" --set "illumination pathtrace" --spp 2 \
    --size 33x33 --hdr "$T/s.vx" > "$T/rpt.vx"
check_close "occlusion, path traced: 0.8" "$(px img "$T/rpt.vx" color 13 19 0)" 0.8 1e-5
raycast --iso 0.5 --set "$O" --set "illumination pathtrace" --explain -n \
    "$T/s.vx" 2>"$T/aoe" >/dev/null || true
check "occlusion: the plan says what it replaces" grep -q "ambient occlusion (rays open past 0.5): a white sky" "$T/aoe"
expect_fail "occlusion: distance 0 refused" 64 "occlusion: distance: 0 outside (0" \
    raycast --iso 0.5 --set "occlusion distance 0" "$T/s.vx"

done_testing
