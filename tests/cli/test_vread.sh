#!/bin/sh
# test_vread.sh: vread's errors (one line, sysexits codes) and imports of
# files written here with printf, checked through tests/cli/mkstream.py
# (an independent reader of the stream format): header fields and every
# sample byte.
. tests/cli/lib.sh
MK="python3 tests/cli/mkstream.py"
# hdr FILE KEY: the value of KEY in the first VOLM chunk's header
hdr() {
	python3 - "$1" "$2" <<'EOF'
import struct, sys
d = open(sys.argv[1], "rb").read()
i = 8
while i < len(d):
    t = d[i:i + 4]; n = struct.unpack("<Q", d[i + 4:i + 12])[0]
    p = d[i + 12:i + 12 + n]; i += 16 + n
    if t == b"VOLM":
        for line in p.split(b"\n\n")[0].decode().split("\n"):
            k, _, v = line.partition(": ")
            if k == sys.argv[2]:
                print(v)
        break
EOF
}
# samples FILE: the volume's samples as hex, x fastest, little-endian
samples() { $MK samples "$1" | od -An -v -tx1 | tr -d ' \n'; }

# ---- errors: one line on stderr, nothing on stdout, the right code ----
expect_fail "missing file" 66 "nosuch.nrrd: No such file" vread "$T/nosuch.nrrd"
expect_fail "unknown option" 64 "unknown option" vread --bogus x
expect_fail "--type without --raw" 64 "go with --raw" vread --type u8 x
expect_fail "--raw without --type" 64 "needs --type" vread --raw 2,2,2 x
expect_fail "bad --raw dims" 64 "sizes must be integers" vread --raw 2,0,2 --type u8 x
expect_fail "bad --type" 64 "--type: unknown type 'u12' (one of: u8, i8, u16, i16, u32, i32, u64, i64, f32, f64)" vread --raw 2,2,2 --type u12 x
expect_fail "bad --endian" 64 "--endian: unknown byte order 'middle' (one of: little, big)" vread --raw 2,2,2 --type u16 --endian middle x
expect_fail "bad -z" 64 "out of range" vread -z 12 --synth sphere
expect_fail "bad --synth" 64 "--synth: unknown field 'cube' (one of: sphere, torus, linear, ml, saddle)" vread --synth cube
expect_fail "--synth with a file" 64 "reads no input" vread --synth sphere x
expect_fail "--size without --synth" 64 "goes with --synth" vread --size 8 x
expect_fail "bad --format" 64 "--format: unknown format 'dicom' (one of: raw, nrrd, nifti, vtk)" vread --format dicom x
expect_fail "--format raw without dims" 64 "--format raw needs" vread --format raw x
expect_fail "--raw against --format" 64 "contradicts" vread --format nrrd --raw 2,2,2 --type u8 x
expect_fail "zero spacing" 64 "must be positive" vread --spacing 1,0,1 --synth sphere
expect_fail "bad name" 64 "--name" vread --name 'a b' --synth sphere
expect_fail "two inputs" 64 "at most one input" vread a b
expect_fail "missing value" 64 "vread: --synth needs a value" vread --synth
expect_fail "missing value of a short option" 64 "vread: -z needs a value" vread -z
expect_fail "unknown short option" 64 "unknown option '-q'" vread -q

printf 'hello' >"$T/mystery.dat"
expect_fail "unknown format" 65 "unknown format" vread "$T/mystery.dat"
printf '\001\002\003' >"$T/short.raw"
expect_fail "raw too short" 65 "truncated" vread --raw 2,2,1 --type u8 "$T/short.raw"
expect_fail "raw too long" 65 "input is longer" vread --raw 1,1,2 --type u8 "$T/short.raw"
printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 0 2\nencoding: raw\n\n' >"$T/bad.nrrd"
expect_fail "nrrd zero size" 65 "nrrd: sizes: expected 3 positive integers" vread "$T/bad.nrrd"
printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\nabc' >"$T/trunc.nrrd"
expect_fail "nrrd truncated data" 65 "trunc.nrrd: nrrd: data: truncated" vread "$T/trunc.nrrd"
printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ndata file: gone.raw\n' >"$T/det.nhdr"
expect_fail "nrrd detached file missing" 66 "gone.raw: No such file" vread "$T/det.nhdr"
vread -o "$T/never.vx" "$T/bad.nrrd" 2>/dev/null
check "no output file after a failure" test ! -e "$T/never.vx"
check "no temporary left behind" sh -c "! ls '$T' | grep -q never"

