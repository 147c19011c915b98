#!/bin/sh
# test_brick.sh: brick(1) on volumes built by mkstream.py (from the spec
# alone): layouts chosen per sample type, samples unchanged in logical
# order (read back by mkstream.py through the layout tables it computes
# itself), padding numbers, other chunks untouched and in order, errors.
. tests/cli/lib.sh
if ! command -v python3 >/dev/null 2>&1; then
	skip "brick CLI tests" "python3 not installed"; done_testing; exit
fi
# st.py make FILE: run FILE with vol() and m (mkstream) at hand;
# st.py Q...: answer each query, one line each:
#   chunks|F  hdr|F|TYPE|KEY[|N] (of the N-th chunk of TYPE)
#   samples|F[|NAME] (CRC-32 of the samples in logical order)
cat >"$T/st.py" <<'EOF'
import argparse, sys, zlib
sys.path.insert(0, "tests/cli")
import mkstream as m

def vol(out, typ, dims, formula, layout="linear", name="density", z=False,
        key=None):
    m.cmd_volume(argparse.Namespace(out=out, type=typ, dims=dims, formula=formula,
        layout=layout, name=name, zlib=z, spacing=["1", "1", "1"],
        origin=["0", "0", "0"], range=None, no_range=False, key=key))

def samples(path, name):
    import io, contextlib
    buf = io.BytesIO()
    class W:  # mkstream writes to sys.stdout.buffer
        buffer = buf
    old, sys.stdout = sys.stdout, W
    try:
        m.cmd_samples(argparse.Namespace(inp=path, name=name))
    finally:
        sys.stdout = old
    return "%08x" % zlib.crc32(buf.getvalue())

def query(q):
    w = q.split("|")
    if w[0] == "samples":
        return samples(w[1], w[2] if len(w) > 2 else None)
    ch = m.read_stream(w[1])
    if w[0] == "chunks":
        return " ".join(t for t, _ in ch)
    if w[0] == "hdr":
        p = [p for t, p in ch if t == w[2]][int(w[4]) if len(w) > 4 else 0]
        return m.parse_payload(p)[0].get(w[3], "")
    if w[0] == "raw":
        return [p for t, p in ch if t == w[2]][0].hex()

if sys.argv[1] == "make":
    exec(open(sys.argv[2]).read())
else:
    for q in sys.argv[1:]:
        print(query(q))
EOF

# Inputs: one 13x9x7 volume per type; two volumes "a" and "b" (b zlib)
# with a note before, an unknown chunk between and an MCEL after.
cat >"$T/make.py" <<EOF
T = "$T"
for t in ("u8", "u16", "i16", "f32"):
    vol(T + "/" + t + ".vx", t, [13, 9, 7], "x*x - 3*y + 7*z + 30")
vol(T + "/a.vx", "u8", [5, 6, 7], "x + 3*y + 11*z", name="a")
vol(T + "/b.vx", "u16", [6, 5, 4], "x*y*z", name="b", z=True)
m.write_stream(T + "/ab.vx", [("note", b"first")] + m.read_stream(T + "/a.vx") +
    [("zzzz", b"\x00\x01opaque")] + m.read_stream(T + "/b.vx") +
    [("MCEL", b"leaves: explicit\nlevels: 0\nsizes:\nleaf-dims: 0 0 0\nrange: empty\n\n")])
EOF
python3 "$T/st.py" make "$T/make.py"

for t in u8 u16 i16 f32; do
	brick <"$T/$t.vx" >"$T/${t}b.vx" 2>"$T/err_$t"
