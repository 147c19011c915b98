#!/bin/sh
# test_vwrite.sh: NRRD export of streams built by mkstream.py: header
# fields, the body against mkstream.py's own decoding of the samples (x
# fastest, whatever the layout), gzip, Teem reading the files, volume
# selection, errors.
. tests/cli/lib.sh
# Debian's python3 (what CI has), not a version manager's slower shim
PY=python3; [ -x /usr/bin/python3 ] && PY=/usr/bin/python3
MK="$PY tests/cli/mkstream.py"
# field FILE NAME: the value of a NRRD header field
field() { sed -n "/^\$/q; s/^$2: //p" "$1"; }
# body FILE: the bytes after the header's empty line
body() { $PY -c 'import sys; d=open(sys.argv[1],"rb").read(); sys.stdout.buffer.write(d[d.index(b"\n\n")+2:])' "$1"; }

$MK volume "$T/a.vx" --dims 5 3 2 --type i16 --layout "bricked 2x2x2" --zlib \
    --formula "x - 3*y + 11*z" --spacing 0.5 1 2.5 --origin -1.5 2 0.1
$MK samples "$T/a.vx" >"$T/a.samples"
check "export a bricked i16 volume" vwrite -o "$T/a.nrrd" "$T/a.vx"
check_eq "magic" "$(head -1 "$T/a.nrrd")" "NRRD0004"
check_eq "type" "$(field "$T/a.nrrd" type)" "int16"
check_eq "sizes" "$(field "$T/a.nrrd" sizes)" "5 3 2"
check_eq "space directions" "$(field "$T/a.nrrd" 'space directions')" "(0.5,0,0) (0,1,0) (0,0,2.5)"
check_eq "space origin" "$(field "$T/a.nrrd" 'space origin')" "(-1.5,2,0.10000000000000001)"
check_eq "endian, encoding" "$(field "$T/a.nrrd" endian) $(field "$T/a.nrrd" encoding)" "little raw"
body "$T/a.nrrd" >"$T/a.body"
check "raw body = samples in x-fastest order" cmp "$T/a.body" "$T/a.samples"
check "history comment" grep -q "^# vwrite 0.1.0 -o $T/a.nrrd $T/a.vx\$" "$T/a.nrrd"

# the volume's other header keys go along as key:=value pairs, in order,
# with NRRD's backslash escape; the writer's pad line does not, nor do the
# keys the VOLM writer makes (oracle: the keys mkstream.py wrote)
$MK volume "$T/k.vx" --dims 3 2 2 --key units HU --key x-note 'a\b := c' \
    --key pad '   '
vwrite -o "$T/k.nrrd" "$T/k.vx"
check_eq "key:=value pairs" "$(sed -n '/^$/q; /:=/p' "$T/k.nrrd" | tr '\n' '|')" \
    'units:=HU|x-note:=a\\b := c|'
check "Teem-style reader: the header still ends before the body" \
    cmp "$(body "$T/k.nrrd" >"$T/k.body"; echo "$T/k.body")" \
    "$($MK samples "$T/k.vx" >"$T/k.samples"; echo "$T/k.samples")"
if command -v teem-unu >/dev/null 2>&1; then
	check_eq "unu reads the pairs" "$(teem-unu head "$T/k.nrrd" | sed -n 's/^units:=//p')" "HU"
else
	skip "unu reads the pairs" "teem-unu not installed"
fi

# gzip, to standard output
vwrite --gzip "$T/a.vx" >"$T/ag.nrrd"
check_eq "gzip encoding" "$(field "$T/ag.nrrd" encoding)" "gzip"
body "$T/ag.nrrd" | $PY -c 'import gzip,sys; sys.stdout.buffer.write(gzip.decompress(sys.stdin.buffer.read()))' >"$T/ag.body"
check "gzip body inflates to the samples" cmp "$T/ag.body" "$T/a.samples"

