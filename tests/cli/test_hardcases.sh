#!/bin/sh
# test_hardcases.sh: hard numerical cases and hostile conditions, each
# built here so that the right answer is known exactly: isovalues between
# floats, touches on cell faces, one-sample-thick volumes, signals and
# closed descriptors during a run, thread creation failing.  The oracle of
# each block is named in its comment.
. tests/cli/lib.sh
if ! command -v python3 >/dev/null 2>&1; then
	skip "hard cases" "python3 not installed"; done_testing; exit
fi
# covered FILE: the percentage of pixels --stats says were covered
covered() { sed -n 's/.*covered pixels \([0-9.]*\)%.*/\1/p' "$1"; }

# 1. Isovalues are doubles.  A u8 block of 100s (4^3 in an 8^3 volume of
# 0s): every sample is <= 100, so an isovalue above 100 by any amount
# draws nothing and one below draws the block (oracle: the samples'
# maximum; the trilinear field never exceeds it).  Volumes and their
# tetrahedral splits alike, one or several isovalues.
python3 -c "
import sys
n = 8
b = bytearray(n ** 3)
for z in range(2, 6):
    for y in range(2, 6):
        for x in range(2, 6):
            b[x + n * (y + n * z)] = 100
sys.stdout.buffer.write(b)" > "$T/cube.raw"
vread --raw 8,8,8 --type u8 "$T/cube.raw" > "$T/cube.vx"
vread --raw 8,8,8 --type u8 --split 5 "$T/cube.raw" > "$T/cube5.vx"
for src in cube cube5; do
	for iso in 100.0000001 100.00000000000003 1e300 100.0000001,200; do
		raycast --iso $iso --size 32x32 --stats -o "$T/r.png" "$T/$src.vx" 2> "$T/r.err"
		check_eq "$src: iso $iso above every sample draws nothing" "$(covered "$T/r.err")" 0.0
	done
	for iso in 100 99.9999999 99.99999999999999 100.0000001,99.9999999; do
		raycast --iso $iso --size 32x32 --stats -o "$T/r.png" "$T/$src.vx" 2> "$T/r.err"
		c=$(covered "$T/r.err")
		if close "$c" 0 0; then not_ok "$src: iso $iso draws the block" "covered $c%"
		else ok "$src: iso $iso draws the block ($c%)"; fi
	done
done
# 4. One-sample-thick volumes.  A slice (8 x 6 x 1 u8 samples) is drawn by
# mip as the slice itself: looking down on it (orthographic, along z) each
# pixel is the bilinear value under it, as for the same slice stacked twice
# (8 x 6 x 2, the field constant along z: oracle); raycast draws nothing (a
# volume without cells has no isosurface) and says so in --stats.
python3 -c "
import sys
v = bytes((7 * x + 31 * y) % 256 for y in range(6) for x in range(8))
open(sys.argv[1], 'wb').write(v)
open(sys.argv[2], 'wb').write(v + v)" "$T/slice.raw" "$T/slice2.raw"
vread --raw 8,6,1 --type u8 "$T/slice.raw" > "$T/slice.vx"
vread --raw 8,6,2 --type u8 "$T/slice2.raw" > "$T/slice2.vx"
mip --view top --size 40x30 --hdr "$T/slice.vx" 2>/dev/null | tonemap --pfm -o "$T/s1.pfm" -
mip --view top --size 40x30 --hdr "$T/slice2.vx" 2>/dev/null | tonemap --pfm -o "$T/s2.pfm" -
cmp_pfm() {   # cmp_pfm A B: the largest difference of two PFMs' values
	python3 -c "
import struct, sys
def rd(p):
    b = open(p, 'rb').read()
    parts = b.split(maxsplit=4)
    w, h = int(parts[1]), int(parts[2])
    n = w * h * (3 if parts[0] == b'PF' else 1)
    return struct.unpack('<%df' % n, b[len(b) - 4 * n:])
a, b = rd(sys.argv[1]), rd(sys.argv[2])
print(max(abs(x - y) for x, y in zip(a, b)) if len(a) == len(b) else 'sizes differ')" "$1" "$2"
}
check_close "mip of a slice from above: the stacked slice's picture" "$(cmp_pfm "$T/s1.pfm" "$T/s2.pfm")" 0 1e-5
mip --view top --size 40x30 --exhaustive --hdr "$T/slice.vx" 2>/dev/null | tonemap --pfm -o "$T/s3.pfm" -
check "mip of a slice: --exhaustive the same bits" cmp -s "$T/s1.pfm" "$T/s3.pfm"
raycast --iso 100 --size 16x16 --stats -o "$T/s.png" "$T/slice.vx" 2> "$T/s.err"
check_eq "raycast of a slice: exit 0" "$?" 0
check_eq "raycast of a slice draws nothing" "$(covered "$T/s.err")" 0.0
for sz in 1,5,6 5,1,1 1,1,1; do
	vread --synth sphere --size $sz > "$T/thin.vx"
	check "mip of a $sz volume runs" sh -c "mip --size 8x8 -o '$T/t.png' '$T/thin.vx' 2>/dev/null"
	check "raycast of a $sz volume runs" sh -c "raycast --iso 0.5 --size 8x8 -o '$T/t.png' '$T/thin.vx' 2>/dev/null"
