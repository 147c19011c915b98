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


# ---- PGM (heightfield's maps) ----
put("pgm", "gray8.pgm", b"P5\n3 2\n255\n" + bytes([0, 1, 2, 128, 254, 255]))
put("pgm", "gray16.pgm", b"P5 2 2 65535\n" + struct.pack(">4H", 0, 1, 65534,
    65535))
put("pgm", "comments.pgm", b"P5\n# made by hand\n2 1 # size\n# maxval\n"
    b"100\n" + bytes([0, 100]))
put("pgm", "over-maxval.pgm", b"P5\n2 1\n100\n" + bytes([5, 200]))
put("pgm", "truncated.pgm", b"P5\n4 4\n255\n" + bytes(5))
put("pgm", "huge.pgm", b"P5\n65536 65536\n255\n" + bytes(4))
# the harness once wanted samples over a 16-bit maxval back within 1e-3
put("pgm", "regress-maxval-65534.pgm", b"P5 2 2 65534\n" +
    bytes([0, 0, 0, 0x2a, 0xff, 0xfe, 0xff, 0xbf]))


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

# ---- tet meshes: first byte = options (fuzz_tetvtk.c, fuzz_gmsh.c) ----
VTK_TET = ("# vtk DataFile Version 3.0\ntwo tets\nASCII\n"
           "DATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n"
           "0 0 0  1 0 0  0 1 0\n0 0 1  1 1 1\nCELLS 3 14\n"
           "4 0 1 2 3\n4 1 2 3 4\n3 0 1 2\nCELL_TYPES 3\n10\n10\n5\n"
           "POINT_DATA 5\nSCALARS density float 1\nLOOKUP_TABLE default\n"
           "0.5 1.5 -2 3e2 4.25\n")
put("tetvtk", "ascii", b"\0" + VTK_TET.encode())
put("tetvtk", "ascii-named", b"\2" + VTK_TET.encode())
put("tetvtk", "hex-cell", b"\1" + VTK_TET.replace(
    "CELLS 3 14", "CELLS 4 23").replace(
    "3 0 1 2\n", "3 0 1 2\n8 0 1 2 3 4 0 1 2\n").replace(
    "CELL_TYPES 3\n10\n10\n5", "CELL_TYPES 4\n10\n10\n5\n12").encode())
put("tetvtk", "v51", b"\0" + (
    "# vtk DataFile Version 5.1\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n"
    "POINTS 5 float\n0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n"
    "METADATA\nINFORMATION 0\n\n"
    "CELLS 4 11\nOFFSETS vtktypeint64\n0 4 8 11\n"
    "CONNECTIVITY vtktypeint64\n0 1 2 3 1 2 3 4 0 1 2\n"
    "CELL_TYPES 3\n10 10 5\n"
    "POINT_DATA 5\nFIELD f 1\ndensity 1 5 float\n0.5 1.5 -2 300 4.25\n"
).encode())
put("tetvtk", "binary", b"\0" + b"# vtk DataFile Version 4.2\nb\nBINARY\n"
    b"DATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n" +
    struct.pack(">12d", 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1) +
    b"\nCELLS 1 5\n" + struct.pack(">5i", 4, 0, 1, 2, 3) +
    b"\nCELL_TYPES 1\n" + struct.pack(">i", 10) +
    b"\nPOINT_DATA 4\nSCALARS s float 1\nLOOKUP_TABLE default\n" +
    struct.pack(">4f", 0, 1, 2, 3) + b"\n")
put("tetvtk", "bad-index", b"\0" + VTK_TET.replace("4 1 2 3 4",
    "4 1 2 3 9").encode())

GMSH2 = ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
         "$PhysicalNames\n1\n3 1 \"fluid region\"\n$EndPhysicalNames\n"
         "$Nodes\n5\n10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n50 1 1 1\n"
         "$EndNodes\n$Elements\n4\n1 15 2 0 1 10\n2 2 2 0 1 10 20 30\n"
         "3 4 2 1 1 10 20 30 40\n4 4 3 1 1 0 20 30 40 50\n$EndElements\n"
         "$NodeData\n1\n\"velocity\"\n1\n0.0\n3\n0\n3\n1\n10 1 2 3\n"
         "$EndNodeData\n"
         "$NodeData\n1\n\"density\"\n1\n0.0\n3\n0\n1\n5\n"
         "10 0.5\n20 1.5\n30 -2\n40 300\n50 4.25\n$EndNodeData\n")
