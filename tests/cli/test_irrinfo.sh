#!/bin/sh
# test_irrinfo.sh: vinfo's description of an irradiance volume (IRRV) and
# vwrite's NRRD export of it, against oracles computed here: the white
# furnace's E = pi, the wanted texels and stored bricks recounted from the
# volume's samples (formats/irradiance.md: the corners of every lattice cell
# whose [min, max] meets the band), the lattice's world spacing from the
# lattice rule, the stores' record sizes; the NRRD read back by a reader
# written here from the NRRD format alone (and by vread for the flags).
. "$(dirname "$0")/lib.sh"
PY=python3; [ -x /usr/bin/python3 ] && PY=/usr/bin/python3
MK="$PY tests/cli/mkstream.py"
jget() { $PY -c "import json,sys; d=json.load(open(sys.argv[1])); print($2)" "$1"; }
# the IRRV chunk's object in vinfo --json
J='[c for c in d["chunks"] if c["type"] == "IRRV"][0]["irradiance"]'

vread --synth sphere --size 32 | macrocell > "$T/s.vx"
bake-irr --light sky --iso 0.5 --side high --samples 4 "$T/s.vx" > "$T/b.vx"
vinfo --json "$T/b.vx" > "$T/b.json"

# 1. white furnace: every usable texel has E = pi per channel (sky of
# radiance 1 over a convex surface), each sample rounded to 2^-24
check_close "furnace: mean E = pi" "$(jget "$T/b.json" "$J[\"e_mean\"][1]")" 3.14159265 1e-6
check_close "furnace: min E = pi" "$(jget "$T/b.json" "$J[\"e_min\"][0]")" 3.14159265 1e-6
check_close "furnace: max E = pi" "$(jget "$T/b.json" "$J[\"e_max\"][2]")" 3.14159265 1e-6

