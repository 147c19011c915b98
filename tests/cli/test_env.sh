#!/bin/sh
# test_env.sh: environment maps from the command line, on real data: the
# eight CC0 lat-long OpenEXR environments of Debian's blender-data (DWAB
# compressed, 1024 x 512) read by tonemap and by vscene, which records each
# map's content hash in the scene; the hash's definition checked by an
# independent implementation (python, from formats/scene.md); a changed
# file refused; relative names beside the scene; vinfo and raycast --explain
# showing the lights; Radiance files written here byte by byte.
. tests/cli/lib.sh
W=/usr/share/blender/datafiles/studiolights/world
vread --synth sphere --size 8 > "$T/s.vx"

# ---- Radiance files (no package needed) ----
python3 - "$T" <<'EOF'
import struct, sys
t = sys.argv[1]
head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n"
# 8 x 2: row 0 run-length (R run 100, G literals 0..7, B 5, E 130 = 2^-6),
# row 1 flat (k, 0, 0, 136 = 2^0)
rle = bytes([2, 2, 0, 8, 136, 100, 8]) + bytes(range(8)) + \
    bytes([136, 5, 136, 130])
flat = b"".join(bytes([k + 1, 0, 0, 136]) for k in range(8))
open(t + "/a.hdr", "wb").write(head + b"-Y 2 +X 8\n" + rle + flat)
# the same pixels, bottom scanline first (+Y), with EXPOSURE=0.5
open(t + "/b.hdr", "wb").write(b"#?RADIANCE\nEXPOSURE=0.5\n\n+Y 2 +X 8\n" +
    b"".join(bytes([k + 1, 0, 0, 135]) for k in range(8)) +
    bytes([2, 2, 0, 8, 136, 100, 8]) + bytes(range(8)) +
    bytes([136, 5, 136, 129]))
EOF
tonemap --pfm -o "$T/a.pfm" "$T/a.hdr"
tonemap --pfm -o "$T/b.pfm" "$T/b.hdr"
pfmvals() {   # pfmvals FILE: the values, top row first, one line
	python3 -c 'import struct,sys
d = open(sys.argv[1], "rb").read(); p = d.split(b"\n", 3)
w, h = map(int, p[1].split()); v = struct.unpack("<%df" % (3 * w * h), p[3])
rows = [v[3 * w * y:3 * w * (y + 1)] for y in range(h)][::-1]
print(" ".join("%g" % x for r in rows for x in r))' "$1"
}
want="1.5625 0 0.078125 1.5625 0.015625 0.078125 1.5625 0.03125 0.078125 1.5625 0.046875 0.078125 1.5625 0.0625 0.078125 1.5625 0.078125 0.078125 1.5625 0.09375 0.078125 1.5625 0.109375 0.078125 1 0 0 2 0 0 3 0 0 4 0 0 5 0 0 6 0 0 7 0 0 8 0 0"
check_eq "tonemap reads Radiance RGBE (run-length and flat): m 2^(e-136)" "$(pfmvals "$T/a.pfm")" "$want"
check_eq "+Y (bottom first) and EXPOSURE=0.5 (values halved back): the same pixels" "$(pfmvals "$T/b.pfm")" "$want"
ha=$(vscene --light "environment file $T/a.hdr" --print "$T/s.vx" | sed -n 's/.* hash \([0-9a-f]*\) .*/\1/p')
hb=$(vscene --light "environment file $T/b.pfm" --print "$T/s.vx" | sed -n 's/.* hash \([0-9a-f]*\) .*/\1/p')
check_eq "a Radiance file and its PFM have one content hash" "$hb" "$ha"

# ---- the blender-data environments ----
if [ ! -r "$W/forest.exr" ]; then
	skip "blender-data environments" "no $W (Debian package blender-data)"
	done_testing; exit
fi
n=0; hashes=""
for f in "$W"/*.exr; do
	tonemap --pfm -o "$T/$(basename "$f" .exr).pfm" "$f" 2>"$T/e" || break
	h=$(vscene --light "environment file $f" --print "$T/s.vx" | sed -n 's/.* hash \([0-9a-f]*\) .*/\1/p')
	hashes="$hashes $h"; n=$((n + 1))
done
check_eq "tonemap and vscene read all eight (DWAB OpenEXR)" "$n" 8
check_eq "eight different content hashes" "$(echo $hashes | tr ' ' '\n' | sort -u | grep -c .)" 8