GMSH4 = ("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
         "$Entities\n1 0 0 1\n1 0 0 0 0\n1 0 0 0 1 1 1 0 0\n$EndEntities\n"
         "$Nodes\n2 5 1 5\n0 1 0 1\n1\n0 0 0\n"
         "3 1 1 4\n2\n3\n4\n5\n1 0 0 0.1 0.2 0.3\n0 1 0 0 0 0\n0 0 1 0 0 0\n"
         "1 1 1 0 0 0\n$EndNodes\n"
         "$Elements\n2 3 1 3\n2 1 2 1\n1 1 2 3\n"
         "3 1 4 2\n2 1 2 3 4\n3 2 3 4 5\n$EndElements\n"
         "$NodeData\n1\n\"pressure\"\n1\n0.0\n3\n0\n1\n5\n"
         "1 0.5\n2 1.5\n3 -2\n4 300\n5 4.25\n$EndNodeData\n")
put("gmsh", "v2", b"\0" + GMSH2.encode())
put("gmsh", "v2-named", b"\2" + GMSH2.encode())
put("gmsh", "v4", b"\0" + GMSH4.encode())
put("gmsh", "v4-truncated", b"\0" + GMSH4[:300].encode())
put("gmsh", "v2-bad-node", b"\0" + GMSH2.replace("20 30 40 50",
    "20 30 40 99").encode())


# ---- Radiance RGBE (.hdr): flat, new and old run-length, orientations ----
HDRHEAD = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n"


def rle_scanline(px):
    """Radiance's new run-length scanline of 4-byte pixels: all literals."""
    w = len(px)
    out = bytes([2, 2, w >> 8, w & 0xff])
    for c in range(4):
        plane = bytes(p[c] for p in px)
        for i in range(0, w, 128):
            chunk = plane[i:i + 128]
            out += bytes([len(chunk)]) + chunk
    return out


put("hdr", "flat.hdr", HDRHEAD + b"-Y 2 +X 3\n" + bytes(
    [128, 64, 32, 129, 255, 0, 1, 136, 0, 0, 0, 0,
     1, 2, 3, 140, 9, 9, 9, 130, 200, 100, 50, 120]))
put("hdr", "rle.hdr", HDRHEAD + b"-Y 2 +X 8\n" +
    bytes([2, 2, 0, 8, 136, 100, 8]) + bytes(range(8)) +
    bytes([132, 5, 4, 1, 2, 3, 4, 136, 130]) +
    rle_scanline([(k, 2 * k, 3 * k, 128 + k) for k in range(8)]))
put("hdr", "old-rle.hdr", b"#?RGBE\nEXPOSURE=2\nCOLORCORR=1 2 0.5\n\n"
    b"+X 3 +Y 4\n" + bytes([7, 8, 9, 136, 1, 1, 1, 3,
                            1, 2, 3, 136, 1, 1, 1, 1, 4, 4, 4, 136, 5, 5, 5, 5,
                            6, 6, 6, 136, 1, 1, 1, 2, 7, 7, 7, 136]))
put("hdr", "truncated.hdr", HDRHEAD + b"-Y 4 +X 16\n" + bytes([2, 2, 0, 16, 140]))