done
brick --linear <"$T/i16b.vx" >"$T/lin.vx"
brick --bricks 2x2x2,2x1x2,2x2x2 -o "$T/b3.vx" "$T/f32.vx"
brick --name b <"$T/ab.vx" >"$T/ab2.vx"
python3 "$T/st.py" \
    "hdr|$T/u8b.vx|VOLM|layout" "samples|$T/u8b.vx" "samples|$T/u8.vx" \
    "hdr|$T/u16b.vx|VOLM|layout" "samples|$T/u16b.vx" "samples|$T/u16.vx" \
    "hdr|$T/i16b.vx|VOLM|layout" "samples|$T/i16b.vx" "samples|$T/i16.vx" \
    "hdr|$T/f32b.vx|VOLM|layout" "samples|$T/f32b.vx" "samples|$T/f32.vx" \
    "hdr|$T/lin.vx|VOLM|layout" "samples|$T/lin.vx" \
    "hdr|$T/lin.vx|VOLM|range" "hdr|$T/i16.vx|VOLM|range" \
    "hdr|$T/b3.vx|VOLM|layout" "samples|$T/b3.vx" \
    "chunks|$T/ab2.vx" "hdr|$T/ab2.vx|VOLM|layout|0" "hdr|$T/ab2.vx|VOLM|layout|1" \
    "hdr|$T/ab2.vx|VOLM|encoding|1" "samples|$T/ab2.vx|b" "samples|$T/b.vx" \
    "raw|$T/ab2.vx|zzzz" "raw|$T/ab2.vx|MCEL" "raw|$T/ab.vx|MCEL" >"$T/ans"
a() { sed -n "$1p" "$T/ans"; }

# default bricks follow the sample size: one 64-byte line, one 4 KiB page
n=1
for tl in "u8 4x4x4" "u16 4x4x2" "i16 4x4x2" "f32 4x2x2"; do
	set -- $tl
	check_eq "$1: default layout" "$(a $n)" "bricked $2 4x4x4"
	check_eq "$1: samples unchanged" "$(a $((n + 1)))" "$(a $((n + 2)))"
	check_eq "$1: quiet without --stats" "$(wc -c <"$T/err_$1" | tr -d ' ')" 0
	n=$((n + 3))
done
check_eq "--linear layout" "$(a 13)" "linear"
check_eq "--linear samples" "$(a 14)" "$(a 9)"
check_eq "range kept" "$(a 15)" "$(a 16)"
check_eq "--bricks three levels" "$(a 17)" "bricked 2x2x2 2x1x2 2x2x2"
check_eq "--bricks samples" "$(a 18)" "$(a 12)"
check_eq "chunk order kept" "$(a 19)" "hist note VOLM zzzz VOLM MCEL"
check_eq "volume a untouched" "$(a 20)" "linear"
check_eq "b: u16 bricks" "$(a 21)" "bricked 4x4x2 4x4x4"
check_eq "b: zlib kept" "$(a 22)" "zlib"
check_eq "b: samples unchanged" "$(a 23)" "$(a 24)"
check_eq "unknown chunk intact" "$(a 25)" "00016f7061717565"
check_eq "MCEL intact" "$(a 26)" "$(a 27)"

# header keys brick does not know pass through with their values (stream.md
# 7.1, 9.1): a short one, one with inner and trailing blanks, one longer
# than the 4 KiB of a formatted header value; raw and zlib, there and back
python3 tests/cli/mkstream.py volume "$T/k.vx" --type u16 --dims 5 4 3 \
    --key units HU --key x-comment "$(printf 'two  blanks and a tab\t')" \
    --key long "$(printf '%5000s' | tr ' ' v)"
python3 tests/cli/mkstream.py volume "$T/kz.vx" --type f32 --dims 5 4 3 --zlib \
    --key units HU --key x-comment "$(printf 'two  blanks and a tab\t')" \
    --key long "$(printf '%5000s' | tr ' ' v)"
