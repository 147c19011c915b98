#!/bin/sh
# test_raycast.sh: raycast(1) and mip(1) in real pipelines, checked by
# numbers: depths against geometry, pixel values against hand-worked
# shading, bit-identical images across threads, layouts and hierarchy,
# the plan --explain prints, and errors.  Images are decoded by
# tests/cli/vximg.py (PFM and the stream's IMAG chunks, from their specs).
. tests/cli/lib.sh
if ! command -v python3 >/dev/null 2>&1; then
	skip "raycast CLI tests" "python3 not installed"; done_testing; exit
fi
px() { python3 tests/cli/vximg.py "$@"; }

# A sphere field: distance from the centre of [-1,1]^3 (vread(1)); the
# isosurface 0.5 is a sphere of radius 0.5 around the origin.
vread --synth sphere --size 48 > "$T/sph.vx"
cam="camera perspective eye 0 -5 0 look 0 0 0 up 0 0 1 fov 30"

# 1. depth of the centre pixel: |eye| - r = 4.5 (oracle: geometry; the
# sampled distance field's trilinear isosurface is within 1e-3 of it)
raycast --iso 0.5 --size 65x65 --set "$cam" --depth "$T/d.pfm" "$T/sph.vx" > "$T/s.png"
check_close "centre depth is |eye| - r" "$(px pfm "$T/d.pfm" 32 32 0)" 4.5 0.001
check_eq "corner pixel misses (depth inf)" "$(px pfm "$T/d.pfm" 0 0 0)" inf

# 2. headlight shading at the centre: n = l = v, so radiance =
# ambient 0.1 * 0.8 + kd 1 * 0.8 * 1 + ks 0.2 * 1 = 1.08 (defaults of
# formats/scene.md; oracle: the shading formula by hand)
raycast --iso 0.5 --size 65x65 --set "$cam" --hdr "$T/sph.vx" > "$T/s.vx"
check_close "centre radiance (headlight, defaults)" "$(px img "$T/s.vx" color 32 32 0)" 1.08 0.002
check_close "centre coverage" "$(px img "$T/s.vx" color 32 32 3)" 1 0
check_close "background coverage" "$(px img "$T/s.vx" color 1 1 3)" 0 0

# 3. the same picture for 1 and 2 threads, bricked or linear, flat or
# hierarchical (oracle: -j 1 over the linear volume without hierarchy)
raycast --iso 0.3,0.6 --set "surface iso 0.6 opacity 0.4" --size 80x60 --view 30,20 \
    --light "directional direction 1 1 -1" -j 1 --flat "$T/sph.vx" > "$T/a.png"
raycast --iso 0.3,0.6 --set "surface iso 0.6 opacity 0.4" --size 80x60 --view 30,20 \
    --light "directional direction 1 1 -1" -j 2 "$T/sph.vx" > "$T/b.png"
check_eq "2 threads + hierarchy = 1 thread flat, pixel for pixel" "$(px pngsame "$T/a.png" "$T/b.png")" same
if [ -x "$VX_BIN/brick" ] && [ -x "$VX_BIN/macrocell" ]; then
	brick < "$T/sph.vx" | macrocell > "$T/sphb.vx"
	raycast --iso 0.3,0.6 --set "surface iso 0.6 opacity 0.4" --size 80x60 --view 30,20 \
	    --light "directional direction 1 1 -1" -j 2 "$T/sphb.vx" > "$T/c.png"
	check_eq "bricked + stored macrocells = linear, pixel for pixel" "$(px pngsame "$T/a.png" "$T/c.png")" same
	# the cell mask changes nothing (oracle: the same render without it,
	# and the flat one above); --stats says how much of it rays used
	raycast --iso 0.3,0.6 --set "surface iso 0.6 opacity 0.4" --size 80x60 --view 30,20 \
	    --light "directional direction 1 1 -1" -j 2 --no-cellmask --depth "$T/dn.pfm" \
	    "$T/sphb.vx" > "$T/d.png"
	raycast --iso 0.3,0.6 --set "surface iso 0.6 opacity 0.4" --size 80x60 --view 30,20 \
	    --light "directional direction 1 1 -1" -j 2 --depth "$T/dm.pfm" --stats \
	    "$T/sphb.vx" > "$T/e.png" 2> "$T/e.err"
	check_eq "--no-cellmask: the same picture" "$(px pngsame "$T/d.png" "$T/e.png")" same
	check "cell mask: the same depths" cmp -s "$T/dn.pfm" "$T/dm.pfm"
	check_eq "cell mask: the same picture as the flat walk" "$(px pngsame "$T/a.png" "$T/e.png")" same
	check "--stats reports the cell mask" grep -q "^raycast: cell mask: [1-9][0-9]* of [0-9]* level-1 macrocells bracket, [1-9][0-9]* of them masked" "$T/e.err"
	check "--explain names the cell mask" sh -c "raycast --iso 0.5 -n '$T/sphb.vx' 2>&1 | grep -q 'with a cell mask'"
	check "--no-cellmask --explain says it is off" sh -c "raycast --iso 0.5 -n --no-cellmask '$T/sphb.vx' 2>&1 | grep -q 'no cell mask'"
