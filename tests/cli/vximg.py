"""vximg.py: read one value from a PFM file or from an IMAG chunk of a
voxlux stream, written from formats/stream.md and the PFM definition only
(no voxlux code), for the command-line tests.

    vximg.py pfm FILE X Y C          value at column X, row Y (top row 0)
    vximg.py img STREAM NAME X Y C   the same in the IMAG chunk named NAME
    vximg.py same A B                "same" if the two streams' IMAG chunks
                                     decode to the same bytes, else "differ"
    vximg.py pngsame A B             "same" if two PNGs hold the same pixel
                                     bytes (text chunks ignored)
    vximg.py pngpx FILE X Y C        the code of sample C of pixel (X, Y) of
                                     an 8- or 16-bit PNG (filters undone)
    vximg.py pngtext FILE KEY        the value of the tEXt chunk KEY
    vximg.py covdiff A B             pixels where one depth PFM is finite
                                     (a hit) and the other is not
    vximg.py relrmse A B             the RMSE of the colour channels of
                                     image "color" of B against A over the
                                     pixels both cover fully (alpha 1),
                                     divided by A's mean there
    vximg.py relmean A B             B's mean colour over A's over the
                                     pixels both cover fully (a bias)
    vximg.py relrmse-all A B         the same over every pixel either
                                     covers at all (alpha > 0), of the
                                     premultiplied colour (translucent
                                     pictures: direct volume rendering)
Prints the value with repr() precision ("inf", "nan" as Python prints).
"""
import struct, sys, zlib

def pfm(path, x, y, c):
    data = open(path, 'rb').read()
    parts = data.split(maxsplit=4)           # PF|Pf, w, h, scale, rest
    kind, w, h, scale = parts[0], int(parts[1]), int(parts[2]), float(parts[3])
    nc = 3 if kind == b'PF' else 1
    # the raster starts after the scale's single whitespace byte
    off = len(data) - w * h * nc * 4
    fmt = ('<' if scale < 0 else '>') + 'f'
    row = h - 1 - y                          # stored bottom row first
    i = off + ((row * w + x) * nc + c) * 4
    return struct.unpack(fmt, data[i:i + 4])[0]

def chunks(data):
    assert data[:8] == b'\x89VXL\r\n\x1a\n'
    p = 8
    while p < len(data):
        t = data[p:p + 4]
        n = struct.unpack('<Q', data[p + 4:p + 12])[0]
        yield t, data[p + 12:p + 12 + n]
        p += 16 + n

def img(path, name, x, y, c):
    for t, pay in chunks(open(path, 'rb').read()):
        if t != b'IMAG':
            continue
        head, body = pay.split(b'\n\n', 1)
        h = dict(l.split(': ', 1) for l in head.decode().split('\n'))
        if h.get('name') != name:
            continue
        if h.get('encoding') == 'zlib':
            body = zlib.decompress(body)
        w, nc = int(h['width']), int(h['channels'])
        i = ((y * w + x) * nc + c) * 4
        return struct.unpack('<f', body[i:i + 4])[0]
    raise SystemExit('no IMAG chunk named %s' % name)

def images(path):
    out = []
    for t, pay in chunks(open(path, 'rb').read()):
        if t == b'IMAG':
            head, body = pay.split(b'\n\n', 1)
            h = dict(l.split(': ', 1) for l in head.decode().split('\n'))
            if h.get('encoding') == 'zlib':
                body = zlib.decompress(body)
            out.append((h.get('name'), h['width'], h['height'],
                        h['channels'], body))
    return out

