#!/bin/sh
# test_dvr.sh: dvr in pipelines: Beer-Lambert through a homogeneous slab
# (coverage 1 - exp(-sigma d) by formula, at two slice counts), the same
# bits at any thread count and with or without empty-space skipping, what
# --explain and --stats say (the compositing order flips when the light
# faces the viewer), PFM and stream output agreeing, and one line on every
# error (malformed transfer lines, a transfer file that cannot be read,
# options out of range, no transfer function).
. "$(dirname "$0")/lib.sh"
MK="python3 tests/cli/mkstream.py"
px() { python3 tests/cli/vximg.py "$@"; }

# 1. a homogeneous slab 39 deep seen straight on, emission 1, no light:
# coverage 1 - (1 - a)^(39 / ref) = 1 - exp(-sigma 39), sigma = -ln(1 - a)
$MK volume "$T/slab0.vx" --type f32 --dims 8 8 40 --formula 1
macrocell < "$T/slab0.vx" > "$T/slab.vx"
slab_scene "$T/slab.scn"
want=$(awk 'BEGIN { printf "%.9f", 1 - exp(39 * log(0.95)) }')
dvr --scene "$T/slab.scn" --hdr "$T/slab.vx" > "$T/slab.out"
check_close "slab: coverage 1 - exp(-sigma d)" \
    "$(px img "$T/slab.out" color 4 4 3)" "$want" 2e-6
check_close "slab: colour = coverage (emission 1)" \
    "$(px img "$T/slab.out" color 3 5 0)" "$want" 2e-6
dvr --scene "$T/slab.scn" --slices 117 --hdr "$T/slab.vx" > "$T/slab3.out"
check_close "slab: the same at 3x the slices (opacity corrected)" \
    "$(px img "$T/slab3.out" color 4 4 3)" "$want" 2e-6
# the reference step: "transfer step 2" makes the same alpha half as dense
want2=$(awk 'BEGIN { printf "%.9f", 1 - exp(19.5 * log(0.95)) }')
dvr --scene "$T/slab.scn" --set "transfer step 2" --hdr "$T/slab.vx" > "$T/slab2.out"
check_close "slab: reference step 2" \
    "$(px img "$T/slab2.out" color 4 4 3)" "$want2" 2e-6

# 2. a lit, scattering sphere: threads, skipping, outputs
vread --synth sphere --size 40 | macrocell > "$T/s.vx"
cat > "$T/s.scn" <<'SCN'
image width 48 height 40
light directional direction 1 -1 -1
light point position 0 3 0 intensity 0.3
transfer opacity 0 0.1 0.6 0.1 0.7 0.02 0.8 0
transfer color 0 1 0.8 0.6 0.7 0.9 0.9 1
transfer transport 0 0.95 0.8 0.6 0.7 0.95 0.8 0.6 0.8 1 1 1
transfer surface 0 0 0.5 1
medium phase henyey-greenstein g 0.3
effects volumetric-shadows scattering specular
SCN
D() { dvr --scene "$T/s.scn" --light-size 48 -j 2 "$@" "$T/s.vx"; }
D -j 1 --hdr > "$T/j1.out"
D -j 2 --hdr > "$T/j2.out"
check_eq "-j 1 = -j 2, bit for bit" "$(px same "$T/j1.out" "$T/j2.out")" same
D -j 2 --no-skip --hdr > "$T/ns.out" 2>"$T/ns.err"
check_eq "empty-space skipping changes no bit" "$(px same "$T/j1.out" "$T/ns.out")" same
check_eq "--no-skip builds no hierarchy" "$(cat "$T/ns.err")" ""
D -j 1 -o "$T/j1.png"
D -j 2 -o "$T/j2.png"
check_eq "PNG: -j 1 = -j 2" "$(px pngsame "$T/j1.png" "$T/j2.png")" same
D --pfm "$T/c.pfm" -o /dev/null
check_close "PFM = the stream's image" "$(px pfm "$T/c.pfm" 20 18 1)" \
    "$(px img "$T/j1.out" color 20 18 1)" 0