else
	skip "bricked = linear" "brick or macrocell not built"
fi

# 3b. texture: a second volume, joined with vread --add, colors the surface.
# The linear field f = x + 2y + 3z + 1/2 at the centre hit (0, -0.5, 0) is
# -0.5; window -1.5..0.5 maps it to 0.5 on the gray map; with ks 0 and no
# ambient the centre radiance is kd * albedo * (n . l) = 0.5 (oracle: the
# field's formula, the shading formula by hand)
vread --synth linear --size 48 --name tex --add "$T/sph.vx" > "$T/tex.vx"
raycast --iso 0.5 --size 65x65 --set "$cam" --set "ambient intensity 0" \
    --set "surface iso 0.5 ks 0 texture tex window -1.5 0.5" --hdr "$T/tex.vx" > "$T/t.vx"
check_close "texture: centre albedo from the second volume" "$(px img "$T/t.vx" color 32 32 0)" 0.5 0.002
raycast --iso 0.5 --size 65x65 --set "$cam" --set "ambient intensity 0" \
    --set "surface iso 0.5 ks 0 texture tex window -1.5 0.5" --effects "-texture" --hdr "$T/tex.vx" > "$T/t2.vx"
check_close "texture effect off: the material color" "$(px img "$T/t2.vx" color 32 32 0)" 0.8 0.002

# 4. --stats counts what was spent: one primary ray per pixel
raycast --iso 0.5 --size 65x65 --set "$cam" --stats "$T/sph.vx" 2>"$T/st" >/dev/null
check_eq "stats: primary rays" "$(sed -n 's/.*rays: \([0-9]*\) primary.*/\1/p' "$T/st")" 4225
check "stats: time shares" grep -q 'traversal [0-9]*%, intersection [0-9]*%, shading [0-9]*%' "$T/st"
# roots solved N (B ruled out by the sign bound, C of them without the
# face values): C <= B <= N, and on the sphere's grazed cells C > 0
rts=$(sed -n 's/.*roots solved \([0-9]*\) (\([0-9]*\) ruled out by the cubic.s sign bound, \([0-9]*\) of them without the face values).*/\1 \2 \3/p' "$T/st")
check "stats: bound misses, settled without faces" sh -c "set -- $rts; [ \$# -eq 3 ] && [ \$3 -gt 0 ] && [ \$3 -le \$2 ] && [ \$2 -le \$1 ]"

# 5. the plan: only what the scene calls for
raycast --iso 0.5 -n "$T/sph.vx" 2>"$T/ex"
check "explain: no shadows without a shadow-casting light" grep -q 'off .*shadows' "$T/ex"
check "explain: no compositing for one opaque surface" grep -q 'off .*transparency' "$T/ex"
raycast --iso 0.5 --light "directional direction 0 0 -1 shadows on" -n "$T/sph.vx" 2>"$T/ex"
check "explain: shadow rays for a shadow-casting light" grep -q 'on .*shadows' "$T/ex"

# 6. the PNG says how it was made: the whole history, the input's lines
# and then this run's
check_eq "PNG carries the history" "$(px pngtext "$T/s.png" voxlux-history)" \
    "$(printf 'vread 0.1.0 --synth sphere --size 48\nraycast 0.1.0 --iso 0.5 --size 65x65 --set %s --depth %s %s' \
    "$cam" "$T/d.pfm" "$T/sph.vx")"