# no arguments with a terminal on stdin: the usage; a terminal on stdout
# is refused (script(1) provides the terminal)
if command -v script >/dev/null 2>&1; then
	script -qec "$VX_BIN/vread" /dev/null </dev/null >"$T/tty.txt" 2>&1
	check_eq "no arguments on a terminal: exit 64" "$?" 64
	check "no arguments on a terminal: usage" grep -q "usage: vread" "$T/tty.txt"
	script -qec "$VX_BIN/vread --synth sphere --size 2" /dev/null </dev/null >"$T/tty.txt" 2>&1
	check_eq "terminal on stdout: exit 64" "$?" 64
	check "terminal on stdout: message" grep -q "standard output is a terminal" "$T/tty.txt"
else
	skip "no arguments on a terminal" "no script(1)"
	skip "terminal on stdout" "no script(1)"
fi
# every option of the usage line is in the man page's synopsis
for o in $(vread --help | grep -o -- '--[a-z]*\|-[oz] ' | sort -u); do
	check "man page synopsis has $o" grep -q -- "$(echo "$o" | sed 's/-/\\\\-/g; s/ $//')" man/man1/vread.1
done

# ---- successes ----
vread --synth sphere --size 9 >"$T/s1.vx"
check_eq "output begins with the signature" \
    "$(head -c 8 "$T/s1.vx" | od -An -tx1 | tr -d ' ')" "8956584c0d0a1a0a"
vread --synth sphere --size 9 >"$T/s2.vx"
check "synth output is deterministic" cmp -s "$T/s1.vx" "$T/s2.vx"
check_eq "synth dims" "$(hdr "$T/s1.vx" dims)" "9 9 9"
check_eq "synth spacing" "$(hdr "$T/s1.vx" spacing)" "0.25 0.25 0.25"
check_eq "synth origin" "$(hdr "$T/s1.vx" origin)" "-1 -1 -1"
# sphere on 9^3 over [-1,1]: centre 0, corners sqrt(3)
r=$(hdr "$T/s1.vx" range)
check_close "sphere min" "${r% *}" 0 0
check_close "sphere max" "${r#* }" 1.7320508 1e-6
vread --synth ml --size 41,41,21 -z 6 --name ml >"$T/ml.vx"
check_eq "ml name" "$(hdr "$T/ml.vx" name)" "ml"
check_eq "ml dims" "$(hdr "$T/ml.vx" dims)" "41 41 21"
check_eq "ml zlib body" "$(hdr "$T/ml.vx" encoding)" "zlib"
r=$(hdr "$T/ml.vx" range)
check "ml range inside [0,1]" awk -v a="${r% *}" -v b="${r#* }" 'BEGIN { exit !(a >= 0 && b <= 1 && b > 0.9) }'

# raw u16, little-endian: 3x2x1 samples 1 2 3 256 513 65535
printf '\001\000\002\000\003\000\000\001\001\002\377\377' >"$T/a.raw"
vread --raw 3,2,1 --type u16 --spacing 0.5,2,3 --origin 1,-2,3.5 "$T/a.raw" >"$T/a.vx"
check_eq "raw u16 type" "$(hdr "$T/a.vx" type)" "u16"
check_eq "raw u16 dims" "$(hdr "$T/a.vx" dims)" "3 2 1"
check_eq "raw spacing" "$(hdr "$T/a.vx" spacing)" "0.5 2 3"
check_eq "raw origin" "$(hdr "$T/a.vx" origin)" "1 -2 3.5"
check_eq "raw u16 range" "$(hdr "$T/a.vx" range)" "1 65535"
check_eq "raw u16 samples" "$(samples "$T/a.vx")" "01000200030000010102ffff"
# the same samples big-endian, after a 5-byte header, from standard input
printf 'HEAD!\000\001\000\002\000\003\001\000\002\001\377\377' |
    vread --raw 3,2,1 --type u16 --endian big --skip 5 >"$T/b.vx"
check_eq "big-endian raw with skip from stdin" "$(samples "$T/b.vx")" \
    "$(samples "$T/a.vx")"
