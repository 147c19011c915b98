#!/bin/sh
# test_perturb.sh: dvr's volume perturbation (the scene's perturb lines):
# amplitude 0 is the unperturbed picture bit for bit (slicer and ray
# march); a perturbation changes it, the same bits at any thread count and
# with or without empty-space skipping (which does skip, and would change
# pictures here without the mask eroded by the displacement); a displaced
# constant slab keeps its Beer-Lambert coverage (oracle: the constant);
# the references render the same perturbed field;
# --explain says what is perturbed; bad lines get one error line.
. "$(dirname "$0")/lib.sh"
MK="python3 tests/cli/mkstream.py"
px() { python3 tests/cli/vximg.py "$@"; }

# 1. a lit, scattering ball with empty space around it
vread --synth sphere --size 40 | macrocell --levels 1 --sizes 2x2x2 > "$T/s.vx"
cat > "$T/s.scn" <<'SCN'
image width 40 height 32
light directional direction 1 -1 -1
transfer opacity 0 0.15 0.45 0.15 0.55 0
transfer transport 0 0.9 0.8 0.7 0.55 1 1 1
transfer surface gradient 0.5 3
medium phase henyey-greenstein g 0.5
effects volumetric-shadows scattering specular
SCN
P='perturb coordinates scale 0.4 amplitude 0.25 octaves 4'
V='perturb value scale 0.3 amplitude 0.05 noise turbulence'
M='perturb density scale 0.2 amplitude 1 octaves 3 seed 9'
D() { dvr --scene "$T/s.scn" --light-size 40 "$@" "$T/s.vx"; }
D -j 2 --hdr > "$T/plain.out"
D -j 2 --set "perturb coordinates scale 0.4 amplitude 0" \
    --set "perturb value scale 1 amplitude 0" \
    --set "perturb density scale 1 amplitude 0" --hdr > "$T/zero.out"
check_eq "amplitude 0: the unperturbed picture, bit for bit" \
    "$(px same "$T/plain.out" "$T/zero.out")" same
D --reference raymarch --hdr > "$T/rplain.out"
D --reference raymarch --set "$P" --set "perturb coordinates scale 0.4 amplitude 0" \
    --hdr > "$T/rzero.out"
check_eq "amplitude 0, ray march: the same bits" \
    "$(px same "$T/rplain.out" "$T/rzero.out")" same
D -j 1 --set "$P" --set "$V" --set "$M" --hdr > "$T/p1.out"
D -j 2 --set "$P" --set "$V" --set "$M" --hdr > "$T/p2.out"
D -j 2 --set "$P" --set "$V" --set "$M" --hdr > "$T/p2b.out"
check_eq "perturbed: a different picture" "$(px same "$T/plain.out" "$T/p1.out")" differ
check_eq "perturbed: deterministic" "$(px same "$T/p2.out" "$T/p2b.out")" same
check_eq "perturbed: -j 1 = -j 2" "$(px same "$T/p1.out" "$T/p2.out")" same
D -j 2 --set "$P" --set "$V" --set "$M" --set "perturb density seed 10 scale 0.2 amplitude 1 octaves 3" \
    --hdr > "$T/seed.out"
check_eq "another seed: another picture" "$(px same "$T/p2.out" "$T/seed.out")" differ
D -j 2 --set "$P" --set "$V" --set "$M" --no-skip --hdr > "$T/ns.out"
check_eq "perturbed: skipping changes no bit" "$(px same "$T/p2.out" "$T/ns.out")" same
D -j 2 --set "$P" --stats -o /dev/null 2> "$T/st.err"
sk=$(sed -n 's/.*eye samples [0-9]* (\([0-9.]*\)% skipped.*/\1/p' "$T/st.err")
check "perturbed: some samples are still skipped" close "${sk:-0}" 50 49.9
# the reference samples the same perturbed field: the slicer's picture
# (shadows, no scattering) is near the ray march's of the perturbed field,
# far from the unperturbed one's
R() { D -j 2 --effects "volumetric-shadows specular" \
    --set "perturb coordinates scale 0.3 amplitude 0.3 octaves 3" --set "$V" "$@"; }