# 6b. one compositing rule: raycast's PNG is what tonemap makes of the
# --hdr stream with the same exposure and background, pixel for pixel
# (transparent layers and 2x2 samples: partly covered pixels), and the
# background is a display color composited after the exposure, which does
# not brighten it: a background pixel holds the sRGB codes of 0.2 0.3 0.4
# (oracle: the IEC 61966-2-1 curve, evaluated here)
layers() {
	raycast --iso 0.3,0.6 --set "surface iso 0.6 opacity 0.4" --aa 2 \
	    --size 40x30 --view 30,20 --background 0.2,0.3,0.4 "$@" "$T/sph.vx"
}
layers --exposure 2 > "$T/e.png"
layers --hdr | tonemap --exposure 2 --background 0.2,0.3,0.4 > "$T/e2.png"
check_eq "raycast PNG = raycast --hdr | tonemap, exposure and background" \
    "$(px pngsame "$T/e.png" "$T/e2.png")" same
check_eq "the background is not brightened by the exposure" \
    "$(px pngpx "$T/e.png" 0 0 0) $(px pngpx "$T/e.png" 0 0 1) $(px pngpx "$T/e.png" 0 0 2)" \
    "$(python3 -c 'print(*[int(255 * (1.055 * v ** (1 / 2.4) - 0.055) + 0.5) for v in (0.2, 0.3, 0.4)])')"

# 7. errors: one line, documented codes
expect_fail "no surface: usage" 64 "no surface" raycast "$T/sph.vx"
expect_fail "bad solver: usage" 64 "solver" raycast --iso 0.5 --solver quartic "$T/sph.vx"
expect_fail "missing input" 66 "cannot open\|No such" raycast --iso 0.5 "$T/none.vx"
printf 'not a stream' > "$T/bad.vx"
expect_fail "not a stream" 65 "signature" raycast --iso 0.5 "$T/bad.vx"

# 8. mip: the central ray of an orthographic front view runs along the y
# axis, midway between samples in x and z (48 samples over [-1,1]): its
# maximum is on the faces y = +-1, the bilinear mean of four samples each at
# distance sqrt(1 + 2 (1/47)^2) = 1.00045259 (oracle: geometry)
mip --size 65x65 --hdr "$T/sph.vx" > "$T/m.vx"
check_close "mip: centre maximum" "$(px img "$T/m.vx" mip 32 32 0)" 1.000452591 1e-6
mip --size 65x65 --hdr --no-last-t "$T/sph.vx" > "$T/m2.vx"
check_eq "mip: last-t bound on = off, bit for bit" "$(px same "$T/m.vx" "$T/m2.vx")" same
mip --size 65x65 --hdr -j 1 "$T/sph.vx" > "$T/m3.vx"
check_eq "mip: 1 thread = 2 threads" "$(px same "$T/m.vx" "$T/m3.vx")" same
mip --size 65x65 --hdr --exhaustive "$T/sph.vx" > "$T/m4.vx"
check_eq "mip: queue = exhaustive at the centre" "$(px img "$T/m4.vx" mip 32 32 0)" "$(px img "$T/m.vx" mip 32 32 0)"
mip --size 65x65 --stats "$T/sph.vx" 2>"$T/mst" >/dev/null
check "mip: stats report queue work" grep -q 'queue pushes [0-9]*, pops [0-9]*' "$T/mst"
check "mip: stats report wall and CPU time" grep -q ' [0-9.]* s (cpu [0-9.]* s)$' "$T/mst"
# mip's PNG carries the whole history: the input's lines, then its own
mip --size 33x33 "$T/sph.vx" > "$T/m.png"
check_eq "mip: PNG carries the stream's history and its own line" \
    "$(px pngtext "$T/m.png" voxlux-history)" \
    "$(printf 'vread 0.1.0 --synth sphere --size 48\nmip 0.1.0 --size 33x33 %s' "$T/sph.vx")"