# every type, through a linear u8/u16 and an f32 with a two-level layout
for spec in "u8 linear" "u16 bricked 4x2x1 2x2x2" "f32 bricked 2x2x2 2x2x2"; do
	set -- $spec; ty=$1; shift
	$MK volume "$T/t.vx" --dims 7 5 3 --type "$ty" --layout "$*" \
	    --formula "x * 9 + y * 20 + z * 40"
	vwrite -o "$T/t.nrrd" "$T/t.vx"
	body "$T/t.nrrd" >"$T/t.body"
	$MK samples "$T/t.vx" >"$T/t.samples"
	check "$ty $*: body = samples" cmp "$T/t.body" "$T/t.samples"
done

# Teem reads both encodings; its range is the samples' range
if command -v teem-unu >/dev/null 2>&1; then
	check_eq "unu minmax (raw)" "$(teem-unu minmax "$T/a.nrrd" | tr '\n' ' ')" "min: -6 max: 15 "
	check_eq "unu minmax (gzip)" "$(teem-unu minmax "$T/ag.nrrd" | tr '\n' ' ')" "min: -6 max: 15 "
	teem-unu save -f nrrd -e raw -i "$T/ag.nrrd" -o "$T/unu.nrrd"
	body "$T/unu.nrrd" >"$T/unu.body"
	check "unu decodes the gzip body to the samples" cmp "$T/unu.body" "$T/a.samples"
else
	skip "unu minmax (raw)" "teem-unu not installed (Debian teem-apps)"
	skip "unu minmax (gzip)" "teem-unu not installed"
	skip "unu decodes the gzip body" "teem-unu not installed"
fi

# --name picks a volume; the default is the first
$MK volume "$T/v1.vx" --dims 2 2 2 --name first --formula "1"
$MK volume "$T/v2.vx" --dims 3 2 2 --name second --formula "2"
$MK cat "$T/two.vx" "$T/v1.vx" "$T/v2.vx"
vwrite "$T/two.vx" >"$T/d.nrrd"
check_eq "default: the first volume" "$(field "$T/d.nrrd" content) $(field "$T/d.nrrd" sizes)" "first 2 2 2"
vwrite --name second "$T/two.vx" >"$T/s.nrrd"
check_eq "--name second" "$(field "$T/s.nrrd" content) $(field "$T/s.nrrd" sizes)" "second 3 2 2"

# the output gets the mode open(2) would give it, not mkstemp's 0600
(umask 022; vwrite -o "$T/mode.nrrd" "$T/a.vx")
check_eq "output mode follows the umask" "$(stat -c %a "$T/mode.nrrd")" "644"

# errors: one line, the right code, no output file touched
echo keep >"$T/keep.nrrd"
expect_fail "no such volume" 65 "no volume named 'third'" vwrite --name third -o "$T/keep.nrrd" "$T/two.vx"
check_eq "failed run leaves the old file" "$(cat "$T/keep.nrrd")" "keep"
$MK image "$T/i.vx" --size 2 2 1
expect_fail "no volume at all" 65 "no volume in the stream" vwrite -o "$T/x.nrrd" "$T/i.vx"
check "no file created on failure" test ! -e "$T/x.nrrd"
expect_fail "not an exportable kind" 64 "only VOLM, IRRV and SHTV" vwrite --chunk MCEL -o "$T/x.nrrd" "$T/a.vx"
expect_fail "SHTV: no SH transfer volume" 65 "no SH transfer volume" vwrite --chunk SHTV -o "$T/x.nrrd" "$T/a.vx"
expect_fail "IRRV: no irradiance volume" 65 "no irradiance volume" vwrite --chunk IRRV -o "$T/x.nrrd" "$T/a.vx"
expect_fail "cannot create output" 73 "nodir" vwrite -o "$T/nodir/a.nrrd" "$T/a.vx"
check "no temporary left behind" test -z "$(ls "$T" | grep tmp)"
printf 'junk' >"$T/junk.vx"
expect_fail "malformed stream" 65 "bad signature" vwrite -o "$T/x.nrrd" "$T/junk.vx"
done_testing
