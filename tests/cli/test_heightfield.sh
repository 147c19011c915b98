#!/bin/sh
# test_heightfield.sh: heightfield(1) with dvr(1): a flat map of height h
# seen straight down is a slab of thickness h whose coverage is
# 1 - exp(-sigma h) by formula (the density's soft step put exactly at h,
# with a transfer function stepping at density 1/2); the same map as an
# 8-bit PGM, a 16-bit PGM, 8- and 16-bit PNGs and a PFM gives the same
# slab; --thickness makes a layer of that thickness; --range moves the
# heights; the map's top row is the far (+y) edge, as seen from above;
# dvr can perturb the height field.  Malformed maps: tests/malformed.
. "$(dirname "$0")/lib.sh"
px() { python3 tests/cli/vximg.py "$@"; }

# maps of 6 x 4 pixels: "flat K BITS" all K, "half K BITS" K in the top two
# rows and 0 below, as PGM, PNG (gray) or PFM
python3 - "$T" <<'PY'
import struct, sys, zlib
t = sys.argv[1]
W, H = 6, 4
def rows(kind, k):
    return [[k if kind == "flat" or y < 2 else 0 for x in range(W)]
            for y in range(H)]
def pgm(name, r, maxval):
    fmt = ">%dH" if maxval > 255 else "%dB"
    body = b"".join(struct.pack(fmt % W, *row) for row in r)
    open("%s/%s" % (t, name), "wb").write(b"P5\n# test\n%d %d\n%d\n" %
        (W, H, maxval) + body)
def png(name, r, bits):
    def chunk(ty, d):
        return struct.pack(">I", len(d)) + ty + d + struct.pack(">I",
            zlib.crc32(ty + d))
    fmt = ">%dH" if bits == 16 else "%dB"
    raw = b"".join(b"\0" + struct.pack(fmt % W, *row) for row in r)
    open("%s/%s" % (t, name), "wb").write(b"\x89PNG\r\n\x1a\n" +
        chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, bits, 0, 0, 0, 0)) +
        chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
def pfm(name, r):
    body = b"".join(struct.pack("<%df" % W, *row) for row in reversed(r))
    open("%s/%s" % (t, name), "wb").write(b"Pf\n%d %d\n-1\n" % (W, H) + body)
pgm("flat8.pgm", rows("flat", 100), 255)
pgm("flat16.pgm", rows("flat", 25700), 65535)
png("flat8.png", rows("flat", 100), 8)
png("flat16.png", rows("flat", 25700), 16)
pfm("flat.pfm", rows("flat", 100 / 255))
pgm("half8.pgm", rows("half", 100), 255)
PY
# 52 samples along z: height 100/255 x 51 = 20 voxels; the slab seen from
# above through an orthographic camera, slices one voxel apart at the
# half-integers, 20 of them inside; emission 1, no light
cat > "$T/hf.scn" <<'SCN'
camera orthographic eye 2.5 1.5 100 look 2.5 1.5 0 up 0 1 0 width 6
image width 6 height 4
light none
ambient intensity 1
effects none
transfer opacity 0 0 0.5 0 0.5 0.05 1 0.05
SCN
cov() {   # cov MAP [heightfield options]: the coverage of pixel (2, 1)
	map=$1; shift
	heightfield --nz 52 "$@" "$T/$map" | macrocell > "$T/hf.vx" &&
	    dvr --scene "$T/hf.scn" --hdr "$T/hf.vx" > "$T/hf.out" &&
	    px img "$T/hf.out" color 2 1 3
}
want=$(awk 'BEGIN { printf "%.9f", 1 - exp(20 * log(0.95)) }')
check_close "flat map, 8-bit PGM: slab coverage 1 - exp(-sigma h)" \
    "$(cov flat8.pgm)" "$want" 2e-6
check_close "flat map, 16-bit PGM: the same" "$(cov flat16.pgm)" "$want" 2e-6
check_close "flat map, 8-bit PNG: the same" "$(cov flat8.png)" "$want" 2e-6
check_close "flat map, 16-bit PNG: the same" "$(cov flat16.png)" "$want" 2e-6
check_close "flat map, PFM: the same" "$(cov flat.pfm)" "$want" 2e-6
check_close "flat map, edge 6: the same (the step stays at h)" \
    "$(cov flat8.pgm --edge 6)" "$want" 2e-6
want8=$(awk 'BEGIN { printf "%.9f", 1 - exp(8 * log(0.95)) }')
check_close "--thickness 8: a layer 8 voxels thick" \
    "$(cov flat8.pgm --thickness 8)" "$want8" 2e-6
# --range 0,2: half the height (10 voxels)
want10=$(awk 'BEGIN { printf "%.9f", 1 - exp(10 * log(0.95)) }')
check_close "--range 0,2: half the height" "$(cov flat8.pgm --range 0,2)" \
    "$want10" 2e-6
# the density itself: 1 up to z = 19, 0.5 at h = 20, 0 from 21 (edge 2):
# a column's mean is 20.5 / 52
heightfield --nz 52 "$T/flat8.pgm" | vinfo - > "$T/hf.info" 2>&1
check "the volume is 6x4x52 f32 named height" \
    grep -q "dims: 6 x 4 x 52 f32" "$T/hf.info"
check_close "the density's mean: 20.5 / 52" \
    "$(sed -n 's/^ *mean: //p' "$T/hf.info")" \
    "$(awk 'BEGIN { printf "%.9f", 20.5 / 52 }')" 1e-8
# orientation: the map's top rows (height 20) at +y, the picture's top
heightfield --nz 52 "$T/half8.pgm" | macrocell > "$T/half.vx"
dvr --scene "$T/hf.scn" --hdr "$T/half.vx" > "$T/half.out"
check_close "map top row: the far edge, covered" \
    "$(px img "$T/half.out" color 3 0 3)" "$want" 2e-6
check_close "map bottom row: the near edge, height 0, empty" \
    "$(px img "$T/half.out" color 3 3 3)" 0 1e-9
# a perturbed height field: the same bits at -j 1 and -j 2, another picture
P='perturb coordinates scale 2 amplitude 1.5 octaves 3'
dvr --scene "$T/hf.scn" --set "$P" -j 1 --hdr "$T/half.vx" > "$T/p1.out"
dvr --scene "$T/hf.scn" --set "$P" -j 2 --hdr "$T/half.vx" > "$T/p2.out"
check_eq "perturbed height field: -j 1 = -j 2" "$(px same "$T/p1.out" "$T/p2.out")" same
check_eq "perturbed height field: another picture" \
    "$(px same "$T/p1.out" "$T/half.out")" differ
# no output on error
heightfield --nz 52 -o "$T/none.vx" "$T/hf.scn" 2>/dev/null
check "no output file after an error" test ! -e "$T/none.vx"
done_testing