# 2. wanted texels and stored bricks recounted from the samples: lattice
# cell (i,j,k) at scale 1 is the volume's cell; its 8 corners are wanted
# when min <= 0.5 <= max over them; a brick of 8^3 is stored when it holds
# a wanted texel
$MK samples "$T/s.vx" > "$T/s.raw"
want=$($PY - "$T/s.raw" <<'PY'
import struct, sys
n = 32
v = struct.unpack('<%df' % n**3, open(sys.argv[1], 'rb').read())
w = set()
for k in range(n - 1):
    for j in range(n - 1):
        for i in range(n - 1):
            c = [(i + a, j + b, k + d) for a in (0, 1) for b in (0, 1) for d in (0, 1)]
            s = [v[x + n * (y + n * z)] for x, y, z in c]
            if min(s) <= 0.5 <= max(s):
                w.update(c)
b = set((x // 8, y // 8, z // 8) for x, y, z in w)
print(len(w), len(b))
PY
)
check_eq "wanted texels, stored bricks (recounted)" \
    "$(jget "$T/b.json" "$J[\"wanted\"], $J[\"bricks\"]")" "$want"
check_eq "all wanted are baked and usable, of 64 bricks" \
    "$(jget "$T/b.json" "$J[\"baked\"] == $J[\"usable\"] == $J[\"wanted\"], $J[\"bricks_total\"], $J[\"flat\"], $J[\"nan\"], $J[\"overflow\"]")" \
    "True 64 0 0 0"
check_eq "samples per texel 4 to 4, 4 x wanted in all" \
    "$(jget "$T/b.json" "$J[\"samples_min\"], $J[\"samples_max\"], $J[\"samples_total\"] == 4 * $J[\"wanted\"]")" \
    "4 4 True"
check_eq "accum: 48 bytes a texel, memory = bricks x 512 x (48 + 16: flags and mean) + the brick table" \
    "$(jget "$T/b.json" "$J[\"texel_bytes\"], $J[\"bytes\"] == $J[\"bricks\"] * 512 * 64 + 64 * 4")" "48 True"
check_eq "the volume matches, the bake's knobs" \
    "$(jget "$T/b.json" "$J[\"status\"], $J[\"side\"], $J[\"offset\"], len($J[\"key\"])")" \
    "matches high 0.5 16"

# 3. world spacing: at scale 1 the volume's (2/31 for the synthetic cube
# [-1, 1]^3 of 32 samples); at scale 0.5, round(31 * 0.5) + 1 = 17 texels an
# axis, 31/16 samples apart: 31/16 * 2/31 = 0.125 world units
check_close "scale 1: world spacing 2/31" "$(jget "$T/b.json" "$J[\"spacing\"][0]")" 0.0645161290322581 1e-15
bake-irr --light sky --iso 0.5 --side high --samples 2 --scale 0.5 --half \
    "$T/s.vx" > "$T/h.vx"
vinfo --json "$T/h.vx" > "$T/h.json"
check_eq "scale 0.5: 17^3 texels, 31/16 samples apart" \
    "$(jget "$T/h.json" "$J[\"lattice_dims\"], $J[\"step\"]")" "[17, 17, 17] [1.9375, 1.9375, 1.9375]"
check_close "scale 0.5: world spacing 0.125" "$(jget "$T/h.json" "$J[\"spacing\"][2]")" 0.125 1e-15
check_eq "scale 0.5: origin the volume's" "$(jget "$T/h.json" "$J[\"origin\"]")" "[-1, -1, -1]"
# binary16 rounds pi to 3.140625 (1 + 0.5703125 of 2^1 in 10 bits)
check_eq "--half: f16, 8 bytes a texel, no counts" \
    "$(jget "$T/h.json" "$J[\"store\"], $J[\"texel_bytes\"], $J[\"samples_max\"], $J[\"e_mean\"][0]")" \
    "f16 8 None 3.140625"

# 4. resumed: 4 + 3 samples make 7 a texel
bake-irr --light sky --iso 0.5 --side high --samples 3 "$T/b.vx" | vinfo --json > "$T/r.json"
check_eq "resumed: 7 samples a texel" \
    "$(jget "$T/r.json" "$J[\"samples_min\"], $J[\"samples_max\"], $J[\"samples_asked\"]")" "7 7 7"

# 5. the volume left out or changed: no world spacing, or stale
$PY - "$T/b.vx" "$T/novol.vx" "$T/other.vx" <<'PY'
import sys
sys.path.insert(0, 'tests/cli')
import mkstream as m
c = m.read_stream(sys.argv[1])
m.write_stream(sys.argv[2], [x for x in c if x[0] != 'VOLM'])
PY
check_eq "no volume: no world spacing" \
    "$(vinfo --json "$T/novol.vx" > "$T/n.json"; jget "$T/n.json" "$J[\"status\"], $J[\"spacing\"]")" "no such volume None"
vread --synth torus --size 32 > "$T/t.vx"
$MK cat "$T/st.vx" "$T/t.vx" "$T/novol.vx"
check "stale: the text says so" sh -c "vinfo '$T/st.vx' | grep -q 'irradiance volume: of density (stale)'"
vinfo "$T/b.vx" > "$T/b.txt"
check "text: texel counts" grep -q "texels: $(echo $want | cut -d' ' -f1) wanted, $(echo $want | cut -d' ' -f1) baked" "$T/b.txt"
check "text: samples range" grep -q "samples per baked texel: 4 to 4" "$T/b.txt"
check "text: mean E" grep -q "R: min 3.1415926[0-9] max 3.1415926[0-9] mean 3.1415926[0-9]" "$T/b.txt"

# ---- vwrite --chunk IRRV ----
# nrrd.py FILE EXPR: read an attached-header NRRD (raw or gzip, little
# endian) and print EXPR over h (the header fields), kv (key:=value pairs)
# and v (the body as numbers, x fastest, the first axis fastest of all)
cat > "$T/nrrd.py" <<'PY'
import gzip, struct, sys
data = open(sys.argv[1], 'rb').read()
head, body = data.split(b'\n\n', 1)
lines = head.decode().split('\n')
assert lines[0] == 'NRRD0004'
h, kv = {}, {}
for l in lines[1:]:
    if l.startswith('#'):
        continue
    if ':=' in l:
        k, x = l.split(':=', 1); kv[k] = x
    else:
        k, x = l.split(': ', 1); h[k] = x
if h['encoding'] == 'gzip':
    body = gzip.decompress(body)
f = {'float': 'f', 'uint8': 'B', 'uint32': 'I'}[h['type']]
n = 1
for d in h['sizes'].split():
    n *= int(d)
assert len(body) == n * struct.calcsize(f), 'body size'
v = struct.unpack('<%d%s' % (n, f), body)
r = eval(sys.argv[2])
print(' '.join(map(str, r)) if isinstance(r, tuple) else r)
PY
N() { $PY "$T/nrrd.py" "$@"; }
vwrite --chunk IRRV --flags "$T/f.nrrd" -o "$T/e.nrrd" "$T/b.vx"
check_eq "NRRD: 4-D float, RGB first, the lattice's dims" \
    "$(N "$T/e.nrrd" '[h[k] for k in ("type", "dimension", "sizes", "kinds", "centerings")]')" \
    "['float', '4', '3 32 32 32', 'RGB-color domain domain domain', '??? node node node']"
check_eq "NRRD: world spacing and origin (the volume's frame)" \
    "$(N "$T/e.nrrd" 'h["space directions"] + " | " + h["space origin"]')" \
    "none (0.064516129032258063,0,0) (0,0.064516129032258063,0) (0,0,0.064516129032258063) | (-1,-1,-1)"
check_eq "NRRD: the bake's key and samples as key:=value" \
    "$(N "$T/e.nrrd" 'kv["key"] == "'"$(jget "$T/b.json" "$J[\"key\"]")"'", kv["samples"]')" "True 4"
# every usable texel E = pi in R, G and B; every other texel 0; as many
# usable texels as vinfo counts
w=$(jget "$T/b.json" "$J[\"usable\"]")
check_eq "NRRD: $w texels of pi, the rest 0" \
    "$(N "$T/e.nrrd" 'sum(1 for i in range(0, len(v), 3) if all(abs(x - 3.14159265) < 1e-6 for x in v[i:i+3])), sum(1 for i in range(0, len(v), 3) if v[i:i+3] == (0.0, 0.0, 0.0)), len(v) // 3')" \
    "$w $((32768 - w)) 32768"
# the flags: u8, read back by vread (a scalar NRRD): 16 (wanted) on every
# wanted texel, 0 elsewhere, so the mean is 16 wanted / 32768
vread "$T/f.nrrd" | vinfo --json > "$T/f.json"
V='[c for c in d["chunks"] if c["type"] == "VOLM"][0]["volume"]'
check_eq "flags: vread reads them back, range [0, 16], mean 16 x wanted / texels" \
    "$(jget "$T/f.json" "$V[\"type\"], $V[\"range\"], $V[\"mean\"] * 32768 == 16 * $w, $V[\"spacing\"][1]")" \
    "u8 [0, 16] True 0.06451612903225806"
vwrite --chunk IRRV --flags "$T/f32.nrrd" --flags-type u32 --gzip -o "$T/eg.nrrd" "$T/b.vx"
check_eq "flags as u32 (gzip): the same values" \
    "$(N "$T/f32.nrrd" 'h["type"], sum(v)')" "uint32 $((16 * w))"
check_eq "gzip: the same texels" "$(N "$T/eg.nrrd" 'hash(v)')" "$(N "$T/e.nrrd" 'hash(v)')"
# scale 0.5, f16: 17^3 texels 0.125 apart, binary16's pi
vwrite --chunk IRRV -o "$T/h.nrrd" "$T/h.vx"
check_eq "scale 0.5: 17^3, spacing 0.125, E = 3.140625" \
    "$(N "$T/h.nrrd" 'h["sizes"], h["space directions"], max(v)')" \
    "3 17 17 17 none (0.125,0,0) (0,0.125,0) (0,0,0.125) 3.140625"
# a NaN sample: the texels whose support holds it are flagged nan (bit 1)
# and written 0; the others of a distance field are baked
$MK volume "$T/nan.vx" --dims 12 12 12 --type f32 \
    --formula "float('nan') if (x, y, z) == (5, 5, 5) else ((x-5.5)**2 + (y-5.5)**2 + (z-5.5)**2) ** 0.5"
bake-irr --light sky --all --side high --samples 1 "$T/nan.vx" 2>/dev/null | \
    vwrite --chunk IRRV --flags "$T/nf.nrrd" -o "$T/ne.nrrd"
# texel (5,5,5) is the NaN sample itself; (9,9,9) is 4 samples away
check_eq "NaN texel: flag nan, E 0; a texel away from it: E > 0, no nan flag" \
    "$(N "$T/nf.nrrd" 'v[5 + 12 * (5 + 12 * 5)] & 2, v[9 + 12 * (9 + 12 * 9)] & 2'),$(N "$T/ne.nrrd" 'v[3 * (5 + 12 * (5 + 12 * 5))], v[3 * (9 + 12 * (9 + 12 * 9))] > 0')" \
    "2 0,0.0 True"
expect_fail "--flags without --chunk IRRV" 64 "only with --chunk IRRV" \
    vwrite --flags "$T/x.nrrd" -o "$T/x.nrrd2" "$T/b.vx"
expect_fail "no irradiance volume" 65 "no irradiance volume" \
    vwrite --chunk IRRV -o "$T/x.nrrd" "$T/s.vx"
expect_fail "the volume left out: no world frame" 65 "its world frame" \
    vwrite --chunk IRRV -o "$T/x.nrrd" "$T/novol.vx"
expect_fail "--chunk of another kind" 64 "only VOLM, IRRV and SHTV" \
    vwrite --chunk TETM -o "$T/x.nrrd" "$T/b.vx"
check "a failed run leaves no file" test ! -e "$T/x.nrrd"
done_testing