c=$(px img "$T/j1.out" color 24 20 0)
check "the sphere is drawn (centre red > 0.05)" close "$c" 0.5 0.45
D --stats --slices 50 -o /dev/null 2>"$T/st.err"
check "--stats: slices" grep -q "^dvr: 50 slices, 2 threads" "$T/st.err"
sk=$(sed -n 's/.*eye samples [0-9]* (\([0-9.]*\)% skipped.*/\1/p' "$T/st.err")
check "--stats: some eye samples skipped ($sk%)" close "$sk" 50 49.9
check "--stats: time per phase" grep -q "eye passes .* light passes" "$T/st.err"

# 3. --explain: the plan and the slicing; the order flips when the light
# comes toward the viewer (front view: the eye looks along -y)
D -n 2>"$T/ex.err" >/dev/null
check "--explain: light buffer driven by light 1" \
    grep -q "light buffer .*driven by light 1 (directional)" "$T/ex.err"
check "--explain: the second light is unshadowed" \
    grep -q "light 2 point .*unshadowed" "$T/ex.err"
check "--explain: front to back" grep -q "eye composites front to back" "$T/ex.err"
check "--explain: the gradient (surface list)" grep -q "on  *gradient" "$T/ex.err"
D -n --set "light none" --light "directional direction 0.2 1 -0.3" 2>"$T/ex2.err" >/dev/null
check "--explain: back to front when the light faces the viewer" \
    grep -q "inverted view .*back to front" "$T/ex2.err"
D -n --effects none 2>"$T/ex3.err" >/dev/null
check "--explain: no light buffer without the effects" \
    grep -q "off  *light buffer .*no volumetric-shadows or scattering" "$T/ex3.err"

# 4. errors: one line each
expect_fail "no transfer function" 65 "dvr: transfer: no opacity" \
    dvr "$T/s.vx"
expect_fail "transfer opacity: odd numbers" 64 "groups of 2" \
    dvr --set "transfer opacity 0" "$T/s.vx"
printf 'image width 8 height 8\ntransfer surface 0 2\n' > "$T/bad.scn"
expect_fail "scene file: surface weight out of range" 65 \
    "line 2: transfer: weight: 2 outside \[0, 1\]" \
    dvr --scene "$T/bad.scn" "$T/s.vx"
expect_fail "transfer step: negative" 64 "step: -1 outside" \
    dvr --set "transfer step -1" "$T/s.vx"
expect_fail "transfer file: unknown format" 64 "unknown value 'csv'" \
    dvr --set "transfer file x.json format csv" "$T/s.vx"
echo "not a transfer function" > "$T/bad.json"
expect_fail "transfer file: unreadable" 65 "dvr: transfer file $T/bad.json: " \
    dvr --scene "$T/s.scn" --set "transfer file $T/bad.json" "$T/s.vx"
# a relative transfer file in a scene file lies beside the scene
mkdir -p "$T/sub"
cp "$T/bad.json" "$T/sub/bad.json"
printf 'transfer file bad.json format paraview\n' > "$T/sub/f.scn"
expect_fail "transfer file: beside the scene" 65 \
    "dvr: transfer file $T/sub/bad.json: " dvr --scene "$T/sub/f.scn" "$T/s.vx"
expect_fail "--slices 0" 64 "--slices" dvr --slices 0 "$T/s.vx"
expect_fail "--light-size 0" 64 "--light-size" dvr --light-size 0 "$T/s.vx"
expect_fail "--blur-angle 95" 64 "--blur-angle" dvr --blur-angle 95 "$T/s.vx"
expect_fail "--blur-samples 99" 64 "--blur-samples" dvr --blur-samples 99 "$T/s.vx"
done_testing
