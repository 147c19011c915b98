#!/bin/sh
# test_bakesh.sh: bake-sh in pipelines, and raycast's `illumination sh`:
# radiance against the white furnace and Ramamoorthi and Hanrahan's
# irradiance formula, SH shading against irradiance shading, rotating the
# light against turning the camera, the same bits at any thread count,
# resumed = merged = one run, lazy = full, the memory limit, one line on
# every error.
. "$(dirname "$0")/lib.sh"
MK="python3 tests/cli/mkstream.py"
shtv() { $MK payload "$1" SHTV | cksum; }
px() { python3 tests/cli/vximg.py "$@"; }

vread --synth sphere --size 32 | macrocell > "$T/s.vx"

# 1. white furnace: a convex surface (the sphere field is a distance: the
# lit side is the high one) under a sky of radiance 1: E = pi, radiance
# 0.8 (the default albedo); the transfer's constant coefficient is exact
# (pi Y00 every sample) and the sky's projection has no other band
bake-sh --iso 0.5 --side high --samples 16 --order 3 -j 2 "$T/s.vx" \
    > "$T/b.vx" 2>"$T/b.err"
check_eq "bake-sh: silent when stderr is not a terminal" "$(cat "$T/b.err")" ""
for m in trilinear nearest nearest-iso tricubic; do
	raycast --iso 0.5 --light sky --set "illumination sh interpolation $m" \
	    --size 33x33 --hdr "$T/b.vx" > "$T/r.vx"
	check_close "white furnace, interpolation $m" \
	    "$(px img "$T/r.vx" color 13 19 1)" 0.8 1e-5
done

# 2. the same bits at any thread count; resumed and merged = one run
S() { bake-sh --iso 0.5 --side high --order 4 --bounces 1 "$@"; }
S --samples 12 -j 1 "$T/s.vx" > "$T/one.vx"
S --samples 12 -j 2 "$T/s.vx" > "$T/one2.vx"
check_eq "-j 1 = -j 2, bit for bit" "$(shtv "$T/one2.vx")" "$(shtv "$T/one.vx")"
S --samples 5 "$T/s.vx" | S --samples 7 > "$T/res.vx"
check_eq "resumed (5 + 7 samples) = one run of 12" "$(shtv "$T/res.vx")" "$(shtv "$T/one.vx")"
S --samples 5 "$T/s.vx" > "$T/a.vx"
S --first-sample 5 --samples 7 "$T/s.vx" > "$T/bb.vx"
S --merge "$T/bb.vx" "$T/a.vx" > "$T/m.vx"
check_eq "merged ([0,5) + [5,12)) = one run of 12" "$(shtv "$T/m.vx")" "$(shtv "$T/one.vx")"
S --samples 12 --half "$T/s.vx" > "$T/h.vx"
check_eq "a half bake holds no accumulators: f16, 2 + 2 x 16 bytes a texel" \
    "$(vinfo "$T/h.vx" | grep -o 'store: f16, [0-9]* bytes a texel')" \
    "store: f16, 34 bytes a texel"
expect_fail "resume: other settings (order)" 65 "other settings" \
    bake-sh --iso 0.5 --side high --order 3 --bounces 1 "$T/one.vx"
expect_fail "resume: a final bake" 65 "final" \
    S --samples 4 "$T/h.vx"

# 3. lazy: raycast --lazy bakes the texels its view reads exactly as
# bake-sh --lazy recorded; the picture equals the full bake's
S --samples 8 --lazy "$T/s.vx" > "$T/empty.vx"
S --samples 8 "$T/s.vx" > "$T/full.vx"
R() { raycast --light sky --set "interreflection bounces 1" \
    --effects +interreflection --iso 0.5 --set "illumination sh order 4" \
    --size 40x40 --hdr "$@"; }