def png_pixels(path):
    data = open(path, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n'
    p, head, idat = 8, None, b''
    while p < len(data):
        n = struct.unpack('>I', data[p:p + 4])[0]
        t = data[p + 4:p + 8]
        if t == b'IHDR':
            head = data[p + 8:p + 8 + n]
        elif t == b'IDAT':
            idat += data[p + 8:p + 8 + n]
        p += 12 + n
    return head, zlib.decompress(idat)

def png_chunks(path):
    data = open(path, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n'
    p = 8
    while p < len(data):
        n = struct.unpack('>I', data[p:p + 4])[0]
        yield data[p + 4:p + 8], data[p + 8:p + 8 + n]
        p += 12 + n

def png_sample(path, x, y, c):
    # non-interlaced, 8 or 16 bits; the five filters of the PNG spec
    head, raw = png_pixels(path)
    w, h, depth, ctype = struct.unpack('>IIBB', head[:10])
    nc = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    bpp = nc * depth // 8
    stride = w * bpp
    prev = bytearray(stride)
    for r in range(y + 1):
        f = raw[r * (stride + 1)]
        line = bytearray(raw[r * (stride + 1) + 1:(r + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            cc = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - cc), abs(a - cc), abs(a + b - 2 * cc)
                pr = a if pa <= pb and pa <= pc else b if pb <= pc else cc
                line[i] = (line[i] + pr) & 255
        prev = line
    i = x * bpp + c * depth // 8
    return prev[i] if depth == 8 else prev[i] << 8 | prev[i + 1]

a = sys.argv[1:]
if a[0] == 'pngpx':
    print(png_sample(a[1], int(a[2]), int(a[3]), int(a[4])))
    raise SystemExit
if a[0] == 'pngtext':
    for t, d in png_chunks(a[1]):
        if t == b'tEXt' and d.split(b'\0', 1)[0].decode('latin-1') == a[2]:
            sys.stdout.write(d.split(b'\0', 1)[1].decode('latin-1'))
            raise SystemExit
    print('<absent>')
    raise SystemExit
if a[0] == 'same':
    print('same' if images(a[1]) == images(a[2]) and images(a[1]) else 'differ')
    raise SystemExit
if a[0] == 'pngsame':
    print('same' if png_pixels(a[1]) == png_pixels(a[2]) else 'differ')
    raise SystemExit
if a[0] == 'covdiff':
    import math
    def cov(path):
        data = open(path, 'rb').read()
        parts = data.split(maxsplit=4)
        w, h, scale = int(parts[1]), int(parts[2]), float(parts[3])
        off = len(data) - w * h * 4
        fmt = ('<' if scale < 0 else '>') + '%df' % (w * h)
        return [math.isfinite(v) for v in struct.unpack(fmt, data[off:])]
    ca, cb = cov(a[1]), cov(a[2])
    print(sum(x != y for x, y in zip(ca, cb)) + abs(len(ca) - len(cb)))
    raise SystemExit
if a[0] in ('relrmse', 'relmean', 'relrmse-all'):
    import math
    def color(path):
        for name, w, h, nc, body in images(path):
            if name == 'color':
                n = int(w) * int(h) * int(nc)
                return int(nc), struct.unpack('<%df' % n, body[:4 * n])
        raise SystemExit('no color image in %s' % path)
    (na, pa), (nb, pb) = color(a[1]), color(a[2])
    assert na == nb == 4 and len(pa) == len(pb)
    se = sm = sb = k = 0
    for i in range(0, len(pa), 4):
        if (pa[i + 3] == 1 and pb[i + 3] == 1) if a[0] != 'relrmse-all' \
                else (pa[i + 3] > 0 or pb[i + 3] > 0):
            for c in range(3):
                se += (pb[i + c] - pa[i + c]) ** 2
                sm += pa[i + c]
                sb += pb[i + c]
                k += 1
    if a[0] == 'relmean':
        print(sb / sm if k and sm else 'nan')
    else:
        print(math.sqrt(se / k) / (sm / k) if k and sm else 'nan')
    raise SystemExit
if a[0] == 'pfm':
    v = pfm(a[1], int(a[2]), int(a[3]), int(a[4]))
else:
    v = img(a[1], a[2], int(a[3]), int(a[4]), int(a[5]))
print(repr(v))
