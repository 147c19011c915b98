#!/bin/sh
# test_shrotate.sh: sh-rotate(1) on synthetic lat-long maps written here
# (formats/scene.md's mapping) and on Debian blender-data's forest.exr.
# Oracles: Y00 = 1/sqrt(4 pi), so a constant L projects to c00 = L sqrt(4 pi)
# exactly (the solid angles sum to 4 pi) and its m != 0 terms vanish (equally
# spaced phi); its m = 0, l > 0 terms are the pixel-centre quadrature's error,
# which falls as 1/h^2; a linear map's band 1 turned by 90 degrees about z
# moves +x's light to +y; a turn and its inverse give the input back; the
# irradiance of a constant is pi L (Ramamoorthi and Hanrahan's A0 = pi);
# c00 of a real map is sqrt(4 pi) times its solid-angle-weighted mean,
# computed here independently in Python.
. tests/cli/lib.sh
W=/usr/share/blender/datafiles/studiolights/world

python3 - "$T" <<'EOF2'
import math, struct, sys
t = sys.argv[1]
def pfm(path, w, h, f):
    rows = []
    for j in range(h):
        row = []
        for i in range(w):
            th = math.pi * (j + .5) / h; ph = math.pi - 2 * math.pi * (i + .5) / w
            row += f((math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)))
        rows.append(row)
    with open(path, "wb") as o:
        o.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        for r in rows[::-1]:
            o.write(struct.pack("<%df" % len(r), *r))
pfm(t + "/c32.pfm", 64, 32, lambda d: [2, 0.5, 1])
pfm(t + "/c64.pfm", 128, 64, lambda d: [2, 0.5, 1])
pfm(t + "/c128.pfm", 256, 128, lambda d: [2, 0.5, 1])
pfm(t + "/lin.pfm", 64, 32, lambda d: [1 + .5 * d[0], 1 + .25 * d[1], 1 + .5 * d[2]])
pfm(t + "/smooth.pfm", 512, 256, lambda d: [math.exp(2 * d[2]), math.exp(d[0]), 1 + .5 * d[1] * d[2]])
pfm(t + "/nan.pfm", 4, 2, lambda d: [float("nan"), 0, 0])
EOF2
co() {   # co FILE L M CH: coefficient (L, M) of channel CH (0 r, 1 g, 2 b)
	awk -v l="$2" -v m="$3" -v c="$4" '!/^#/ && $1 == l && $2 == m { print $(3 + c) }' "$1"
}
maxabs() {   # maxabs FILE: the largest |c| over l > 0 with m != 0 / m == 0
	awk -v z="$2" '!/^#/ && $1 > 0 && (z ? $2 == 0 : $2 != 0) {
	    for (k = 3; k <= 5; k++) { v = $k < 0 ? -$k : $k; if (v > x) x = v } }
	    END { printf "%.3g\n", x + 0 }' "$1"
}
rel() { awk -v a="$1" -v b="$2" 'BEGIN { d = (a - b) / b; print d < 0 ? -d : d }'; }

# ---- a constant map ----
sh-rotate --env "$T/c32.pfm" --print > "$T/c32.txt"
sh-rotate --env "$T/c64.pfm" --print > "$T/c64.txt"
s4pi=3.5449077018110318
check_close "constant: c00 r = 2 sqrt(4 pi)" "$(co "$T/c32.txt" 0 0 0)" "$(awk -v s=$s4pi 'BEGIN { printf "%.17g", 2 * s }')" 1e-13
check_close "constant: c00 g = 0.5 sqrt(4 pi)" "$(co "$T/c32.txt" 0 0 1)" "$(awk -v s=$s4pi 'BEGIN { printf "%.17g", .5 * s }')" 1e-13
check_close "constant: every m != 0 term is 0 (to rounding)" "$(maxabs "$T/c32.txt" 0)" 0 1e-14
a=$(maxabs "$T/c32.txt" 1); b=$(maxabs "$T/c64.txt" 1)
check_close "constant: m = 0 terms (quadrature error) below 2e-3 c00 at h = 32" "$a" 0 0.014
check_close "constant: and they fall as 1/h^2 (h 32 -> 64: ratio 4)" "$(awk -v a=$a -v b=$b 'BEGIN { print a / b }')" 4 0.1
check_eq "constant: order 5 by default (25 coefficients)" "$(grep -vc '^#' "$T/c32.txt")" 25
check_eq "reads no standard input with --env (stdin closed)" "$(sh-rotate --env "$T/c32.pfm" --print --order 1 0<&- | grep -vc '^#')" 1