R "$T/full.vx" > "$T/rfull.vx"
R --lazy --lazy-save "$T/lazy.vx" --stats "$T/empty.vx" > "$T/rlazy.vx" 2>"$T/lst"
check_eq "lazy: the picture of the full bake" "$(px same "$T/rfull.vx" "$T/rlazy.vx")" same
check "lazy: says what it baked" grep -q "lazy: the view reads [1-9][0-9]* texels: [1-9][0-9]* baked now" "$T/lst"
S --merge "$T/lazy.vx" "$T/full.vx" > "$T/lm.vx"
check_eq "lazy texels = the full bake's, bit for bit" "$(shtv "$T/lm.vx")" "$(shtv "$T/full.vx")"

# 4. Ramamoorthi and Hanrahan: a convex sphere under order-3 lighting
# (an environment that varies with direction, written here as a PFM) has
# E(n) = c1 L22 (x^2 - y^2) + c3 L20 z^2 + c4 L00 - c5 L20
#        + 2 c1 (L2-2 xy + L21 xz + L2-1 yz) + 2 c2 (L11 x + L1-1 y + L10 z)
# (their eq. 13, their basis); the centre pixel of the front view sees the
# normal +y: E = -c1 L22 + c4 L00 - c5 L20 + 2 c2 L1-1.  The transfer's
# Monte Carlo error at 256 scrambled Sobol samples is below 0.3% there.
python3 - "$T/env.pfm" <<'PY'
import math, struct, sys
w, h = 64, 32
with open(sys.argv[1], 'wb') as f:
    f.write(b'PF\n%d %d\n-1.0\n' % (w, h))
    for j in range(h - 1, -1, -1):            # PFM: bottom row first
        for i in range(w):
            th = (j + 0.5) / h * math.pi
            ph = ((i + 0.5) / w - 0.5) * 2 * math.pi
            r = 1 + 0.8 * math.sin(th) * math.cos(ph) + 0.3 * math.cos(th)
            f.write(struct.pack('<3f', r, 0.7 * r,
                0.5 + 0.3 * math.sin(th) * math.sin(ph)))
PY
bake-sh --iso 0.5 --side high --samples 256 --order 3 "$T/s.vx" > "$T/b3.vx"
sh-rotate --env "$T/env.pfm" --order 3 "$T/b3.vx" > "$T/lit.vx"
sh-rotate --env "$T/env.pfm" --order 3 --irradiance "$T/b3.vx" > "$T/rh.txt"
raycast --iso 0.5 --set "illumination sh" --size 33x33 --hdr "$T/lit.vx" \
    > "$T/rl.vx"
