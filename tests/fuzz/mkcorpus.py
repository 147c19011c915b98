#!/usr/bin/env python3
"""mkcorpus.py DIR: the hand-made seeds of the fuzz corpus (small valid files
of each format and a few malformed ones), written from the format specs
alone.  tests/fuzz/mkcorpus.sh calls it; the output is committed."""
import gzip
import os
import struct
import sys
import zlib

top = sys.argv[1]


def put(sub, name, data):
    d = os.path.join(top, sub)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def gz(b):
    return gzip.compress(b, mtime=0)


# ---- NRRD ----
u8 = bytes(range(24))
put("nrrd", "raw-u8.nrrd", b"NRRD0004\ntype: uchar\ndimension: 3\n"
    b"sizes: 4 3 2\nencoding: raw\nspacings: 1 2 0.5\n\n" + u8)
put("nrrd", "gzip-i16.nrrd", b"NRRD0005\ntype: short\ndimension: 3\n"
    b"sizes: 2 2 2\nendian: big\nencoding: gzip\n"
    b"space: right-anterior-superior\nspace directions: (1,0,0) (0,-2,0) "
    b"(0,0,3)\nspace origin: (1,2,3)\n\n" +
    gz(struct.pack(">8h", -3, 2, 1, 0, 7, -8, 9, 100)))
put("nrrd", "ascii-f64.nrrd", "NRRD0001\ntype: double\ndimension: 2\n"
    "sizes: 3 2\nencoding: ascii\n\n1.5 2 -3\n4e2 nan 6\n")
put("nrrd", "hex-u16.nrrd", "NRRD0004\ntype: ushort\ndimension: 1\n"
    "sizes: 3\nencoding: hex\nendian: little\n\n0100ff00abcd\n")
put("nrrd", "kv-comments.nrrd", b"NRRD0004\n# comment\ntype: float\n"
    b"dimension: 3\nsizes: 1 1 2\nkinds: domain domain domain\n"
    b"key:=value\nencoding: raw\nendian: little\n\n" +
    struct.pack("<2f", 1.0, -2.0))
put("nrrd", "bad-sizes.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\n"
    "sizes: 4 -3 18446744073709551615\nencoding: raw\n\n")
put("nrrd", "gzip-short.nrrd", b"NRRD0004\ntype: uchar\ndimension: 3\n"
    b"sizes: 4 4 4\nencoding: gzip\n\n" + gz(bytes(10))[:-6])
put("nrrd", "detached.nhdr", "NRRD0004\ntype: uchar\ndimension: 3\n"
    "sizes: 2 2 2\nencoding: raw\ndata file: x.raw\n\n")


# ---- NIfTI-1 ----
def nifti(dims, datatype, bitpix, data, pixdim=(1, 1, 1), magic=b"n+1\0",
          offset=352, scl=(0, 0), qform=0, sform=1, srow=None, swap=False):
    e = ">" if swap else "<"
    h = bytearray(348)
    struct.pack_into(e + "i", h, 0, 348)
    dim = [len(dims)] + list(dims) + [1] * (7 - len(dims))
    struct.pack_into(e + "8h", h, 40, *dim)
    struct.pack_into(e + "h", h, 70, datatype)
    struct.pack_into(e + "h", h, 72, bitpix)
    struct.pack_into(e + "8f", h, 76, 1, *pixdim, 0, 0, 0, 0)
    struct.pack_into(e + "f", h, 108, offset)
    struct.pack_into(e + "2f", h, 112, *scl)
    struct.pack_into(e + "h", h, 252, qform)
    struct.pack_into(e + "h", h, 254, sform)
    if srow is None:
        srow = [(pixdim[0], 0, 0, -1), (0, pixdim[1], 0, -2),
                (0, 0, pixdim[2], -3)]
    for i, r in enumerate(srow):
        struct.pack_into(e + "4f", h, 280 + 16 * i, *r)
    h[344:348] = magic
    ext = bytes(int(offset) - 348) if int(offset) >= 348 else b""
    return bytes(h) + ext + data


put("nifti", "u8.nii", nifti((3, 2, 2), 2, 8, bytes(range(12))))
put("nifti", "i16-scaled.nii", nifti((2, 2, 1), 4, 16,
    struct.pack("<4h", -1, 2, 300, -400), scl=(0.5, 10)))
put("nifti", "f32-big.nii", nifti((2, 1, 2), 16, 32,
    struct.pack(">4f", 1, 2, 3, float("inf")), swap=True))
put("nifti", "f64-qform.nii", nifti((2, 2, 2), 64, 64,
    struct.pack("<8d", *range(8)), qform=1, sform=0, pixdim=(2, 2, 2)))
put("nifti", "u8.nii.gz", gz(nifti((2, 2, 2), 2, 8, bytes(range(8)))))
put("nifti", "pair.hdr-img", nifti((2, 2, 1), 512, 16,
    struct.pack("<4H", 1, 2, 3, 65535), magic=b"ni1\0", offset=0))