brick -o "$T/kb.vx" "$T/k.vx"
brick --linear -o "$T/kbl.vx" "$T/kb.vx"
brick --bricks 2x2x2 -o "$T/kzb.vx" "$T/kz.vx"
for f in kb kbl kzb; do
	python3 "$T/st.py" "hdr|$T/$f.vx|VOLM|units" "hdr|$T/$f.vx|VOLM|x-comment" \
	    "hdr|$T/$f.vx|VOLM|long" "hdr|$T/$f.vx|VOLM|layout" >"$T/kans"
	check_eq "$f: unknown keys kept" "$(head -2 "$T/kans" | tr '\n' '|')" \
	    "$(printf 'HU|two  blanks and a tab\t|')"
	check_eq "$f: a 5000-byte value kept" \
	    "$(sed -n 3p "$T/kans" | grep -x 'v*' | tr -d '\n' | wc -c | tr -d ' ')" 5000
	vinfo "$T/$f.vx" >"$T/kinfo"
	check "$f: vinfo shows units" grep -qx '    units: HU' "$T/kinfo"
	check_eq "$f: vinfo: the volume decodes, no error" "$(grep -c 'error' "$T/kinfo")" 0
done
check_eq "kb: layout rewritten" "$(python3 "$T/st.py" "hdr|$T/kb.vx|VOLM|layout")" "bricked 4x4x2 4x4x4"
check_eq "kbl: back to linear" "$(python3 "$T/st.py" "hdr|$T/kbl.vx|VOLM|layout")" "linear"
check_eq "kbl: samples unchanged" "$(python3 "$T/st.py" "samples|$T/kbl.vx")" "$(python3 "$T/st.py" "samples|$T/k.vx")"
check_eq "kzb: zlib kept" "$(python3 "$T/st.py" "hdr|$T/kzb.vx|VOLM|encoding")" "zlib"
# the known keys in the table's order, the others in theirs before encoding;
# then the writer's own pad line (the input's is not kept: one pad key)
check_eq "kb: key order" "$(vinfo "$T/kb.vx" | sed -n '/^  header:/,/^  [a-z]/s/^    \([a-z-]*\):.*/\1/p' | tr '\n' ' ')" \
    "name dims type spacing origin layout range units x-comment long encoding pad "

# padding reported with --stats: 13x9x7 u8 in 16x16x16 bricks: 4096
# samples for 819, padding (4096 - 819) / 819 = 400.12 %
brick --stats <"$T/u8.vx" >/dev/null 2>"$T/err"
check "--stats names the layouts" grep -q 'linear -> bricked 4x4x4 4x4x4' "$T/err"
check "--stats padded dims" grep -q '16x16x16 padded, 4096 samples for 819' "$T/err"
check "--stats padding percent" grep -q '(padding 400.12 %)' "$T/err"
brick -v <"$T/u8.vx" 2>"$T/err" >/dev/null
check "-v is --stats" grep -q 'padding 400.12' "$T/err"

# errors: the right code, a line naming the problem, nothing on stdout
expect_fail "bricks not a power of two" 64 "power of two" brick --bricks 3x4x4 "$T/u8.vx"
expect_fail "bricks malformed" 64 "expected 1 to 4 sizes" brick --bricks 4x4 "$T/u8.vx"
expect_fail "bricks too many levels" 64 "expected 1 to 4" brick --bricks 1x1x1,1x1x1,1x1x1,1x1x1,1x1x1 "$T/u8.vx"
expect_fail "--bricks with --linear" 64 "exclude" brick --linear --bricks 4x4x4 "$T/u8.vx"
expect_fail "no such volume" 65 "no volume named 'zz'" brick --name zz "$T/u8.vx"
expect_fail "no input file" 66 "nope.vx" brick "$T/nope.vx"
printf 'not a stream' >"$T/junk"
expect_fail "not a stream" 65 "junk" brick "$T/junk"
expect_fail "unknown option" 64 "unknown option '--frobnicate'" brick --frobnicate "$T/u8.vx"
expect_fail "missing value" 64 "needs a value" brick --bricks
expect_fail "unknown option in a cluster" 64 "unknown option '-q'" brick -vq "$T/u8.vx"
expect_fail "padded volume too large" 65 "exceeds" brick --bricks 1024x1024x1024,64x64x64 "$T/u8.vx"

done_testing
