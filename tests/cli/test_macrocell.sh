#!/bin/sh
# test_macrocell.sh: macrocell(1) against an oracle in Python written from
# formats/macrocell.md alone: the MCEL header (levels, sizes, dims, the
# volume's identity and CRC) and every stored (min, max) pair recomputed
# from the samples mkstream.py reads back; placement and replacement of the
# chunk, bricking leaves it valid, thread counts agree, errors.
. tests/cli/lib.sh
if ! command -v python3 >/dev/null 2>&1; then
	skip "macrocell CLI tests" "python3 not installed"; done_testing; exit
fi
MK="python3 tests/cli/mkstream.py"
cat >"$T/mc.py" <<'EOF'
# mc.py check STREAM [NAME]: recompute the MCEL chunk of volume NAME from
# the samples and print "ok" or the first difference.
# mc.py chunks STREAM | hdr STREAM KEY | payload STREAM
import math, struct, sys, zlib
sys.path.insert(0, "tests/cli")
import mkstream as m

def volume(ch, name):
    for t, p in ch:
        if t != "VOLM":
            continue
        h, body = m.parse_payload(p)
        if name and h.get("name") != name:
            continue
        dims = [int(d) for d in h["dims"].split()]
        tabs, total = m.layout_offsets(dims, h.get("layout", "linear"))
        vals = struct.unpack("<%d%s" % (total, m.FMT[h["type"]]), body)
        get = lambda x, y, z: vals[tabs[0][x] + tabs[1][y] + tabs[2][z]]
        return h, dims, get
    sys.exit("no volume")

def mcel(ch, name):
    for t, p in ch:
        if t == "MCEL":
            h, body = m.parse_payload(p)
            if h.get("volume") == name:
                return h, body
    return None, None

def f32(v):
    return struct.unpack("<f", struct.pack("<f", v))[0]