R --hdr > "$T/sp.out"
R --reference raymarch --hdr > "$T/rp.out"
R --reference raymarch --set "perturb none" --hdr > "$T/ru.out"
rr=$(px relrmse-all "$T/sp.out" "$T/rp.out")
ru=$(px relrmse-all "$T/sp.out" "$T/ru.out")
check "ray march of the perturbed field: rel. RMSE $rr < 0.1" close "$rr" 0 0.1
check "ray march of the unperturbed field: rel. RMSE $ru > 0.12 (> 2x)" \
    awk -v a="$ru" -v b="$rr" "BEGIN { exit !(a > 0.12 && a > 2 * b) }"
# the path tracer's majorant covers the perturbed extinction (density
# up to 1 + A): unbiased, it meets the ray march of the same field
# (shadows only, single scattering), not of the unperturbed one
Q() { D --effects volumetric-shadows --set "perturb coordinates scale 0.3 amplitude 0.3 octaves 3" \
    --set "perturb density scale 0.2 amplitude 2 octaves 2" "$@"; }
Q --reference pathtrace --spp 64 --hdr > "$T/qp.out"
Q --reference raymarch --hdr > "$T/qr.out"
Q --reference raymarch --set "perturb none" --hdr > "$T/qu.out"
rr=$(px relrmse-all "$T/qr.out" "$T/qp.out")
ru=$(px relrmse-all "$T/qu.out" "$T/qp.out")
check "path tracer vs ray march, perturbed: rel. RMSE $rr < 0.12" close "$rr" 0 0.12
check "path tracer vs the unperturbed ray march: rel. RMSE $ru > 2x that" \
    awk -v a="$ru" -v b="$rr" "BEGIN { exit !(a > 2 * b) }"

# 2. a constant slab displaced: still 1 - exp(-sigma d) (section 1 of
# test_dvr.sh, with the data coordinates perturbed)
$MK volume "$T/slab0.vx" --type f32 --dims 8 8 40 --formula 1
macrocell < "$T/slab0.vx" > "$T/slab.vx"
slab_scene "$T/slab.scn" "perturb coordinates scale 3 amplitude 2 octaves 5"
want=$(awk 'BEGIN { printf "%.9f", 1 - exp(39 * log(0.95)) }')
dvr --scene "$T/slab.scn" --hdr "$T/slab.vx" > "$T/slab.out"
check_close "constant slab displaced: coverage 1 - exp(-sigma d)" \
    "$(px img "$T/slab.out" color 4 4 3)" "$want" 2e-6
check_close "constant slab displaced: another pixel" \
    "$(px img "$T/slab.out" color 1 6 3)" "$want" 2e-6

# 3. what --explain says
D -n --set "$P" --set "$M" 2> "$T/ex.err" > /dev/null
check "--explain: coordinates perturbed" \
    grep -q "on  *perturb coordinates .*fBm(x / 0.4): A 0.25, 4 octaves" "$T/ex.err"
check "--explain: density perturbed" grep -q "on  *perturb density .*seed 9" "$T/ex.err"
D -n 2> "$T/ex0.err" > /dev/null
check "--explain: nothing perturbed without a line" \
    grep -q "off  *perturbation .*no perturb line" "$T/ex0.err"
D -n --set "perturb value scale 1 amplitude 0" 2> "$T/ex1.err" > /dev/null
check "--explain: amplitude 0 perturbs nothing" \
    grep -q "off  *perturbation .*amplitude 0" "$T/ex1.err"
check "--explain: the gradient for the surface ramp" \
    grep -q "on  *gradient .*surface list or ramp" "$T/ex0.err"

# 4. errors: one line each
expect_fail "perturb: unknown target" 64 "unknown value 'sideways'" \
    D --set "perturb sideways scale 1 amplitude 1"
expect_fail "perturb: no scale" 64 "scale and amplitude are required" \
    D --set "perturb value amplitude 1"
expect_fail "perturb: octaves 30" 64 "octaves: 30 outside" \
    D --set "perturb value scale 1 amplitude 1 octaves 30"
expect_fail "transfer surface gradient: G1 < G0" 64 "need 0 <= G0 < G1" \
    D --set "transfer surface gradient 2 1"
done_testing