# ---- irradiance of a constant: pi L in every direction ----
sh-rotate --env "$T/c128.pfm" --irradiance > "$T/irr.txt"
bad=$(awk -v p=3.14159265358979 '$1 == "E" { for (k = 3; k <= 5; k++) {
    L = (k == 3 ? 2 : k == 4 ? .5 : 1); d = ($k - p * L) / (p * L); if (d < 0) d = -d
    if (d > 1e-4) n++ } } END { print n + 0 }' "$T/irr.txt")
check_eq "irradiance of a constant: E = pi L at the six axes, to 1e-4 (256 x 128)" "$bad" 0
check_eq "irradiance: nine L_lm and six E lines" "$(grep -c '^L' "$T/irr.txt") $(grep -c '^E' "$T/irr.txt")" "9 6"
check_close "irradiance: L00 is c00" "$(awk '$1 == "L00" { print $2 }' "$T/irr.txt")" "$(awk -v s=$s4pi 'BEGIN { printf "%.17g", 2 * s }')" 1e-6

r1=$(sh-rotate --env "$T/c128.pfm" --order 3 --irradiance-error | awk '{ print $4 }')
check_close "--irradiance-error of a constant: quadrature-level (< 1e-4)" "$r1" 0 1e-4
r1=$(sh-rotate --env "$T/smooth.pfm" --order 2 --irradiance-error | awk '{ print $4 }')
r2=$(sh-rotate --env "$T/smooth.pfm" --order 5 --irradiance-error | awk '{ print $4 }')
check "--irradiance-error of exp(2z): order 5 below order 2's tenth" awk -v a="$r1" -v b="$r2" 'BEGIN { exit !(b < a / 10 && a > 1e-3) }'

# ---- rotation ----
sh-rotate --env "$T/lin.pfm" --order 2 --print > "$T/l0.txt"
sh-rotate --env "$T/lin.pfm" --order 2 --euler 90,0,0 > "$T/l90.vx"
sh-rotate --print "$T/l90.vx" > "$T/l90.txt"
check_close "90 deg about z: +x's light (r) comes from +y: c'(1,-1) = c(1,1)" "$(co "$T/l90.txt" 1 -1 0)" "$(co "$T/l0.txt" 1 1 0)" 1e-13
check_close "90 deg about z: g = 1 + y/4 becomes 1 - x/4: c'(1,1) = -c(1,-1)" "$(co "$T/l90.txt" 1 1 1)" "$(awk -v x="$(co "$T/l0.txt" 1 -1 1)" 'BEGIN { printf "%.17g", -x }')" 1e-13
check "the turn changes the coefficients" sh -c "! cmp -s '$T/l0.txt' '$T/l90.txt'"
sh-rotate --euler -90,0,0 "$T/l90.vx" | sh-rotate --print > "$T/lback.txt"
d=$(paste "$T/l0.txt" "$T/lback.txt" | awk '!/^#/ { for (k = 3; k <= 5; k++) { d = $k - $(k + 5); if (d < 0) d = -d; if (d > x) x = d } } END { printf "%.3g", x + 0 }')
check_close "90 deg about z, then -90: the input back (1e-14)" "$d" 0 1e-14
check_eq "... and the recorded rotation is the identity" "$(sed -n 2p "$T/lback.txt" | awk '{ for (k = 3; k <= 11; k++) s = s sprintf(" %.6f", $k + 0) ; print s }')" " 1.000000 0.000000 0.000000 0.000000 1.000000 0.000000 0.000000 0.000000 1.000000"
sh-rotate --env "$T/smooth.pfm" --order 6 --axis 1,2,3,40 --print > "$T/ax.txt"
sh-rotate --env "$T/smooth.pfm" --order 6 --matrix "$(sed -n 2p "$T/ax.txt" | cut -d' ' -f3- | tr ' ' ,)" --print > "$T/mx.txt"
check_eq "--axis and --matrix of the same turn agree" "$(sed 1,2d "$T/ax.txt" | md5sum)" "$(sed 1,2d "$T/mx.txt" | md5sum)"