put("nifti", "bad-datatype.nii", nifti((2, 2, 2), 1234, 8, bytes(8)))
put("nifti", "dims-overflow.nii", nifti((32767, 32767, 32767), 16, 32,
    bytes(16)))

# ---- VTK legacy structured points ----
vtk_head = ("# vtk DataFile Version 3.0\nseed\n{enc}\nDATASET "
            "STRUCTURED_POINTS\nDIMENSIONS 3 2 2\nSPACING 1 0.5 2\n"
            "ORIGIN 0 0 -1\nPOINT_DATA 12\nSCALARS density {t} 1\n"
            "LOOKUP_TABLE default\n")
put("vtk", "ascii-float.vtk", vtk_head.format(enc="ASCII", t="float") +
    " ".join(str(i * 0.5) for i in range(12)) + "\n")
put("vtk", "binary-short.vtk", vtk_head.format(enc="BINARY", t="short")
    .encode() + struct.pack(">12h", *range(-6, 6)) + b"\n")
put("vtk", "binary-uchar.vtk", vtk_head.format(enc="BINARY",
    t="unsigned_char").encode() + bytes(range(12)))
put("vtk", "ascii-double-aspect.vtk", (vtk_head.format(enc="ASCII",
    t="double").replace("SPACING", "ASPECT_RATIO") +
    "1 2 3 4 5 6 7 8 9 10 11 12\n"))
put("vtk", "truncated.vtk", vtk_head.format(enc="BINARY", t="float")
    .encode() + bytes(10))
put("vtk", "bad-dims.vtk", vtk_head.format(enc="ASCII", t="int").replace(
    "DIMENSIONS 3 2 2", "DIMENSIONS 0 -2 99999999999") + "1\n")

# ---- raw: 8 bytes of parameters (fuzz_raw.c), then the file ----
def raw(dims, t, big, skip, body):
    return struct.pack("<3hBB", *dims, t, (skip << 1) | big) + body


put("raw", "u8-4x3x2", raw((4, 3, 2), 1, 0, 0, bytes(range(24))))
put("raw", "i16-big-skip", raw((2, 2, 1), 4, 1, 3,
    b"abc" + struct.pack(">4h", 1, -2, 3, -4)))
put("raw", "f64", raw((2, 1, 1), 10, 0, 0, struct.pack("<2d", 1e300, -0.5)))
put("raw", "gzip-u16", raw((3, 1, 1), 3, 0, 0,
    gz(struct.pack("<3H", 1, 2, 65535))))
put("raw", "short", raw((4, 4, 4), 1, 0, 0, bytes(5)))

# ---- PFM ----
def pfm(kind, w, h, scale, vals, endian="<"):
    return (b"%s\n%d %d\n%s\n" % (kind, w, h, scale) +
            struct.pack(endian + "%df" % len(vals), *vals))


put("pfm", "gray-le.pfm", pfm(b"Pf", 3, 2, b"-1.0", [0, 1, 2, 3, 4, 5]))
put("pfm", "rgb-be.pfm", pfm(b"PF", 2, 1, b"1.0",
    [1, 0.5, 0.25, float("inf"), float("nan"), -1], ">"))
put("pfm", "one-line.pfm", b"Pf 1 1 -1 " + struct.pack("<f", 0.5))
put("pfm", "truncated.pfm", pfm(b"PF", 4, 4, b"-1", [1, 2, 3]))
put("pfm", "huge.pfm", b"PF\n4294967296 1\n-1\n" + bytes(12))


# ---- PNG ----
def png_chunk(t, d):
    return (struct.pack(">I", len(d)) + t + d +
            struct.pack(">I", zlib.crc32(t + d)))


def png(w, h, depth, ctype, rows, extra=b"", interlace=0):
    raw_ = b"".join(b"\0" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" +
            png_chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, ctype,
                                           0, 0, interlace)) + extra +
            png_chunk(b"IDAT", zlib.compress(raw_)) + png_chunk(b"IEND", b""))


put("png", "gray1.png", png(5, 2, 1, 0, [b"\xa8", b"\x50"]))
put("png", "palette-trns.png", png(2, 2, 8, 3, [b"\0\1", b"\1\2"],
    png_chunk(b"PLTE", b"\xff\0\0\0\xff\0\0\0\xff") +
    png_chunk(b"tRNS", b"\x80\xff")))
put("png", "rgba16.png", png(1, 2, 16, 6, [bytes(range(8)),
    bytes(range(8, 16))]))
put("png", "graya8-text.png", png(2, 1, 8, 4, [b"\x10\x20\x30\x40"],
    png_chunk(b"tEXt", b"history\0seed") + png_chunk(b"gAMA",
    struct.pack(">I", 45455))))
put("png", "interlaced-rgb.png", png(1, 1, 8, 2, [b"\1\2\3"], interlace=1))
put("png", "truncated.png", png(4, 4, 8, 2, [bytes(12)] * 4)[:50])
put("png", "huge.png", png(100000, 100000, 8, 0, [b""]))
