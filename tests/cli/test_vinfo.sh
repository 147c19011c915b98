#!/bin/sh
# test_vinfo.sh: vinfo on streams built independently by mkstream.py (from
# formats/stream.md alone): chunk listing, unknown chunks, volume statistics
# against values computed by hand, images, JSON validity, errors.
. tests/cli/lib.sh
# Debian's python3 (what CI has), not a version manager's slower shim
PY=python3; [ -x /usr/bin/python3 ] && PY=/usr/bin/python3
MK="$PY tests/cli/mkstream.py"
# jget FILE EXPR: evaluate a Python expression over the JSON document d
jget() { $PY -c "import json,sys; d=json.load(open(sys.argv[1])); print($2)" "$1"; }

# A bricked, zlib-compressed i16 volume: samples x - 3y + 11z over 5x3x2,
# so the range is [0 - 6 + 0, 4 - 0 + 11] = [-6, 15] and the mean is
# 2 - 3 + 5.5 = 4.5 (means of x, y, z: 2, 1, 0.5).
$MK volume "$T/a.vx" --dims 5 3 2 --type i16 --layout "bricked 2x2x2" \
    --zlib --formula "x - 3*y + 11*z"
check "vinfo reads a bricked zlib volume" vinfo "$T/a.vx"
vinfo --json --histogram 4 "$T/a.vx" >"$T/a.json"
check_eq "dims" "$(jget "$T/a.json" 'd["chunks"][0]["volume"]["dims"]')" "[5, 3, 2]"
check_eq "range" "$(jget "$T/a.json" 'd["chunks"][0]["volume"]["range"]')" "[-6, 15]"
check_eq "mean" "$(jget "$T/a.json" 'd["chunks"][0]["volume"]["mean"]')" "4.5"
check_eq "padding counted apart" \
    "$(jget "$T/a.json" '[d["chunks"][0]["volume"][k] for k in ("samples","stored")]')" "[30, 48]"