# ---- reconstruction ----
sh-rotate --env "$T/smooth.pfm" --order 16 --reconstruct "$T/rec.pfm" --width 64 --height 32
err=$(python3 - "$T/rec.pfm" <<'EOF2'
import math, struct, sys
d = open(sys.argv[1], "rb").read(); p = d.split(b"\n", 3); w, h = map(int, p[1].split())
v = struct.unpack("<%df" % (3 * w * h), p[3]); rows = [v[3 * w * y:3 * w * (y + 1)] for y in range(h)][::-1]
m = 0
for j in range(h):
    for i in range(w):
        th = math.pi * (j + .5) / h; ph = math.pi - 2 * math.pi * (i + .5) / w
        x, y, z = math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)
        for k, f in enumerate([math.exp(2 * z), math.exp(x), 1 + .5 * y * z]):
            m = max(m, abs(rows[j][3 * i + k] - f) / f)
print("%.3g" % m)
EOF2
)
check_close "order 16 rebuilds exp(2z), exp(x), 1 + yz/2 (512 x 256) within 0.5%" "$err" 0 5e-3
sh-rotate --env "$T/smooth.pfm" --order 16 --reconstruct "$T/rech.pfm" --window hanning --width 8 --height 4
check "--window hanning changes the picture" sh -c "! cmp -s '$T/rech.pfm' '$T/rec.pfm'"

# ---- in a pipeline: chunks pass through, SHLC replaced ----
vread --synth sphere --size 8 > "$T/s.vx"
sh-rotate --env "$T/lin.pfm" --order 3 - < "$T/s.vx" | sh-rotate --env "$T/c32.pfm" - > "$T/p.vx"
check_eq "pipeline: VOLM kept, one SHLC (replaced)" "$(python3 -c 'import struct, sys
d = open(sys.argv[1], "rb").read(); p = 8; t = []
while p < len(d):
    t.append(d[p:p + 4].decode()); p += 16 + struct.unpack("<Q", d[p + 4:p + 12])[0]
print(" ".join(t))' "$T/p.vx")" "hist VOLM SHLC VEND"
check_close "pipeline: the SHLC is the second map's" "$(sh-rotate --print "$T/p.vx" | co /dev/stdin 0 0 0)" "$(co "$T/c32.txt" 0 0 0)" 0
vscene --light "environment file $T/lin.pfm" "$T/s.vx" | sh-rotate --order 2 --print > "$T/sc.txt"
check_eq "the scene's environment light projects as --env does" "$(sed 1d "$T/sc.txt")" "$(sed 1d "$T/l0.txt")"
check_eq "the source hash is the scene's" "$(sed -n '1s/.*source //p' "$T/sc.txt")" "$(vscene --light "environment file $T/lin.pfm" --print "$T/s.vx" | sed -n 's/.* hash \([0-9a-f]*\) .*/\1/p')"
# the scene's environment and sky lights add: two skies of intensity 2 and 3
# project as one of 5 (oracle: a constant L has c00 = 2 sqrt(pi) L), with
# no single source hash
vscene --lights none --light "sky color 1 1 1 intensity 2" \
    --light "sky color 1 1 1 intensity 3" "$T/s.vx" | sh-rotate --order 1 --print > "$T/two.txt"
check_close "two sky lights: their sum" "$(co "$T/two.txt" 0 0 1)" "$(awk -v s=$s4pi 'BEGIN { printf "%.17g", 5 * s }')" 1e-13
check_eq "two sky lights: no single source hash" "$(sed -n '1s/.*source //p' "$T/two.txt")" none

# ---- errors: one line, the right code ----
expect_fail "--order 0" 64 "order" sh-rotate --env "$T/c32.pfm" --order 0 --print
expect_fail "--order 17" 64 "order" sh-rotate --env "$T/c32.pfm" --order 17 --print
expect_fail "--euler with two numbers" 64 "euler" sh-rotate --env "$T/c32.pfm" --euler 1,2 --print
expect_fail "--matrix not a rotation" 64 "not a rotation" sh-rotate --env "$T/c32.pfm" --matrix 1,0,0,0,1,0,0,0,-1 --print
expect_fail "two rotations" 64 "one of" sh-rotate --env "$T/c32.pfm" --euler 1,2,3 --axis 0,0,1,5 --print
expect_fail "--window unknown" 64 "window" sh-rotate --env "$T/c32.pfm" --window kaiser --reconstruct "$T/x.pfm"
expect_fail "missing --env file" 66 "nothere" sh-rotate --env "$T/nothere.pfm" --print
expect_fail "a NaN pixel" 65 "nan.pfm" sh-rotate --env "$T/nan.pfm" --print
expect_fail "no light and no SH lighting" 64 "no environment" sh-rotate --print "$T/s.vx"
expect_fail "--order above the stream's" 64 "order 5" sh-rotate --order 6 --print "$T/p.vx"
check "no half-written PFM on error" test ! -e "$T/x.pfm"