# ---- OpenEXR: uncompressed scanline files from the OpenEXR layout ----
def exr(chans, w, h, ptype=2, vals=None, dw=None, dp=None):
    def attr(name, typ, val):
        return (name.encode() + b"\0" + typ.encode() + b"\0" +
                struct.pack("<i", len(val)) + val)
    dw = dw or (0, 0, w - 1, h - 1)
    dp = dp or dw
    cl = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", ptype, 0, 1, 1)
                  for c in chans) + b"\0"
    head = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) +
            attr("channels", "chlist", cl) +
            attr("compression", "compression", b"\0") +
            attr("dataWindow", "box2i", struct.pack("<4i", *dw)) +
            attr("displayWindow", "box2i", struct.pack("<4i", *dp)) +
            attr("lineOrder", "lineOrder", b"\0") +
            attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
            attr("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0)) +
            attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    fmt = "<e" if ptype == 1 else "<f"
    size = len(chans) * w * struct.calcsize(fmt)
    first = len(head) + 8 * h
    out = head + b"".join(struct.pack("<Q", first + y * (8 + size))
                          for y in range(h))
    for y in range(h):
        out += struct.pack("<ii", dw[1] + y, size)
        for c in range(len(chans)):
            for x in range(w):
                v = vals(c, x, y) if vals else 0.5 * c + 0.25 * x + y
                out += struct.pack(fmt, v)
    return out


put("exr", "rgb-float.exr", exr("BGR", 4, 3))
put("exr", "rgba-half.exr", exr("ABGR", 3, 2, ptype=1))
put("exr", "y-float.exr", exr("Y", 2, 2))
put("exr", "windows.exr", exr("BGR", 2, 2, dw=(1, 1, 2, 2), dp=(0, 0, 3, 3)))
put("exr", "nan.exr", exr("BGR", 2, 1, vals=lambda c, x, y:
                          float("nan") if x == 1 else -0.5))


# ---- readers over a pipe (fuzz_pipe: first byte 0 vx_import_file, 1
# vx_import_volume_or_mesh, 2 raw with fuzz_raw's 8 parameter bytes) ----
def seeds(sub):
    d = os.path.join(top, sub)
    return sorted((n, open(os.path.join(d, n), "rb").read())
                  for n in os.listdir(d))


for sub, mode in (("nrrd", 0), ("nifti", 0), ("vtk", 1), ("tetvtk", 1),
                  ("gmsh", 1)):
    for n, b in seeds(sub)[:4]:
        if sub in ("tetvtk", "gmsh"):
            b = b[1:]      # their targets' options byte
        put("pipe", "%s-%s" % (sub, n), bytes([mode]) + b)
put("pipe", "raw-u8", bytes([2, 2, 0, 3, 0, 2, 0, 1, 0]) + bytes(range(12)))
put("pipe", "raw-gz", bytes([2, 2, 0, 2, 0, 2, 0, 3, 1]) +
    gz(struct.pack(">8h", 1, -2, 3, -4, 5, -6, 7, -8)))
put("pipe", "raw-long", bytes([2, 1, 0, 1, 0, 1, 0, 1, 0]) + bytes(64))

# ---- numbers beyond the double range, extents that overflow ----
put("nrrd", "ascii-overflow.nrrd", "NRRD0004\ntype: double\ndimension: 3\n"
    "sizes: 2 1 1\nencoding: ascii\n\n1 1e999\n")
put("nrrd", "extent-overflow.nrrd", b"NRRD0004\ntype: uchar\ndimension: 3\n"
    b"sizes: 3 1 1\nencoding: raw\nspacings: 1e308 1 1\n\n" + bytes(3))
put("vtk", "ascii-overflow.vtk", "# vtk DataFile Version 3.0\nx\nASCII\n"
    "DATASET STRUCTURED_POINTS\nDIMENSIONS 2 1 1\nSPACING 1 1 1\n"
    "ORIGIN 0 0 0\nPOINT_DATA 2\nSCALARS d float 1\n"
    "LOOKUP_TABLE default\n-1e999 2\n")
put("tetvtk", "scalar-overflow.vtk", "\x00# vtk DataFile Version 3.0\nx\n"
    "ASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
    "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n"
    "POINT_DATA 4\nSCALARS d double 1\nLOOKUP_TABLE default\n"
    "0.5 1.5 1e999 3.5\n")

# ---- transfer functions (fuzz_tf: first byte 0 auto, 1 paraview, 2 slicer,
# 3 miter; then the file) ----
def tf(name, fmt, data):
    put("tf", name, bytes([fmt]) + (data if isinstance(data, bytes)
                                     else data.encode()))


tf("paraview.json", 1, '[{"ColorSpace": "RGB", "Name": "a", '
   '"RGBPoints": [0, 1, 0, 0.25, 100, 0, 1, 0.5, 200, 0.25, 0.5, 1], '
   '"Points": [0, 0, 0.5, 0, 100, 0.5, 0.25, 0.3, 200, 1, 0.5, 1]}]\n')
for cs in ("HSV", "Lab", "Diverging"):
    tf("paraview-%s.json" % cs.lower(), 1, '[{"ColorSpace": "%s", '
       '"RGBPoints": [0, 0.23, 0.3, 0.75, 1, 0.7, 0.02, 0.15, 2, 0.9, 0.9, '
       '0.2, 2, 0, 0, 0, 3, 0.1, 0.8, 0.9]}]' % cs)
tf("paraview-ramp.json", 0, '{"Name": "\\u00e9\\ud83d\\ude00", '
   '"RGBPoints": [-1e3, 0, 0, 0, 1e3, 1, 1, 1], "NanColor": [1, 1, 0]}')
tf("slicer.vp", 0, "1\n1\n0.7\n0.1\n0.2\n10\n6 0 0 100 0.5 200 1\n"
   "4 0 0.25 255 1\n12 0 1 0 0.25 100 0 1 0.5 200 0.25 0.5 1\n")
tf("slicer.vp.json", 2, '{"volumeProperties": [{"components": [{'
   '"scalarOpacityUnitDistance": 0.5, "disableGradientOpacity": false, '
   '"rgbTransferFunction": {"points": [{"x": 0, "color": [1, 0, 0], '
   '"midpoint": 0.3, "sharpness": 0.6}, {"x": 9, "color": [0, 1, 0]}]}, '
   '"scalarOpacity": {"points": [{"x": 0, "y": 0}, {"x": 9, "y": 1, '
   '"midpoint": 0.5, "sharpness": 1}, {"x": 20, "y": 0.5}]}, '
   '"gradientOpacity": {"points": [{"x": 0, "y": 0.5}]}}]}]}\n')
tf("miter-1d.txf", 3, "NRRD0004\ntype: float\ndimension: 2\nsizes: 4 3\n"
   "axis mins: nan -50\naxis maxs: nan 250\n"
   "labels: \"RGBA\" \"gage(scalar:v)\"\nencoding: ascii\n\n"
   "1 0 0.25 0\n0 1 0.5 0.5\n0.25 0.5 1 1\n")
tf("miter-2d.txf", 0, b"NRRD0004\ntype: float\ndimension: 3\nsizes: 4 2 3\n"
   b"centers: ??? node cell\naxis mins: nan 0 0\naxis maxs: nan 2 30\n"
   b"labels: \"ARGB\" \"gage(gm)\" \"gage(v)\"\nencoding: raw\n"
   b"endian: little\n\n" + struct.pack("<24f", *[i / 24 for i in range(24)]))
tf("miter-u8-gzip.txf", 3, b"NRRD0004\ntype: uchar\ndimension: 2\n"
   b"sizes: 1 4\nold min: 0\nold max: 0.5\naxis mins: nan 0\n"
   b"axis maxs: nan 1\nlabels: \"A\" \"gage(v)\"\nencoding: gzip\n\n" +
   gz(bytes([0, 80, 160, 255])))
tf("bad-count.vp", 2, "1\n1\n0.7\n0.1\n0.2\n10\n8 0 0 1 1\n")
tf("bad-deep.json", 1, "[" * 40)
# found by fuzz_tf: a string decoded with a newline reached the message
tf("found-newline-message.json", 1, '[{"ColorSpace": "a\\nb\\u001b", '
   '"Points": [0, 0, 0.5, 0]}]')

# ---- regression seeds of the stream target (formats/stream.md and
# formats/irradiance.md): inputs fuzz_stream once failed on ----
def vchunk(typ, keys, body):
    p = ("".join("%s: %s\n" % kv for kv in keys) + "\n").encode() + body
    t = typ.encode()
    return t + struct.pack("<Q", len(p)) + p + struct.pack("<I",
                                                          zlib.crc32(t + p))


def vstream(*chunks):
    end = b"VEND" + struct.pack("<QI", 0, zlib.crc32(b"VEND"))
    return b"\x89VXL\r\n\x1a\n" + b"".join(chunks) + end


IRR_VOL = bytes([0, 10, 20, 30, 40, 50, 60, 70])


def irrv_accum(records):
    """An accum IRRV of a 2x2x2 lattice (one brick) over a 2x2x2 u8 volume:
    records maps texel index -> (count, flags, sum)."""
    body = b"\x01"
    for t in range(512):
        n, fl, s = records.get(t, (0, 0, 0))
        body += struct.pack("<II3qQQ", n, fl, s, s, s, 0, 0)
    keys = [("volume", "density"), ("volume-dims", "2 2 2"),
            ("volume-crc32", "%08x" % zlib.crc32(IRR_VOL)),
            ("lattice-dims", "2 2 2"), ("scale", "1"), ("brick", "8"),
            ("bricks", "1"), ("store", "accum"), ("fixed", "24"),
            ("first-sample", "0"), ("samples", "4"), ("offset", "0.5"),
            ("seed", "1"), ("side", "low"), ("key", "0123456789abcdef"),
            ("encoding", "zlib")]
    return vchunk("IRRV", keys, zlib.compress(body, 9))


VOLM = vchunk("VOLM", [("name", "density"), ("dims", "2 2 2"), ("type", "u8"),
                       ("spacing", "1 1 1"), ("origin", "0 0 0"),
                       ("layout", "linear"), ("encoding", "raw")], IRR_VOL)
# a record without samples whose flags carry the in-memory SAMPLED bit
# (bit 31): it was taken as a usable texel of irradiance 0
put("stream", "regress-irrv-sampled-bit.vxs", vstream(VOLM, irrv_accum({
    0: (0, 16 | 1 << 31, 0), 1: (4, 16, 4 << 24)})))
# a mean of 10^6, beyond binary16: made final f16 (bake-irr --half) it was
# written as an infinity that no reader takes
put("stream", "regress-irrv-f16-range.vxs", vstream(VOLM, irrv_accum({
    0: (4, 16, 4 * 10**6 << 24)})))