# the renderers share their output options (tool_run_opts): mip's --hdr
# stream carries the scene it drew, as raycast's and dvr's do, and the
# three refuse a bad --bits alike
mip --size 33x33 --hdr "$T/sph.vx" 2>/dev/null > "$T/mscene.vx"
check_eq "mip --hdr: the stream holds the scene it drew" \
    "$(vinfo "$T/mscene.vx" | grep -c 'camera auto projection orthographic')" 1
check_eq "mip --hdr: the scene is the options' (--size)" \
    "$(vinfo "$T/mscene.vx" | grep -c 'image width 33 height 33')" 1
for r in raycast mip dvr; do
	expect_fail "$r --bits 12" 64 "$r: --bits: 8 or 16" $r --bits 12 "$T/sph.vx"
	expect_fail "$r -z 10" 64 "$r: -z: 10 is out of range" $r -z 10 "$T/sph.vx"
done

# 9. -z: the images of --hdr are zlib level 1 by default, raw with -z 0,
# and decode to the same bytes at every level (oracle: vximg.py decodes
# both encodings from the spec)
enc() { python3 -c 'import sys
d = open(sys.argv[1], "rb").read()
print(" ".join(sorted(set(l.split(b": ")[1].decode() for l in d.split(b"\n") if l.startswith(b"encoding: ")))))' "$1"; }
raycast --iso 0.5 --size 65x65 --set "$cam" --hdr -z 0 "$T/sph.vx" > "$T/s0.vx"
raycast --iso 0.5 --size 65x65 --set "$cam" --hdr -z 9 "$T/sph.vx" > "$T/s9.vx"
check_eq "raycast --hdr: zlib by default" "$(enc "$T/s.vx")" "raw zlib"
check_eq "raycast -z 0: raw images" "$(enc "$T/s0.vx")" "raw"
check_eq "raycast -z 0 = default, decoded" "$(px same "$T/s.vx" "$T/s0.vx")" same
check_eq "raycast -z 9 = default, decoded" "$(px same "$T/s.vx" "$T/s9.vx")" same
mip --size 65x65 --hdr -z 0 "$T/sph.vx" > "$T/m0.vx"
check_eq "mip -z 0: raw images" "$(enc "$T/m0.vx")" "raw"
check_eq "mip -z 0 = default, decoded" "$(px same "$T/m.vx" "$T/m0.vx")" same
expect_fail "raycast -z 10" 64 "-z" raycast -z 10 --hdr "$T/sph.vx"

# 11. binning: primary rays walk the boxes they enter, one after the
# other, among the boxes of the bracketing leaves of each block of 8^3
# leaves (with the cell mask; else the bracketing level-1 macrocells), and
# rays that enter none are not walked:
# the same images, bit for bit, as rays walked from the eye
# (--no-binning), over cameras with hard cases: the eye inside the volume
# and inside a bracketing macrocell, orthographic views along an axis
# (rays through the macrocells' faces and edges: ties), 2x2 samples per
# pixel, layers and shadows, small macrocells; and with blocks of 1^3 to
# 5^3 leaves (--bin-block).  Oracle: --no-binning.
vread --synth ml --size 33 | macrocell --sizes 2x3x2,2x2x2 >"$T/mlb.vx"
vread --synth ml --size 33 | macrocell --sizes 8x8x8 >"$T/ml8.vx"
nb=0
for c in "camera perspective eye 0 -5 0 look 0 0 0 up 0 0 1 fov 30" \
    "camera perspective eye 0.1 0.05 -0.2 look 1 1 1 up 0 0 1 fov 90" \
    "camera perspective eye -0.9 -0.8 -0.95 look 1 1 1 up 0 0 1 fov 60" \
    "camera perspective eye -1.6 -1.3 -0.4 look 0 0 0 up 0 0 1 fov 120" \
    "camera orthographic eye 0 -5 0 look 0 0 0 up 0 0 1 width 2.5" \
    "camera orthographic eye 5 0 0 look 0 0 0 up 0 0 1 width 2" \
    "camera orthographic eye 3 -4 2 look 0 0 0 up 0 0 1 width 2.2"; do
	for v in sph mlb ml8; do
		nb=$((nb + 1))
		iso=0.5; [ $v != sph ] && iso=0.2,0.45
		set -- --iso $iso --set "surface iso 0.5 opacity 0.5" --size 40x30 \
		    --light "directional direction 1 1 -1" --set "$c"
		raycast "$@" --hdr --stats "$T/$v.vx" >"$T/bin$nb.vx" 2>"$T/bs1"
		raycast "$@" --hdr --stats --no-binning "$T/$v.vx" \
		    >"$T/nobin$nb.vx" 2>"$T/bs2"
		check_eq "binning = no binning: $v, $c" \
		    "$(px same "$T/bin$nb.vx" "$T/nobin$nb.vx")" same
		bb=$((nb % 5 + 1))
		raycast "$@" --hdr --bin-block $bb "$T/$v.vx" >"$T/bb$nb.vx"
		check_eq "binning with --bin-block $bb = no binning: $v, $c" \
		    "$(px same "$T/bb$nb.vx" "$T/nobin$nb.vx")" same
		# the same cells handed to the cell kernel, the same roots
		check_eq "binning visits the same cells: $v, $c" \
		    "$(grep 'cells visited' "$T/bs1")" "$(grep 'cells visited' "$T/bs2")"
	done
done
raycast --iso 0.5 --aa 2 --size 33x33 --set "$cam" --hdr "$T/sph.vx" >"$T/aa1.vx"
raycast --iso 0.5 --aa 2 --size 33x33 --set "$cam" --hdr --no-binning \
    "$T/sph.vx" >"$T/aa2.vx"
check_eq "binning = no binning: 2x2 samples" "$(px same "$T/aa1.vx" "$T/aa2.vx")" same
raycast --iso 0.5 --size 65x65 --set "$cam" --stats "$T/sph.vx" 2>"$T/bst" >/dev/null
check "binning: --stats counts the rays not walked" \
    grep -q 'binning: [1-9][0-9]* boxes (of the bracketing leaves of each block of 8x8x8, and [0-9]* bracketing level-1 macrocells whole, [0-9.]* ms); [1-9][0-9]* of 4225 primary rays enter none' "$T/bst"
raycast --iso 0.5 --size 65x65 --set "$cam" --stats -j 2 "$T/sph.vx" 2>"$T/bst7" >/dev/null
check "--stats: the tiles' time on 2 threads and outside them" \
    grep -q "^raycast: tiles: [0-9.]* ms on 2 threads, [0-9.]* ms of the threads' time (balance [0-9]*%); outside them [0-9.]* ms" "$T/bst7"
raycast --iso 0.5 --size 65x65 --set "$cam" --stats --bin-block 3 "$T/sph.vx" \
    2>"$T/bst6" >/dev/null
check "binning: --bin-block 3 in --stats" grep -q 'of each block of 3x3x3, and' "$T/bst6"
expect_fail "--bin-block past 64: one line, exit 64" 64 \
    "raycast: --bin-block: 65 is out of range" \
    raycast --iso 0.5 --bin-block 65 "$T/sph.vx"
# without a cell mask, whole level-1 macrocells: the same picture
raycast --iso 0.5 --size 65x65 --set "$cam" --stats --no-cellmask --hdr \
    "$T/sph.vx" 2>"$T/bst3" >"$T/nm1.vx"
raycast --iso 0.5 --size 65x65 --set "$cam" --no-binning --hdr "$T/sph.vx" \
    >"$T/nm2.vx"
check "binning without a cell mask: level-1 macrocells" \
    grep -q 'binning: [1-9][0-9]* boxes (bracketing level-1 macrocells, [0-9.]* ms); [1-9][0-9]* of 4225' "$T/bst3"
check_eq "binning without a cell mask = no binning" \
    "$(px same "$T/nm1.vx" "$T/nm2.vx")" same
# the eye inside a volume of many small bracketing blocks, 16^3
# macrocells: the same picture and cells (the fall-back to whole
# macrocells when the blocks' lists pass the bound is the unit test
# binning_modes': a fresh mask has bits only where the first rays went)
vread --synth ml --size 129 | macrocell --sizes 16x16x16,2x2x2 >"$T/ml16.vx"
set -- --iso 0.2,0.45 --size 40x30 --set "camera perspective eye 0.1 0.05 -0.2 look 1 1 1 up 0 0 1 fov 90"
raycast "$@" --hdr --stats "$T/ml16.vx" >"$T/fb1.vx" 2>"$T/bst4"
raycast "$@" --hdr --stats --no-binning "$T/ml16.vx" >"$T/fb2.vx" 2>"$T/bst5"
check_eq "binning: eye among small blocks, the same picture" \
    "$(px same "$T/fb1.vx" "$T/fb2.vx")" same
check_eq "binning: eye among small blocks, the same cells" \
    "$(grep 'cells visited' "$T/bst4")" "$(grep 'cells visited' "$T/bst5")"
# an eye among 32768 one-cell macrocells: boxes behind the eye span the
# image, the lists would pass 8 entries a pixel: no bins, the same picture
vread --synth ml --size 33 | macrocell --sizes 1x1x1 >"$T/ml1.vx"
set -- --iso 0.2,0.45 --size 40x30 --set "camera perspective eye 0.1 0.05 -0.2 look 1 1 1 up 0 0 1 fov 90"
raycast "$@" --hdr --stats "$T/ml1.vx" >"$T/cap1.vx" 2>"$T/bst2"
raycast "$@" --hdr --no-binning "$T/ml1.vx" >"$T/cap2.vx"
check_eq "binning: over 8 entries a pixel, none" "$(grep -c 'binning:' "$T/bst2")" 0
check_eq "binning: over 8 entries a pixel, the same picture" \
    "$(px same "$T/cap1.vx" "$T/cap2.vx")" same

# 10. -j 1 means one thread for the whole run, not only the frame: the
# stream below has macrocells built before brick re-laid the volume out
# (proving them costs a pass over the samples) and the PNG is tone-mapped,
# both parallel loops of their own.  Oracle: strace counts the threads
# made (clones with CLONE_THREAD: none with -j 1; at least one with -j 2 on a
# machine with 2 cores).  Under the sanitizers, LeakSanitizer would clone a
# tracer of its own at exit, and cannot run under ptrace: it is off here.
vread --synth ml --size 41 | macrocell | brick >"$T/mlrb.vx"
if command -v strace >/dev/null 2>&1 && strace -f -qq -o /dev/null true 2>/dev/null; then
	ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
	    strace -f -qq -e trace=clone,clone3 -o "$T/st1" "$VX_BIN/raycast" \
	    -j 1 --iso 0.5 --size 32x32 "$T/mlrb.vx" >/dev/null
	check_eq "-j 1: no thread made" "$(grep -c CLONE_THREAD "$T/st1")" 0
	if [ "$(nproc)" -ge 2 ]; then
		ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
		    strace -f -qq -e trace=clone,clone3 -o "$T/st2" \
		    "$VX_BIN/raycast" -j 2 --iso 0.5 --size 32x32 "$T/mlrb.vx" \
		    >/dev/null
		check "-j 2: a second thread" [ "$(grep -c CLONE_THREAD "$T/st2")" -ge 1 ]
	else
		skip "-j 2: a second thread" "one core"
	fi
	# a pipe on standard input is widened to 1 MiB (fewer turns for a big
	# stream), a file is left alone (oracle: the fcntl calls strace sees)
	cat "$T/mlrb.vx" | ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
	    strace -qq -e trace=fcntl -o "$T/st3" "$VX_BIN/raycast" -j 1 \
	    --iso 0.5 --size 8x8 >/dev/null
	check "stdin pipe widened" grep -q 'fcntl(0, F_SETPIPE_SZ, 1048576)' "$T/st3"
	ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
	    strace -qq -e trace=fcntl -o "$T/st4" "$VX_BIN/raycast" -j 1 \
	    --iso 0.5 --size 8x8 <"$T/mlrb.vx" >/dev/null
	check_eq "stdin file left alone" "$(grep -c F_SETPIPE_SZ "$T/st4")" 0
else
	skip "-j 1: no thread made" "strace missing or not allowed to trace"
	skip "-j 2: a second thread" "strace missing or not allowed to trace"
	skip "stdin pipe widened" "strace missing or not allowed to trace"
	skip "stdin file left alone" "strace missing or not allowed to trace"
fi
done_testing
