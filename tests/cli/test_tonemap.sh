#!/bin/sh
# test_tonemap.sh: tonemap(1) on hand-made PFM files and streams.  Inputs are
# written and outputs decoded by a small python3 helper (PFM, the voxlux
# stream and PNG written out from their specs, zlib from python), so the
# expected pixel values come from formulas evaluated outside voxlux.
. tests/cli/lib.sh
if ! command -v python3 >/dev/null 2>&1; then
	skip "tonemap CLI tests" "python3 not installed"; done_testing; exit
fi

cat >"$T/vx.py" <<'EOF'
import json, math, struct, sys, zlib

def fval(s):
    return float(s)          # accepts nan, inf, -inf

def pfm(args):
    # pfm RGB|GRAY W H [be] v... (values top row first)
    kind, w, h = args[0], int(args[1]), int(args[2])
    be = args[3] == 'be'
    vals = [fval(v) for v in args[4 if be else 3:]]
    nc = 3 if kind == 'RGB' else 1
    assert len(vals) == w * h * nc
    rows = [vals[y * w * nc:(y + 1) * w * nc] for y in range(h)]
    out = b'%s\n%d %d\n%s\n' % (b'PF' if nc == 3 else b'Pf', w, h,
                                b'1.0' if be else b'-1.0')
    for r in reversed(rows):
        out += struct.pack(('>' if be else '<') + '%df' % len(r), *r)
    sys.stdout.buffer.write(out)

def chunk(t, payload):
    return (t + struct.pack('<Q', len(payload)) + payload +
            struct.pack('<I', zlib.crc32(t + payload) & 0xffffffff))

def stream(args):
    # stream SPEC.json: {"history": [...], "images": [{"name", "w", "h",
    # "nc", "v": [...], "zlib": bool}]}
    spec = json.load(open(args[0]))
    out = b'\x89VXL\r\n\x1a\n'
    if spec.get('history'):
        out += chunk(b'hist', ''.join(l + '\n' for l in spec['history']).encode())
    for im in spec['images']:
        body = struct.pack('<%df' % len(im['v']), *[fval(str(v)) for v in im['v']])
        hdr = 'name: %s\nwidth: %d\nheight: %d\nchannels: %d\ncolorspace: linear\n' % (
            im['name'], im['w'], im['h'], im['nc'])
        if im['nc'] in (2, 4):
            hdr += 'alpha: premultiplied\n'
        if im.get('zlib'):
            hdr += 'encoding: zlib\n'
            body = zlib.compress(body)
        else:
            hdr += 'encoding: raw\n'
        out += chunk(b'IMAG', (hdr + '\n').encode() + body)
    out += chunk(b'VEND', b'')
    sys.stdout.buffer.write(out)