def check(path, name):
    ch = m.read_stream(path)
    vh, dims, get = volume(ch, name)
    name = vh.get("name", "density")
    h, body = mcel(ch, name)
    if h is None:
        return "no MCEL for " + name
    n = [d - 1 for d in dims]
    if min(n) == 0:
        n = [0, 0, 0]
    smp = b"".join(struct.pack("<" + m.FMT[vh["type"]], get(x, y, z))
                   for z in range(dims[2]) for y in range(dims[1]) for x in range(dims[0]))
    want = {"leaves": "cells", "volume": name,
            "volume-dims": "%d %d %d" % tuple(dims), "volume-type": vh["type"],
            "volume-crc32": "%08x" % zlib.crc32(smp),
            "leaf-dims": "%d %d %d" % tuple(n)}
    for k, v in want.items():
        if h.get(k) != v:
            return "%s: %r, want %r" % (k, h.get(k), v)
    L = int(h["levels"])
    sizes = [[int(e) for e in s.split("x")] for s in h["sizes"].split()]
    if len(sizes) != L:
        return "sizes"
    ld, width, off, out = [n], [[1, 1, 1]], 0, []
    for l in range(1, L + 1):
        ld.append([-(-ld[l - 1][a] // sizes[l - 1][a]) for a in range(3)])
        width.append([width[l - 1][a] * sizes[l - 1][a] for a in range(3)])
        if h["dims-%d" % l] != "%d %d %d" % tuple(ld[l]):
            return "dims-%d" % l
    if len(body) != 8 * sum(ld[l][0] * ld[l][1] * ld[l][2] for l in range(1, L + 1)):
        return "body length %d" % len(body)
    allv = []
    for l in range(1, L + 1):
        for cz in range(ld[l][2]):
            for cy in range(ld[l][1]):
                for cx in range(ld[l][0]):
                    c = (cx, cy, cz)
                    # samples c*W .. min((c+1)*W, n) inclusive, finite only
                    r = [range(c[a] * width[l][a], min((c[a] + 1) * width[l][a], n[a]) + 1)
                         for a in range(3)]
                    v = [f32(get(x, y, z)) for z in r[2] for y in r[1] for x in r[0]]
                    v = [s for s in v if math.isfinite(s)]
                    lo, hi = (min(v), max(v)) if v else (math.inf, -math.inf)
                    got = struct.unpack("<2f", body[off:off + 8])
                    off += 8
                    if got != (lo, hi):
                        return "level %d cell %s: %r, want %r" % (l, c, got, (lo, hi))
                    allv += v
    if L == 0:
        allv = [f32(get(x, y, z)) for z in range(n[2] + 1 if n[0] else 0)
                for y in range(n[1] + 1) for x in range(n[0] + 1)]
        allv = [s for s in allv if math.isfinite(s)]
    if allv:
        got = [f32(float(w)) for w in h["range"].split()]
        if got != [min(allv), max(allv)]:
            return "range %r, want %r" % (h["range"], (min(allv), max(allv)))
    elif h["range"] != "empty":
        return "range %r, want empty" % h["range"]
    return "ok"

def vol(out, typ, dims, formula, layout="linear", name="density"):
    # build a volume stream with mkstream's own writer
    import argparse
    m.cmd_volume(argparse.Namespace(out=out, type=typ, dims=dims, formula=formula,
        layout=layout, name=name, zlib=False, spacing=["1", "1", "1"],
        origin=["0", "0", "0"], range=None, no_range=False))

def query(q):
    w = q.split("|")
    if w[0] == "check":
        return check(w[1], w[2] if len(w) > 2 else None)
    ch = m.read_stream(w[1])
    if w[0] == "chunks":
        return " ".join(t for t, _ in ch)
    if w[0] == "hdr":
        h, _ = mcel(ch, w[3] if len(w) > 3 else "density")
        return h.get(w[2], "") if h else ""
    if w[0] == "payload":
        return "%08x" % zlib.crc32(b"".join(p for t, p in ch if t == "MCEL"))
    if w[0] == "vcrc":
        # the CRC of the VOLM chunk as stored: type and payload
        return "%08x" % zlib.crc32(b"VOLM" + next(p for t, p in ch if t == "VOLM"))

if sys.argv[1] == "make":
    exec(open(sys.argv[2]).read())
else:
    # one query per argument, one answer per line
    for q in sys.argv[1:]:
        print(query(q))
EOF
MC="python3 $T/mc.py"

# Inputs, built in one go by mkstream.py's writer.  f32 with NaN and
# infinities (ignored by min/max), i16 with negatives, a bricked u8, a
# second volume "a", a volume with a dimension of 1, and a stream with two
# volumes and an unknown chunk between them.
cat >"$T/make.py" <<EOF
T = "$T"
vol(T + "/f.vx", "f32", [13, 11, 9], "nan if (x * 7 + y * 3 + z) % 11 == 0 else "
    "(inf if (x + z) % 17 == 5 else math.sin(x / 3.0) * y - z * 0.25)")
vol(T + "/i.vx", "i16", [34, 17, 10], "(x - 18) * (y - 5) - 40 * z")
vol(T + "/u.vx", "u8", [34, 20, 9], "(x * y + 3 * z) % 256", "bricked 4x4x4")
vol(T + "/a.vx", "u8", [9, 8, 7], "x + 3*y + 11*z", name="a")
vol(T + "/flat.vx", "u8", [5, 1, 4], "x + 3*y + 11*z")
m.write_stream(T + "/ai.vx", m.read_stream(T + "/a.vx") + [("zzzz", b"opaque")] +
               m.read_stream(T + "/i.vx"))
EOF
python3 "$T/mc.py" make "$T/make.py"

# Run everything, then ask the oracle all questions in one go.
for v in f i u; do macrocell <"$T/$v.vx" >"$T/${v}m.vx"; done
macrocell --sizes 3x5x2,2x1x3,2x2x2 <"$T/i.vx" >"$T/i3.vx"
macrocell --levels 1 <"$T/f.vx" >"$T/f1.vx"
macrocell --levels 0 <"$T/f.vx" >"$T/f0.vx"
macrocell --levels 3 <"$T/u.vx" >"$T/u3.vx"
macrocell --sizes 2x2x2 <"$T/im.vx" >"$T/im2.vx"        # replaces
brick <"$T/im.vx" >"$T/imb.vx"                           # keeps it valid
macrocell -j 1 <"$T/f.vx" >"$T/j1.vx"
macrocell -j 3 <"$T/f.vx" >"$T/j3.vx"
macrocell --name density <"$T/ai.vx" | macrocell --name a >"$T/ai2.vx"
macrocell <"$T/flat.vx" >"$T/flatm.vx"
python3 "$T/mc.py" \
    "chunks|$T/fm.vx" "check|$T/fm.vx" "chunks|$T/im.vx" "check|$T/im.vx" \
    "chunks|$T/um.vx" "check|$T/um.vx" \
    "hdr|$T/fm.vx|sizes" "hdr|$T/im.vx|sizes" "hdr|$T/um.vx|sizes" "hdr|$T/im.vx|levels" \
    "hdr|$T/um.vx|volume-crc32" \
    "check|$T/i3.vx" "hdr|$T/i3.vx|dims-3" "check|$T/f1.vx" "check|$T/f0.vx" \
    "hdr|$T/u3.vx|sizes" "chunks|$T/im2.vx" "hdr|$T/im2.vx|sizes" \
    "check|$T/imb.vx" "payload|$T/imb.vx" "payload|$T/im.vx" \
    "payload|$T/j1.vx" "payload|$T/j3.vx" \
    "chunks|$T/ai2.vx" "check|$T/ai2.vx|a" "check|$T/ai2.vx|density" \
    "check|$T/flatm.vx" "hdr|$T/flatm.vx|leaf-dims" \
    "hdr|$T/um.vx|volume-chunk-crc32" "vcrc|$T/um.vx" \
    "hdr|$T/imb.vx|volume-chunk-crc32" "vcrc|$T/imb.vx" >"$T/ans"
a() { sed -n "$1p" "$T/ans"; }
check_eq "f32: MCEL after the volume" "$(a 1)" "hist VOLM MCEL"
check_eq "f32: header and every pair match the oracle" "$(a 2)" ok
check_eq "i16: MCEL after the volume" "$(a 3)" "hist VOLM MCEL"
check_eq "i16: header and every pair match the oracle" "$(a 4)" ok
check_eq "u8 bricked: MCEL after the volume" "$(a 5)" "hist VOLM MCEL"
check_eq "u8 bricked: header and every pair match the oracle" "$(a 6)" ok
check_eq "f32 default sizes" "$(a 7)" "8x8x8 8x8x8"
check_eq "i16 default sizes" "$(a 8)" "16x8x8 4x8x8"
check_eq "u8 default sizes" "$(a 9)" "16x16x8 4x4x8"
check_eq "levels 2" "$(a 10)" 2
# the CRC is the one vinfo prints for the volume
check_eq "volume-crc32 is vinfo's crc32" "$(a 11)" \
    "$(vinfo "$T/u.vx" | sed -n 's/^ *crc32: \([0-9a-f]*\) .*/\1/p')"
# other levels and sizes, non-power-of-two and partial macrocells
# (33x16x9 cells by 3x5x2 -> 11x4x5, by 2x1x3 -> 6x4x2, by 2x2x2 -> 3x2x1)
check_eq "three levels, odd sizes" "$(a 12)" ok
check_eq "three levels header" "$(a 13)" "3 2 1"
check_eq "--levels 1" "$(a 14)" ok
check_eq "--levels 0: root only" "$(a 15)" ok
check_eq "--levels 3 defaults" "$(a 16)" "16x16x8 4x4x8 4x4x4"
check_eq "run again: replaced, not added" "$(a 17)" "hist VOLM MCEL"
check_eq "replacement is the new one" "$(a 18)" "2x2x2"
check_eq "brick keeps MCEL valid" "$(a 19)" ok
check_eq "brick keeps MCEL bytes" "$(a 20)" "$(a 21)"
check_eq "-j 1 and -j 3 agree" "$(a 22)" "$(a 23)"
check_eq "two MCELs, each after its volume" "$(a 24)" "hist VOLM MCEL zzzz VOLM MCEL"
check_eq "volume a's MCEL" "$(a 25)" ok
check_eq "volume density's MCEL" "$(a 26)" ok
check_eq "no cells: empty hierarchy" "$(a 27)" ok
check_eq "no cells: leaf-dims" "$(a 28)" "0 0 0"
# the volume's chunk goes through macrocell unchanged, and its CRC is
# recorded (a renderer holding that chunk skips the pass over the samples)
check_eq "volume-chunk-crc32 is the VOLM chunk's CRC" "$(a 29)" "$(a 30)"
# brick rewrites the volume: the key no longer names it, the cells still
# match through the samples' CRC (check|imb.vx above), and raycast uses them
check "brick: the old chunk CRC names another chunk" [ "$(a 31)" != "$(a 32)" ]
raycast --size 8x8 --iso 3 <"$T/imb.vx" >/dev/null 2>"$T/imb.err"
check_eq "brick: raycast takes the cells, no note" "$(cat "$T/imb.err")" ""

# --stats: sizes, per-level numbers and the overhead against the data
# (i16 34x17x10: 33x16x9 cells; level 1 16x8x8 -> 3x2x2 = 12 macrocells,
# level 2 4x8x8 -> 1x1x1; 13 * 8 = 104 bytes of 11560 = 0.900 %)
macrocell --stats <"$T/i.vx" 2>"$T/err" >/dev/null
check "--stats levels" grep -q 'level 1: 3x2x2 macrocells of 16x8x8 cells' "$T/err"
check "--stats memory and overhead" grep -q 'memory 104 bytes = 0.900 % of the data (11560 bytes)' "$T/err"
macrocell <"$T/i.vx" 2>"$T/err" >/dev/null
check_eq "quiet without --stats" "$(wc -c <"$T/err" | tr -d ' ')" 0

# errors
expect_fail "levels and sizes disagree" 64 "--levels 3 but --sizes gives 1" macrocell --levels 3 --sizes 2x2x2 "$T/i.vx"
expect_fail "bad sizes" 64 "sizes" macrocell --sizes 2x2 "$T/i.vx"
expect_fail "size 0" 64 "1..1024" macrocell --sizes 0x2x2 "$T/i.vx"
expect_fail "levels out of range" 64 "out of range" macrocell --levels 7 "$T/i.vx"
expect_fail "-j 0" 64 "out of range" macrocell -j 0 "$T/i.vx"
expect_fail "no such volume or mesh" 65 "no volume or mesh named 'q'" macrocell --name q "$T/i.vx"
expect_fail "unknown option" 64 "unknown option '--fast'" macrocell --fast "$T/i.vx"

done_testing