# gzip-compressed input is read as is
gzip -n -c "$T/a.raw" >"$T/a.raw.gz"
vread --raw 3,2,1 --type u16 "$T/a.raw.gz" >"$T/c.vx"
check_eq "gzipped raw" "$(samples "$T/c.vx")" "$(samples "$T/a.vx")"
# i8 widens to i16: -128 -1 0 127
printf '\200\377\000\177' >"$T/i8.raw"
vread --raw 2,2,1 --type i8 "$T/i8.raw" >"$T/i8.vx"
check_eq "i8 becomes i16" "$(hdr "$T/i8.vx" type)" "i16"
check_eq "i8 samples" "$(samples "$T/i8.vx")" "80ffffff00007f00"
# i32 becomes f32: 1 and -2 (f32 bits 3f800000, c0000000)
printf '\001\000\000\000\376\377\377\377' >"$T/i32.raw"
vread --raw 2,1,1 --type i32 "$T/i32.raw" >"$T/i32.vx"
check_eq "i32 becomes f32" "$(hdr "$T/i32.vx" type)" "f32"
check_eq "i32 samples" "$(samples "$T/i32.vx")" "0000803f000000c0"
# -o writes the file atomically
vread -o "$T/o.vx" --raw 3,2,1 --type u16 "$T/a.raw"
check_eq "-o output" "$(samples "$T/o.vx")" "$(samples "$T/a.vx")"

# NRRD, attached and detached, by extension and by magic
printf 'NRRD0004\ntype: short\ndimension: 2\nsizes: 2 2\nendian: big\nencoding: raw\nspacings: 0.5 0.25\n\n\000\001\377\376\000\002\200\000' >"$T/n.nrrd"
vread "$T/n.nrrd" >"$T/n.vx"
check_eq "nrrd attached dims" "$(hdr "$T/n.vx" dims)" "2 2 1"
check_eq "nrrd spacings" "$(hdr "$T/n.vx" spacing)" "0.5 0.25 1"
check_eq "nrrd big-endian short samples" "$(samples "$T/n.vx")" "0100feff02000080"
mkdir "$T/d"
printf '\000\001\377\376\000\002\200\000' >"$T/d/n.raw"
printf 'NRRD0004\ntype: short\ndimension: 2\nsizes: 2 2\nendian: big\nencoding: raw\nspace: RAS\nspace directions: (0.5,0,0) (0,0.25,0)\nspace origin: (1,2,3)\ndata file: n.raw\n' >"$T/d/n.nhdr"
vread "$T/d/n.nhdr" >"$T/nd.vx"
check_eq "nrrd detached: file beside the header" "$(samples "$T/nd.vx")" "0100feff02000080"
check_eq "nrrd space origin" "$(hdr "$T/nd.vx" origin)" "1 2 3"
vread --format nrrd <"$T/n.nrrd" >"$T/ns.vx"
check_eq "nrrd from stdin" "$(samples "$T/ns.vx")" "0100feff02000080"

# VTK ASCII
printf '# vtk DataFile Version 3.0\nby hand\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 1 2\nSPACING 1 1 2\nORIGIN 0 0 -1\nPOINT_DATA 4\nSCALARS v unsigned_char\nLOOKUP_TABLE default\n0 10\n200 255\n' >"$T/v.vtk"
vread "$T/v.vtk" >"$T/v.vx"
check_eq "vtk ascii samples" "$(samples "$T/v.vx")" "000ac8ff"
check_eq "vtk origin" "$(hdr "$T/v.vx" origin)" "0 0 -1"

# The MNI template of mricron-data, when installed (data README values)
ch2=/usr/share/mricron/templates/ch2.nii.gz
if [ -r "$ch2" ]; then
	vread "$ch2" >"$T/ch2.vx"
	check_eq "ch2 dims" "$(hdr "$T/ch2.vx" dims)" "181 217 181"
	check_eq "ch2 type" "$(hdr "$T/ch2.vx" type)" "u8"
	check_eq "ch2 range" "$(hdr "$T/ch2.vx" range)" "0 254"
	check_eq "ch2 origin" "$(hdr "$T/ch2.vx" origin)" "-90 -125 -71"
else
	skip "ch2 template" "mricron-data not installed"
fi

done_testing