def png_decode(path):
    d = open(path, 'rb').read()
    assert d[:8] == b'\x89PNG\r\n\x1a\n'
    pos, idat, text, info = 8, b'', {}, {}
    while pos < len(d):
        n, t = struct.unpack('>I4s', d[pos:pos + 8])
        data = d[pos + 8:pos + 8 + n]
        assert struct.unpack('>I', d[pos + 8 + n:pos + 12 + n])[0] == zlib.crc32(t + data) & 0xffffffff
        if t == b'IHDR':
            w, h, depth, ct, _, _, il = struct.unpack('>IIBBBBB', data)
            assert il == 0
        elif t == b'IDAT':
            idat += data
        elif t == b'tEXt':
            k, v = data.split(b'\0', 1)
            text[k.decode('latin-1')] = v.decode('latin-1')
        elif t in (b'sRGB', b'gAMA'):
            info[t.decode()] = data
        pos += 12 + n
    nc = {0: 1, 4: 2, 2: 3, 6: 4}[ct]
    bpp = nc * depth // 8
    raw = zlib.decompress(idat)
    stride = w * bpp
    prev = bytearray(stride)
    vals = []
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pr = a if pa <= pb and pa <= pc else b if pb <= pc else c
                line[i] = (line[i] + pr) & 255
        if depth == 8:
            vals += list(line)
        else:
            vals += [line[2 * i] << 8 | line[2 * i + 1] for i in range(stride // 2)]
        prev = line
    return w, h, nc, depth, vals, text, info

def png(args):
    # png FILE: "W H NC DEPTH" then the codes, top row first
    w, h, nc, depth, vals, _, _ = png_decode(args[0])
    print(w, h, nc, depth, *vals)

def pngtext(args):
    print(png_decode(args[0])[5].get(args[1], '<absent>'))

def pnginfo(args):
    print(' '.join(sorted(png_decode(args[0])[6])))

def pfmvals(args):
    # pfmvals FILE: "KIND W H" then the values top row first (%.9g)
    d = open(args[0], 'rb').read()
    parts = d.split(b'\n', 3)
    kind = parts[0].decode()
    w, h = map(int, parts[1].split())
    scale = float(parts[2])
    nc = 3 if kind == 'PF' else 1
    v = struct.unpack(('<' if scale < 0 else '>') + '%df' % (w * h * nc), parts[3])
    rows = [v[y * w * nc:(y + 1) * w * nc] for y in range(h)]
    out = [x for r in reversed(rows) for x in r]
    print(kind, w, h, *['%.9g' % x for x in out])

def srgb(args):
    # srgb BITS x...: the codes of the IEC 61966-2-1 curve, clamped
    m = (1 << int(args[0])) - 1
    out = []
    for s in args[1:]:
        x = min(max(float(s), 0.0), 1.0)
        e = 12.92 * x if x <= 0.0031308 else 1.055 * x ** (1 / 2.4) - 0.055
        out.append(math.floor(e * m + 0.5))
    print(*out)

def jsonget(args):
    v = json.load(sys.stdin)[args[0]]
    print('null' if v is None else v)

globals()[sys.argv[1]](sys.argv[2:])
EOF
# the interpreter itself, not a version-manager shim (faster to start)
PY=$(python3 -c 'import sys; print(sys.executable)')
py() { "$PY" -S "$T/vx.py" "$@"; }

# ---- PFM in, PNG out: pixel values ----
# 3x2 RGB, top row first; gray triples except the last pixel
py pfm RGB 3 2 0 0 0  0.5 0.5 0.5  1 1 1  0.18 0.18 0.18  2 2 2  0.001 0.25 0.9 >"$T/a.pfm"
check "pfm to png" tonemap -o "$T/a.png" "$T/a.pfm"
want=$(py srgb 8 0 0 0 0.5 0.5 0.5 1 1 1 0.18 0.18 0.18 2 2 2 0.001 0.25 0.9)
check_eq "8-bit sRGB codes, rows top first" "$(py png "$T/a.png")" "3 2 3 8 $want"
check_eq "sRGB chunk" "$(py pnginfo "$T/a.png")" "gAMA sRGB"
check_eq "Software text" "$(py pngtext "$T/a.png" Software)" "voxlux 0.1.0"
check_eq "history text" "$(py pngtext "$T/a.png" voxlux-history)" \
    "tonemap 0.1.0 -o $T/a.png $T/a.pfm"
# big-endian PFM, same values: same PNG codes
py pfm RGB 3 2 be 0 0 0  0.5 0.5 0.5  1 1 1  0.18 0.18 0.18  2 2 2  0.001 0.25 0.9 >"$T/abe.pfm"
tonemap "$T/abe.pfm" >"$T/abe.png"
check_eq "big-endian PFM, PNG on stdout" "$(py png "$T/abe.png")" "3 2 3 8 $want"

# 16-bit linear: round(65535 x)
py pfm GRAY 4 1 0.25 0.5 0.75 0.1 >"$T/g.pfm"
tonemap --linear --bits 16 -o "$T/g16.png" "$T/g.pfm"
check_eq "16-bit linear gray" "$(py png "$T/g16.png")" "4 1 1 16 16384 32768 49151 6554"
check_eq "gAMA 1 for linear" "$(py pnginfo "$T/g16.png")" "gAMA"
# gamma 2.2: floor(255 x^(1/2.2) + 0.5)
tonemap --gamma 2.2 -o "$T/gg.png" "$T/g.pfm"
want=$("$PY" -S -c "import math; print(*[math.floor(255*x**(1/2.2)+0.5) for x in (0.25,0.5,0.75,0.1)])")
check_eq "gamma 2.2" "$(py png "$T/gg.png" | cut -d' ' -f5-)" "$want"
# exposure +1 stop doubles: 0.5 and 0.75 clip
tonemap --exposure 1 --linear -o "$T/ge.png" "$T/g.pfm"
check_eq "exposure +1" "$(py png "$T/ge.png" | cut -d' ' -f5-)" "128 255 255 51"

# operators, linear output: reinhard x/(1+x), with white 2 x(1+x/4)/(1+x),
# aces x(2.51x+0.03)/(x(2.43x+0.59)+0.14); codes floor(255 y + 0.5)
py pfm GRAY 4 1 0.25 1 3 1e30 >"$T/op.pfm"
tonemap --op reinhard --linear -o "$T/r.png" "$T/op.pfm"
check_eq "reinhard" "$(py png "$T/r.png" | cut -d' ' -f5-)" "51 128 191 255"
tonemap --op reinhard --white 2 --linear -o "$T/rw.png" "$T/op.pfm"
want=$("$PY" -S -c "import math; print(*[math.floor(255*min(1,x*(1+x/4)/(1+x))+0.5) for x in (0.25,1,3,1e30)])")
check_eq "reinhard white 2" "$(py png "$T/rw.png" | cut -d' ' -f5-)" "$want"
tonemap --op aces --linear -o "$T/ac.png" "$T/op.pfm"
want=$("$PY" -S -c "import math; print(*[math.floor(255*min(1,x*(2.51*x+0.03)/(x*(2.43*x+0.59)+0.14))+0.5) for x in (0.25,1,3,1e30)])")
check_eq "aces" "$(py png "$T/ac.png" | cut -d' ' -f5-)" "$want"

# NaN, infinities, negatives: NaN -> 0 with a warning, +inf -> 1, the rest 0
py pfm GRAY 5 1 nan inf -inf -2 0.5 >"$T/bad.pfm"
tonemap --linear -o "$T/bad.png" "$T/bad.pfm" 2>"$T/bad.err"
check_eq "NaN inf -inf negative" "$(py png "$T/bad.png" | cut -d' ' -f5-)" "0 255 0 0 128"
check_eq "NaN warning" "$(cat "$T/bad.err")" "tonemap: warning: 1 NaN values shown as 0"

# ---- streams: named images, premultiplied alpha, history ----
cat >"$T/spec.json" <<'EOF'
{"history": ["vread 0.1.0 --synth sphere", "raycast 0.1.0 --scene s.scn"],
 "images": [
  {"name": "color", "w": 2, "h": 1, "nc": 4, "zlib": true,
   "v": [0.25, 0.125, 0, 0.5,   0.3, 0.3, 0.3, 0]},
  {"name": "depth", "w": 2, "h": 1, "nc": 1, "v": [0.5, "inf"]}]}
EOF
py stream "$T/spec.json" >"$T/s.vxl"
tonemap --linear -o "$T/c.png" "$T/s.vxl"
# straight color = premultiplied / alpha: (0.5, 0.25, 0), alpha 0.5;
# no coverage gives 0
check_eq "RGBA straight alpha" "$(py png "$T/c.png")" "2 1 4 8 128 64 0 128 0 0 0 0"
check_eq "history carried" "$(py pngtext "$T/c.png" voxlux-history)" \
    "vread 0.1.0 --synth sphere
raycast 0.1.0 --scene s.scn
tonemap 0.1.0 --linear -o $T/c.png $T/s.vxl"
tonemap --linear --background 1,1,1 -o "$T/cb.png" "$T/s.vxl"
# over white: 0.5 * 0.5 + 0.5 = 0.75, 0.25 * 0.5 + 0.5 = 0.625, 0.5
check_eq "flattened over white" "$(py png "$T/cb.png")" "2 1 3 8 191 159 128 255 255 255"
tonemap --name depth --linear -o "$T/d.png" <"$T/s.vxl"
check_eq "--name depth, stdin" "$(py png "$T/d.png")" "2 1 1 8 128 255"
# PFM out: premultiplied color as is (over black), times 2^exposure
tonemap --exposure 1 -o "$T/c.pfm" "$T/s.vxl"
check_eq "pfm output" "$(py pfmvals "$T/c.pfm")" "PF 2 1 0.5 0.25 0 0.600000024 0.600000024 0.600000024"
tonemap --pfm --background 0,0,2 "$T/s.vxl" >"$T/cb.pfm"
check_eq "pfm over a background" "$(py pfmvals "$T/cb.pfm")" "PF 2 1 0.25 0.125 1 0.300000012 0.300000012 2.29999995"
# round trip: PFM out, PFM in, PFM out again is byte-identical
tonemap -o "$T/a2.pfm" "$T/a.pfm"
check "pfm round trip" cmp "$T/a.pfm" "$T/a2.pfm"

# ---- comparison ----
# a = 0 everywhere, b = 0.5 at (1, 0): mse 0.25/4, rmse 0.25,
# psnr 10 log10(16) = 12.0412, relmse (0.25 / 0.26) / 4
py pfm GRAY 2 2 0 0 0 0 >"$T/z.pfm"
py pfm GRAY 2 2 0 0.5 0 0 >"$T/h.pfm"
tonemap --compare "$T/h.pfm" "$T/z.pfm" >"$T/m.txt"
m() { awk -v k="$1" '$1 == k { print $2 }' "$T/m.txt"; }
check_close "rmse" "$(m rmse)" 0.25 1e-12
check_close "mse" "$(m mse)" 0.0625 1e-12
check_close "psnr" "$(m psnr)" 12.0411998266 1e-8
check_close "relmse" "$(m relmse)" 0.2403846154 1e-9
check_eq "max where (top row is y 0)" "$(m max_abs) $(m max_x) $(m max_y) $(m max_c)" "0.5 1 0 0"
check_eq "compared count" "$(m compared)" 4
tonemap --compare "$T/h.pfm" --peak 255 --json "$T/z.pfm" >"$T/m.json"
check_close "json psnr, peak 255" "$(py jsonget psnr <"$T/m.json")" 60.17200344 1e-6
check_eq "json psnr of identical images is null" \
    "$(tonemap --compare "$T/z.pfm" --json "$T/z.pfm" | py jsonget psnr)" null
# NaN in the reference is skipped and counted
py pfm GRAY 2 2 nan 0.5 0 0 >"$T/hn.pfm"
tonemap --compare "$T/hn.pfm" "$T/z.pfm" >"$T/m.txt"
check_eq "nan_b counted" "$(m nan_b) $(m compared)" "1 3"
check_close "mse without the NaN" "$(m mse)" 0.0833333333 1e-9
# against its own PNG: zero error (same tone mapping, same quantization)
check_eq "PNG reference, 8 bit" \
    "$(tonemap --compare "$T/a.png" "$T/a.pfm" | awk '$1 == "max_abs" { print $2 }')" 0
tonemap --bits 16 --op aces -o "$T/a16.png" "$T/a.pfm"
check_eq "PNG reference, 16 bit" \
    "$(tonemap --op aces --compare "$T/a16.png" "$T/a.pfm" | awk '$1 == "max_abs" { print $2 }')" 0
# RGBA stream against its PNG, and against a PFM without alpha
check_eq "RGBA stream vs its PNG" \
    "$(tonemap --linear --compare "$T/c.png" "$T/s.vxl" | awk '$1 == "rmse" { print $2 }')" 0
tonemap -o "$T/c0.pfm" "$T/s.vxl"
check_eq "RGBA stream vs PFM (flattened over black)" \
    "$(tonemap --compare "$T/c0.pfm" "$T/s.vxl" | awk '$1 == "rmse" { print $2 }')" 0
# image and output together; the difference picture
tonemap --compare "$T/h.pfm" --diff "$T/diff.png" -o "$T/z.png" "$T/z.pfm" >"$T/m.txt"
check_eq "diff_scale is the largest difference" "$(m diff_scale)" 0.5
check_eq "diff picture: viridis ends" "$(py png "$T/diff.png")" \
    "2 2 3 8 68 1 84 253 231 37 68 1 84 68 1 84"
check_eq "diff scale text" "$(py pngtext "$T/diff.png" voxlux-diff-scale)" 0.5
check_eq "output written too" "$(py png "$T/z.png")" "2 2 1 8 0 0 0 0"
tonemap --compare "$T/z.pfm" --diff "$T/sd.png" --diff-map signed --diff-scale 2 "$T/h.pfm" >/dev/null
# a - b = +0.5 at (1, 0) on a scale of 2: a quarter of the way from white
# to #b40426: 255 * 3/4 + (180, 4, 38) / 4
check_eq "signed diff" "$(py png "$T/sd.png")" \
    "2 2 3 8 255 255 255 236 192 201 255 255 255 255 255 255"

# an output path that is not a regular file (here a FIFO; /dev/null alike)
# is written in place, not replaced by the atomic rename
mkfifo "$T/fifo"
cat "$T/fifo" >"$T/fromfifo" & catpid=$!
tonemap -o "$T/fifo" "$T/g.pfm"; rc=$?
if [ -p "$T/fifo" ]; then wait $catpid; else kill $catpid; wait $catpid; fi
check_eq "output to a FIFO, written in place" \
    "$rc $(test -p "$T/fifo" && echo fifo) $(py png "$T/fromfifo" 2>&1 | cut -d' ' -f1-4)" "0 fifo 4 1 1 8"

# ---- errors: one line, the right code, nothing on stdout, no file ----
printf 'hello' >"$T/junk"
expect_fail "missing input" 66 "nope.pfm" tonemap -o "$T/x.png" "$T/nope.pfm"
expect_fail "not an image" 65 "not a voxlux stream" tonemap -o "$T/x.png" "$T/junk"
head -c 30 "$T/a.pfm" >"$T/trunc.pfm"
expect_fail "truncated PFM" 65 "pfm:" tonemap -o "$T/x.png" "$T/trunc.pfm"
printf 'PF\n65536 65536\n-1\n' >"$T/huge.pfm"
expect_fail "oversized PFM header" 65 "needs" tonemap -o "$T/x.png" "$T/huge.pfm"
check_eq "no output or temporary left" "$(ls "$T" | grep -c '^x\.png')" 0
expect_fail "PNG as input" 65 "PNG holds display" tonemap -o "$T/x.pfm" "$T/a.png"
expect_fail "--bits 12" 64 "bits" tonemap --bits 12 "$T/a.pfm"
expect_fail "--op hable" 64 "--op: unknown operator 'hable' (one of: clamp, reinhard, aces)" tonemap --op hable "$T/a.pfm"
expect_fail "--diff-map bad" 64 "--diff-map: unknown map 'log' (one of: abs, signed)" tonemap --diff-map log "$T/a.pfm"
expect_fail "--white without reinhard" 64 "reinhard" tonemap --white 4 "$T/a.pfm"
expect_fail "PNG options with PFM output" 64 "PFM output" tonemap --op aces -o "$T/x.pfm" "$T/a.pfm"
expect_fail "--json without --compare" 64 "compare" tonemap --json "$T/a.pfm"
expect_fail "two encodings" 64 "exclude" tonemap --srgb --linear "$T/a.pfm"
expect_fail "--exposure out of range" 64 "exposure" tonemap --exposure 1000 "$T/a.pfm"
# option values read numbers by the scene's grammar (formats/scene.md, 2):
# no hexadecimal, blanks, inf or nan; a value beyond a double is no number
expect_fail "--exposure hexadecimal" 64 "--exposure: '0x1p1' is not a number" tonemap --exposure 0x1p1 "$T/a.pfm"
expect_fail "--exposure with a blank" 64 "is not a number" tonemap --exposure " 1" "$T/a.pfm"
expect_fail "--exposure 1e999" 64 "is not a number" tonemap --exposure 1e999 "$T/a.pfm"
expect_fail "--gamma nan" 64 "--gamma: 'nan' is not a number" tonemap --gamma nan "$T/a.pfm"
expect_fail "--bits hexadecimal" 64 "--bits: '0x8' is not an integer" tonemap --bits 0x8 "$T/a.pfm"
expect_fail "--background inf" 64 "expected 3 numbers" tonemap --background 0,inf,0 "$T/a.pfm"
expect_fail "--background hexadecimal" 64 "expected 3 numbers" tonemap --background 0,0x1,0 "$T/a.pfm"
tonemap --exposure 1 --bits 8 --background 0,0,0.5 "$T/a.pfm" >"$T/n1.png"
tonemap --exposure 1. --bits +8 --background .0,0.,5e-1 "$T/a.pfm" >"$T/n2.png"
check_eq "'1.', '+8', '.0', '5e-1' are numbers (the same pixels)" \
    "$(py png "$T/n2.png")" "$(py png "$T/n1.png")"
expect_fail "no such image" 65 "no image named 'albedo'" tonemap --name albedo "$T/s.vxl"
expect_fail "--name with PFM" 64 "PFM" tonemap --name color "$T/a.pfm"
expect_fail "size mismatch" 65 "reference" tonemap --compare "$T/a.pfm" "$T/z.pfm"
expect_fail "unwritable output" 73 "x.png" tonemap -o "$T/nodir/x.png" "$T/a.pfm"
expect_fail "compare to stdout and -o -" 64 "metrics" tonemap --compare "$T/z.pfm" -o - "$T/z.pfm"

done_testing