# histogram over [-6, 15], width 5.25: count the 30 values by hand
want=$($PY -c '
v = [x - 3*y + 11*z for x in range(5) for y in range(3) for z in range(2)]
c = [0]*4
for s in v: c[min(int((s + 6) / 5.25), 3)] += 1
print(c)')
check_eq "histogram" "$(jget "$T/a.json" 'd["chunks"][0]["volume"]["histogram"]["counts"]')" "$want"
# the checksum is that of the samples in x-fastest order, whatever the layout
want=$($MK samples "$T/a.vx" | $PY -c 'import sys,zlib; print("%08x" % zlib.crc32(sys.stdin.buffer.read()))')
check_eq "crc32 of samples in linear order" \
    "$(jget "$T/a.json" 'd["chunks"][0]["volume"]["crc32"]')" "$want"
$MK volume "$T/a_lin.vx" --dims 5 3 2 --type i16 --formula "x - 3*y + 11*z"
check_eq "same crc32 for the linear raw volume" \
    "$(vinfo --json "$T/a_lin.vx" | $PY -c 'import json,sys; print(json.load(sys.stdin)["chunks"][0]["volume"]["crc32"])')" "$want"

# Non-finite f32 samples: counted, kept out of the range, JSON stays valid
$MK volume "$T/f.vx" --dims 3 2 2 --type f32 --name 'q"uo\te' \
    --formula "nan if x == 0 else (inf if y == 0 and x == 1 else (-inf if x == 1 else 0.5 * x + y))"
vinfo --json "$T/f.vx" >"$T/f.json"
check "JSON with NaN samples parses" $PY -c 'import json,sys; json.load(open(sys.argv[1]))' "$T/f.json"
check_eq "nan / +inf / -inf counts" \
    "$(jget "$T/f.json" '[d["chunks"][0]["volume"][k] for k in ("nan","posinf","neginf")]')" "[4, 2, 2]"
check_eq "range of the finite samples" "$(jget "$T/f.json" 'd["chunks"][0]["volume"]["range"]')" "[1, 2]"
check_eq "name with quote and backslash" "$(jget "$T/f.json" 'd["chunks"][0]["volume"]["name"]')" 'q"uo\te'

# All samples NaN: no range anywhere, null in JSON
$MK volume "$T/n.vx" --dims 2 1 1 --type f32 --formula "nan"
check_eq "no finite sample: range null" \
    "$(vinfo --json "$T/n.vx" | $PY -c 'import json,sys; v=json.load(sys.stdin)["chunks"][0]["volume"]; print(v["range"], v["mean"], "histogram" in v)')" "None None False"

# An unknown ancillary chunk is listed (type, length, unknown), a history
# line with bytes that are not UTF-8 survives in both outputs
$MK add "$T/a.vx" "$T/u.vx" zzzz "opaque data" --at 0
$MK add "$T/u.vx" "$T/u.vx" hist "$(printf 'vread 0.1.0 caf\351.nii')"
vinfo "$T/u.vx" >"$T/u.txt"
check "unknown ancillary chunk listed" \
    grep -q '^chunk 0: zzzz at 8, length 11, ancillary, unknown$' "$T/u.txt"
check "history line, bad byte escaped" grep -q '^    vread 0.1.0 caf\\xe9.nii$' "$T/u.txt"
vinfo --json "$T/u.vx" >"$T/u.json"
check_eq "unknown chunk in JSON" \
    "$(jget "$T/u.json" '[(c["type"], c["offset"], c["length"], c["critical"], c["known"]) for c in d["chunks"]][0]')" \
    "('zzzz', 8, 11, False, False)"
check_eq "history in JSON" "$(jget "$T/u.json" 'ascii(d["chunks"][2]["history"])')" \
    "['vread 0.1.0 caf\\ufffd.nii']"
check_eq "--chunks lists without decoding" \
    "$(vinfo --chunks "$T/u.vx" | grep -c '^chunk ')/$(vinfo --chunks "$T/u.vx" | grep -c volume)" "3/0"

# An image: per-channel min and max (value x + 10y + 100c over 3x2x4)
$MK image "$T/i.vx" --size 3 2 4
vinfo --json "$T/i.vx" >"$T/i.json"
check_eq "image size" "$(jget "$T/i.json" '[d["chunks"][0]["image"][k] for k in ("width","height","channels")]')" "[3, 2, 4]"
check_eq "image min per channel" "$(jget "$T/i.json" 'd["chunks"][0]["image"]["min"]')" "[0, 100, 200, 300]"
check_eq "image max per channel" "$(jget "$T/i.json" 'd["chunks"][0]["image"]["max"]')" "[12, 112, 212, 312]"

# A tetrahedral mesh: counts, bounds and the recomputed scalar range
$MK tetm "$T/m.vx"
vinfo --json "$T/m.vx" >"$T/m.json"
check_eq "mesh summary" \
    "$(jget "$T/m.json" '[d["chunks"][0]["mesh"][k] for k in ("name","scalar","points","tets","bounds","range")]')" \
    "['corner', 'heat', 4, 1, [0, 0, 0, 1, 1, 2], [0.5, 3.5]]"

# A header range that disagrees with the samples: reported, exit 65
$MK volume "$T/r.vx" --dims 2 2 2 --range 0 99
vinfo "$T/r.vx" >"$T/r.out" 2>"$T/r.err"; rc=$?
check_eq "range mismatch exits 65" "$rc" 65
check "range mismatch shown" grep -q 'DIFFERS from the header' "$T/r.out"
check "range mismatch on stderr" grep -q '^vinfo: chunk VOLM at 8: volume: the header.s range differs' "$T/r.err"

# Malformed input: one line, the right code, nothing on stdout
printf 'not a stream' >"$T/bad.vx"
expect_fail "bad signature" 65 "bad signature" vinfo "$T/bad.vx"
head -c 60 "$T/a.vx" >"$T/trunc.vx"
expect_fail "truncated stream" 65 "truncated" vinfo "$T/trunc.vx"
: >"$T/empty.vx"
expect_fail "empty input" 66 "empty input" vinfo "$T/empty.vx"
expect_fail "missing file" 66 "nope.vx" vinfo "$T/nope.vx"
expect_fail "bad option value" 64 "histogram" vinfo --histogram 5000 "$T/a.vx"
vinfo "$T/a.vx" "$T/a.vx" >"$T/two.out" 2>"$T/two.err"; rc=$?
check_eq "two inputs: usage error, one line" \
    "$rc/$(head -1 "$T/two.err")/$(wc -l <"$T/two.err" | tr -d ' ')/$(wc -c <"$T/two.out" | tr -d ' ')" \
    "64/vinfo: at most one input (see vinfo --help)/1/0"
done_testing