# ---- vinfo decodes the SHLC chunk: what it holds, and the bands' energy,
# which a rotation keeps (the rotation mixes coefficients within a band) ----
sh-rotate --env "$T/c32.pfm" --order 3 > "$T/v.vx"
sh-rotate --env "$T/lin.pfm" --order 3 > "$T/vl.vx"
sh-rotate --axis 0,0,1,90 "$T/vl.vx" > "$T/vr.vx"
vinfo "$T/v.vx" > "$T/v.info"
check "vinfo: SHLC order and phase" grep -q "SH lighting: order 3 (9 coefficients a channel, r g b), phase condon-shortley" "$T/v.info"
check "vinfo: the source map's hash, no rotation" sh -c "grep -q 'source map: content hash [0-9a-f]\{16\}' '$T/v.info' && grep -q 'rotation: identity' '$T/v.info'"
check_close "vinfo: c00 r of the constant map = 2 sqrt(4 pi)" "$(awk '/c00:/ { print $2 }' "$T/v.info")" "$(awk -v s=$s4pi 'BEGIN { printf "%.17g", 2 * s }')" 1e-7
check_close "vinfo: band 0 energy r = c00^2 = 16 pi" "$(awk '/band 0 energy:/ { print $4 }' "$T/v.info")" 50.26548245743669 1e-6
vinfo "$T/vr.vx" | grep -q "rotation: 6.123234e-17 -1 0 / 1 6.123234e-17 0 / 0 0 1 (rows)"
check_eq "vinfo: the turn's rotation matrix (90 degrees about z)" "$?" 0
vinfo --json "$T/vl.vx" > "$T/vl.json"
vinfo --json "$T/vr.vx" > "$T/vr.json"
check_close "vinfo --json: a rotation keeps each band's energy (bands 1, 2; r g b)" "$(python3 - "$T/vl.json" "$T/vr.json" <<'EOF2'
import json, sys
def bands(p):
    return [c["sh_lighting"]["band_energy"] for c in json.load(open(p))["chunks"] if "sh_lighting" in c][0]
a, b = bands(sys.argv[1]), bands(sys.argv[2])
assert a[1][0] > 1e-3 and len(a) == 3
print(max(abs(x - y) / max(abs(x), 1e-300) for l in (1, 2) for x, y in zip(a[l], b[l])))
EOF2
)" 0 1e-12

# ---- blender-data: c00 = sqrt(4 pi) x the mean radiance ----
if [ ! -r "$W/forest.exr" ]; then
	skip "blender-data forest.exr" "no $W (Debian package blender-data)"
	done_testing; exit
fi
tonemap --pfm -o "$T/forest.pfm" "$W/forest.exr"
sh-rotate --env "$W/forest.exr" --print --order 3 > "$T/f.txt"
mean=$(python3 - "$T/forest.pfm" <<'EOF2'
import math, struct, sys
d = open(sys.argv[1], "rb").read(); p = d.split(b"\n", 3); w, h = map(int, p[1].split())
v = struct.unpack("<%df" % (3 * w * h), p[3])
s = [0.0, 0.0, 0.0]
for r in range(h):          # stored bottom row first: image row h-1-r
    j = h - 1 - r
    om = 4 * math.pi / w * math.sin(math.pi * (j + .5) / h) * math.sin(math.pi / (2 * h))
    for i in range(w):
        for k in range(3):
            s[k] += max(v[3 * (r * w + i) + k], 0.0) * om
print(" ".join("%.17g" % (x / (4 * math.pi)) for x in s))
EOF2
)
for k in 0 1 2; do
	m=$(echo $mean | cut -d' ' -f$((k + 1)))
	check_close "forest.exr channel $k: c00 = sqrt(4 pi) mean radiance (1e-6 relative)" "$(rel "$(co "$T/f.txt" 0 0 $k)" "$(awk -v m=$m -v s=$s4pi 'BEGIN { printf "%.17g", m * s }')")" 0 1e-6
done
done_testing