done

# 8. A signal during the output write removes the temporary: strace
# delivers the signal as the process enters fsync (after every byte is
# written, before the rename) or its first write; the run dies of it as it
# would have, and neither the output nor a temporary is left.  SIGXFSZ
# under a file size limit is a write error instead: one line, exit 74.
# Oracle: the directory's listing.
if command -v strace >/dev/null 2>&1 && strace -f -qq -o /dev/null true 2>/dev/null; then
	mkdir -p "$T/sig"
	for how in fsync:TERM fsync:INT write:HUP write:TERM fsync:PIPE; do
		call=${how%%:*} sig=${how#*:}
		ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
		    strace -f -qq -o /dev/null -e trace=$call \
		    -e inject=$call:signal=SIG$sig:when=1 \
		    "$VX_BIN/vread" --synth sphere --size 16 -o "$T/sig/s.vx" 2>/dev/null
		rc=$?
		left=$(ls "$T/sig" | tr '\n' ' ')
		if [ "$rc" -ne 0 ] && [ -z "$left" ]; then ok "SIG$sig at $call: the run dies, nothing left ($rc)"
		else not_ok "SIG$sig at $call: the run dies, nothing left" "exit $rc, left: $left"; fi
		rm -f "$T/sig"/*
	done
	ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
	    strace -f -qq -o /dev/null -e trace=fsync -e inject=fsync:signal=SIGTERM \
	    "$VX_BIN/raycast" --iso 0.5 --size 16x16 -o "$T/sig/r.png" "$T/cube.vx" 2>/dev/null
	check_eq "raycast: SIGTERM at fsync leaves nothing" "$(ls "$T/sig")" ""
else
	skip "signals remove the temporary" "strace missing or not allowed to trace"
fi
(ulimit -f 40; vread --synth sphere --size 64 -o "$T/sig-big.vx") 2> "$T/xfsz.err"
rc=$?
check_eq "file size limit: exit 74" "$rc" 74
check_eq "file size limit: one line" "$(wc -l < "$T/xfsz.err" | tr -d ' ')" 1
check "file size limit: File too large" grep -q "^vread: .*sig-big.vx: .*File too large" "$T/xfsz.err"
check_eq "file size limit: nothing left" "$(ls "$T" | grep -c sig-big)" 0

# 9. A closed standard output is no error for a run that does not write
# to it (-o FILE); one that does write there still fails, once, with 74.
# Closed standard input and error are held the same way.  Oracle: the
# output file equals the one written with the descriptors open.
vread --synth sphere --size 16 -o "$T/open.vx"
raycast --iso 0.5 --size 16x16 --hdr -o "$T/ref.vx" "$T/open.vx" 2>/dev/null
for prog in vread vread-stdin raycast tonemap vwrite; do
	case $prog in
	vread*) cmd="vread --synth sphere --size 16 -o $T/closed.out" ;;
	raycast) cmd="raycast --iso 0.5 --size 16x16 --hdr -o $T/closed.out $T/open.vx" ;;
	tonemap) cmd="tonemap --pfm -o $T/closed.out $T/ref.vx" ;;
	vwrite) cmd="vwrite -o $T/closed.out $T/open.vx" ;;
	esac
	# the reference: the same command with the descriptors open
	$cmd 2>/dev/null && mv "$T/closed.out" "$T/ref.out"
	if [ $prog = vread-stdin ]; then
		$cmd <&- >&- 2>"$T/c.err"; rc=$?
	else
		$cmd >&- 2>"$T/c.err"; rc=$?
	fi
	if [ "$rc" -eq 0 ] && cmp -s "$T/closed.out" "$T/ref.out"; then ok "$prog -o FILE with stdout closed: exit 0, the same file"
	else not_ok "$prog -o FILE with stdout closed" "exit $rc: $(head -2 "$T/c.err")"; fi
	rm -f "$T/closed.out" "$T/ref.out"
done
vread --synth sphere --size 16 -o "$T/closed.vx" 2>&-
check_eq "stderr closed: exit 0" "$?" 0
expect_fail "vinfo writing to a closed stdout: one line, exit 74" 74 "write <stdout>" \
    sh -c "vinfo '$T/open.vx' >&-"
expect_fail "raycast writing a PNG to a closed stdout: one line, exit 74" 74 "Bad file descriptor" \
    sh -c "raycast --iso 0.5 --size 8x8 '$T/open.vx' >&-"

# 10. Threads that cannot be made: strace makes the thread creation calls
# fail (EAGAIN, as a memory or process limit does).  An explicit -j N is
# one line and exit 71; the default takes the threads that can be made.
# Under a real address-space limit (not under the sanitizers, which need
# far more address space), -j 64 fails the same way and the default runs.
vread --synth sphere --size 24 | macrocell > "$T/sphm.vx"
raycast --iso 0.5 --size 32x32 --hdr -j 1 -o "$T/j1.vx" "$T/sphm.vx"
if command -v strace >/dev/null 2>&1 && strace -f -qq -o /dev/null true 2>/dev/null; then
	for prog in raycast mip macrocell; do
		case $prog in
		raycast) args="--iso 0.5 --size 16x16 -o $T/tj.png $T/sphm.vx" ;;
		mip) args="--size 16x16 -o $T/tj.png $T/sphm.vx" ;;
		macrocell) args="-o $T/tj.vx $T/sphm.vx" ;;
		esac
		for when in 1 2; do
			ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
			    strace -f -qq -o /dev/null -e trace=clone,clone3 \
			    -e inject=clone3:error=EAGAIN:when=$when \
			    -e inject=clone:error=EAGAIN:when=$when \
			    "$VX_BIN/$prog" -j 3 $args > "$T/tj.out" 2> "$T/tj.err"
			rc=$?
			if [ "$rc" -eq 71 ] && [ "$(wc -l < "$T/tj.err")" -eq 1 ] &&
			    grep -q "^$prog: -j 3: cannot start 3 threads: " "$T/tj.err" &&
			    [ ! -e "$T/tj.png" ] && [ ! -e "$T/tj.vx" ]; then
				ok "$prog -j 3, thread $when not made: one line, exit 71"
			else
				not_ok "$prog -j 3, thread $when not made" "exit $rc: $(head -3 "$T/tj.err")"
			fi
		done
	done
	ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
	    strace -f -qq -o /dev/null -e trace=clone,clone3 \
	    -e inject=clone3:error=EAGAIN -e inject=clone:error=EAGAIN \
	    "$VX_BIN/raycast" --iso 0.5 --size 32x32 --hdr -o "$T/j0.vx" "$T/sphm.vx"
	check_eq "default -j with no thread to be made: exit 0" "$?" 0
	check_eq "default -j with no thread to be made: the 1-thread picture" \
	    "$(python3 tests/cli/vximg.py same "$T/j0.vx" "$T/j1.vx")" same
else
	skip "thread creation failures" "strace missing or not allowed to trace"
fi
if (ulimit -v 400000; vinfo "$T/sphm.vx") >/dev/null 2>&1; then
	(ulimit -v 400000; raycast -j 64 --iso 0.5 --size 16x16 -o "$T/uj.png" "$T/sphm.vx") 2> "$T/uj.err"
	rc=$?
	if [ "$rc" -eq 71 ] && [ "$(wc -l < "$T/uj.err")" -eq 1 ] && [ ! -e "$T/uj.png" ]; then
		ok "ulimit -v: -j 64 is one line, exit 71"
	else
		not_ok "ulimit -v: -j 64 is one line, exit 71" "exit $rc: $(head -3 "$T/uj.err")"
	fi
	(ulimit -v 400000; raycast --iso 0.5 --size 16x16 -o "$T/uj.png" "$T/sphm.vx")
	check_eq "ulimit -v: the default -j runs" "$?" 0
else
	skip "ulimit -v: -j 64" "an address-space limit stops every run here (sanitizers)"
	skip "ulimit -v: the default -j runs" "(as above)"
fi

# 11. One line on failure: the note that macrocells were built is kept
# until the run succeeds, so an error found after the build is the only
# line; vread refuses a volume whose extent overflows (oracle: the box's
# far corner, origin + (n - 1) spacing, is not a double).
vread --synth sphere --size 16 > "$T/nomc.vx"
expect_fail "missing texture volume after the macrocell build: one line" 65 "tex" \
    raycast --size 8x8 --set "surface iso 0.5 texture nosuch" -o "$T/o.png" "$T/nomc.vx"
raycast --iso 0.5 --size 8x8 -o "$T/o.png" "$T/nomc.vx" 2> "$T/note.err"
check "a successful run still notes the build" grep -q "^raycast: note: no macrocells for 'density'; built them" "$T/note.err"
for sp in 1e308,1e308,1e308 1,1e307,1 2.4e306,1,2.4e306; do
	expect_fail "vread --spacing $sp: extent overflows" 65 "extent overflows" \
	    vread --synth sphere --size 64 --spacing $sp -o "$T/o.vx"
done
expect_fail "vread --origin -1.7e308 --spacing 1e307: the box's side overflows" 65 "extent overflows" \
    vread --synth sphere --size 64 --origin -1.7e308,0,0 --spacing 1e307,1,1 -o "$T/o.vx"
vread --synth sphere --size 64 --spacing 1e300,1,1 -o "$T/big.vx"
check_eq "a huge but finite extent is kept" "$?" 0
# 12. No undefined behaviour from far or degenerate cameras: eyes at
# 1e308 (their |eye| overflows), orthographic and perspective, mip and
# raycast with shadows.  The oracle is the sanitizer build (SANITIZE=1
# adds -fsanitize=float-cast-overflow): no runtime error, exit 0.
for e in "1e308 1e308 1e308" "-1.7e308 1.7e308 1e308" "1e308 1e-308 0"; do
	for cam in "perspective eye $e look 0 0 0 up 0 0 1 fov 30" \
	    "orthographic eye $e look 0 0 0 up 0 0 1 width 1e300"; do
		printf 'camera %s\n' "$cam" > "$T/far.scn"
		mip --scene "$T/far.scn" --size 8x8 -o "$T/far.png" "$T/sphm.vx" 2> "$T/far.err"
		rc=$?
		raycast --scene "$T/far.scn" --iso 0.5 --effects shadows --size 8x8 \
		    -o "$T/far.png" "$T/sphm.vx" 2>> "$T/far.err"
		rc=$((rc + $?))
		if [ "$rc" -eq 0 ] && ! grep -q "runtime error" "$T/far.err"; then
			ok "far camera ($cam): no undefined behaviour"
		else
			not_ok "far camera ($cam)" "$(head -3 "$T/far.err")"
		fi
	done
done
done_testing