# forest.pfm (tonemap's copy of forest.exr): its size, its brightest pixel
# (the sun: (1010.5, 943, 895.5) at column 613, row 199 from the top, as
# measured for this file's PFM in the shared data's README), its mean
# radiance, and its content hash by formats/scene.md's definition
python3 - "$T/forest.pfm" >"$T/forest.txt" <<'EOF'
import struct, sys
d = open(sys.argv[1], "rb").read(); p = d.split(b"\n", 3)
w, h = map(int, p[1].split())
v = struct.unpack("<%df" % (3 * w * h), p[3])
rows = [v[3 * w * y:3 * w * (y + 1)] for y in range(h)][::-1]   # top first
px = [x for r in rows for x in r]
best = max(range(w * h), key=lambda i: sum(px[3 * i:3 * i + 3]))
print(w, h)
print(best % w, best // w, *px[3 * best:3 * best + 3])
print(" ".join("%.6f" % (sum(px[c::3]) / (w * h)) for c in range(3)))
print(sum(1 for x in px if x < 0))
x = 0xcbf29ce484222325
data = struct.pack("<II", w, h) + struct.pack("<%df" % len(px),
    *[a if a > 0 else 0.0 for a in px])
for b in data:
    x = ((x ^ b) * 0x100000001b3) & 0xffffffffffffffff
print("%016x" % x)
EOF
check_eq "forest: 1024 x 512" "$(sed -n 1p "$T/forest.txt")" "1024 512"
check_eq "forest: the sun at column 613, row 199, (1010.5, 943, 895.5)" "$(sed -n 2p "$T/forest.txt")" "613 199 1010.5 943.0 895.5"
check_eq "forest: mean radiance per channel" "$(sed -n 3p "$T/forest.txt")" "0.510292 0.546371 0.627810"
check "forest: DWA left negative values (read as 0)" test "$(sed -n 4p "$T/forest.txt")" -gt 0
hf=$(vscene --light "environment file $W/forest.exr" --print "$T/s.vx" | sed -n 's/.* hash \([0-9a-f]*\) .*/\1/p')
check_eq "forest: vscene's hash is formats/scene.md's (python FNV-1a, negatives as +0)" "$hf" "$(sed -n 5p "$T/forest.txt")"
check_eq "forest: the PFM copy has the same hash" "$(vscene --light "environment file $T/forest.pfm" --print "$T/s.vx" | sed -n 's/.* hash \([0-9a-f]*\) .*/\1/p')" "$hf"

# a scene beside its map: the relative name is taken beside the scene
mkdir -p "$T/scn"
cp "$W/forest.exr" "$T/scn/sky.exr"
printf 'light environment file sky.exr rotation 0 0 90 intensity 0.5\nlight sky color 0.1 0.2 0.3\n' > "$T/scn/a.scn"
vscene --scene "$T/scn/a.scn" "$T/s.vx" > "$T/e.vx"
check_eq "vscene: the name beside the scene, the hash recorded" \
    "$(vinfo "$T/e.vx" | grep -c "light environment file $T/scn/sky.exr layout latlong rotation 0 0 90 hash $hf color 1 1 1 intensity 0.5")" 1
check_eq "vinfo shows the sky" "$(vinfo "$T/e.vx" | grep -c 'light sky color 0.1 0.2 0.3 intensity 1 shadows off')" 1
raycast --explain -n --iso 0.5 "$T/e.vx" > "$T/plan.txt" 2>&1
check_eq "raycast --explain: the environment is named, unsupported" \
    "$(grep -c "unsupported light 1 environment .*sky.exr (latlong, hash $hf): not shaded" "$T/plan.txt")" 1
check_eq "raycast --explain: the sky's radiance, unsupported" \
    "$(grep -c 'unsupported light 2 sky .*radiance 0.1 0.2 0.3' "$T/plan.txt")" 1
raycast --size 16x16 --iso 0.5 "$T/e.vx" > "$T/e.png" 2>/dev/null
check_eq "raycast renders without them (exit 0)" "$?" 0
check "the stream's scene passes another vscene (file unchanged)" sh -c "vscene --size 8x8 '$T/e.vx' > '$T/e2.vx'"
cp "$W/city.exr" "$T/scn/sky.exr"
expect_fail "the file changed: refused, naming the file and both hashes" 65 "sky.exr: content hash .* differs from the scene's $hf" vscene --size 8x8 "$T/e.vx"
expect_fail "a map that does not exist" 66 "light 1: $T/none.exr" vscene --light "environment file $T/none.exr" "$T/s.vx"
expect_fail "an angular map must be square" 65 "square" vscene --light "environment file $W/city.exr layout angular" "$T/s.vx"
done_testing