for c in 0 1 2; do
	want=$(awk -v c=$c '$1 ~ /^L/ { L[$1] = $(2 + c) }
	    END { e = -0.429043 * L["L22"] + 0.886227 * L["L00"] - 0.247708 * L["L20"] + 2 * 0.511664 * L["L1-1"]; printf "%.9g", 0.8 / 3.14159265358979 * e }' "$T/rh.txt")
	check_close "R&H formula at the normal +y, channel $c" \
	    "$(px img "$T/rl.vx" color 16 16 $c)" "$want" 3e-3
done

# 5. rotating the lighting by R = turning the camera by R^-1 about a
# sphere (rotationally symmetric): the lighting turned 90 degrees about +z
# seen from the front (the eye toward +y) equals the unturned lighting
# seen from R^-1 (+y) = +x, azimuth 90 (formats/scene.md),
# pixel for pixel within the transfer's Monte Carlo error (different
# texels carry different sample sequences)
sh-rotate --env "$T/env.pfm" --order 3 --axis 0,0,1,90 "$T/b3.vx" > "$T/rot.vx"
raycast --iso 0.5 --set "illumination sh" --size 33x33 --hdr "$T/rot.vx" > "$T/ra.vx"
raycast --iso 0.5 --set "illumination sh" --view 90,0 --size 33x33 --hdr \
    "$T/lit.vx" > "$T/rb.vx"
check "rotated light = turned camera (relative RMSE < 1%)" python3 -c "
import sys; sys.exit(0 if float('$(px relrmse "$T/ra.vx" "$T/rb.vx")') < 0.01 else 1)"
raycast --iso 0.5 --set "illumination sh" --view -90,0 --size 33x33 --hdr \
    "$T/lit.vx" > "$T/rc.vx"
check "... and not the camera turned the other way" python3 -c "
import sys; sys.exit(0 if float('$(px relrmse "$T/ra.vx" "$T/rc.vx")') > 0.05 else 1)"

# 6. SH shading = irradiance shading for a smooth environment (this one is
# of bands 0 and 1 but for its pixels): order 3 against bake-irr's
# importance-sampled irradiance, within their Monte Carlo errors (1.5%)
cat > "$T/env.scn" <<EOS
light environment file "$T/env.pfm"
EOS
bake-irr --scene "$T/env.scn" --iso 0.5 --side high --samples 256 "$T/s.vx" \
    > "$T/irr.vx"
raycast --scene "$T/env.scn" --iso 0.5 --set "illumination irradiance" \
    --size 33x33 --hdr "$T/irr.vx" > "$T/ri.vx"
raycast --scene "$T/env.scn" --iso 0.5 --set "illumination sh" --size 33x33 \
    --hdr "$T/b3.vx" > "$T/rs.vx"
check "SH (order 3, the scene's map projected) = irradiance (RMSE < 1.5%)" python3 -c "
import sys; sys.exit(0 if float('$(px relrmse "$T/ri.vx" "$T/rs.vx")') < 0.015 else 1)"

# 7. memory: refused before any work, naming the knobs; reported
expect_fail "--max-memory: refused, with the knobs that fit" 71 \
    "lower --order" bake-sh --iso 0.5 --side high --order 16 --max-memory 0.001 "$T/s.vx"
bake-sh --iso 0.5 --side high --order 5 --half -n "$T/s.vx" 2>"$T/ex"
check "--explain: bytes a texel in memory and in the stream" \
    grep -q "f16 SH order 5 (25 coefficients x 1 channel): 104 bytes a texel in memory (52 in the stream)" "$T/ex"
check "vinfo names the transfer volume" sh -c "vinfo '$T/b3.vx' | grep -q 'SH transfer volume: order 3, 1 channel'"
vwrite --chunk SHTV -o "$T/t.nrrd" "$T/b3.vx"
check_eq "vwrite: NRRD of 9 coefficients a texel (kind list), 2272 usable texels with c0 = pi Y00" \
    "$(python3 - "$T/t.nrrd" <<'PY'
import struct, sys
d = open(sys.argv[1], 'rb').read()
head, body = d.split(b'\n\n', 1)
h = dict(l.split(': ', 1) for l in head.decode().split('\n')[1:] if ': ' in l)
n = len(body) // 4
v = struct.unpack('<%df' % n, body)
c0 = [v[i] for i in range(0, n, 9)]
print(h['sizes'], h['kinds'].split()[0],
      sum(1 for x in c0 if abs(x - 0.886226925) < 1e-6))
PY
)" "9 32 32 32 list 2272"
expect_fail "illumination sh without a transfer volume" 65 "no SH transfer volume" \
    raycast --iso 0.5 --light sky --set "illumination sh" "$T/s.vx"
expect_fail "illumination sh without lighting" 64 "no SH lighting" \
    raycast --iso 0.5 --set "illumination sh" "$T/b3.vx"
expect_fail "--order out of range" 64 "--order" bake-sh --order 17 "$T/s.vx"
# one program, two faces: each synopsis names its own options, then the
# shared ones, and -h and --help print it
check_eq "bake-sh -h: its synopsis" "$(bake-sh -h | sed -n '1p;2p;7p')" \
    "$(printf '%s\n' 'usage: bake-sh [--scene FILE] [--set LINE] [--effects WORDS] [--iso V[,V...]]' \
    '    [--name VOLUME] [--order N] [--channels 1|3] [--scale S]' \
    '    [--max-memory GB] [-z LEVEL] [-j N] [--stats] [--explain] [-n]')"
check_eq "bake-irr --help: its synopsis, the shared tail the same" \
    "$(bake-irr --help | sed -n '1p;3,$p')" \
    "$(printf '%s\n' 'usage: bake-irr [--scene FILE] [--set LINE] [--light SPEC] [--lights none]'; bake-sh -h | sed -n '3,$p')"
done_testing
